//! Planner B: multi-impulse reconfiguration under J2 at fixed impulse points (Wang et al. 2018).
//!
//! ## Units
//! Lengths in km, times in s, angles in rad, impulses in m/s (`dv_rtn_mps`: radial,
//! along-track, normal in the deputy's local frame at the impulse). Degrees appear only at the
//! host's I/O edge.

mod types;

pub use types::*;
// Firmware branch only: compile-only placeholder API, replaced at merge by planner B's own.
mod placeholder;
pub use placeholder::*;
