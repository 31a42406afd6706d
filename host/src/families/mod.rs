//! Planner A's generated problems (`reconfig sweep`).
//!
//! * [`six`]: the six families of issue 9, the default set, on which planner A's settings were
//!   tuned (the oracle's golden problems).

pub mod six;

/// A generated problem and the name of its family or kind.
pub type Named = (&'static str, reconfig_core::pseudospectral::Problem);
