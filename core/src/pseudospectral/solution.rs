//! The planner-A result: node states and controls, cost, verified separation.

use super::certificate::Certificate;
use super::status::SolveInfo;
use crate::capacity::{MAX_NODES, MAX_PAIRS, MAX_SPACECRAFT, TEST_POINTS_PER_PAIR};
use serde::{Deserialize, Serialize};

/// A solved (or best) trajectory set, written by a solve into caller-owned memory.
///
/// Units: normalised (see the [module docs](super)). Only the first `spacecraft_count`
/// spacecraft and the first `degree + 1` nodes are meaningful; the rest are zero.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Solution {
    /// Polynomial degree N; `N + 1` nodes.
    pub degree: u16,
    /// Number of spacecraft M.
    pub spacecraft_count: u8,
    /// Horizon T in TU.
    pub horizon_tu: f64,
    /// Node times `t_h = T/2 (tau_h + 1)` in TU.
    pub node_times_tu: [f64; MAX_NODES],
    /// States `[x, y, z, vx, vy, vz]` (LU, LU/TU) per spacecraft per node.
    pub states: [[[f64; 6]; MAX_NODES]; MAX_SPACECRAFT],
    /// Control forces `[ux, uy, uz]` (FU) per spacecraft per node.
    pub controls_fu: [[[f64; 3]; MAX_NODES]; MAX_SPACECRAFT],
    /// Control energy `J = 1/2 sum_i int |U_i|^2 dt` (Huang 2012, eq. 18), in FU^2 TU.
    pub cost: f64,
    /// Least separation of any pair over the continuous interpolated trajectory, in LU.
    pub min_separation_lu: f64,
    /// The pair `(i, j)`, `i < j`, where the least separation occurs.
    pub min_separation_pair: (u8, u8),
    /// When the least separation occurs, in TU.
    pub min_separation_time_tu: f64,
    /// Largest position or velocity error when the true double integrator is propagated with
    /// the interpolated control and compared with the interpolated states (Huang 2012, eq. 29).
    pub max_dynamics_error: f64,
    /// Gaussian test-point times per pair (pairs in order (0,1), (0,2), ..., (1,2), ...), in TU;
    /// only meaningful when the problem asked for test points.
    pub test_point_times_tu: [[f64; TEST_POINTS_PER_PAIR]; MAX_PAIRS],
    /// Counters and status.
    pub info: SolveInfo,
    /// Optimality measures of the returned trajectory (`Solved` requires them met).
    pub certificate: Certificate,
}

impl Solution {
    /// An empty solution (status `Unsolved`), for use as an output buffer.
    pub const fn new() -> Self {
        Self {
            degree: 0,
            spacecraft_count: 0,
            horizon_tu: 0.0,
            node_times_tu: [0.0; MAX_NODES],
            states: [[[0.0; 6]; MAX_NODES]; MAX_SPACECRAFT],
            controls_fu: [[[0.0; 3]; MAX_NODES]; MAX_SPACECRAFT],
            cost: 0.0,
            min_separation_lu: 0.0,
            min_separation_pair: (0, 0),
            min_separation_time_tu: 0.0,
            max_dynamics_error: 0.0,
            test_point_times_tu: [[0.0; TEST_POINTS_PER_PAIR]; MAX_PAIRS],
            info: SolveInfo {
                status: super::status::SolveStatus::Unsolved,
                sqp_iterations: 0,
                qp_iterations: 0,
                verify_rounds: 0,
                verify_points_added: 0,
                keep_out_checks: 0,
                max_active: 0,
                warm_start_used: false,
                work_units: 0,
                max_violation: 0.0,
                saddle_escapes: 0,
            },
            certificate: Certificate::new(),
        }
    }
}

impl Solution {
    /// Reset to the empty state in place (no large temporary on the stack).
    pub fn reset(&mut self) {
        self.degree = 0;
        self.spacecraft_count = 0;
        self.horizon_tu = 0.0;
        self.node_times_tu.fill(0.0);
        for sc in self.states.iter_mut() {
            sc.fill([0.0; 6]);
        }
        for sc in self.controls_fu.iter_mut() {
            sc.fill([0.0; 3]);
        }
        self.cost = 0.0;
        self.min_separation_lu = 0.0;
        self.min_separation_pair = (0, 0);
        self.min_separation_time_tu = 0.0;
        self.max_dynamics_error = 0.0;
        for pair in self.test_point_times_tu.iter_mut() {
            pair.fill(0.0);
        }
        self.info = SolveInfo::default();
        self.certificate = Certificate::new();
    }
}

impl Default for Solution {
    fn default() -> Self {
        Self::new()
    }
}
