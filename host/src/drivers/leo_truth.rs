//! The paper's multi-round correction, chained: the tour flown in the full truth model (JGM-3
//! 8×8, drag, Sun, Moon; `crate::truth`), each arc planned by the core from the truth states
//! reached, then its last leg re-planned against the truth model, and the next arc starting
//! from where the chaser really is.
//!
//! Round n (warm-started from the tour's plan of the same arc, `solve_arc_warm`): the clients'
//! truth states at the arc start (each flown in the truth model from the
//! tour epoch), the chaser's truth state (the end of round n − 1, or the first client's state
//! at the epoch); the core plans the arc from those osculating states in its J2 model
//! (`leo_tour::solve_arc`, the planning model re-initialised from the truth, as in the paper);
//! the plan flown in the truth model as made gives the miss before correction; the last leg
//! re-planned against the truth (`solve_leo_tour::replan_last_leg_states`: at most 20 truth
//! flights) gives the miss after; the chaser then matches the client's truth velocity and the
//! next round starts there. Deterministic: no clock, thread or randomness in any step.

use crate::cli::solve_leo_tour::{replan_last_leg_states, truth_flight, truth_miss_m, PlannedArc};
use crate::fixture::leo_tour::LeoTourFixture;
use crate::truth::ephemeris::julian_date;
use crate::truth::integrator::Tolerance;
use crate::truth::plan_check::{full_model, TruthSettings};
use crate::truth::propagate::{propagate, EciState};
use anyhow::{anyhow, Result};
use reconfig_core::leo_tour::j2::State;
use reconfig_core::leo_tour::{solve_arc, solve_arc_warm, ArcProblem, Status};
use serde_json::json;
use std::time::Instant;

/// One round of the chained correction.
#[derive(Debug, Clone)]
pub struct Round {
    /// The core's plan of the arc from the truth states at its start (those states are its
    /// problem).
    pub arc: PlannedArc,
    /// Truth-model arrival miss of that plan as made, m.
    pub miss_before_m: f64,
    /// Truth-model arrival miss after the last leg's re-plan, m.
    pub miss_after_m: f64,
    /// The arc's Δv after the re-plan, m/s.
    pub dv_after_mps: f64,
    /// Whether the last leg's re-plan succeeded; when it did not, the plan was flown as made
    /// and the next round starts from where that left the chaser.
    pub corrected: bool,
    /// Distance between the chaser's truth state at the arc start and the client's (the
    /// previous round's arrival miss carried in), m.
    pub start_offset_m: f64,
}

fn to_state(s: &EciState) -> State {
    let (p, v) = (s.pos_km, s.vel_km_s);
    [p[0], p[1], p[2], v[0], v[1], v[2]]
}

fn to_eci(s: &State) -> EciState {
    EciState {
        pos_km: [s[0], s[1], s[2]],
        vel_km_s: [s[3], s[4], s[5]],
    }
}

