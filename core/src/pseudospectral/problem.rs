//! The planner-A request: spacecraft, boundary states, horizon, bounds.

use crate::capacity::MAX_SPACECRAFT;
use serde::{Deserialize, Serialize};

/// One spacecraft's boundary conditions and mass.
///
/// Units: normalised (see the [module docs](super)). States are `[x, y, z, vx, vy, vz]`:
/// position in LU, velocity in LU/TU.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct Spacecraft {
    /// Mass in MU; must be finite and positive.
    pub mass_mu: f64,
    /// State at t = 0: position (LU) then velocity (LU/TU).
    pub initial_state: [f64; 6],
    /// State at t = T: position (LU) then velocity (LU/TU).
    pub final_state: [f64; 6],
}

/// A collision-free reconfiguration problem (Huang 2012, eq. 1-5).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Problem {
    /// Fixed manoeuvre time T in TU.
    pub horizon_tu: f64,
    /// Bound on each control-force component, |u| <= Umax, in FU (= MU LU / TU^2).
    pub max_control_fu: f64,
    /// Keep-out distance d between any two spacecraft, in LU.
    pub keep_out_lu: f64,
    /// Polynomial degree N of the transcription; the solve uses N + 1 LGL nodes.
    pub degree: u16,
    /// Enforce keep-out at the Gaussian test points between nodes (Huang 2012, eq. 27-28).
    pub test_points: bool,
    /// The spacecraft, at most [`MAX_SPACECRAFT`].
    pub spacecraft: heapless::Vec<Spacecraft, MAX_SPACECRAFT>,
}
