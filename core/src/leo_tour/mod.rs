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
//!    arrival miss decides the status ([`SolveStatus::Solved`] only when within
//!    `arrival_tol_km`).
//!
//! The contract's shape ([`crate::contract::Planner`], [`LeoArc`]): [`solve_arc`] plans an
//! [`ArcProblem`] with [`Settings`] in a caller-owned [`Workspace`] into an [`ArcSolution`]
//! whose `info` holds the [`SolveStatus`]; the sequencing ([`tour_order::solve_sequence`],
//! [`tour_order::LeoSequence`]) likewise.
//!
//! See `docs/leo-tour.md`.

mod altitude;
mod arc;
mod arc_descent;
mod arc_grid;
mod arc_hops;
mod arc_node_seed;
mod arc_warm;
pub mod bound;
pub mod elements;
pub mod flight;
pub mod j2;
pub mod kernels;
pub mod mean_j2;
pub mod schedule;
pub mod sequence;
pub mod shoot;
pub mod tour_order;
pub mod track;
mod types;
pub mod validate;
pub mod work_units;
mod workspace;

#[cfg(test)]
mod tests;

pub use arc::rtn;
pub use types::*;
pub use workspace::Workspace;

use crate::work::Meter;
use arc::{Ctx, Flown, Point};
use flight::Model;
use j2::{propagate_steps, step_count};
use track::Track;

/// `state` flown for `dt_s` in the planning model (the host's tour bookkeeping uses this one
/// implementation); `None` beyond `settings.max_steps` steps or on a non-finite state.
pub fn propagate(settings: &Settings, state: &j2::State, dt_s: f64) -> Option<j2::State> {
    let n = step_count(dt_s, settings.step_s, settings.max_steps)?;
    propagate_steps(&settings.gravity(), state, dt_s, n)
}

/// Plan one arc into `out`, with `workspace`'s buffers.
///
/// Worst case: see `docs/leo-tour.md` (every loop bounded by a setting, the work budget
/// stopping it first when smaller).
///
/// # Errors
/// [`PlanError`] when the request is refused before planning (a field or a setting out of
/// range, a client state that cannot be propagated over the arc); `out` is then untouched.
/// Every plan that ends without a usable transfer is a [`SolveStatus`] in `out`.
pub fn solve_arc(
    problem: &ArcProblem,
    settings: &Settings,
    workspace: &mut Workspace,
    out: &mut ArcSolution,
) -> Result<(), PlanError> {
    solve_arc_from(problem, settings, None, workspace, out)
}

/// Plan one arc warm-started from `plan`, an earlier plan of the same arc (same epochs from
/// the arc start): it is the one candidate of the local search (then the hops) instead of the
/// grid; where that gives no plan (or `plan` has none), the full search runs.
///
/// # Errors
/// As [`solve_arc`].
pub fn solve_arc_warm(
    problem: &ArcProblem,
    settings: &Settings,
    plan: &ArcSolution,
    workspace: &mut Workspace,
    out: &mut ArcSolution,
) -> Result<(), PlanError> {
    solve_arc_from(problem, settings, Some(plan), workspace, out)
}

/// The per-arc rendezvous in the planners' contract ([`crate::contract::Planner`]):
/// [`solve_arc`].
#[derive(Clone, Copy, Debug)]
pub struct LeoArc;

crate::impl_planner!(
    LeoArc: ArcProblem, Settings, Workspace, ArcSolution, PlanError, SolveStatus,
    LeoArc, solve_arc, reset |out| out.reset()
);

/// Why the search's context could not be built.
enum NoContext {
    /// The request is refused.
    Refused(PlanError),
    /// The work budget was spent building it (units used).
    Exhausted(u64),
}

impl From<PlanError> for NoContext {
    fn from(e: PlanError) -> Self {
        Self::Refused(e)
    }
}

