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
//!   Jacobian), from a given departure state.
//!
//! Not yet a planner: the departure of eq. 4 with κ and θ, minimum time, the ε ladder to
//! minimum fuel with the bang-bang switches, the published cases and the request path follow
//! (issue 30 stays open).

pub mod dynamics;
pub mod flow;
pub mod integrate;
pub mod jacobian;
pub mod shooting;
pub mod units;

pub use dynamics::{Augmented, Model, Throttle};
