//! `reconfig solve` for GEO-tour fixtures: a table per leg, or `--json`.

use crate::cli::solve::{report_rejection, EXIT_NOT_USABLE, EXIT_USABLE};
use crate::fixture::geo_tour::{GeoTourFixture, DAY_S};
use anyhow::Result;
use reconfig_core::geo_tour::{solve, Solution, SolveStatus, Workspace};
use serde_json::json;
use std::process::ExitCode;
use std::time::Instant;

/// Solve a GEO-tour fixture (with the mission time overridden when `mission_days` is given).
///
/// # Errors
/// The core's `PlanError` as text when the request is refused.
pub fn solve_fixture(
    fixture: &GeoTourFixture,
    mission_days: Option<f64>,
) -> Result<(Box<Solution>, f64), reconfig_core::geo_tour::PlanError> {
    let mut problem = fixture.problem.clone();
    if let Some(d) = mission_days {
        problem.mission_time_s = d * DAY_S;
    }
    let mut ws = Box::new(Workspace::new());
    let mut out = Box::new(Solution::new());
    let started = Instant::now();
    solve(&problem, &fixture.settings, &mut ws, &mut out)?;
    Ok((out, started.elapsed().as_secs_f64()))
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
        other => format!("{other:?}"),
    }
}

/// Solve and report. Exit code 0 when the plan is `Solved`, 1 otherwise.
pub fn run(fixture: &GeoTourFixture, json: bool, mission_days: Option<f64>) -> Result<ExitCode> {
    let limit_s = mission_days.map_or(fixture.problem.mission_time_s, |d| d * DAY_S);
    let (s, solve_time_s) = match solve_fixture(fixture, mission_days) {
        Ok(v) => v,
        Err(err) => {
            return Ok(report_rejection(&fixture.name, &err, json));
        }
    };
    if json {
        println!(
            "{}",
            serde_json::to_string_pretty(&to_json(&fixture.name, limit_s, &s, solve_time_s))?
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
        println!(
            "time price {:.5} m/s per day; fastest tour {:.4} d; {} price steps, {} gap assignments, {} Lambert legs refined; solve time {:.6} s",
            s.info.price_mps_per_s * DAY_S,
            s.info.fastest_tour_s / DAY_S,
            s.info.price_iterations,
            s.info.gap_assignments,
            s.info.refined_legs,
            solve_time_s
        );
        if let Some(p) = fixture.published.total_dv_mps {
            println!("published total (paper's GA, its own cost model): {p} m/s");
        }
        println!("burns: RTN frame (radial, along-track, normal), epochs in --json");
    }
    Ok(if s.info.status == SolveStatus::Solved {
        ExitCode::from(EXIT_USABLE)
    } else {
        ExitCode::from(EXIT_NOT_USABLE)
    })
}
