//! Planner B: multi-impulse reconfiguration under J2 at fixed impulse points (Wang et al. 2018),
//! with a least-fuel refinement, a nonlinear check with defect correction, and a bounded
//! deterministic search over the impulse points.
//!
//! ## Problem
//! A deputy changes its mean elements relative to a non-manoeuvring chief,
//! `Delta sigma = sigma_deputy - sigma_chief`, `sigma = [a, e, i, Omega, omega, M]`, from
//! `Delta sigma_0` at the epoch to `Delta sigma_N` at the last of N impulses. Impulse k happens
//! at mean argument of latitude `u_k` after `dN_k` whole revolutions (eq. 7). Between impulses
//! the mean elements drift with J2 (eq. 4); an impulse changes them by `B(sigma) dv` (eq. 3).
//! Linearising the drift gives `F dX = dY` (eq. 11-12); `dX = F^+ dY` (eq. 14) iterated to a
//! fixed point, since F depends on the impulses.
//!
//! ## Element sets
//! The paper's classical sigma is singular at e = 0 and sin i = 0. By default the model is
//! written in equinoctial elements `(a, lambda, e cos(omega+Omega), e sin(omega+Omega),
//! tan(i/2) cos Omega, tan(i/2) sin Omega)`, regular at e = 0 and i = 0 (`equinoctial`,
//! `equinoctial_drift`, dispatched by `model`); `Settings::element_set = Classical` is the
//! paper-reproduction mode. Requests stay in classical mean elements (`forms` converts other
//! input forms).
//!
//! ## Units and frame
//! Lengths in km, times in s, angles in rad inside the core; impulses in m/s
//! (`dv_rtn_mps`: radial, along-track, normal in the deputy's local frame at the impulse).
//! Degrees appear only at the host's I/O edge.
//!
//! ## Bounds
//! Every loop is bounded by a field of [`Settings`]; see its docs for the worst case.

pub(crate) mod elements;
mod equinoctial;
mod equinoctial_drift;
mod error;
mod form_problem;
mod forms;
mod gve;
pub(crate) mod kepler;
pub use kepler::WORST_NEWTON_STEPS;
#[cfg(feature = "kernel-counters")]
pub use kepler::{newton_counts, newton_counts_reset};
#[doc(hidden)]
pub mod kernels;
mod min_fuel;
mod model;
pub(crate) mod nonlinear;
mod osculating;
mod pinv;
mod returned;
mod search;
pub(crate) mod secular;
mod settings;
mod socp;
mod solution;
mod solver;
mod status;
mod trajectory;
mod transfer;
mod types;
mod validate;
mod work_units;
pub use work_units::{MAX_INSTRUCTIONS_PER_UNIT, MAX_SOLVE_INSTRUCTIONS};
mod workspace;

pub use error::{Orbit, PlanError, Quantity, MAX_ANGLE_RAD};
pub use form_problem::{
    end_state, EndForm, EndState, FormPart, FormProblem, OrbitForm, RelativeForm,
};
pub use forms::{
    classical_of, deputy_of, equinoctial_of, mean_and_evaluations_of_osculating_state,
    mean_of_osculating_state, osculating_shape, osculating_state_of_mean, relative_between,
    relative_of_roe, roe_of, CartesianState, FormError, Roe, OSCULATING_MAX_ITER, OSCULATING_TOL,
};
pub use model::{point_phase, Phase};
pub use settings::{
    ElementSet, SettingId, Settings, DEFAULT_WORK_BUDGET, MAX_SEARCH_STARTS, MAX_SMA_KM,
};
pub use socp::{least_fuel_rows, LeastFuel, SocpStatus};
pub use solution::{Impulse, Solution, TerminalError};
pub use status::{SolveInfo, SolveStatus, Stage};
pub use trajectory::{formation_position_rtn_km, relative_position_rtn_km, TrajectoryError};
pub use types::*;
pub use workspace::Workspace;

/// Planner B in the planners' contract ([`crate::contract::Planner`]): [`solve`]. (A
/// request in the user's input forms goes through [`solve_form`], which writes the same
/// solution.)
#[derive(Clone, Copy, Debug)]
pub struct Impulsive;

crate::impl_planner!(
    Impulsive: Problem, Settings, Workspace, Solution, PlanError, SolveStatus,
    Impulsive, solve, reset |out| *out = Solution::new()
);

