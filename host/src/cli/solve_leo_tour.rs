//! `reconfig solve` for LEO tour fixtures: each arc of the fixture's order planned by the
//! core's per-arc rendezvous (`reconfig_core::leo_tour::solve_arc`), then flown in the host
//! truth model (J2 alone with the core's constants, and the full model) to report each arc's
//! arrival miss. No re-planning yet: the misses are those of the plan as made.

use crate::cli::solve::{report_rejection, EXIT_NOT_USABLE, EXIT_USABLE};
use crate::fixture::leo_tour::LeoTourFixture;
use crate::truth::ephemeris::julian_date;
use crate::truth::integrator::Tolerance;
use crate::truth::plan_check::{full_model, j2_model, TruthSettings};
use crate::truth::propagate::{propagate, Burn, EciState};
use anyhow::{anyhow, Result};
use reconfig_core::leo_tour::j2::State;
use reconfig_core::leo_tour::{propagate as core_propagate, solve_arc, ArcProblem, ArcSolution};
use serde_json::json;
use std::process::ExitCode;
use std::time::Instant;

/// One planned arc of the tour.
#[derive(Debug, Clone)]
pub struct PlannedArc {
    /// Client index (0-based) the arc leaves.
    pub from: usize,
    /// Client index (0-based) the arc reaches.
    pub to: usize,
    /// Arc start from the tour epoch, s.
    pub start_s: f64,
    /// Arc end from the tour epoch, s.
    pub end_s: f64,
    /// The core's plan (epochs from the arc start).
    pub solution: ArcSolution,
    /// The arc's problem (states at the arc start).
    pub problem: ArcProblem,
    /// Planning time, s.
    pub solve_time_s: f64,
}

/// Plan every arc of the fixture's order.
///
/// # Errors
/// A client that cannot be propagated to an arc start, or the core's `PlanError` (as text).
pub fn plan(f: &LeoTourFixture) -> Result<Vec<PlannedArc>> {
    let mut arcs = Vec::new();
    let mut t0 = 0.0;
    for (pair, &interval) in f.order.windows(2).zip(f.intervals_s.iter()) {
        let (from, to) = (pair[0], pair[1]);
        let at = |k: usize| -> Result<State> {
            core_propagate(&f.settings, &f.clients[k], t0)
                .ok_or_else(|| anyhow!("client {} cannot be propagated to {t0} s", k + 1))
        };
        let problem = ArcProblem {
            from: at(from)?,
            to: at(to)?,
            duration_s: interval,
            impulses: f.impulses,
        };
        let started = Instant::now();
        let solution = solve_arc(&problem, &f.settings)
            .map_err(|e| anyhow!("arc {} -> {}: {e:?}", from + 1, to + 1))?;
        arcs.push(PlannedArc {
            from,
            to,
            start_s: t0,
            end_s: t0 + interval,
            solution,
            problem,
            solve_time_s: started.elapsed().as_secs_f64(),
        });
        t0 += interval;
    }
    Ok(arcs)
}

fn eci(s: &State) -> EciState {
    EciState {
        pos_km: [s[0], s[1], s[2]],
        vel_km_s: [s[3], s[4], s[5]],
    }
}

