//! The LEO tour's plans flown in the host's truth model (`crate::truth`: JGM-3 8×8, drag, Sun,
//! Moon, or J2 alone) and corrected there: each arc's arrival miss, its last leg re-planned
//! against the truth model (the paper's correction, with the core's J2-corrected Lambert leg
//! aimed by the truth model's miss), and the paper's multi-round correction chained over the
//! tour.
//!
//! Multi-round (round n warm-started from the tour's plan of the same arc, `solve_arc_warm`):
//! the clients' truth states at the arc start (each flown in the truth model from the
//! tour epoch), the chaser's truth state (the end of round n − 1, or the first client's state
//! at the epoch); the core plans the arc from those osculating states in its J2 model
//! (the planning model re-initialised from the truth, as in the paper); the plan flown in the
//! truth model as made gives the miss before correction; the last leg re-planned against the
//! truth ([`replan_last_leg_states`]: at most 20 truth flights) gives the miss after; the
//! chaser then matches the client's truth velocity and the next round starts there.
//! Deterministic: no clock, thread or randomness in any step. A round's warm start is a
//! host-side refinement of an earlier plan, not a request kind (the wire carries no warm
//! start): it calls the core's `solve_arc_warm`; a round with no earlier plan of its arc is an
//! arc request answered through the request path.

use super::answer::{answer, no_plan};
use super::leo_tour::{LeoBuffers, PlannedArc};
use crate::fixture::leo_tour::LeoTourFixture;
use crate::truth::ephemeris::DAY_S;
use crate::truth::forces::ForceModel;
use crate::truth::integrator::Tolerance;
use crate::truth::plan_check::{full_model, j2_model, TruthSettings};
use crate::truth::propagate::{propagate, Burn, EciState};
use anyhow::{anyhow, Result};
use reconfig_core::leo_tour::flight::Model;
use reconfig_core::leo_tour::j2::State;
use reconfig_core::leo_tour::shoot::{corrected_lambert, shoot_continued, Family, Offset, Secant};
use reconfig_core::leo_tour::{
    propagate as core_propagate, solve_arc_warm, ArcProblem, ArcSolution, Workspace,
};
use reconfig_core::limits::Limits;
use reconfig_core::wire::{OutcomeRef, Request};
use reconfig_core::work::Meter;
use std::time::Instant;

/// `from` (a planning-model state) flown through `burns` for `duration_s` in the truth model
/// `model`: where it ends.
///
/// # Errors
/// A truth-model propagation error.
fn fly(model: &ForceModel, from: &State, burns: &[Burn], duration_s: f64) -> Result<EciState> {
    Ok(propagate(
        model,
        &EciState::from_array(from),
        burns,
        duration_s,
        &Tolerance::TRUTH,
    )?
    .end)
}

/// An arc plan's burns as the truth model flies them (epochs from the arc start, RTN Δv).
fn truth_burns(burns: &[reconfig_core::leo_tour::Burn]) -> Vec<Burn> {
    burns
        .iter()
        .map(|b| Burn {
            time_s: b.epoch_s,
            dv_rtn_mps: b.rtn_mps,
        })
        .collect()
}

/// The truth model's settings `t_s` after the tour epoch `tour_epoch_jd` (the fixture's
/// `epoch`, UTC): the one place a LEO tour's time becomes the truth model's clock, which places
/// the Sun, the Moon and the Earth's rotation (GMST).
///
/// The model takes one time scale for all three, and gets UTC: for GMST it stands for UT1
/// (|UT1 - UTC| < 0.9 s by definition), for the Sun and Moon series for TT (TT - UTC = 69.184 s
/// since 2017, in which the Moon moves 0.01 deg and the Sun 0.0008 deg: a tenth of the series'
/// own error, ~0.1 deg for the Moon; see `truth::ephemeris`).
fn truth_settings_at(tour_epoch_jd: f64, t_s: f64) -> TruthSettings {
    TruthSettings {
        epoch_jd: tour_epoch_jd + t_s / DAY_S,
        ..TruthSettings::default_settings()
    }
}

