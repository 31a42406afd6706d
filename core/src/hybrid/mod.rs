//! The hybrid chemical + electric transfer to an Earth–Moon libration-point orbit (issue 30;
//! SPEC-hybrid.md): a tangential chemical impulse on a circular parking orbit, then low thrust
//! in the circular restricted three-body problem, for least propellant, by the indirect method
//! (Pontryagin's principle, shooting on the costates, a homotopy from minimum energy to
//! minimum fuel).
//!
//! Built so far (docs/hybrid.md), each checked against finite differences or a known answer:
//!
//! * [`units`]: the paper's units and constants;
//! * [`dynamics`]: the canonical system (14 unknowns), its Hamiltonian, the switching
//!   function and the optimal smoothed throttle;
//! * [`jacobian`]: its Jacobian, the matrix of the variational equations;
//! * [`integrate`]: DOP853 with a bounded step count;
//! * [`flow`]: the flow and its state-transition matrix (210 equations);
//! * [`shooting`]: fixed-time shooting on the initial costates (damped Newton, analytic
//!   Jacobian), from a given departure state;
//! * [`departure`]: the state after the impulse (eq. 4) and its derivatives in κ and θ;
//! * [`free`]: shooting with κ and/or θ free by their transversality conditions;
//! * [`min_time`]: minimum-time shooting (normalised multipliers, free t_f);
//! * [`ladder`]: the ε homotopy from minimum energy to minimum fuel (bang-bang at ε = 0, its
//!   switches located by [`flow`]);
//! * [`trace`]: a plan flown again in pieces, its switches and the Hamiltonian's drift.
//!
//! The planner (`Hybrid`, [`solve`]; the one request path's `Request::Hybrid`): the request's
//! shooting from the ground's design (`objective_shooting`), a walk from that design to the
//! request where the shooting alone does not converge (`walk`), the plan flown once more to
//! check it, and a status that says what was shown (docs/hybrid.md). Not yet: θ free to
//! convergence, the published cases below κ = 1.40, the C interface and the M7 image (issue 30
//! stays open).

pub mod departure;
pub mod dynamics;
pub mod flow;
pub mod free;
pub mod halo;
pub mod integrate;
pub mod jacobian;
pub mod ladder;
mod linear;
pub mod min_time;
mod newton;
mod objective_shooting;
mod planner;
#[cfg(test)]
mod planner_tests;
mod problem;
pub mod shooting;
mod solution;
pub mod trace;
pub mod units;
mod walk;

pub use dynamics::{Augmented, Model, Throttle};
pub use planner::{fly_plan, solve, transversality, Hybrid, Workspace};
pub use problem::{Field, Objective, PlanError, Problem, MAX_COSTATE};
pub use solution::{
    FlownPlan, SettingId, Settings, Solution, SolveInfo, SolveStatus, Stopped, Walked,
    DEFAULT_WORK_BUDGET,
};
pub use walk::secant_start;
