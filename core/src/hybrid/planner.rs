//! The hybrid transfer as a planner (the one contract, `contract::Planner`): from costates
//! designed on the ground, converge the shooting of the request's objective (a navigation
//! update of the departure, a changed time of flight or a derated engine move it from the
//! design), fly the result once more to check it, and say what was shown.

use super::dynamics::{Augmented, Model, Throttle};
use super::flow::propagate;
use super::free::Point;
use super::integrate::{Counts, Stop, Tolerance};
use super::objective_shooting::{departure_of, departure_state, law, model_of, Shot};
use super::problem::{PlanError, Problem};
use super::shooting::{self, Status};
use super::solution::{FlownPlan, Settings, Solution, SolveStatus, Stopped};
use super::trace::{fly, Flight, Sample, Span};
use super::walk::shoot_or_walk;

/// The hybrid planner (the contract's unit).
#[derive(Clone, Copy, Debug)]
pub struct Hybrid;

/// The hybrid planner's scratch: none beyond the stack. The integrator's stages sit in the
/// solve's frame (13 × 210 numbers with the state-transition matrix, about 22 KB; to be
/// measured on the M7 image, which is not built yet).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Workspace;

impl Workspace {
    /// The (empty) workspace.
    pub const fn new() -> Self {
        Self
    }
}

crate::impl_planner!(
    Hybrid: Problem, Settings, Workspace, Solution, PlanError, SolveStatus,
    Hybrid, solve, reset |out| *out = Solution::new()
);

/// The work budget's shares: the halo check's and the shooting's (the check flight has the
/// rest, at least three sixteenths).
const fn shares(budget: u64) -> (u64, u64) {
    (budget / 16, (budget / 4).saturating_mul(3))
}

/// Plan `problem` into `out`.
///
/// # Errors
/// [`PlanError`] when a field or setting is outside its range or the arrival point is not on a
/// periodic orbit; `out` is then untouched.
pub fn solve(
    problem: &Problem,
    settings: &Settings,
    _workspace: &mut Workspace,
    out: &mut Solution,
) -> Result<(), PlanError> {
    problem.validate()?;
    settings.check_ranges().map_err(PlanError::InvalidSetting)?;
    let model = model_of(problem);
    let (halo_share, shooting_share) = shares(settings.work_budget);
    let tolerance = |max_steps: u64| settings.tolerance(max_steps);
    let mut halo_counts = Counts::default();
    check_halo(
        &model,
        problem,
        settings,
        &tolerance(halo_share),
        &mut halo_counts,
    )?;

    *out = Solution::new();
    let departure = departure_of(problem);
    let shooting_settings = shooting::Settings {
        max_iterations: u32::from(settings.max_iterations),
        max_halvings: u32::from(settings.max_halvings),
        tolerance: settings.tolerance,
        integration: tolerance(shooting_share),
    };
    let (shot, walked) = shoot_or_walk(
        &departure,
        problem,
        settings,
        &shooting_settings,
        shooting_share,
    );
    out.info.walked = walked;
    out.objective = problem.objective;
    out.kappa = shot.point.kappa;
    out.theta_rad = shot.point.theta_rad;
    out.duration_tu = shot.duration_tu;
    out.costates = shot.point.costates;
    out.cost_multiplier = shot.cost_multiplier;
    out.mass_after_impulse = departure.mass_after_impulse(shot.point.kappa);
    out.residual = Some(shot.residual).filter(|r| r.is_finite());
    out.info.iterations = shot.iterations;

    // The check flight, from the returned point whatever the shooting's end: with the rest of
    // the budget.
    let used =
        u64::from(halo_counts.step_trials()).saturating_add(u64::from(shot.counts.step_trials()));
    let mut check_counts = Counts::default();
    let flown = check_flight(
        &model,
        problem,
        &shot,
        settings,
        &tolerance(settings.work_budget.saturating_sub(used)),
        &mut check_counts,
    );
    out.flown = flown.ok();
    out.info.work_units = used.saturating_add(u64::from(check_counts.step_trials()));
    out.info.evaluations = [halo_counts, shot.counts, check_counts]
        .iter()
        .map(|c| u64::from(c.evaluations))
        .sum();
    out.info.status = status(&shot, &flown, settings);
    Ok(())
}

/// The largest component of `y`'s position and velocity off `r_lu`, `v_vu`.
fn state_miss(y: &Augmented, r_lu: &[f64; 3], v_vu: &[f64; 3]) -> f64 {
    y.r_lu
        .iter()
        .zip(r_lu)
        .chain(y.v_vu.iter().zip(v_vu))
        .map(|(a, b)| libm::fabs(a - b))
        .fold(0.0, f64::max)
}

/// Fly the arrival point ballistically over the halo period: it must come back to itself.
fn check_halo(
    model: &Model,
    problem: &Problem,
    settings: &Settings,
    tol: &Tolerance,
    counts: &mut Counts,
) -> Result<(), PlanError> {
    let start = Augmented::ballistic(problem.arrival_r_lu, problem.arrival_v_vu);
    let end = propagate(
        model,
        Throttle::Coast,
        &start,
        problem.halo_period_tu,
        tol,
        counts,
    )
    .map_err(|_| PlanError::HaloCheckUnfinished)?;
    let miss = state_miss(&end, &start.r_lu, &start.v_vu);
    if miss.is_finite() && miss <= settings.halo_closure_tol {
        Ok(())
    } else {
        Err(PlanError::NotOnPeriodicOrbit {
            miss: if miss.is_finite() { miss } else { f64::MAX },
            limit: settings.halo_closure_tol,
        })
    }
}

