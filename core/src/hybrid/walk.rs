//! Neighbouring re-convergence on board: where the shooting does not converge from the ground's
//! design straight away (a navigation update of the departure, a changed time of flight, a
//! derated engine), walk from the problem the design solved to the request, each step's
//! shooting starting from the last converged one extrapolated along the secant through the
//! two last (the design counting as the first), the step doubled after a success and halved
//! after a failure, within a bounded number of shootings and the work budget.

use super::departure::Departure;
use super::integrate::{Counts, Stop};
use super::objective_shooting::{model_of, shoot, Shot};
use super::problem::{Objective, Problem};
use super::shooting::{self, Status};
use super::solution::{Settings, Walked};
use super::units;

/// The smallest step of the walk (as a fraction of the way): below it the walk gives up.
const MIN_STEP: f64 = 1.0 / 64.0;

/// A walk's shooting is cut short sooner than the request's own: a step that does not
/// converge quickly is retried at half the size, which is cheaper than a long damped search.
const WALK_MAX_ITERATIONS: u32 = 8;
/// Halvings of a Newton step in a walk's shooting at most.
const WALK_MAX_HALVINGS: u32 = 4;

/// The straight shooting's share of the budget, 1 / this, where a walk may follow.
const STRAIGHT_SHARE: u64 = 4;

/// Whether the request is the problem its start was designed for (nothing to walk).
fn is_its_design(problem: &Problem) -> bool {
    let same_duration = problem.objective == Objective::MinTime
        || problem.duration_days.to_bits() == problem.design_duration_days.to_bits();
    same_duration
        && problem.thrust_n.to_bits() == problem.design_thrust_n.to_bits()
        && problem.departure_offset.iter().all(|x| *x == 0.0)
}

/// The problem a fraction `s` of the way from the design to the request: the navigation
/// update scaled by `s`, the time of flight and the thrust blended.
fn between(problem: &Problem, s: f64) -> Problem {
    let blend = |design: f64, request: f64| design + s * (request - design);
    let mut p = *problem;
    for o in &mut p.departure_offset {
        *o *= s;
    }
    if p.objective != Objective::MinTime {
        p.duration_days = blend(problem.design_duration_days, problem.duration_days);
    }
    p.thrust_n = blend(problem.design_thrust_n, problem.thrust_n);
    p
}

/// `p` started from a converged shot (its costates, impulse, λ0 and, for minimum time, its
/// time of flight).
fn started_from(mut p: Problem, shot: &Shot) -> Problem {
    p.costates = shot.point.costates;
    p.kappa = shot.point.kappa;
    p.theta_rad = shot.point.theta_rad;
    if p.objective == Objective::MinTime {
        p.cost_multiplier = shot.cost_multiplier;
        p.duration_days = units::days(shot.duration_tu);
    }
    p
}

/// Add `more`'s work to `total`.
fn add(total: &mut Counts, more: &Counts) {
    total.accepted = total.accepted.saturating_add(more.accepted);
    total.rejected = total.rejected.saturating_add(more.rejected);
    total.evaluations = total.evaluations.saturating_add(more.evaluations);
    total.event_trials = total.event_trials.saturating_add(more.event_trials);
}

