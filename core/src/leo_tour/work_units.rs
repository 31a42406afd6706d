//! The per-arc search's work units (issue 33): every step of an arc's solve is charged to the
//! work meter ([`crate::work::Meter`]) before it runs, by the most that step can cost. A unit is
//! at most [`MAX_INSTRUCTIONS_PER_UNIT`] Cortex-M7 instructions, the GEO tour's unit: each
//! constant below is the measured M7 instruction count of its step on its dearest path
//! (`kernels.rs` runs them), divided by 90 and rounded up, so a solve's units bound its
//! instructions, `instructions <= units x MAX_INSTRUCTIONS_PER_UNIT`. The LEO image measures
//! every kernel case on the M7 under QEMU in CI and fails above that bound
//! (`tests/tests/qemu_firmware/kernels_leo_image.rs`; the figures and the argument:
//! docs/leo-tour.md, "Work budget").
//!
//! What each charge covers:
//! * a flight of the planning model: [`FLIGHT`] for its set-up and [`RK4_STEP`] per step;
//! * a flight of the search model ([`MEAN_FLIGHT`]), a client's state from its mean orbit
//!   ([`MEAN_STATE`]), a client's mean orbit ([`MEAN_ORBIT`]): each with its Kepler solves at
//!   the Newton steps they took; the kernel image counts the solves and steps and its test
//!   holds each case to every solve at [`mean_j2`](super::mean_j2)'s limit of
//!   `impulsive::kepler::WORST_NEWTON_STEPS + 2` steps;
//! * a Lambert solve: [`LAMBERT_SOLVE`] for its set-up and velocities, and each Householder or
//!   Halley step as it starts (`crate::lambert::step_units`);
//! * the two-body propagation of a client to the arrival (the grid's J2 offset):
//!   [`two_body_propagation`], at its bound of [`TWO_BODY_MAX_ITER`] iterations;
//! * an evaluation of the compass search (a plan's variables checked and flown to its last
//!   leg, the loop's bookkeeping): [`EVALUATION`]; a last leg costed: [`LAST_LEG`];
//! * an aim-point iteration of a shooting outside its Lambert solve and flight:
//!   [`SHOOT_ITERATION`];
//! * a grid epoch: [`GRID_POINT`], [`GRID_FAMILY`] per family it scans, [`GRID_INSERT`] per
//!   candidate it ranks; a hop: [`HOP`]; the returned plan's burns: [`FINISH`]; a solve's fixed
//!   part (the request checked, the answer written): [`SOLVE`].

/// The most Cortex-M7 instructions one unit stands for: `work_budget x
/// MAX_INSTRUCTIONS_PER_UNIT` bounds an arc's instructions.
pub const MAX_INSTRUCTIONS_PER_UNIT: u64 = 100;

/// The default work budget (and the service's built-in limit): 4 M units, so an arc takes at
/// most `4 M x MAX_INSTRUCTIONS_PER_UNIT` = 400 M M7 instructions (1 s at 400 MHz), the
/// on-board promise of every planner. The search stops at its share of it and the plan it
/// has is polished and checked in the planning model with the rest (`SEARCH_SHARE_PERCENT`
/// in `mod.rs`): a cut search is `BudgetExhausted { verified: true }` with a plan that
/// arrives, not a lost plan. The figures on generated arcs: docs/leo-tour.md, "Work budget".
pub const DEFAULT_WORK_BUDGET: u64 = 4_000_000;

