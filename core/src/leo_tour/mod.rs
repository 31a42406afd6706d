//! Multi-target rendezvous tour in LEO under J2 (issue 13, after Zhang et al.'s servicing
//! tour): the on-board per-arc rendezvous and the sequencing ([`sequence`], branch-and-bound
//! over the order with the lower bound of [`bound`]).
//!
//! One arc: the chaser starts on client A's state at the arc start and must arrive on client
//! B's position and velocity at a fixed epoch, with `M <= 4` impulses at free epochs inside the
//! arc, the last pinned to the arrival. The planning model is two-body + J2 integrated by
//! fixed-step RK4 ([`j2`]). The method, every step bounded and charged to the work meter:
//! 1. the clients' trajectories as checkpoints ([`track`]);
//! 2. a coarse grid of the first impulse epoch with two-impulse transfers: the bounded
//!    multi-revolution Lambert solver ([`crate::lambert`]) over every revolution count and
//!    branch, aimed with the J2 offset of the client's own orbit;
//! 3. from the best grid candidates, a compass search over the free epochs and the free impulse
//!    vectors, the last leg's J2 correction frozen and re-shot (aim-point iteration, [`shoot`])
//!    after each sweep that moved, by a quasi-Newton aim-point iteration;
//! 4. hops: the best plan's free epochs moved by half revolutions, refined again;
//! 5. the best plan flown again in the planning model with an exact J2 shooting: its arrival
//!    miss decides the status ([`Status::Solved`] only when within `arrival_tol_km`).
//!
//! See `docs/leo-tour.md`.

mod arc;
mod arc_hops;
mod arc_warm;
pub mod bound;
pub mod elements;
pub mod j2;
pub mod sequence;
pub mod shoot;
pub mod track;
mod types;
pub mod validate;

#[cfg(test)]
mod tests;

pub use arc::rtn;
pub use types::*;

use crate::work::Meter;
use arc::Ctx;
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

fn solve_arc_from(
    problem: &ArcProblem,
    settings: &Settings,
    warm: Option<&ArcSolution>,
) -> Result<ArcSolution, PlanError> {
    validate::check(problem, settings)?;
    let g = settings.gravity();
    let mut meter = Meter::new(settings.work_budget);
    let tf = problem.duration_s;
    let exhausted = |m: &Meter| PlanError::BudgetExhausted {
        used: m.used(),
        budget: settings.work_budget,
    };
    let a =
        Track::new(&g, settings, &problem.from, tf, &mut meter).ok_or(if meter.exhausted() {
            exhausted(&meter)
        } else {
            PlanError::Propagation { field: Field::From }
        })?;
    let b = Track::new(&g, settings, &problem.to, tf, &mut meter).ok_or(if meter.exhausted() {
        exhausted(&meter)
    } else {
        PlanError::Propagation { field: Field::To }
    })?;
    let n = step_count(tf, settings.step_s, settings.max_steps.saturating_mul(64))
        .ok_or(PlanError::Propagation { field: Field::To })?;
    meter.charge(u64::from(n));
    let b_end = propagate_steps(&g, &problem.to, tf, n)
        .ok_or(PlanError::Propagation { field: Field::To })?;
    let mut ctx = Ctx {
        settings,
        g,
        impulses: usize::from(problem.impulses),
        tf,
        a,
        b,
        b_end,
        meter,
        evals: 0,
        secant: shoot::Secant::default(),
    };
    let mut candidates = match warm {
        Some(plan) => ctx.warm_candidates(plan),
        None => ctx.grid(),
    };
    let mut best: Option<(ArcSolution, arc::Point)> = None;
    let consider = |ctx: &mut Ctx, q: arc::Point, best: &mut Option<(ArcSolution, arc::Point)>| {
        if let Some(sol) = ctx.finish(&q) {
            let better = best.as_ref().is_none_or(|(b, _)| {
                let rank = |s: &ArcSolution| u8::from(s.status == Status::ArrivalMissed);
                (rank(&sol), sol.total_dv_mps) < (rank(b), b.total_dv_mps)
            });
            if better {
                *best = Some((sol, q));
            }
        }
    };
    for p in candidates.iter().flatten() {
        let q = ctx.refine(*p);
        consider(&mut ctx, q, &mut best);
    }
    // A warm start that gives no arriving plan falls back to the full search.
    let warm_failed = best.is_none_or(|(b, _)| b.status == Status::ArrivalMissed);
    if warm.is_some() && warm_failed && !ctx.meter.exhausted() {
        candidates = ctx.grid();
        for p in candidates.iter().flatten() {
            let q = ctx.refine(*p);
            consider(&mut ctx, q, &mut best);
        }
    }
    // Hops: the best plan with its intermediate impulses moved by half revolutions (to the
    // other node of the plane change), refined again.
    for _round in 0..settings.hop_rounds {
        let Some((_, q0)) = best else { break };
        let mut any = false;
        for hop in ctx.hops(&q0).iter().flatten() {
            let q = ctx.refine(*hop);
            let before = best.map(|(b, _)| b.total_dv_mps);
            consider(&mut ctx, q, &mut best);
            any |= best.map(|(b, _)| b.total_dv_mps) != before;
        }
        if !any {
            break;
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
