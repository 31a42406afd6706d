//! Compile-time capacities. Every buffer in the core is sized from these; runtime sizes up to a
//! capacity are accepted, anything above is `PlanError::CapacityExceeded`, never a panic.

/// Most spacecraft planner A plans together (M).
pub const MAX_SPACECRAFT: usize = 8;
/// Highest polynomial degree N planner A accepts; a solve uses N + 1 LGL nodes.
pub const MAX_DEGREE: usize = 24;
/// Lowest polynomial degree: N - 3 free coefficients per axis must be at least one.
pub const MIN_DEGREE: usize = 4;
/// LGL nodes at the highest degree.
pub const MAX_NODES: usize = MAX_DEGREE + 1;
/// Free polynomial coefficients per axis per spacecraft at the highest degree (N - 3).
pub const MAX_FREE_PER_AXIS: usize = MAX_DEGREE - 3;
/// Spacecraft pairs at capacity, M (M - 1) / 2.
pub const MAX_PAIRS: usize = MAX_SPACECRAFT * (MAX_SPACECRAFT - 1) / 2;
/// Gaussian test points per pair (Huang 2012, eq. 27).
pub const TEST_POINTS_PER_PAIR: usize = 7;
/// Extra keep-out points per pair that continuous verification may add over all its rounds.
pub const MAX_VERIFY_POINTS_PER_PAIR: usize = 3;
/// Keep-out check times per pair: nodes, test points and verification points.
pub const MAX_CHECKS_PER_PAIR: usize =
    MAX_NODES + TEST_POINTS_PER_PAIR + MAX_VERIFY_POINTS_PER_PAIR;
/// Constraints the QP may hold active at once (keep-out plus control bounds).
pub const MAX_ACTIVE: usize = 56;

/// Most impulses planner B plans.
pub const MAX_IMPULSES: usize = 6;