/// One RK4 step of two-body + J2 (`j2::rk4_step`: four accelerations).
pub const RK4_STEP: u64 = 7;
/// A planning-model flight outside its steps: the step count, the loop's set-up.
pub const FLIGHT: u64 = 4;
/// A search-model flight (`mean_j2::fly`: to mean elements, the secular drift, back to an
/// osculating state), its Kepler solves at the steps they took.
pub const MEAN_FLIGHT: u64 = 123;
/// A client's state from its mean orbit (`MeanOrbit::state_at`).
pub const MEAN_STATE: u64 = 77;
/// A client's mean orbit from its state (`MeanOrbit::of_state`), once per arc and client.
pub const MEAN_ORBIT: u64 = 47;
/// A Lambert solve outside its steps: the geometry, Izzo's guess, the velocities.
pub const LAMBERT_SOLVE: u64 = 20;
/// Iterations of the two-body propagation of the grid's offset (`lambert::propagate`).
pub const TWO_BODY_MAX_ITER: u16 = 60;
/// The two-body propagation's set-up and velocities.
pub const TWO_BODY_SET_UP: u64 = 12;
/// One of its universal-variable Newton iterations.
pub const TWO_BODY_ITERATION: u64 = 5;
/// A compass-search evaluation outside its flights and Lambert solves.
pub const EVALUATION: u64 = 10;
/// A coast of a compass evaluation looked up among the last evaluation's (its inputs compared,
/// its end copied when they match: the flight is then not flown, nor charged).
pub const COAST_LOOKUP: u64 = 1;
/// A last leg costed outside its Lambert solve (the burns summed).
pub const LAST_LEG: u64 = 4;
/// An aim-point iteration outside its Lambert solve and flight (the miss, the secant update).
pub const SHOOT_ITERATION: u64 = 6;
/// A grid epoch outside its client states, Lambert solves and ranking.
pub const GRID_POINT: u64 = 20;
/// A family scanned at a grid epoch (whether its revolutions are in the window).
pub const GRID_FAMILY: u64 = 1;
/// A grid candidate ranked among the kept ones (`arc_grid::insert`).
pub const GRID_INSERT: u64 = 50;
/// A hop built outside its flights and evaluation.
pub const HOP: u64 = 10;
/// A node seed's own arithmetic (the node's epoch, the transfer, its split's golden section),
/// without its client states and flights (charged by theirs): 10,069 M7 instructions (kernel
/// case `node-seed-arithmetic`), 112 units by the rule, 120 charged.
pub const NODE_SEED: u64 = 120;
/// The returned plan's burns written and checked, its transfer's lowest altitude found (a
/// conic per coast, `altitude.rs`) (`Ctx::finish` outside its flights).
pub const FINISH: u64 = 15;
/// A solve's fixed part: the request checked, the context built, the answer written.
pub const SOLVE: u64 = 30;

/// The sequencing's fixed part (`sequence::best_order` and `tour_order::solve_sequence`
/// outside their nodes and arcs): the request checked, the clients' planes and perigees, the
/// matrix of entry bounds of every pair of [`super::sequence::MAX_CLIENTS`] clients, the
/// memos emptied, the answer written.
pub const SEQUENCE_FIXED: u64 = 4_000;
/// A node of the sequencing's enumeration outside its arcs: the duration and bound of each of
/// its at most `MAX_CLIENTS - 1` children, their sort, and each child's pruning test (the
/// bound of the clients still to visit).
pub const SEQUENCE_NODE: u64 = 400;
/// A planned arc of the sequencing outside its flights and estimate: its memo lookups (the
/// arc's and its two clients' states', each memo searched to its capacity), its pruning test
/// once costed, the complete order kept.
pub const SEQUENCE_ARC: u64 = 100;

/// A planning-model flight of `steps` RK4 steps.
pub const fn flight(steps: u32) -> u64 {
    FLIGHT.saturating_add(RK4_STEP.saturating_mul(steps as u64))
}

/// The two-body propagation at its bound.
pub const fn two_body_propagation() -> u64 {
    TWO_BODY_SET_UP.saturating_add(TWO_BODY_ITERATION.saturating_mul(TWO_BODY_MAX_ITER as u64))
}

/// An iteration of the descent outside its evaluations and shooting (`arc_descent.rs`: the
/// direction, the step's scaling, the inverse Hessian's update, over at most `MAX_VARS` = 9
/// variables).
pub const DESCENT_ITERATION: u64 = 40;
