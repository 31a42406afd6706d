//! Multi-target rendezvous tour in LEO under J2 (issue 13, after Zhang et al.'s servicing
//! tour): the on-board per-arc rendezvous and the sequencing ([`sequence`], branch-and-bound
//! over the order with the lower bound of [`bound`]).
//!
//! One arc: the chaser starts on client A's state at the arc start and must arrive on client
//! B's position and velocity at a fixed epoch, with `M <= 4` impulses at free epochs inside the
//! arc, the last pinned to the arrival. The planning model is two-body + J2 integrated by
//! fixed-step RK4 ([`j2`]); it decides every status. The search flies in the search model, the
//! first-order J2 theory in closed form ([`mean_j2`], [`flight`]). The method, every step
//! bounded and charged to the work meter:
//! 1. the clients' trajectories as checkpoints ([`track`]) and as mean orbits;
//! 2. a coarse grid of the first impulse epoch with two-impulse transfers: the bounded
//!    multi-revolution Lambert solver ([`crate::lambert`]) over every revolution count and
//!    branch, aimed with the J2 offset of the client's own orbit;
//! 3. from the best grid candidates, a compass search over the free epochs and the free impulse
//!    vectors, the last leg's J2 correction frozen and re-shot (aim-point iteration, [`shoot`])
//!    after each sweep that moved, by a quasi-Newton aim-point iteration;
//! 4. hops: the best plan's free epochs moved by half revolutions, refined again;
//! 5. the best plan polished in the planning model (shot there, a short compass search);
//! 6. the polished plan flown again in the planning model with an exact J2 shooting: its
//!    arrival miss decides the status ([`Status::Solved`] only when within `arrival_tol_km`).
//!
//! See `docs/leo-tour.md`.

mod arc;
mod arc_grid;
mod arc_hops;
mod arc_warm;
pub mod bound;
pub mod elements;
pub mod flight;
pub mod j2;
pub mod mean_j2;
pub mod schedule;
pub mod sequence;
pub mod shoot;
pub mod tour_order;
pub mod track;
mod types;
pub mod validate;

#[cfg(test)]
mod tests;

pub use arc::rtn;
pub use types::*;

use crate::work::Meter;
use arc::{Ctx, Point};
use flight::Model;
use j2::{propagate_steps, step_count};
use track::Track;

/// `state` flown for `dt_s` in the planning model (the host's tour bookkeeping uses this one
/// implementation); `None` beyond `settings.max_steps` steps or on a non-finite state.
pub fn propagate(settings: &Settings, state: &j2::State, dt_s: f64) -> Option<j2::State> {
    let n = step_count(dt_s, settings.step_s, settings.max_steps)?;
    propagate_steps(&settings.gravity(), state, dt_s, n)
}

/// Plan one arc.
///
/// # Errors
/// [`PlanError`]: a field out of range, a client trajectory that cannot be propagated, no
/// transfer found, or the budget spent before any plan.
pub fn solve_arc(problem: &ArcProblem, settings: &Settings) -> Result<ArcSolution, PlanError> {
    solve_arc_from(problem, settings, None)
}

/// Plan one arc warm-started from `plan`, an earlier plan of the same arc (same epochs from
/// the arc start): it is the one candidate of the local search (then the hops) instead of the
/// grid; where that gives no plan, the full search runs.
///
/// # Errors
/// As [`solve_arc`].
pub fn solve_arc_warm(
    problem: &ArcProblem,
    settings: &Settings,
    plan: &ArcSolution,
) -> Result<ArcSolution, PlanError> {
    solve_arc_from(problem, settings, Some(plan))
}