/// Plan the impulses of `problem`: at its fixed impulse points, or by a bounded search over
/// them (`ImpulsePlan::Search`).
///
/// Writes the plan (or the best so far, with a status saying why) into `out`. Time is bounded
/// by `settings` alone (see [`Settings`]); no heap, no panics, bit-identical on every run.
///
/// # Errors
/// A [`PlanError`] when the request is rejected before iterating (bad settings, NaN or
/// infinite input, angles beyond [`MAX_ANGLE_RAD`], an orbit that is not an ellipse, a
/// semi-major axis outside `(Re + min_perigee_altitude_km, MAX_SMA_KM]`, an inclination outside
/// `[0, pi]`, a perigee below `min_perigee_altitude_km`, a retrograde equatorial orbit, in the
/// classical set eccentricity or `sin i` below the singularity thresholds, negative or
/// excessive revolution counts, no impulses or more than
/// [`crate::capacity::MAX_IMPULSES`]); `out` and `workspace` are then untouched. Once accepted,
/// every number written to `out` is finite (see [`SolveStatus`]).
pub fn solve(
    problem: &Problem,
    settings: &Settings,
    workspace: &mut Workspace,
    out: &mut Solution,
) -> Result<(), PlanError> {
    settings.validate().map_err(PlanError::InvalidSetting)?;
    let ctx = validate::validate(problem, settings)?;
    let impulses = match &problem.plan {
        ImpulsePlan::Fixed(points) => points.len(),
        ImpulsePlan::Search { impulses, .. } => usize::from(*impulses),
    };
    workspace.seq.work = crate::work::Meter::new(settings.work_budget);
    workspace
        .seq
        .work
        .reserve(work_units::final_reserve(impulses, settings));
    let evaluations = match &problem.plan {
        ImpulsePlan::Fixed(points) => {
            workspace.points = transfer::Points::new();
            for (slot, p) in workspace.points.at.iter_mut().zip(points.iter()) {
                *slot = *p;
            }
            workspace.points.n = points.len();
            1
        }
        ImpulsePlan::Search {
            impulses,
            max_revolutions,
        } => {
            let search_reserve = work_units::search_reserve(usize::from(*impulses), settings);
            workspace.seq.work.reserve(search_reserve);
            let used = search::search(
                &ctx,
                usize::from(*impulses),
                *max_revolutions,
                settings,
                &mut workspace.seq,
                &mut workspace.points,
                &mut workspace.search,
            );
            // The final solve at the best points may spend what the search left.
            let checks = work_units::final_reserve(usize::from(*impulses), settings);
            workspace.seq.work.next_stage(checks);
            used.saturating_add(1)
        }
    };
    let report = solver::solve_points(&ctx, &workspace.points, settings, &mut workspace.seq);
    workspace
        .seq
        .work
        .charge(work_units::final_checks(impulses));
    returned::write_solution(
        &ctx,
        &workspace.points,
        settings,
        &mut workspace.seq,
        &report,
        evaluations,
        out,
    );
    // Stopped by the budget: the status says so, and whether the plan passed the checks.
    if workspace.seq.work.exhausted() {
        out.info.status = SolveStatus::BudgetExhausted {
            verified: out.info.status.is_usable(),
        };
    }
    out.info.work_units = workspace.seq.work.used();
    Ok(())
}

/// Plan a request given in the user's forms ([`FormProblem`]): convert it with
/// [`FormProblem::to_problem`], [`solve`] it, and return the plan's end state in the form the
/// user gave the target in ([`end_state`]). The conversion adds a bounded number of steps (see
/// `form_problem`).
///
/// # Errors
/// [`PlanError::InvalidSetting`], [`PlanError::InputForm`] naming the part that cannot be
/// converted, or any [`PlanError`] of [`solve`]; `out` and `workspace` are then untouched.
pub fn solve_form(
    problem: &FormProblem,
    settings: &Settings,
    workspace: &mut Workspace,
    out: &mut Solution,
) -> Result<EndState, PlanError> {
    settings.validate().map_err(PlanError::InvalidSetting)?;
    let (converted, evaluations) = problem
        .to_problem_and_evaluations(settings)
        .map_err(|(part, error)| PlanError::InputForm { part, error })?;
    // The conversions are charged to the same work budget as the plan (the request's time
    // bound covers them): the osculating-to-mean steps made, and the one mean-to-osculating
    // evaluation an end state in state form needs. The plan gets what is left.
    let end_evaluations = u32::from(problem.end_form() == EndForm::DeputyState);
    let conversion_units = work_units::osculating_evaluation()
        .saturating_mul(u64::from(evaluations.saturating_add(end_evaluations)));
    let plan_settings = Settings {
        work_budget: settings.work_budget.saturating_sub(conversion_units),
        ..*settings
    };
    let planned = solve(&converted, &plan_settings, workspace, out);
    out.info.work_units = out.info.work_units.saturating_add(conversion_units);
    planned?;
    Ok(end_state(
        &converted.chief,
        &converted.target,
        out,
        problem.end_form(),
    ))
}
