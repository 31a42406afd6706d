//! The GEO tour's driver: the report of an answered GEO-tour fixture (a table per leg, or
//! `--json`), and its plan as the plots draw it.

use super::answer::{answer, buffers, exit_code, no_plan, report_other, Answered};
use crate::fixture::geo_tour::{GeoTourFixture, DAY_S};
use crate::fixture::Fixture;
use anyhow::{bail, Result};
use reconfig_core::geo_tour::{Solution, SolveStatus};
use reconfig_core::limits::Limits;
use reconfig_core::wire::OutcomeRef;
use serde_json::json;
use std::process::ExitCode;

/// The plan of a GEO-tour fixture (with the mission time overridden when `mission_days` is
/// given), answered through the request path under the built-in limits.
///
/// # Errors
/// The request refused or rejected (named).
pub fn plan(fixture: &GeoTourFixture, mission_days: Option<f64>) -> Result<Box<Solution>> {
    let mut fixture = fixture.clone();
    if let Some(d) = mission_days {
        fixture.problem.mission_time_s = d * DAY_S;
    }
    let mut buffers = buffers();
    let [r] = &Fixture::GeoTour(fixture).requests()?[..] else {
        bail!("a GEO-tour fixture stands for one request");
    };
    let answered = answer(&r.request, &Limits::default(), &mut *buffers);
    match answered.outcome {
        OutcomeRef::GeoTour(s) => Ok(Box::new(s.clone())),
        _ => Err(no_plan(&r.label, &answered)),
    }
}

/// The plan as one JSON object.
pub fn to_json(name: &str, limit_s: f64, s: &Solution, solve_time_s: f64) -> serde_json::Value {
    let legs: Vec<_> = s
        .legs
        .iter()
        .map(|l| {
            let burns: Vec<_> = l
                .burns
                .iter()
                .map(|b| {
                    json!({
                        "epoch_s": l.start_s + b.offset_s,
                        "dv_rtn_mps": b.dv_rtn_mps,
                        "dv_mps": b.size_mps(),
                    })
                })
                .collect();
            json!({
                "target_index": l.target_index,
                "from_lon_deg": l.from_lon_rad.to_degrees(),
                "to_lon_deg": l.to_lon_rad.to_degrees(),
                "phase_deg": l.phase_rad.to_degrees(),
                "method": format!("{:?}", l.method),
                "start_s": l.start_s,
                "duration_s": l.duration_s,
                "transfer_s": l.transfer_s,
                "wait_s": l.wait_s,
                "dv_mps": l.dv_mps,
                "max_burn_mps": l.max_burn_mps,
                "orbit_sma_km": l.orbit_sma_km,
                "revolutions": l.revolutions,
                "burns": burns,
            })
        })
        .collect();
    json!({
        "name": name,
        "status": status_text(&s.info.status),
        "direction": s.info.direction.map(|d| format!("{d:?}")),
        "total_dv_mps": s.total_dv_mps,
        "mission_time_s": s.mission_time_s,
        "mission_time_limit_s": limit_s,
        "max_burn_mps": s.max_burn_mps,
        "price_mps_per_day": s.info.price_mps_per_s * DAY_S,
        "fastest_tour_s": s.info.fastest_tour_s,
        "price_iterations": s.info.price_iterations,
        "gap_assignments": s.info.gap_assignments,
        "refined_legs": s.info.refined_legs,
        "work_units": s.info.work_units,
        "legs": legs,
        "solve_time_s": solve_time_s,
    })
}

/// The status as text (`Solved`, `MissionTooShort(leg 3)`, ...).
pub fn status_text(s: &SolveStatus) -> String {
    match s {
        SolveStatus::MissionTooShort { leg } => format!("MissionTooShort(leg {leg})"),
        SolveStatus::CapTooLow { leg } => format!("CapTooLow(leg {leg})"),
        SolveStatus::RuleMethodInadmissible { leg } => {
            format!("RuleMethodInadmissible(leg {leg})")
        }
        SolveStatus::CheckFailed { leg } => format!("CheckFailed(leg {leg})"),
        SolveStatus::BudgetExhausted { verified } => {
            format!("BudgetExhausted(verified: {verified})")
        }
        other => format!("{other:?}"),
    }
}

/// Report a GEO-tour fixture's answer (its mission time is the limit the tour was planned
/// for). Exit code 0 when the plan is `Solved`, 1 otherwise, 2 when the request was refused or
/// rejected.
///
/// # Errors
/// An answer of another planner, or JSON that does not print.
pub fn report(fixture: &GeoTourFixture, answered: &Answered, json: bool) -> Result<ExitCode> {
    let OutcomeRef::GeoTour(s) = answered.outcome else {
        return report_other(&fixture.name, answered, json);
    };
    let limit_s = fixture.problem.mission_time_s;
    let solve_time_s = answered.time_s;
    if json {
        println!(
            "{}",
            serde_json::to_string_pretty(&to_json(&fixture.name, limit_s, s, solve_time_s))?
        );
    } else {
        println!(
            "{} ({:?}, {:?} sweep requested, cap {} m/s, mission {:.3} d)",
            fixture.name,
            fixture.problem.policy,
            fixture.problem.sweep,
            fixture.problem.max_burn_mps,
            limit_s / DAY_S
        );
        println!(
            "status {} ({:?} sweep)",
            status_text(&s.info.status),
            s.info.direction
        );
        println!(
            "  leg  from [deg]  to [deg]  phase [deg]  method    duration [d]  wait [d]  burns  max burn   dv [m/s]"
        );
        for (k, l) in s.legs.iter().enumerate() {
            let method = if l.revolutions > 0 {
                format!("{:?}/{}rev", l.method, l.revolutions)
            } else {
                format!("{:?}", l.method)
            };
            println!(
                "  {:<3} {:>10.3} {:>9.3} {:>12.3}  {:<11} {:>10.4} {:>9.4} {:>6} {:>9.4} {:>10.4}",
                k + 1,
                l.from_lon_rad.to_degrees(),
                l.to_lon_rad.to_degrees(),
                l.phase_rad.to_degrees(),
                method,
                l.duration_s / DAY_S,
                l.wait_s / DAY_S,
                l.burns.len(),
                l.max_burn_mps,
                l.dv_mps
            );
        }
        println!(
            "total dv {:.4} m/s, mission time {:.4} d (limit {:.4} d), largest burn {:.4} m/s",
            s.total_dv_mps,
            s.mission_time_s / DAY_S,
            limit_s / DAY_S,
            s.max_burn_mps
        );
        let fastest = s.info.fastest_tour_s.map_or_else(
            || "none admissible".to_owned(),
            |t| format!("{:.4} d", t / DAY_S),
        );
        println!(
            "time price {:.5} m/s per day; fastest tour {fastest}; {} price steps, {} gap assignments, {} Lambert legs refined; {} work units; solve time {:.6} s",
            s.info.price_mps_per_s * DAY_S,
            s.info.price_iterations,
            s.info.gap_assignments,
            s.info.refined_legs,
            s.info.work_units,
            solve_time_s
        );
        if let Some(p) = fixture.published.total_dv_mps {
            println!("published total (paper's GA, its own cost model): {p} m/s");
        }
        println!("burns: RTN frame (radial, along-track, normal), epochs in --json");
    }
    Ok(exit_code(s.info.status.is_usable()))
}
