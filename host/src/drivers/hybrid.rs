//! The hybrid transfer's driver: the report of an answered hybrid fixture (readable, or
//! `--json` with the trajectory and the throttle), its plan for the plots, and the flight of a
//! returned plan sampled by the core's own check flight (`hybrid::fly_plan`).

use super::answer::{answer, buffers, exit_code, no_plan, report_other, Answered};
use crate::fixture::hybrid::HybridFixture;
use crate::fixture::Fixture;
use anyhow::{anyhow, bail, Result};
use reconfig_core::hybrid::trace::Sample;
use reconfig_core::hybrid::units::{days, LU_KM, MU_KG};
use reconfig_core::hybrid::{fly_plan, Solution};
use reconfig_core::limits::Limits;
use reconfig_core::wire::OutcomeRef;
use serde_json::{json, Value};
use std::process::ExitCode;

/// Samples of the trajectory in `--json` and the plots.
pub const TRAJECTORY_SAMPLES: u32 = 400;

/// The plan of a hybrid fixture, answered through the request path under `limits`.
///
/// # Errors
/// The request refused or rejected (named).
pub fn plan(fixture: &HybridFixture, limits: &Limits) -> Result<Box<Solution>> {
    let mut buffers = buffers();
    let [r] = &Fixture::Hybrid(fixture.clone()).requests()?[..] else {
        bail!("a hybrid fixture stands for one request");
    };
    let answered = answer(&r.request, limits, &mut *buffers);
    match answered.outcome {
        OutcomeRef::Hybrid(s) => Ok(Box::new(*s)),
        _ => Err(no_plan(&r.label, &answered)),
    }
}

/// The returned plan flown in `segments` pieces (the start and every piece's end).
///
/// # Errors
/// The flight stopped early (a singularity, the step bound).
pub fn trajectory(fixture: &HybridFixture, s: &Solution, segments: u32) -> Result<Vec<Sample>> {
    let mut samples = Vec::new();
    fly_plan(&fixture.problem, s, &fixture.settings, segments, &mut |x| {
        samples.push(*x);
    })
    .map_err(|stop| anyhow!("the plan's flight stopped: {stop:?}"))?;
    Ok(samples)
}

/// The switch times of a flown plan, days.
pub fn switch_times_days(s: &Solution) -> Vec<f64> {
    s.flown.map_or_else(Vec::new, |f| {
        let count = usize::try_from(f.switches).unwrap_or(usize::MAX);
        f.switch_times_tu
            .iter()
            .take(count)
            .map(|t| days(*t))
            .collect()
    })
}

/// The status as text.
pub fn status_text(s: &Solution) -> String {
    format!("{:?}", s.info.status)
}

/// The plan as one JSON object (`samples`: the flight for the trajectory, empty when not
/// flown).
pub fn to_json(fixture: &HybridFixture, s: &Solution, samples: &[Sample], time_s: f64) -> Value {
    let trajectory: Vec<Value> = samples
        .iter()
        .map(|x| {
            json!({
                "t_days": days(x.time_tu),
                "r_lu": x.state.r_lu,
                "v_vu": x.state.v_vu,
                "mass": x.state.m_mu,
                "throttle": x.throttle,
                "switching": x.switching,
                "hamiltonian": x.hamiltonian,
            })
        })
        .collect();
    let flown = s.flown;
    json!({
        "name": fixture.name,
        "status": status_text(s),
        "usable": s.info.status.is_usable(),
        "objective": s.objective.name(),
        "kappa": s.kappa,
        "theta_rad": s.theta_rad,
        "tf_days": days(s.duration_tu),
        "final_mass": flown.map(|f| f.final_mass),
        "final_mass_kg": flown.map(|f| f.final_mass * MU_KG),
        "mass_after_impulse": s.mass_after_impulse,
        "residual": s.residual,
        "end_miss": flown.map(|f| f.end_miss),
        "hamiltonian_drift": flown.map(|f| f.hamiltonian_drift),
        "thrust_arcs": flown.map(|f| f.thrust_arcs),
        "switches": flown.map(|f| f.switches),
        "switch_times_days": switch_times_days(s),
        "costates": s.costates,
        "cost_multiplier": s.cost_multiplier,
        "iterations": s.info.iterations,
        "work_units": s.info.work_units,
        "evaluations": s.info.evaluations,
        "solve_time_s": time_s,
        "published": {
            "final_mass": fixture.published.final_mass,
            "tf_days": fixture.published.duration_days,
            "kappa": fixture.published.kappa,
            "source": fixture.published.source,
        },
        "trajectory": trajectory,
    })
}