/// Arrival miss (m) of `arc`'s plan flown in the truth model `model` (J2 alone or full), the
/// chaser and the client both starting from their planning states at the arc start.
pub fn truth_miss_m(arc: &PlannedArc, full: bool) -> Result<f64> {
    let (chaser, client) = truth_flight(arc, full)?;
    let d: Vec<f64> = (0..3)
        .map(|k| chaser.pos_km[k] - client.pos_km[k])
        .collect();
    Ok((d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt() * 1e3)
}

/// `arc`'s plan (every burn, the last included) flown in the truth model (J2 alone or full)
/// from the arc's start states: (the chaser's end state, the client's).
///
/// # Errors
/// A truth-model propagation error.
pub fn truth_flight(arc: &PlannedArc, full: bool) -> Result<(EciState, EciState)> {
    let ts = truth_settings_at(arc.tour_epoch_jd, arc.start_s);
    let model = if full {
        full_model(&ts, ts.deputy_ballistic_m2_kg)?
    } else {
        j2_model(&ts)?
    };
    let s = &arc.solution;
    let burns = truth_burns(&s.burns[..usize::from(s.impulses)]);
    let dur = arc.problem.duration_s;
    let chaser = fly(&model, &arc.problem.from, &burns, dur)?;
    let client = fly(&model, &arc.problem.to, &[], dur)?;
    Ok((chaser, client))
}

/// The arc's last leg re-planned against the full truth model from the truth state reached at
/// the last leg's departure (the paper's correction, with the core's J2-corrected Lambert leg
/// aimed by the truth model's miss: at most 20 truth flights). Returns (arrival miss m, the
/// arc's Δv m/s after the re-plan).
///
/// # Errors
/// A truth-model propagation error or a Lambert leg that does not solve.
pub fn replan_last_leg(
    arc: &PlannedArc,
    settings: &reconfig_core::leo_tour::Settings,
) -> Result<(f64, f64)> {
    replan_last_leg_states(arc, settings).map(|r| (r.miss_m, r.dv_mps))
}

/// What a last-leg re-plan in the truth model reached.
#[derive(Debug, Clone, Copy)]
pub struct Replanned {
    /// Arrival miss, m.
    pub miss_m: f64,
    /// The arc's Δv after the re-plan, m/s.
    pub dv_mps: f64,
    /// The chaser's truth state at the arrival after the matching burn (the reached position,
    /// the client's velocity).
    pub chaser_end: EciState,
    /// The client's truth state at the arrival.
    pub client_end: EciState,
}

/// [`replan_last_leg`] with the states it reached.
///
/// # Errors
/// As [`replan_last_leg`]; also when no truth flight of the re-planned leg succeeded.
pub fn replan_last_leg_states(
    arc: &PlannedArc,
    settings: &reconfig_core::leo_tour::Settings,
) -> Result<Replanned> {
    let s = &arc.solution;
    let m = usize::from(s.impulses);
    let Some(last) = m.checked_sub(2) else {
        return Err(anyhow!("the arc has no plan ({:?})", s.info.status));
    };
    let t_last = s.burns[last].epoch_s;
    let dur = arc.problem.duration_s;
    let at = |t: f64| truth_settings_at(arc.tour_epoch_jd, arc.start_s + t);
    let ts0 = at(0.0);
    let model0 = full_model(&ts0, ts0.deputy_ballistic_m2_kg)?;
    let burns = truth_burns(&s.burns[..last]);
    let reached = fly(&model0, &arc.problem.from, &burns, t_last)?;
    let client = fly(&model0, &arc.problem.to, &[], dur)?;
    let ts1 = at(t_last);
    let model1 = full_model(&ts1, ts1.deputy_ballistic_m2_kg)?;
    let r = reached;
    let from: State = r.to_array();
    let fam = Family {
        revs: s.last_leg_revolutions,
        branch: s.last_leg_branch,
    };
    // First aim offset as in the core's grid: where the client's own two-body and truth flights
    // over the last leg part (the leg ends on that orbit).
    let client_then = fly(&model0, &arc.problem.to, &[], t_last)?;
    let (r_kep, _) = reconfig_core::lambert::propagate(
        settings.mu_km3_s2,
        &client_then.pos_km,
        &client_then.vel_km_s,
        dur - t_last,
        60,
    )
    .ok_or_else(|| anyhow!("two-body flight of the client did not converge"))?;
    let mut off = Offset {
        dr_km: [
            r_kep[0] - client.pos_km[0],
            r_kep[1] - client.pos_km[1],
            r_kep[2] - client.pos_km[2],
        ],
        dv_km_s: [0.0; 3],
    };
    let mut meter = Meter::new(u64::MAX);
    // Then the core's J2 shooting from the reached truth state (the planning model's own
    // correction): the truth iterations start a J2-to-truth difference away, not a
    // two-body-to-truth one, and with the J2 model's Jacobian of the miss in the aim offset
    // (the inverse of the shooting's quasi-Newton matrix), which the truth model's is close
    // to: on 30-revolution legs the identity start diverged (a 11 km miss went to 2500 km).
    let mut secant = Secant::default();
    // Continuation: first the J2 shooting from the plan's own departure state (the planning
    // model's flight of the burns before the last leg, where the core's search converged), then
    // from the truth state with that offset and quasi-Newton matrix. Started from the client's
    // two-body offset directly, the shooting from the truth state could fail on 30-revolution
    // legs (thousands of km of J2 drift) and the truth iterations then diverged.
    let planning_model = settings.flight(Model::Planning);
    let planned_departure = (|| {
        let mut state = arc.problem.from;
        let mut t = 0.0;
        for b in &s.burns[..last] {
            state = core_propagate(settings, &state, b.epoch_s - t)?;
            for k in 0..3 {
                state[3 + k] += b.dv_km_s[k];
            }
            t = b.epoch_s;
        }
        core_propagate(settings, &state, t_last - t)
    })();
    let target = client.pos_km;
    let j2_shot = |from: &State, start: &Offset, secant: &mut Secant, meter: &mut Meter| {
        shoot_continued(
            &planning_model,
            settings,
            from,
            &target,
            dur - t_last,
            fam,
            start,
            (8, 1e-3),
            secant,
            meter,
        )
        .filter(|shot| shot.miss_km <= 1.0)
    };
    if let Some(dep) = planned_departure {
        if let Some(shot) = j2_shot(&dep, &off, &mut secant, &mut meter) {
            off = shot.offset;
        }
    }
    // The truth iterations keep the J2 shooting's quasi-Newton matrix as their start: the
    // truth model's Jacobian of the miss in the aim offset is close to the J2 model's.
    if let Some(shot) = j2_shot(&from, &off, &mut secant, &mut meter) {
        off = shot.offset;
    } else {
        secant = Secant::default();
    }
    let mut best = (f64::INFINITY, f64::INFINITY);
    let mut best_end: Option<EciState> = None;
    let mut prev: Option<([f64; 3], [f64; 3])> = None;
    let norm3 = |v: &[f64; 3]| v.iter().map(|x| x * x).sum::<f64>().sqrt();
    for _ in 0..20 {
        // A Lambert leg that does not solve at a moved aim point ends the re-plan with the
        // best flight so far (none at all is an error, below).
        let Some((v_dep, _)) = corrected_lambert(
            settings,
            &from,
            &client.pos_km,
            dur - t_last,
            fam,
            &off,
            &mut meter,
        ) else {
            break;
        };
        let start = EciState {
            pos_km: r.pos_km,
            vel_km_s: v_dep,
        };
        // A trial leg that dips into the atmosphere ends the re-plan with the best so far.
        let Ok(flown) = propagate(&model1, &start, &[], dur - t_last, &Tolerance::TRUTH) else {
            break;
        };
        let end = flown.end;
        let miss: Vec<f64> = (0..3).map(|k| end.pos_km[k] - client.pos_km[k]).collect();
        let miss_m = miss.iter().map(|x| x * x).sum::<f64>().sqrt() * 1e3;
        let dv = |a: &[f64; 3], b: &[f64; 3]| {
            (0..3).map(|k| (a[k] - b[k]).powi(2)).sum::<f64>().sqrt() * 1e3
        };
        let free: f64 = s.burns[..last]
            .iter()
            .map(|b| b.rtn_mps.iter().map(|x| x * x).sum::<f64>().sqrt())
            .sum();
        let total = free + dv(&v_dep, &r.vel_km_s) + dv(&client.vel_km_s, &end.vel_km_s);
        if miss_m < best.0 {
            best = (miss_m, total);
            best_end = Some(end);
        }
        if miss_m < 1e-3 {
            break;
        }
        // Broyden's update of the inverse Jacobian (the core's `Secant`, as in its J2
        // shooting; the plain aim-point step contracts only ~0.7 per flight in the full model).
        let m3 = [miss[0], miss[1], miss[2]];
        if let Some((d_prev, m_prev)) = prev {
            let dd: [f64; 3] = std::array::from_fn(|k| off.dr_km[k] - d_prev[k]);
            let dm: [f64; 3] = std::array::from_fn(|k| m3[k] - m_prev[k]);
            secant.update(&dd, &dm);
        }
        prev = Some((off.dr_km, m3));
        // A quasi-Newton step longer than five plain ones is not trusted (the plain step).
        let step = Some(secant.apply(&m3))
            .filter(|st| st.iter().all(|v| v.is_finite()) && norm3(st) <= 5.0 * norm3(&m3))
            .unwrap_or(m3);
        for (o, d) in off.dr_km.iter_mut().zip(&step) {
            *o -= d;
        }
    }
    let end = best_end.ok_or_else(|| {
        anyhow!("the re-planned last leg has no Lambert solution or no truth flight")
    })?;
    Ok(Replanned {
        miss_m: best.0,
        dv_mps: best.1,
        chaser_end: EciState {
            pos_km: end.pos_km,
            vel_km_s: client.vel_km_s,
        },
        client_end: client,
    })
}

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

/// Fly the fixture's tour (its order and intervals) with the chained multi-round correction,
/// each round's arc warm-started from `planned`'s plan of the same arc where there is one
/// (`leo_tour::solve_arc_warm`; the full search otherwise).
///
/// # Errors
/// A truth-model propagation error, a core refusal of an arc, or a re-plan with no truth
/// flight.
pub fn multi_round(
    f: &LeoTourFixture,
    planned: &[PlannedArc],
    limits: &Limits,
) -> Result<Vec<Round>> {
    let ts = truth_settings_at(f.epoch_jd, 0.0);
    let model = full_model(&ts, ts.deputy_ballistic_m2_kg)?;
    let first = *f.order.first().ok_or_else(|| anyhow!("empty order"))?;
    let mut chaser = EciState::from_array(&f.clients[first]);
    let mut t0 = 0.0;
    let mut rounds = Vec::new();
    let mut workspace = Box::new(Workspace::new());
    for (pair, &interval) in f.order.windows(2).zip(f.intervals_s.iter()) {
        let (from, to) = (pair[0], pair[1]);
        // The client's truth state at the arc start, flown from the tour epoch.
        let client = if t0 > 0.0 {
            fly(&model, &f.clients[to], &[], t0)?
        } else {
            EciState::from_array(&f.clients[to])
        };
        let start_offset_m = if from == first && t0 == 0.0 {
            0.0
        } else {
            let own = fly(&model, &f.clients[from], &[], t0)?;
            (0..3)
                .map(|k| (chaser.pos_km[k] - own.pos_km[k]).powi(2))
                .sum::<f64>()
                .sqrt()
                * 1e3
        };
        let problem = ArcProblem {
            from: chaser.to_array(),
            to: client.to_array(),
            duration_s: interval,
            impulses: f.impulses,
        };
        let started = Instant::now();
        let warm = planned
            .iter()
            .find(|a| a.from == from && a.to == to && a.start_s.to_bits() == t0.to_bits());
        let label = format!("round {} -> {}", from + 1, to + 1);
        let solution = match warm {
            Some(a) => {
                let mut solution = ArcSolution::new();
                solve_arc_warm(
                    &problem,
                    &f.settings,
                    &a.solution,
                    &mut workspace,
                    &mut solution,
                )
                .map_err(|e| anyhow!("{label}: {e:?}"))?;
                solution
            }
            None => {
                let request = Request::LeoArc {
                    problem,
                    settings: f.settings,
                };
                let mut buffers = LeoBuffers::default();
                let answered = answer(&request, limits, &mut buffers);
                let OutcomeRef::LeoArc(solution) = answered.outcome else {
                    return Err(no_plan(&label, &answered));
                };
                *solution
            }
        };
        let arc = PlannedArc {
            from,
            to,
            tour_epoch_jd: f.epoch_jd,
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

/// Whether every round was planned with a usable status (`Solved`, or `BudgetExhausted { verified: true }`), re-planned, and arrives within `tol_m`.
pub fn all_within(rounds: &[Round], tol_m: f64) -> bool {
    rounds
        .iter()
        .all(|r| r.arc.solution.info.status.is_usable() && r.corrected && r.miss_after_m <= tol_m)
}

#[cfg(test)]
#[path = "leo_truth_tests.rs"]
mod tests;