/// Arrival miss (m) of `arc`'s plan flown in the truth model `model` (J2 alone or full), the
/// chaser and the client both starting from their planning states at the arc start.
pub fn truth_miss_m(arc: &PlannedArc, full: bool) -> Result<f64> {
    let ts = TruthSettings {
        epoch_jd: julian_date(2022, 11, 3, 0, 0, 0.0) + arc.start_s / 86_400.0,
        ..TruthSettings::default_settings()
    };
    let model = if full {
        full_model(&ts, ts.deputy_ballistic_m2_kg)?
    } else {
        j2_model(&ts)?
    };
    let s = &arc.solution;
    let burns: Vec<Burn> = s
        .burns
        .iter()
        .take(usize::from(s.impulses))
        .map(|b| Burn {
            time_s: b.epoch_s,
            dv_rtn_mps: b.rtn_mps,
        })
        .collect();
    let dur = arc.problem.duration_s;
    let chaser = propagate(
        &model,
        &eci(&arc.problem.from),
        &burns,
        dur,
        &Tolerance::TRUTH,
    )?;
    let client = propagate(&model, &eci(&arc.problem.to), &[], dur, &Tolerance::TRUTH)?;
    let d: Vec<f64> = (0..3)
        .map(|k| chaser.end.pos_km[k] - client.end.pos_km[k])
        .collect();
    Ok((d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt() * 1e3)
}

/// Solve and report a LEO tour fixture.
///
/// # Errors
/// A truth-model propagation error.
pub fn run(f: &LeoTourFixture, json_output: bool) -> Result<ExitCode> {
    let arcs = match plan(f) {
        Ok(a) => a,
        Err(e) => return Ok(report_rejection(&f.name, &e, json_output)),
    };
    let total: f64 = arcs.iter().map(|a| a.solution.total_dv_mps).sum();
    let usable = arcs
        .iter()
        .all(|a| a.solution.status == reconfig_core::leo_tour::Status::Solved);
    let status = if usable { "Solved" } else { "NotSolved" };
    let mut rows = Vec::new();
    for a in &arcs {
        let j2_miss = truth_miss_m(a, false)?;
        let full_miss = truth_miss_m(a, true)?;
        rows.push((a, j2_miss, full_miss));
    }
    if json_output {
        let arcs_json: Vec<_> = rows
            .iter()
            .map(|(a, j2m, fm)| {
                let s = &a.solution;
                let burns: Vec<_> = s
                    .burns
                    .iter()
                    .take(usize::from(s.impulses))
                    .map(|b| {
                        json!({
                            "epoch_s": a.start_s + b.epoch_s,
                            "dv_rtn_mps": b.rtn_mps,
                            "dv_mps": (b.rtn_mps.iter().map(|x| x * x).sum::<f64>()).sqrt(),
                        })
                    })
                    .collect();
                json!({
                    "from": a.from + 1,
                    "to": a.to + 1,
                    "start_s": a.start_s,
                    "end_s": a.end_s,
                    "status": format!("{:?}", s.status),
                    "dv_mps": s.total_dv_mps,
                    "burns": burns,
                    "model_miss_m": s.miss_m,
                    "truth_miss_m": { "j2_only": j2m, "full": fm, "after_replanning": null },
                    "evaluations": s.evaluations,
                    "work_units": s.work_units,
                    "solve_time_s": a.solve_time_s,
                })
            })
            .collect();
        println!(
            "{}",
            json!({
                "name": f.name,
                "status": status,
                "order": f.order.iter().map(|k| k + 1).collect::<Vec<_>>(),
                "total_dv_mps": total,
                "arcs": arcs_json,
                "published": {
                    "arc_dv_mps": f.published.arc_dv_mps,
                    "total_dv_mps": f.published.total_dv_mps,
                },
            })
        );
    } else {
        let order: Vec<String> = f.order.iter().map(|k| (k + 1).to_string()).collect();
        println!("{}: {status}, order {}", f.name, order.join(" -> "));
        for (n, (a, j2m, fm)) in rows.iter().enumerate() {
            let s = &a.solution;
            let published = f
                .published
                .arc_dv_mps
                .get(n)
                .map_or(String::new(), |p| format!(" (published {p:.3})"));
            println!(
                "  arc {} -> {}  [{:.4} s, {:.4} s]  {:?}  dv {:.3} m/s{published}",
                a.from + 1,
                a.to + 1,
                a.start_s,
                a.end_s,
                s.status,
                s.total_dv_mps
            );
            for b in s.burns.iter().take(usize::from(s.impulses)) {
                let size = b.rtn_mps.iter().map(|x| x * x).sum::<f64>().sqrt();
                println!(
                    "    burn at {:>12.4} s  RTN [{:>9.3} {:>9.3} {:>9.3}] m/s  |dv| {:.3} m/s",
                    a.start_s + b.epoch_s,
                    b.rtn_mps[0],
                    b.rtn_mps[1],
                    b.rtn_mps[2],
                    size
                );
            }
            println!(
                "    arrival miss: planning model {:.2e} m, truth J2-only {:.3} m, truth full {:.3} m  ({} evaluations, {:.2} s)",
                s.miss_m, j2m, fm, s.evaluations, a.solve_time_s
            );
        }
        let published = f
            .published
            .total_dv_mps
            .map_or(String::new(), |p| format!(" (published {p:.3})"));
        println!("  total {total:.3} m/s{published}");
    }
    Ok(ExitCode::from(if usable {
        EXIT_USABLE
    } else {
        EXIT_NOT_USABLE
    }))
}