/// The JSON object of an answered hybrid fixture, its trajectory flown.
///
/// # Errors
/// An answer of another planner (its shared object is built instead by the caller).
pub fn answered_json(fixture: &HybridFixture, s: &Solution, time_s: f64) -> Value {
    // A plan that cannot be flown (not converged, far off) has no trajectory to show.
    let samples = trajectory(fixture, s, TRAJECTORY_SAMPLES).unwrap_or_default();
    to_json(fixture, s, &samples, time_s)
}

/// Report a hybrid fixture's answer. Exit code 0 when `Solved`, 1 otherwise, 2 when the
/// request was refused or rejected.
///
/// # Errors
/// JSON that does not print.
pub fn report(fixture: &HybridFixture, answered: &Answered, json: bool) -> Result<ExitCode> {
    let OutcomeRef::Hybrid(s) = answered.outcome else {
        return report_other(&fixture.name, answered, json);
    };
    if json {
        let value = answered_json(fixture, s, answered.time_s);
        println!("{}", serde_json::to_string_pretty(&value)?);
        return Ok(exit_code(s.info.status.is_usable()));
    }
    let p = &fixture.problem;
    println!(
        "{} ({}, thrust {} N, Isp {} s, chemical Isp {} s, parking orbit {} km)",
        fixture.name,
        s.objective.name(),
        p.thrust_n,
        p.specific_impulse_s,
        p.chemical_specific_impulse_s,
        p.parking_radius_km
    );
    println!("status {}", status_text(s));
    let free = match (p.free_kappa, p.free_theta) {
        (true, true) => " (both free)",
        (true, false) => " (kappa free)",
        (false, true) => " (theta free)",
        (false, false) => "",
    };
    println!(
        "kappa {:.6}, theta {:.6} rad{free}; mass after the impulse {:.6} ({:.1} kg)",
        s.kappa,
        s.theta_rad,
        s.mass_after_impulse,
        s.mass_after_impulse * MU_KG
    );
    match s.flown {
        Some(f) => {
            println!(
                "t_f {:.5} d, final mass {:.6} ({:.1} kg); {} thrust arcs, {} switches",
                days(s.duration_tu),
                f.final_mass,
                f.final_mass * MU_KG,
                f.thrust_arcs,
                f.switches
            );
            let times: Vec<String> = switch_times_days(s)
                .iter()
                .map(|t| format!("{t:.5}"))
                .collect();
            if !times.is_empty() {
                println!("switch times [d]: {}", times.join(", "));
            }
            println!(
                "shooting residual {}, check flight's miss {:.3e} ({:.3} m), H drift {:.3e}",
                s.residual
                    .map_or_else(|| "none".to_owned(), |r| format!("{r:.3e}")),
                f.end_miss,
                f.end_miss * LU_KM * 1e3,
                f.hamiltonian_drift
            );
        }
        None => println!(
            "t_f {:.5} d; the returned costates could not be flown to the end",
            days(s.duration_tu)
        ),
    }
    println!(
        "{} Newton iterations, {} work units (step trials), {} evaluations; solve time {:.6} s",
        s.info.iterations, s.info.work_units, s.info.evaluations, answered.time_s
    );
    let pb = &fixture.published;
    if pb.final_mass.is_some() || pb.duration_days.is_some() {
        println!(
            "published ({}): final mass {}, t_f {} d, kappa {}",
            pb.source.as_deref().unwrap_or("paper"),
            pb.final_mass
                .map_or_else(|| "-".to_owned(), |m| m.to_string()),
            pb.duration_days
                .map_or_else(|| "-".to_owned(), |d| d.to_string()),
            pb.kappa.map_or_else(|| "-".to_owned(), |k| k.to_string())
        );
    }
    Ok(exit_code(s.info.status.is_usable()))
}