/// Fly the fixture's tour (its order and intervals) with the chained multi-round correction,
/// each round's arc warm-started from `planned`'s plan of the same arc where there is one
/// (`leo_tour::solve_arc_warm`; the full search otherwise).
///
/// # Errors
/// A truth-model propagation error, a core refusal of an arc, or a re-plan with no truth
/// flight.
pub fn multi_round(f: &LeoTourFixture, planned: &[PlannedArc]) -> Result<Vec<Round>> {
    let ts = TruthSettings {
        epoch_jd: julian_date(2022, 11, 3, 0, 0, 0.0),
        ..TruthSettings::default_settings()
    };
    let model = full_model(&ts, ts.deputy_ballistic_m2_kg)?;
    let first = *f.order.first().ok_or_else(|| anyhow!("empty order"))?;
    let mut chaser = to_eci(&f.clients[first]);
    let mut t0 = 0.0;
    let mut rounds = Vec::new();
    for (pair, &interval) in f.order.windows(2).zip(f.intervals_s.iter()) {
        let (from, to) = (pair[0], pair[1]);
        // The client's truth state at the arc start, flown from the tour epoch.
        let client = if t0 > 0.0 {
            propagate(&model, &to_eci(&f.clients[to]), &[], t0, &Tolerance::TRUTH)?.end
        } else {
            to_eci(&f.clients[to])
        };
        let start_offset_m = if from == first && t0 == 0.0 {
            0.0
        } else {
            let own = propagate(
                &model,
                &to_eci(&f.clients[from]),
                &[],
                t0,
                &Tolerance::TRUTH,
            )?
            .end;
            (0..3)
                .map(|k| (chaser.pos_km[k] - own.pos_km[k]).powi(2))
                .sum::<f64>()
                .sqrt()
                * 1e3
        };
        let problem = ArcProblem {
            from: to_state(&chaser),
            to: to_state(&client),
            duration_s: interval,
            impulses: f.impulses,
        };
        let started = Instant::now();
        let warm = planned
            .iter()
            .find(|a| a.from == from && a.to == to && a.start_s.to_bits() == t0.to_bits());
        let solution = match warm {
            Some(a) => solve_arc_warm(&problem, &f.settings, &a.solution),
            None => solve_arc(&problem, &f.settings),
        }
        .map_err(|e| anyhow!("round {} -> {}: {e:?}", from + 1, to + 1))?;
        let arc = PlannedArc {
            from,
            to,
            start_s: t0,
            end_s: t0 + interval,
            solution,
            problem,
            solve_time_s: started.elapsed().as_secs_f64(),
        };
        let miss_before_m = truth_miss_m(&arc, true)?;
        // A re-plan that fails (its Lambert leg does not solve from the truth state, or its
        // best flight misses by more than the plan as made) leaves the plan as made: the next
        // round re-plans from where it left the chaser.
        let (miss_after_m, dv_after_mps, end, corrected) =
            match replan_last_leg_states(&arc, &f.settings) {
                Ok(r) if r.miss_m < miss_before_m => (r.miss_m, r.dv_mps, r.chaser_end, true),
                _ => {
                    let (end, _) = truth_flight(&arc, true)?;
                    (miss_before_m, arc.solution.total_dv_mps, end, false)
                }
            };
        rounds.push(Round {
            arc,
            miss_before_m,
            miss_after_m,
            dv_after_mps,
            corrected,
            start_offset_m,
        });
        chaser = end;
        t0 += interval;
    }
    Ok(rounds)
}

/// Whether every round was planned `Solved`, re-planned, and arrives within `tol_m`.
pub fn all_within(rounds: &[Round], tol_m: f64) -> bool {
    rounds
        .iter()
        .all(|r| r.arc.solution.status == Status::Solved && r.corrected && r.miss_after_m <= tol_m)
}

/// `multi_round`'s outcome as JSON (an error as `{"error": ...}`).
pub fn rounds_json(rounds: &Result<Vec<Round>>) -> serde_json::Value {
    match rounds {
        Err(e) => json!({ "error": e.to_string() }),
        Ok(rs) => json!({
            "total_dv_after_mps": rs.iter().map(|r| r.dv_after_mps).sum::<f64>(),
            "arcs": rs.iter().map(|r| json!({
                "from": r.arc.from + 1,
                "to": r.arc.to + 1,
                "start_s": r.arc.start_s,
                "end_s": r.arc.end_s,
                "status": format!("{:?}", r.arc.solution.status),
                "dv_mps": r.arc.solution.total_dv_mps,
                "dv_after_mps": r.dv_after_mps,
                "corrected": r.corrected,
                "start_offset_m": r.start_offset_m,
                "truth_miss_m": { "before": r.miss_before_m, "after": r.miss_after_m },
            })).collect::<Vec<_>>(),
        }),
    }
}

/// Print `multi_round`'s outcome.
pub fn print_rounds(rounds: &Result<Vec<Round>>) {
    match rounds {
        Err(e) => println!("  multi-round correction in the truth model failed: {e:#}"),
        Ok(rs) => {
            println!("  multi-round correction (each arc planned from the truth state reached, its last leg re-planned in the truth model):");
            for r in rs {
                println!(
                    "    arc {} -> {}  {:?}{}  dv {:.3} m/s planned, {:.3} m/s flown; start offset {:.3e} m; truth miss {:.3} m before, {:.3e} m after",
                    r.arc.from + 1,
                    r.arc.to + 1,
                    r.arc.solution.status,
                    if r.corrected { "" } else { " (last leg not re-planned: flown as made)" },
                    r.arc.solution.total_dv_mps,
                    r.dv_after_mps,
                    r.start_offset_m,
                    r.miss_before_m,
                    r.miss_after_m
                );
            }
            let total: f64 = rs.iter().map(|r| r.dv_after_mps).sum();
            println!("    total flown {total:.3} m/s");
        }
    }
}
