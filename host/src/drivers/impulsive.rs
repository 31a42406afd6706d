//! Planner B's driver: the report of an answered planner-B fixture (readable, or `--json`),
//! with the plan's end state in the form the fixture gave its target in.

use super::answer::{exit_code, report_other, Answered};
use crate::fixture::impulsive::ImpulsiveFixture;
use anyhow::{bail, Result};
use reconfig_core::impulsive::{
    end_state, point_phase, EndForm, EndState, ImpulsePlan, MeanElements, Phase, RelativeElements,
    Solution,
};
use reconfig_core::wire::OutcomeRef;
use serde_json::{json, Value};
use std::process::ExitCode;

/// Report a planner-B fixture's answer (a fixture in other forms is answered as the service
/// answers it: the conversion in the core, charged to the same work budget). Exit code 0 when
/// the plan is usable, 1 when it is not, 2 when the request was refused or rejected.
///
/// # Errors
/// An answer of another planner, or an end state that cannot be written.
pub fn report(fixture: &ImpulsiveFixture, answered: &Answered, json: bool) -> Result<ExitCode> {
    let (OutcomeRef::Impulsive(s) | OutcomeRef::ImpulsiveForm { solution: s, .. }) =
        answered.outcome
    else {
        return report_other(&fixture.name, answered, json);
    };
    let solve_time_s = answered.time_s;
    if json {
        println!(
            "{}",
            serde_json::to_string_pretty(&to_json(fixture, s, solve_time_s)?)?
        );
    } else {
        // The angle the impulse points are counted in (mean longitude for an equatorial chief).
        let (mean_head, true_head) = if point_keys(fixture).0 == "mean_longitude_deg" {
            ("l mean [deg]", "l true [deg]")
        } else {
            ("u mean [deg]", "u true [deg]")
        };
        // The end state in the form the fixture gave the relative state (or the deputy) in.
        let end = end_state_json(
            &fixture.problem.chief,
            &fixture.problem.target,
            s,
            fixture.end_form,
        )?;
        let plan = match &fixture.problem.plan {
            ImpulsePlan::Fixed(p) => format!("{} impulses at fixed points", p.len()),
            ImpulsePlan::Search {
                impulses,
                max_revolutions,
            } => {
                format!("search: {impulses} impulses, at most {max_revolutions} revolutions")
            }
        };
        println!("{} ({plan})", fixture.name);
        println!("status {:?}", s.info.status);
        println!("  k      t [s]   {mean_head}  {true_head}  dN   dv radial   along-track      normal [m/s]   |dv|");
        for (k, i) in s.impulses.iter().enumerate() {
            let d = i.dv_rtn_mps;
            println!(
                "  {:<2} {:>10.3} {:>12.4} {:>13.4} {:>4} {:>11.5} {:>13.5} {:>11.5} {:>12.5}",
                k + 1,
                i.time_s,
                i.arg_latitude_rad.to_degrees(),
                i.true_arg_latitude_rad.to_degrees(),
                i.revolutions,
                d[0],
                d[1],
                d[2],
                (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt()
            );
        }
        let figure = |x: Option<f64>| x.map_or_else(|| "absent".to_string(), |v| format!("{v:.5}"));
        println!(
            "total dv            {:.5} m/s (linear model: minimum norm {}, returned plan {} m/s)",
            s.total_dv_mps,
            figure(s.min_norm_total_dv_mps),
            figure(s.linear_total_dv_mps)
        );
        match &s.terminal_error {
            Some(t) => println!(
                "terminal error      {:.3e} m along-track, {:.3e} m position (nonlinear check)",
                t.along_track_m, t.position_m
            ),
            None => println!("terminal error      absent (the nonlinear check could not be flown)"),
        }
        let cond = s.info.condition_number.map_or_else(
            || "absent (rank-deficient)".to_string(),
            |c| format!("{c:.3e}"),
        );
        println!(
            "iterations          {} fixed point, {} min-fuel, {} correction; rank {}, cond {cond}",
            s.info.iterations,
            s.info.min_fuel_iterations,
            s.info.correction_iterations,
            s.info.rank,
        );
        println!(
            "min fuel used {}, nonlinear correction used {}, evaluations {}, solve time {:.6} s",
            s.info.min_fuel_used, s.info.correction_used, s.info.evaluations, solve_time_s
        );
        println!("end state           {end}");
        println!("frame: dv in the deputy's local frame (radial, along-track, normal)");
    }
    Ok(exit_code(s.info.status.is_usable()))
}

/// The JSON object `reconfig solve --json` prints for planner B: the impulses (their points in
/// the angle the chief counts them in), the end state in the form the fixture gave its target
/// in, the nonlinear check and the iteration figures.
///
/// # Errors
/// An end state that cannot be written.
pub fn to_json(fixture: &ImpulsiveFixture, s: &Solution, solve_time_s: f64) -> Result<Value> {
    let settings = fixture.settings;
    let (mean_key, true_key) = point_keys(fixture);
    let end = end_state_json(
        &fixture.problem.chief,
        &fixture.problem.target,
        s,
        fixture.end_form,
    )?;
    let impulses: Vec<_> = s
        .impulses
        .iter()
        .map(|i| {
            let mut entry = json!({
                "time_s": i.time_s,
                "revolutions": i.revolutions,
                "dv_rtn_mps": i.dv_rtn_mps,
            });
            entry[mean_key] = json!(i.arg_latitude_rad.to_degrees());
            entry[true_key] = json!(i.true_arg_latitude_rad.to_degrees());
            entry
        })
        .collect();
    let t = s.terminal_error.as_ref();
    Ok(json!({
        "name": fixture.name,
        "status": format!("{:?}", s.info.status),
        "total_dv_mps": s.total_dv_mps,
        "min_norm_total_dv_mps": s.min_norm_total_dv_mps,
        "linear_total_dv_mps": s.linear_total_dv_mps,
        "impulses": impulses,
        "final_time_s": s.final_time_s,
        // Absent (null) when the nonlinear check could not be flown.
        "terminal_error_m": t.map(|t| t.along_track_m),
        "terminal_position_error_m": t.map(|t| t.position_m),
        "terminal_error_elements": t.map(|t| t.elements.as_array()),
        "terminal_error_equinoctial": t.map(|t| t.equinoctial.as_array()),
        "end_state": end,
        "element_set": format!("{:?}", settings.element_set),
        "iterations": s.info.iterations,
        "min_fuel_iterations": s.info.min_fuel_iterations,
        "correction_iterations": s.info.correction_iterations,
        "rank": s.info.rank,
        "condition_number": s.info.condition_number,
        "min_fuel_used": s.info.min_fuel_used,
        "correction_used": s.info.correction_used,
        "evaluations": s.info.evaluations,
        "solve_time_s": solve_time_s,
    }))
}

/// The JSON keys of an impulse point's mean and true angles: the argument of latitude, or
/// the mean longitude for an equatorial chief (`point_phase`).
fn point_keys(fixture: &ImpulsiveFixture) -> (&'static str, &'static str) {
    if point_phase(&fixture.problem.chief, &fixture.settings) == Phase::MeanLongitude {
        ("mean_longitude_deg", "true_longitude_deg")
    } else {
        ("arg_latitude_deg", "true_arg_latitude_deg")
    }
}

/// The plan's end state (the core's [`end_state`]) as JSON, in the form the fixture gave the
/// target in.
fn end_state_json(
    chief: &MeanElements,
    target: &RelativeElements,
    solution: &Solution,
    form: EndForm,
) -> Result<Value> {
    end_state_value(&end_state(chief, target, solution, form))
}

/// An end state as JSON (angles in degrees).
fn end_state_value(end: &EndState) -> Result<Value> {
    Ok(match end {
        EndState::Elements(r) => json!({"relative_elements_deg": [
            r.dsma_km, r.decc, r.dinc_rad.to_degrees(), r.draan_rad.to_degrees(),
            r.dargp_rad.to_degrees(), r.dmean_anomaly_rad.to_degrees()]}),
        EndState::Roe(r) => {
            json!({"roe_m": [r.da_m, r.dlambda_m, r.dex_m, r.dey_m, r.dix_m, r.diy_m]})
        }
        EndState::DeputyClassical(d) => json!({"deputy_classical_deg": [
            d.sma_km, d.ecc, d.inc_rad.to_degrees(), d.raan_rad.to_degrees(),
            d.argp_rad.to_degrees(), d.mean_anomaly_rad.to_degrees()]}),
        EndState::DeputyEquinoctial(q) => {
            json!({"deputy_equinoctial": [q.sma_km, q.mean_longitude_rad.to_degrees(), q.ex, q.ey, q.hx, q.hy]})
        }
        EndState::DeputyState(s) => {
            json!({"deputy_state": {"position_km": s.pos_km, "velocity_km_s": s.vel_km_s}})
        }
        EndState::Unavailable(e) => bail!("end state: {e}"),
        EndState::NotFlown => Value::Null,
    })
}