/// The search's context for `problem`: the request checked, the clients' checkpoints (built in
/// `tracks` when given: the planning model is flown) and mean orbits, the flights in
/// `settings.search_model`.
fn context<'a>(
    problem: &ArcProblem,
    settings: &'a Settings,
    tracks: Option<(&'a mut Track, &'a mut Track)>,
) -> Result<Ctx<'a>, NoContext> {
    validate::check(problem, settings)?;
    let g = settings.gravity();
    let mut meter = Meter::new(settings.work_budget);
    let tf = problem.duration_s;
    // The solve's fixed part and the clients' mean orbits (one conversion each).
    meter.charge(work_units::SOLVE + 2 * work_units::MEAN_ORBIT);
    let mean_a = mean_j2::MeanOrbit::of_state(&g, &problem.from);
    let mean_b = mean_j2::MeanOrbit::of_state(&g, &problem.to);
    let (a, b, b_end) = if let Some((a, b)) = tracks {
        let planning = settings.flight(Model::Planning);
        let failed = |m: &Meter, field: Field| {
            if m.exhausted() {
                NoContext::Exhausted(m.used())
            } else {
                NoContext::Refused(PlanError::Propagation { field })
            }
        };
        a.fill(&planning, &problem.from, tf, &mut meter)
            .ok_or_else(|| failed(&meter, Field::From))?;
        b.fill(&planning, &problem.to, tf, &mut meter)
            .ok_or_else(|| failed(&meter, Field::To))?;
        let n = step_count(tf, settings.step_s, settings.max_steps.saturating_mul(64))
            .ok_or(PlanError::Propagation { field: Field::To })?;
        meter.charge(work_units::flight(n));
        let b_end = propagate_steps(&g, &problem.to, tf, n)
            .ok_or(PlanError::Propagation { field: Field::To })?;
        (Some(&*a), Some(&*b), b_end)
    } else {
        // An estimate aims at the client's arrival in the search model.
        meter.charge(work_units::MEAN_STATE);
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
        coasts: [None; MAX_IMPULSES],
        polish_follows: false,
    })
}

/// The units an estimate of an arc of `duration_s` searched in `model` charges before its
/// meter can refuse a step (its fixed part; in the planning model also the clients'
/// checkpoints and the arrival, flown first): an estimate given at least this many units
/// spends at most its budget. The sequencing starts no estimate with less left
/// ([`tour_order`]).
pub(crate) fn estimate_floor_units(duration_s: f64, settings: &Settings, model: Model) -> u64 {
    let fixed = work_units::SOLVE + 2 * work_units::MEAN_ORBIT;
    match model {
        Model::MeanElements => fixed + work_units::MEAN_STATE,
        Model::Planning => {
            // The arrival's flight, and each track's checkpoints (each segment at most one
            // step more than its share of the arrival's).
            let max_steps = settings.max_steps.saturating_mul(64);
            let n = step_count(duration_s, settings.step_s, max_steps).unwrap_or(max_steps);
            let segments = types::CHECKPOINTS as u64;
            let track = work_units::flight(n)
                .saturating_add(segments.saturating_mul(work_units::flight(1)));
            fixed
                .saturating_add(work_units::flight(n))
                .saturating_add(track.saturating_mul(2))
        }
    }
}

/// The arc planned in full ([`solve_arc`]: the search, the planning model's polish and the
/// final check), as an [`ArcEstimate`]: its Δv when the plan is usable. The sequencing's arc
/// cost with `full_plans` (and an estimate's with `search_model = Planning`).
///
/// # Errors
/// As [`solve_arc`].
pub fn planned_arc_mps(
    problem: &ArcProblem,
    settings: &Settings,
    workspace: &mut Workspace,
) -> Result<ArcEstimate, PlanError> {
    let mut planned = ArcSolution::new();
    solve_arc(problem, settings, workspace, &mut planned)?;
    let status = planned.info.status;
    Ok(ArcEstimate {
        dv_mps: status.is_usable().then_some(planned.total_dv_mps),
        status,
        work_units: planned.info.work_units,
    })
}

/// The arc's Δv estimate, m/s: the cost of the best plan the search finds in
/// `settings.search_model`, shot in that model, without the planning model's polish and
/// check (with `search_model = Planning`, the planned arc's Δv when it is usable), aimed at
/// the client's arrival in the search model (no planning-model flight at all). The
/// sequencing's arc cost: the order is chosen on these, and the chosen order planned with
/// [`solve_arc`]. `workspace` holds the search's candidates (and with `search_model =
/// Planning` the clients' checkpoints).
///
/// # Errors
/// As [`solve_arc`]; a search that shot no plan is an estimate without `dv_mps`.
pub fn estimate_arc_mps(
    problem: &ArcProblem,
    settings: &Settings,
    workspace: &mut Workspace,
) -> Result<ArcEstimate, PlanError> {
    if settings.search_model == Model::Planning {
        return planned_arc_mps(problem, settings, workspace);
    }
    let Workspace {
        candidates, hops, ..
    } = workspace;
    let mut ctx = match context(problem, settings, None) {
        Ok(ctx) => ctx,
        Err(NoContext::Refused(e)) => return Err(e),
        Err(NoContext::Exhausted(used)) => {
            return Ok(ArcEstimate {
                dv_mps: None,
                status: SolveStatus::BudgetExhausted { verified: false },
                work_units: used,
            })
        }
    };
    let kept = search(&mut ctx, None, (candidates, hops));
    let exhausted = ctx.meter.exhausted();
    let work_units = ctx.meter.used();
    Ok(match kept.first().copied().flatten() {
        Some(p) if p.shot && p.cost.is_finite() => ArcEstimate {
            dv_mps: Some(p.cost * 1e3),
            status: if exhausted {
                SolveStatus::BudgetExhausted { verified: true }
            } else {
                SolveStatus::Solved
            },
            work_units,
        },
        _ => ArcEstimate {
            dv_mps: None,
            status: if exhausted {
                SolveStatus::BudgetExhausted { verified: false }
            } else {
                SolveStatus::NoTransfer
            },
            work_units,
        },
    })
}

