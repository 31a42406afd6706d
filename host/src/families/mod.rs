//! Planner A's generated problems (`reconfig sweep`).
//!
//! * [`six`]: the six families of issue 9, the default set, on which planner A's settings were
//!   tuned (the oracle's golden problems);
//! * [`sets`]: the seeded `tuning` and `held-out` sets of issue 28, disjoint, each problem of
//!   one of the [`kinds`] (every kind in both), so that figures are measured on problems the
//!   settings were never tuned on;
//! * [`kinds`]: the kinds' names and one problem of a kind; [`swaps`], [`motion`],
//!   [`overtaking`] and [`placements`] build their spacecraft;
//! * [`bound`]: what the kinds share (keep-out, clearance of the ends, the common draws) and the
//!   control bound from the least force the ends need;
//! * [`geometry`]: vectors, rotations, shapes, lattices and seeded sampling.

pub mod bound;
pub mod geometry;
pub mod kinds;
pub mod motion;
pub mod overtaking;
pub mod placements;
pub mod sets;
pub mod six;
pub mod swaps;

#[cfg(test)]
mod tests;

/// A generated problem and the name of its family or kind.
pub type Named = (&'static str, reconfig_core::pseudospectral::Problem);