/// The search's context for `problem`: the request checked, the clients' checkpoints and
/// mean orbits, the flights in `settings.search_model`.
fn context<'a>(
    problem: &ArcProblem,
    settings: &'a Settings,
    with_planning_model: bool,
) -> Result<Ctx<'a>, PlanError> {
    validate::check(problem, settings)?;
    let g = settings.gravity();
    let mut meter = Meter::new(settings.work_budget);
    let tf = problem.duration_s;
    let exhausted = |m: &Meter| PlanError::BudgetExhausted {
        used: m.used(),
        budget: settings.work_budget,
    };
    // The clients' mean orbits: one conversion each (charged as a flight).
    meter.charge(2 * mean_j2::FLIGHT_UNITS);
    let mean_a = mean_j2::MeanOrbit::of_state(&g, &problem.from);
    let mean_b = mean_j2::MeanOrbit::of_state(&g, &problem.to);
    let (a, b, b_end) = if with_planning_model {
        let planning = settings.flight(Model::Planning);
        let a =
            Track::new(&planning, &problem.from, tf, &mut meter).ok_or(if meter.exhausted() {
                exhausted(&meter)
            } else {
                PlanError::Propagation { field: Field::From }
            })?;
        let b = Track::new(&planning, &problem.to, tf, &mut meter).ok_or(if meter.exhausted() {
            exhausted(&meter)
        } else {
            PlanError::Propagation { field: Field::To }
        })?;
        let n = step_count(tf, settings.step_s, settings.max_steps.saturating_mul(64))
            .ok_or(PlanError::Propagation { field: Field::To })?;
        meter.charge(u64::from(n));
        let b_end = propagate_steps(&g, &problem.to, tf, n)
            .ok_or(PlanError::Propagation { field: Field::To })?;
        (Some(a), Some(b), b_end)
    } else {
        // An estimate aims at the client's arrival in the search model.
        meter.charge(mean_j2::STATE_UNITS);
        let b_end = mean_b
            .and_then(|m| m.state_at(&g, tf))
            .ok_or(PlanError::Propagation { field: Field::To })?;
        (None, None, b_end)
    };
    Ok(Ctx {
        settings,
        g,
        impulses: usize::from(problem.impulses),
        tf,
        a,
        b,
        b_end,
        flight: settings.flight(settings.search_model),
        mean_a,
        mean_b,
        meter,
        evals: 0,
        secant: shoot::Secant::default(),
        lambert_guess: None,
        start_cache: None,
    })
}

/// The arc's Δv estimate, m/s: the cost of the best plan the search finds in
/// `settings.search_model`, shot in that model, without the planning model's polish and
/// check (with `search_model = Planning`, the planned arc's Δv), aimed at the client's
/// arrival in the search model (no planning-model flight at all). The sequencing's arc cost:
/// the order is chosen on these, and the chosen order planned with [`solve_arc`].
///
/// # Errors
/// As [`solve_arc`]; [`PlanError::NoTransfer`] when no plan of the search was shot.
pub fn estimate_arc_mps(problem: &ArcProblem, settings: &Settings) -> Result<f64, PlanError> {
    if settings.search_model == Model::Planning {
        return solve_arc(problem, settings).and_then(|s| {
            if s.status == Status::ArrivalMissed {
                Err(PlanError::NoTransfer)
            } else {
                Ok(s.total_dv_mps)
            }
        });
    }
    let mut ctx = context(problem, settings, false)?;
    let kept = search(&mut ctx, None);
    match kept.first().copied().flatten() {
        Some(p) if p.shot && p.cost.is_finite() => Ok(p.cost * 1e3),
        _ if ctx.meter.exhausted() => Err(PlanError::BudgetExhausted {
            used: ctx.meter.used(),
            budget: settings.work_budget,
        }),
        _ => Err(PlanError::NoTransfer),
    }
}