/// Fly a plan (its impulse, costates and duration) in `span.segments` pieces: the flight, the
/// largest component of its miss of the arrival (with `λm(t_f)`), `visit` at every piece's end.
fn fly_from(
    model: &Model,
    problem: &Problem,
    point: &Point,
    span: Span,
    tol: &Tolerance,
    counts: &mut Counts,
    visit: &mut dyn FnMut(&Sample),
) -> Result<(Flight, f64), Stop> {
    let moved = Problem {
        kappa: point.kappa,
        theta_rad: point.theta_rad,
        ..*problem
    };
    let x = departure_state(&departure_of(problem), &moved);
    let l = point.costates;
    let y0 = Augmented {
        r_lu: [x[0], x[1], x[2]],
        v_vu: [x[3], x[4], x[5]],
        m_mu: x[6],
        lambda_r: [l[0], l[1], l[2]],
        lambda_v: [l[3], l[4], l[5]],
        lambda_m: l[6],
    };
    let flight = fly(model, law(problem.objective), &y0, span, tol, counts, visit)?;
    let end = flight.end;
    let miss = state_miss(&end, &problem.arrival_r_lu, &problem.arrival_v_vu)
        .max(libm::fabs(end.lambda_m));
    Ok((flight, miss))
}

/// Fly the shot's plan once more in `check_segments` pieces: its end against the arrival, the
/// Hamiltonian's drift, the thrust arcs and switches.
fn check_flight(
    model: &Model,
    problem: &Problem,
    shot: &Shot,
    settings: &Settings,
    tol: &Tolerance,
    counts: &mut Counts,
) -> Result<FlownPlan, Stop> {
    let span = Span {
        duration_tu: shot.duration_tu,
        segments: u32::from(settings.check_segments),
    };
    let (flight, miss) = fly_from(model, problem, &shot.point, span, tol, counts, &mut |_| {})?;
    Ok(FlownPlan {
        final_mass: flight.end.m_mu,
        end_miss: miss,
        hamiltonian_drift: flight.hamiltonian_drift,
        thrust_arcs: flight.thrust_arcs,
        switches: flight.switches,
        switch_times_tu: flight.switch_times_tu,
    })
}

/// Fly a returned plan of `problem` (its κ, θ, duration and costates) in `segments` pieces of
/// equal duration with the settings' integrator tolerances and `work_budget` step trials,
/// `visit` seeing the start and every piece's end: what the reports and plots draw is what
/// the planner's check flew (the same function, in more pieces).
///
/// # Errors
/// The integrator's [`Stop`].
pub fn fly_plan(
    problem: &Problem,
    solution: &Solution,
    settings: &Settings,
    segments: u32,
    visit: &mut dyn FnMut(&Sample),
) -> Result<Flight, Stop> {
    let point = Point {
        costates: solution.costates,
        kappa: solution.kappa,
        theta_rad: solution.theta_rad,
    };
    let tol = settings.tolerance(settings.work_budget);
    let span = Span {
        duration_tu: solution.duration_tu,
        segments,
    };
    let mut counts = Counts::default();
    fly_from(
        &model_of(problem),
        problem,
        &point,
        span,
        &tol,
        &mut counts,
        visit,
    )
    .map(|(f, _)| f)
}

/// The transversality conditions of a returned plan, `[κ, θ]` (SPEC-hybrid.md eq. 12): the
/// derivatives of its cost in κ and θ with the impulse's other parameter held (the envelope
/// of the fixed-parameter family, `∂Θ/∂κ + λ(t0)·∂x0/∂κ` and `λ(t0)·∂x0/∂θ`); both 0 where
/// the plan is optimal in them. A ground tool finds the optimum in θ as the root of the
/// second along a family of fixed-θ plans, where the shooting with θ free is too steep for
/// Newton (docs/hybrid.md, "κ and θ free").
pub fn transversality(problem: &Problem, solution: &Solution) -> [f64; 2] {
    let departure = departure_of(problem);
    let d = departure.state(solution.kappa, solution.theta_rad);
    let dot = |a: &[f64; 7]| {
        a.iter()
            .zip(&solution.costates)
            .map(|(x, l)| x * l)
            .sum::<f64>()
    };
    let (_, cost_in_kappa, _) = departure.chemical_cost(solution.kappa);
    [cost_in_kappa + dot(&d.d_kappa), dot(&d.d_theta)]
}

/// The status the shot and its check flight support.
fn status(shot: &Shot, flown: &Result<FlownPlan, Stop>, settings: &Settings) -> SolveStatus {
    let stopped = |stop: &Stop| match stop {
        Stop::StepLimit { .. } => SolveStatus::BudgetExhausted { verified: false },
        Stop::StepTooSmall { .. } => SolveStatus::IntegrationStopped(Stopped::StepTooSmall),
        Stop::NotFinite { .. } => SolveStatus::IntegrationStopped(Stopped::NotFinite),
        Stop::SwitchLimit { .. } => SolveStatus::IntegrationStopped(Stopped::SwitchLimit),
    };
    match shot.status {
        Status::Converged => match flown {
            Err(stop) => stopped(stop),
            Ok(plan) => {
                let finite = [
                    plan.final_mass,
                    plan.end_miss,
                    plan.hamiltonian_drift,
                    shot.duration_tu,
                ]
                .iter()
                .chain(shot.point.costates.iter())
                .all(|x| x.is_finite());
                if finite
                    && shot.residual <= settings.tolerance
                    && plan.end_miss <= settings.flight_tol
                    && plan.hamiltonian_drift <= settings.hamiltonian_tol
                {
                    SolveStatus::Solved
                } else {
                    SolveStatus::CheckFailed
                }
            }
        },
        Status::IterationLimit => SolveStatus::IterationLimit,
        Status::NoDescent => SolveStatus::NoDescent,
        Status::Singular => SolveStatus::Singular,
        Status::Integration(stop) => stopped(&stop),
    }
}