fn solve_arc_from(
    problem: &ArcProblem,
    settings: &Settings,
    warm: Option<&ArcSolution>,
    workspace: &mut Workspace,
    out: &mut ArcSolution,
) -> Result<(), PlanError> {
    let Workspace {
        a,
        b,
        candidates,
        hops,
    } = workspace;
    let mut ctx = match context(problem, settings, Some((a, b))) {
        Ok(ctx) => Ctx {
            polish_follows: settings.search_model == Model::MeanElements,
            ..ctx
        },
        Err(NoContext::Refused(e)) => return Err(e),
        Err(NoContext::Exhausted(used)) => {
            out.reset();
            out.info = SolveInfo {
                status: SolveStatus::BudgetExhausted { verified: false },
                evaluations: 0,
                work_units: used,
            };
            return Ok(());
        }
    };
    let mut best: Option<Flown> = None;
    // The search stops at its share of the budget, the polish at its own, so that a budget
    // that cuts the search still pays for the plan's polish and final check.
    let check = check_units(settings, problem.duration_s);
    let reserve = |share_percent: u64, at_least: u64| {
        (settings.work_budget / 100)
            .saturating_mul(100u64.saturating_sub(share_percent))
            .max(at_least)
    };
    let polish_reserve = reserve(POLISH_SHARE_PERCENT, check);
    let descent_reserve = reserve(DESCENT_SHARE_PERCENT, check.saturating_mul(2));
    ctx.meter.reserve(match settings.search_model {
        Model::Planning => polish_reserve,
        Model::MeanElements => reserve(SEARCH_SHARE_PERCENT, check.saturating_mul(2)),
    });
    let kept = search(&mut ctx, warm, (candidates, hops));
    match settings.search_model {
        Model::Planning => {
            for q in kept.iter().flatten() {
                ctx.meter.next_stage(0);
                consider(&mut ctx, *q, &mut best);
            }
        }
        Model::MeanElements => {
            // The search model ranked the plans; each kept one is shot again and polished in
            // the planning model, which decides.
            ctx.flight.model = Model::Planning;
            for q in kept.iter().flatten() {
                // The descent finishes the search in its own model (arc_descent.rs: the
                // compass search's frozen offset leaves it short of the bottom).
                ctx.meter.next_stage(descent_reserve);
                let descended = ctx.in_model(Model::MeanElements, |c| {
                    c.descend(*q, arc_descent::DESCENT_MAX_ITERATIONS)
                });
                ctx.meter.next_stage(polish_reserve);
                let mut polished = ctx.polish(descended);
                // The descent may end at the edge of the last leg's Lambert family, which the
                // planning model moves a little: where its point has no transfer there, the
                // search's own point is polished instead.
                if !polished.shot && descended.cost < q.cost {
                    polished = ctx.polish(*q);
                }
                ctx.meter.next_stage(0);
                consider(&mut ctx, polished, &mut best);
            }
            // A warm plan is polished as it is too: the search model's optimum can lie a few
            // m/s from the planning model's, and the warm plan is near the latter.
            if let Some(plan) = warm {
                ctx.warm_candidates(plan, candidates);
                for p in candidates.iter().flatten() {
                    ctx.meter.next_stage(polish_reserve);
                    let polished = ctx.polish(*p);
                    ctx.meter.next_stage(0);
                    consider(&mut ctx, polished, &mut best);
                }
            }
            // Where that gives no arriving plan, the search runs again in the planning model.
            let failed = best.is_none_or(|b| !b.admissible());
            if failed && !ctx.meter.exhausted() {
                for q in search(&mut ctx, warm, (candidates, hops)).iter().flatten() {
                    consider(&mut ctx, *q, &mut best);
                }
            }
        }
    }
    let exhausted = ctx.meter.exhausted();
    out.reset();
    let status = match best {
        Some(plan) => {
            out.burns = plan.burns;
            out.impulses = plan.impulses;
            out.total_dv_mps = plan.total_dv_mps;
            out.miss_m = Some(plan.miss_m);
            out.last_leg_revolutions = plan.fam.revs;
            out.last_leg_branch = plan.fam.branch;
            out.lowest_altitude_km = plan
                .lowest_altitude_km
                .is_finite()
                .then_some(plan.lowest_altitude_km);
            if exhausted {
                SolveStatus::BudgetExhausted {
                    verified: plan.admissible(),
                }
            } else if plan.admissible() {
                SolveStatus::Solved
            } else if !plan.arrives {
                SolveStatus::ArrivalMissed
            } else {
                SolveStatus::BelowMinAltitude
            }
        }
        None if exhausted => SolveStatus::BudgetExhausted { verified: false },
        None => SolveStatus::NoTransfer,
    };
    out.info = SolveInfo {
        status,
        evaluations: ctx.evals,
        work_units: ctx.meter.used(),
    };
    Ok(())
}