fn solve_arc_from(
    problem: &ArcProblem,
    settings: &Settings,
    warm: Option<&ArcSolution>,
) -> Result<ArcSolution, PlanError> {
    let mut ctx = context(problem, settings, true)?;
    let exhausted = |m: &Meter| PlanError::BudgetExhausted {
        used: m.used(),
        budget: settings.work_budget,
    };
    let mut best: Option<(ArcSolution, Point)> = None;
    let kept = search(&mut ctx, warm);
    match settings.search_model {
        Model::Planning => {
            for q in kept.iter().flatten() {
                consider(&mut ctx, *q, &mut best);
            }
        }
        Model::MeanElements => {
            // The search model ranked the plans; each kept one is shot again and polished in
            // the planning model, which decides.
            ctx.flight.model = Model::Planning;
            for q in kept.iter().flatten() {
                let polished = ctx.polish(*q);
                consider(&mut ctx, polished, &mut best);
            }
            // A warm plan is polished as it is too: the search model's optimum can lie a few
            // m/s from the planning model's, and the warm plan is near the latter.
            if let Some(plan) = warm {
                for p in ctx.warm_candidates(plan).iter().flatten() {
                    let polished = ctx.polish(*p);
                    consider(&mut ctx, polished, &mut best);
                }
            }
            // Where that gives no arriving plan, the search runs again in the planning model.
            let failed = best.is_none_or(|(b, _)| b.status == Status::ArrivalMissed);
            if failed && !ctx.meter.exhausted() {
                for q in search(&mut ctx, warm).iter().flatten() {
                    consider(&mut ctx, *q, &mut best);
                }
            }
        }
    }
    let best = best.map(|(b, _)| b);
    match best {
        Some(mut sol) => {
            sol.evaluations = ctx.evals;
            sol.work_units = ctx.meter.used();
            if sol.status == Status::Solved && ctx.meter.exhausted() {
                sol.status = Status::BudgetExhaustedSolved;
            }
            Ok(sol)
        }
        None if ctx.meter.exhausted() => Err(exhausted(&ctx.meter)),
        None => Err(PlanError::NoTransfer),
    }
}

/// Finish `q` in the planning model and keep it in `best` if it beats it (arriving first,
/// then the cheaper).
fn consider(ctx: &mut Ctx, q: Point, best: &mut Option<(ArcSolution, Point)>) {
    if let Some(sol) = ctx.finish(&q) {
        let better = best.as_ref().is_none_or(|(b, _)| {
            let rank = |s: &ArcSolution| u8::from(s.status == Status::ArrivalMissed);
            (rank(&sol), sol.total_dv_mps) < (rank(b), b.total_dv_mps)
        });
        if better {
            *best = Some((sol, q));
        }
    }
}

/// Refined points kept for the planning model's polish and final check. One: polishing the
/// second best too changed one arc of the ten of Examples I and II (Example II's 3 -> 4,
/// 1825.076 instead of 1826.483 m/s) for a third more time.
const KEPT: usize = 1;

/// Keep `q` among the `KEPT` best (shot first, then the cheaper); whether it is the new best.
fn keep(kept: &mut [Option<Point>; KEPT], q: Point) -> bool {
    let Some(pos) = kept
        .iter()
        .position(|k| k.is_none_or(|k| q.better_than(&k)))
    else {
        return false;
    };
    // Shift the worse ones down by one (the last falls off).
    let mut carry = Some(q);
    for slot in kept.iter_mut().skip(pos) {
        core::mem::swap(slot, &mut carry);
    }
    pos == 0
}

/// The search in the model of `ctx`'s flights: the candidates (the grid, or the warm plan
/// with the grid behind it when it gives no shot plan) refined, then the hops; the `KEPT`
/// best refined points.
fn search(ctx: &mut Ctx, warm: Option<&ArcSolution>) -> [Option<Point>; KEPT] {
    let mut kept = [None; KEPT];
    let candidates = match warm {
        Some(plan) => ctx.warm_candidates(plan),
        None => ctx.grid(),
    };
    for p in candidates.iter().flatten() {
        let q = ctx.refine(*p);
        keep(&mut kept, q);
    }
    // A warm start that gives no shot plan falls back to the grid.
    let warm_failed = kept.first().copied().flatten().is_none_or(|b| !b.shot);
    if warm.is_some() && warm_failed && !ctx.meter.exhausted() {
        for p in ctx.grid().iter().flatten() {
            let q = ctx.refine(*p);
            keep(&mut kept, q);
        }
    }
    // Hops: the best plan with its intermediate impulses moved by half revolutions (to the
    // other node of the plane change), refined again.
    for _round in 0..ctx.settings.hop_rounds {
        let Some(q0) = kept.first().copied().flatten() else {
            break;
        };
        let mut any = false;
        for hop in ctx.hops(&q0).iter().flatten() {
            let q = ctx.refine(*hop);
            any |= keep(&mut kept, q);
        }
        if !any || ctx.meter.exhausted() {
            break;
        }
    }
    kept
}