/// Shoot the request from its start; where that fails (not for want of budget), walk from its
/// design. At most `1 + settings.continuation_steps` shootings, together at most `budget` step
/// trials (`base`'s other bounds per shooting). The returned shot's work and iterations are
/// the whole walk's; its point is the request's converged one, else the last shooting's best
/// iterate (of the fraction `Walked::reached`).
pub(super) fn shoot_or_walk(
    departure: &Departure,
    problem: &Problem,
    settings: &Settings,
    base: &shooting::Settings,
    budget: u64,
) -> (Shot, Walked) {
    let mut total = Counts::default();
    let mut iterations = 0_u32;
    // The straight shooting's share of the budget when a walk may follow (a diverging Newton
    // iteration must not spend what the walk needs); then the whole.
    let cap = if settings.continuation_steps == 0 || is_its_design(problem) {
        budget
    } else {
        budget / STRAIGHT_SHARE
    };
    let attempt = |p: &Problem,
                   base: &shooting::Settings,
                   cap: u64,
                   total: &mut Counts,
                   iterations: &mut u32| {
        let left = budget
            .saturating_sub(u64::from(total.step_trials()))
            .min(cap);
        let mut bounded = *base;
        bounded.integration.max_steps = u32::try_from(left).unwrap_or(u32::MAX);
        let shot = shoot(&model_of(p), departure, p, &bounded);
        add(total, &shot.counts);
        *iterations = iterations.saturating_add(shot.iterations);
        shot
    };
    let finish = |mut shot: Shot, total: Counts, iterations: u32, walked: Walked| {
        shot.counts = total;
        shot.iterations = iterations;
        (shot, walked)
    };
    let first = attempt(problem, base, cap, &mut total, &mut iterations);
    // The straight shooting stopped by its share, not by the budget: the walk has the rest.
    let out_of_budget = matches!(first.status, Status::Integration(Stop::StepLimit { .. }))
        && (settings.continuation_steps == 0 || is_its_design(problem));
    if first.status == Status::Converged
        || out_of_budget
        || settings.continuation_steps == 0
        || is_its_design(problem)
    {
        let reached = if first.status == Status::Converged {
            1.0
        } else {
            0.0
        };
        return finish(
            first,
            total,
            iterations,
            Walked {
                shootings: 0,
                reached,
            },
        );
    }
    let mut walked = Walked {
        shootings: 0,
        reached: 0.0,
    };
    let walk_base = shooting::Settings {
        max_iterations: base.max_iterations.min(WALK_MAX_ITERATIONS),
        max_halvings: base.max_halvings.min(WALK_MAX_HALVINGS),
        ..*base
    };
    let mut from = *problem;
    // The converged point before `from` and its fraction (none until the walk's first).
    let mut before: Option<(f64, Problem)> = None;
    let mut step = 0.5;
    let mut last = first;
    for _ in 0..settings.continuation_steps {
        let s = (walked.reached + step).min(1.0);
        let start = match &before {
            Some((at, b)) => secant_start(&from, b, walked.reached - at, s - walked.reached),
            None => from,
        };
        let shot = attempt(
            &started_from_problem(&start, problem, s),
            &walk_base,
            budget,
            &mut total,
            &mut iterations,
        );
        walked.shootings = walked.shootings.saturating_add(1);
        match shot.status {
            Status::Converged => {
                before = Some((walked.reached, from));
                walked.reached = s;
                from = started_from(*problem, &shot);
                if s >= 1.0 {
                    return finish(shot, total, iterations, walked);
                }
                step = (step * 2.0).min(1.0 - s);
            }
            Status::Integration(Stop::StepLimit { .. }) => {
                return finish(shot, total, iterations, walked);
            }
            _ => {
                step *= 0.5;
                if step < MIN_STEP {
                    return finish(shot, total, iterations, walked);
                }
            }
        }
        last = shot;
    }
    // The walk's shootings ran out before the request: its last shot (converged or not) is
    // not the request's answer.
    last.status = Status::IterationLimit;
    finish(last, total, iterations, walked)
}

/// `from`'s start point extrapolated along the secant from `before`'s, the predictor of every
/// continuation (this walk on board, `reconfig pareto` on the ground): `from` lies `behind`
/// after `before` in the walked parameter, the next step `ahead` after `from` (either sign).
/// The costates, a free κ or θ, and minimum time's λ0 and time of flight move; the rest is
/// `from`'s. Without a distance between the two (`behind` 0 or not finite), `from` itself.
pub fn secant_start(from: &Problem, before: &Problem, behind: f64, ahead: f64) -> Problem {
    if behind.abs() <= 0.0 || !behind.is_finite() {
        return *from;
    }
    let ratio = ahead / behind;
    let on = |x: f64, y: f64| x + ratio * (x - y);
    let mut p = *from;
    for (c, b) in p.costates.iter_mut().zip(before.costates) {
        *c = on(*c, b);
    }
    if p.free_kappa {
        p.kappa = on(from.kappa, before.kappa);
    }
    if p.free_theta {
        p.theta_rad = on(from.theta_rad, before.theta_rad);
    }
    if p.objective == Objective::MinTime {
        p.cost_multiplier = on(from.cost_multiplier, before.cost_multiplier);
        p.duration_days = on(from.duration_days, before.duration_days);
    }
    p
}

/// The problem at fraction `s`, started from `from`'s start point (the design's, or the last
/// converged shot's).
fn started_from_problem(from: &Problem, problem: &Problem, s: f64) -> Problem {
    let mut p = between(problem, s);
    p.costates = from.costates;
    p.kappa = from.kappa;
    p.theta_rad = from.theta_rad;
    if p.objective == Objective::MinTime {
        p.cost_multiplier = from.cost_multiplier;
        p.duration_days = from.duration_days;
    }
    p
}