/// The search's share of the work budget, percent: it stops there, leaving the rest for the
/// descent of its best point, then the planning model's polish and final check (on the tuning
/// seeds the polish and check took 10-30 % of an arc's units). Chosen on the tuning seeds
/// 0-39 of `host/examples/leo_arc_campaign.rs` among 70-85 (80: the lowest mean Δv, no arc
/// dearer than with no descent; docs/leo-tour.md, "The descent").
const SEARCH_SHARE_PERCENT: u64 = 80;

/// Where the descent stops, percent of the budget (the polish then runs to its own share).
const DESCENT_SHARE_PERCENT: u64 = 85;

/// Where the polish stops, percent of the budget: the final check (an exact shooting of the
/// last leg in the planning model) may spend the rest, and at least [`check_units`]; the
/// search leaves at least twice that (the polish starts with a shooting too).
const POLISH_SHARE_PERCENT: u64 = 95;

/// Aim-point iterations kept for the final check: from the polish's quasi-Newton matrix the
/// shooting converges in 2-4 (unit test
/// `the_quasi_newton_shooting_converges_in_a_few_iterations`).
const CHECK_ITERATIONS: u64 = 8;

/// The units of [`CHECK_ITERATIONS`] aim-point iterations of a last leg as long as the arc
/// (each a planning-model flight of the leg, a Lambert solve at its step limit, the
/// iteration's own work): what the final check is sure to have.
fn check_units(settings: &Settings, duration_s: f64) -> u64 {
    // A leg that needs more than `max_steps` steps is refused: the check flies at most that.
    let steps =
        step_count(duration_s, settings.step_s, settings.max_steps).unwrap_or(settings.max_steps);
    let lambert = work_units::LAMBERT_SOLVE.saturating_add(
        u64::from(settings.lambert_max_iter).saturating_mul(crate::lambert::step_units(0)),
    );
    work_units::flight(steps)
        .saturating_add(lambert)
        .saturating_add(work_units::SHOOT_ITERATION)
        .saturating_mul(CHECK_ITERATIONS)
}

/// Finish `q` in the planning model and keep it in `best` if it beats it (arriving first,
/// then the cheaper).
fn consider(ctx: &mut Ctx, q: Point, best: &mut Option<Flown>) {
    if let Some(plan) = ctx.finish(&q) {
        let better = best.as_ref().is_none_or(|b| {
            let rank = |p: &Flown| u8::from(!p.admissible());
            (rank(&plan), plan.total_dv_mps) < (rank(b), b.total_dv_mps)
        });
        if better {
            *best = Some(plan);
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

/// The candidate lists of a search, in the caller's workspace: the grid's (or the warm
/// start's) and the hops'.
type Lists<'w> = (
    &'w mut [Option<Point>; MAX_CANDIDATES],
    &'w mut [Option<Point>; MAX_HOPS],
);

/// The search in the model of `ctx`'s flights: the candidates (the grid, or the warm plan
/// with the grid behind it when it gives no shot plan) refined, then the hops; the `KEPT`
/// best refined points.
fn search(
    ctx: &mut Ctx,
    warm: Option<&ArcSolution>,
    (candidates, hops): Lists<'_>,
) -> [Option<Point>; KEPT] {
    let mut kept = [None; KEPT];
    match warm {
        Some(plan) => ctx.warm_candidates(plan, candidates),
        None => ctx.grid(candidates),
    }
    for p in candidates.iter().flatten() {
        let q = ctx.refine(*p);
        keep(&mut kept, q);
    }
    // A warm start that gives no shot plan falls back to the grid.
    let warm_failed = kept.first().copied().flatten().is_none_or(|b| !b.shot);
    if warm.is_some() && warm_failed && !ctx.meter.exhausted() {
        ctx.grid(candidates);
        for p in candidates.iter().flatten() {
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
        ctx.hops(&q0, hops);
        for hop in hops.iter().flatten() {
            let q = ctx.refine(*hop);
            any |= keep(&mut kept, q);
        }
        if !any || ctx.meter.exhausted() {
            break;
        }
    }
    kept
}
