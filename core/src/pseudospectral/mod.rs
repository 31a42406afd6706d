//! Planner A: collision-free reconfiguration of M spacecraft by a Legendre–Gauss–Lobatto
//! pseudospectral transcription of the double integrator (Huang et al. 2012).
//!
//! ## Units
//! The paper's normalised units: a length unit LU, a time unit TU and a mass unit MU; forces in
//! FU = MU LU / TU^2. Field names carry `_lu`, `_tu`, `_mu`, `_fu`.
//!
//! ## Method
//! See `README.md` ("Planner A") for the derivation and the measured figures.

mod certificate;
mod error;
mod problem;
mod settings;
mod solution;
mod status;

pub use alternative::{solve_with_alternative_starts, AlternativeStarts, StartsOutcome};
pub use certificate::{
    ActiveConstraint, Certificate, Multiplier, COMPLEMENTARITY_TOL, CURVATURE_TOL,
    POWER_ITERATIONS, STATIONARITY_TOL,
};
pub use error::{Boundary, Capacity, PlanError, Quantity, MAX_MAGNITUDE, MIN_POSITIVE};
pub use lanczos::LANCZOS_STEPS;
pub use problem::{Problem, Spacecraft};
pub use settings::{
    SettingId, Settings, DEFAULT_WORK_BUDGET, MAX_ACCELERATION_MEMORY, MAX_VERIFY_ROUNDS,
};
pub use solution::{Solution, Unmet, UnmetConstraint, MAX_UNMET};
pub use status::{SolveInfo, SolveStatus, Stage};
mod workspace;
pub use work_units::{MAX_INSTRUCTIONS_PER_UNIT, MAX_SOLVE_INSTRUCTIONS};
pub use workspace::Workspace;

/// Planner A in the planners' contract ([`crate::contract::Planner`]): [`solve`] from the
/// analytic guess.
#[derive(Clone, Copy, Debug)]
pub struct Pseudospectral;

crate::impl_planner!(
    Pseudospectral: Problem, Settings, Workspace, Solution, PlanError, SolveStatus,
    Pseudospectral, solve, reset |out| out.reset()
);

/// Solve a reconfiguration problem from the analytic Pontryagin guess.
///
/// Writes the result (or the best iterate, with a status saying why) into `out`.
///
/// # Errors
/// A [`PlanError`] when the request is rejected before iterating; `out` is then untouched.
pub fn solve(
    problem: &Problem,
    settings: &Settings,
    workspace: &mut Workspace,
    out: &mut Solution,
) -> Result<(), PlanError> {
    solver::solve(problem, settings, workspace, None, [0.0; 3], out)
}

/// Solve starting from a previous solution of a problem with the same spacecraft count and
/// degree (for example the last cycle's plan). `SolveInfo::warm_start_used` reports whether it
/// was used.
///
/// # Errors
/// As [`solve`], plus [`PlanError::WarmStartMismatch`].
pub fn solve_warm(
    problem: &Problem,
    settings: &Settings,
    workspace: &mut Workspace,
    previous: &Solution,
    out: &mut Solution,
) -> Result<(), PlanError> {
    solver::solve(problem, settings, workspace, Some(previous), [0.0; 3], out)
}

mod alternative;
mod anderson;
mod anytime;
mod basis;
mod collision;
mod convex_minimum;
mod curvature;
mod guess;
mod iteration;
mod kept;
mod kernel;
#[doc(hidden)]
pub mod kernels;
mod lanczos;
mod lgl;
mod linalg;
mod linearise;
mod newton;
mod newton_cycle;
mod output;
mod packed;
mod qp;
mod qp_dual;
#[cfg(test)]
mod qp_elastic_tests;
mod qp_scan;
mod qp_state;
mod setup;
mod solver;
mod swerve;
mod symmetry;
#[cfg(test)]
mod test_problems;
mod transcription;
mod validate;
mod verify;
mod work_units;
