//! # reconfig-core
//!
//! On-board planners for spacecraft formation reconfiguration, in fixed time and fixed memory.
//!
//! * [`pseudospectral`] (planner A, Huang et al. 2012): M spacecraft with double-integrator
//!   dynamics move between fixed boundary states in a fixed horizon T with least control energy
//!   `J = 1/2 sum_i int_0^T |U_i|^2 dt`, subject to `|U_i,axis| <= Umax` and the pairwise keep-out
//!   `|r_i(t) - r_j(t)| >= d` on the *continuous* trajectory. Legendre–Gauss–Lobatto transcription,
//!   Pontryagin initial guess, Gaussian test points, a convex-concave sequence of QPs, and
//!   continuous verification of the separation. Normalised units (see the module docs).
//! * [`impulsive`] (planner B, Wang et al. 2018): a deputy changes its mean orbital elements
//!   relative to a chief on a J2-perturbed elliptic orbit with N impulses at fixed impulse points,
//!   found by the pseudo-inverse of the Gauss-variational map and a bounded fixed-point iteration.
//!
//! ## The on-board contract
//! * `#![no_std]`, no `alloc`: every buffer lives in a caller-owned `Workspace` sized by the
//!   constants in [`capacity`]. Exceeding a capacity is a `PlanError`, never a panic.
//! * Every loop is bounded by a setting or a capacity; a solve that hits a bound returns its best
//!   iterate with a status saying so. There is no clock in the core.
//! * No panics on any input: lints deny `unwrap`, `expect`, `panic!`, unchecked indexing and
//!   unchecked integer arithmetic.
//! * Deterministic: `libm` for all transcendental functions, no fused multiply-add, so the host
//!   and the Cortex-M7 builds produce bit-identical results.
#![no_std]
#![forbid(unsafe_code)]
#![deny(missing_docs)]
// Tests may unwrap, index, compare floats exactly and use unchecked arithmetic: a test that
// panics is a failing test, not a fault in flight. Written once here instead of on every test
// module; the library build (`cargo clippy` checks it without `cfg(test)`) keeps every lint.
#![cfg_attr(
    test,
    allow(
        clippy::unwrap_used,
        clippy::expect_used,
        clippy::panic,
        clippy::indexing_slicing,
        clippy::float_cmp,
        clippy::arithmetic_side_effects
    )
)]

pub mod astro;
pub mod capacity;
pub mod contract;
pub mod geo_tour;
pub mod hybrid;
pub mod impulsive;
pub mod indexed;
pub mod lambert;
pub mod leo_tour;
pub mod limits;
pub mod pseudospectral;
mod vec3;
pub mod wire;
pub mod work;
