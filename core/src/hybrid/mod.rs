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
//!   switches located by [`flow`]).
//!
//! Not yet a planner: θ free to convergence, the published cases beyond κ = 1.40, the request
//! path, the CLI and the on-board re-convergence follow (issue 30 stays open).

pub mod departure;
pub mod dynamics;
pub mod flow;
pub mod free;
pub mod integrate;
pub mod jacobian;
pub mod ladder;
pub mod min_time;
mod newton;
pub mod shooting;
pub mod units;

pub use dynamics::{Augmented, Model, Throttle};
