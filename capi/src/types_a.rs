//! Planner A (pseudospectral, Huang 2012) as plain C structs. Normalised units: LU, TU, MU,
//! FU = MU LU / TU^2 (see `reconfig_core::pseudospectral`).

use crate::status::ReconfigError;
use reconfig_core::capacity::{MAX_NODES, MAX_SPACECRAFT};

/// Most spacecraft planner A plans together (`capacity::MAX_SPACECRAFT`).
pub const RECONFIG_A_MAX_SPACECRAFT: usize = 8;
/// LGL nodes at the highest degree (`capacity::MAX_NODES`).
pub const RECONFIG_A_MAX_NODES: usize = 25;

// Literals so that the header can spell them; the core's capacities decide, and a change there
// fails the build here until these follow.
const _: () = assert!(RECONFIG_A_MAX_SPACECRAFT == MAX_SPACECRAFT);
const _: () = assert!(RECONFIG_A_MAX_NODES == MAX_NODES);

/// One spacecraft's boundary conditions and mass.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct ReconfigASpacecraft {
    /// Mass, MU.
    pub mass_mu: f64,
    /// State at t = 0: position (LU) then velocity (LU/TU).
    pub initial_state_lu_lutu: [f64; 6],
    /// State at t = T: position (LU) then velocity (LU/TU).
    pub final_state_lu_lutu: [f64; 6],
}

/// A collision-free reconfiguration problem (Huang 2012, eq. 1-5).
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct ReconfigAProblem {
    /// Fixed manoeuvre time T, TU.
    pub horizon_tu: f64,
    /// Bound on each control-force component, FU.
    pub max_control_fu: f64,
    /// Keep-out distance between any two spacecraft, LU.
    pub keep_out_lu: f64,
    /// Polynomial degree N (N + 1 LGL nodes).
    pub degree: u16,
    /// 1: enforce keep-out at the Gaussian test points between nodes; 0: not.
    pub test_points: u8,
    /// Spacecraft used, at most `RECONFIG_A_MAX_SPACECRAFT`.
    pub spacecraft_count: u8,
    /// The spacecraft; the first `spacecraft_count` are used.
    pub spacecraft: [ReconfigASpacecraft; RECONFIG_A_MAX_SPACECRAFT],
}

/// Loop bounds and tolerances (`reconfig_core::pseudospectral::Settings`, same names). Flags
/// are 0 or 1.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct ReconfigASettings {
    /// Work budget of a solve, work units.
    pub work_budget: u64,
    /// Relative cost-change stop tolerance of the convex-concave iteration.
    pub sqp_tol_cost: f64,
    /// Coefficient-change stop tolerance, LU.
    pub sqp_tol_step_lu: f64,
    /// Constraint violation a QP accepts, LU or FU.
    pub qp_tol_feas: f64,
    /// Continuous separation accepted as meeting the keep-out, LU.
    pub verify_tol_lu: f64,
    /// Keep-out enlargement used in the constraints, LU.
    pub keep_out_margin_lu: f64,
    /// Most convex subproblems per verification round.
    pub sqp_max_iter: u16,
    /// Most active-set changes per QP.
    pub qp_max_iter: u16,
    /// Newton iterations for LGL nodes and the guess's root-finds.
    pub newton_max_iter: u16,
    /// Refinement steps of a separation minimum.
    pub refine_max_iter: u16,
    /// Anderson-acceleration memory (0 or 1).
    pub acceleration_memory: u8,
    /// 1: continuous verification of the separation; 0: nodes and test points only.
    pub continuous_verification: u8,
    /// Rounds of continuous verification.
    pub verify_max_rounds: u8,
}

/// Most constraints an `RECONFIG_A_INFEASIBLE` answer names (`pseudospectral::MAX_UNMET`).
pub const RECONFIG_A_MAX_UNMET: usize = 8;
const _: () = assert!(RECONFIG_A_MAX_UNMET == reconfig_core::pseudospectral::MAX_UNMET);

/// A constraint the l1-elastic subproblem could not meet (`RECONFIG_A_INFEASIBLE`).
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct ReconfigAUnmet {
    /// 0: the keep-out of `pair` at `time_tu`; 1: the control bound of `spacecraft`, `axis`
    /// (0 = x), `node`, `upper` (1: `u <= Umax`, 0: `u >= -Umax`).
    pub kind: u8,
    /// Keep-out: the spacecraft pair, `i < j`, numbered from 0.
    pub pair: [u8; 2],
    /// Control: the spacecraft, numbered from 0.
    pub spacecraft: u8,
    /// Control: the axis.
    pub axis: u8,
    /// Control: the node.
    pub node: u8,
    /// Control: 1 for the upper bound.
    pub upper: u8,
    /// Keep-out: the check's time, TU (0 for a control bound).
    pub time_tu: f64,
    /// LU inside the linearised keep-out, or FU beyond Umax.
    pub shortfall: f64,
    /// `shortfall` relative to d or Umax.
    pub shortfall_rel: f64,
}

/// A planner-A result. Only the first `spacecraft_count` spacecraft and `degree + 1` nodes are
/// meaningful; the rest are zero.
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ReconfigASolution {
    /// The status code the solve returned (`RECONFIG_A_*`, or a refusal).
    pub status: i32,
    /// With `RECONFIG_A_NUMERICAL_FAILURE`: 0 transcription, 1 basis, 2 QP factor; else 0.
    pub numerical_stage: i32,
    /// Why the request was refused (all zero when it was not).
    pub error: ReconfigError,
    /// 1 when the trajectory may be flown (SOLVED, FEASIBLE, BUDGET_EXHAUSTED_VERIFIED).
    pub usable: u8,
    /// Number of spacecraft M.
    pub spacecraft_count: u8,
    /// Polynomial degree N.
    pub degree: u16,
    /// Convex subproblems solved.
    pub sqp_iterations: u16,
    /// Verification rounds that added points.
    pub verify_rounds: u8,
    /// Saddle escapes tried.
    pub saddle_escapes: u8,
    /// Active-set changes over all QPs.
    pub qp_iterations: u32,
    /// Work units used.
    pub work_units: u64,
    /// Horizon, TU.
    pub horizon_tu: f64,
    /// Control energy J = 1/2 sum int |U|^2 dt, FU^2 TU.
    pub cost_fu2_tu: f64,
    /// 1 when the least separation exists (two spacecraft or more); 0 with one spacecraft,
    /// and then `min_separation_lu`, `min_separation_time_tu` and `min_separation_pair` are 0.
    pub has_min_separation: u8,
    /// Least separation over the continuous trajectory, LU, when `has_min_separation`.
    pub min_separation_lu: f64,
    /// When it occurs, TU.
    pub min_separation_time_tu: f64,
    /// The pair where it occurs.
    pub min_separation_pair: [u8; 2],
    /// Largest dynamics error of the interpolated trajectory (Huang 2012, eq. 29).
    pub max_dynamics_error: f64,
    /// Largest violation of a checked constraint at the returned iterate.
    pub max_violation: f64,
    /// Node times, TU.
    pub node_times_tu: [f64; RECONFIG_A_MAX_NODES],
    /// States `[x, y, z, vx, vy, vz]` (LU, LU/TU) per spacecraft per node.
    pub states_lu_lutu: [[[f64; 6]; RECONFIG_A_MAX_NODES]; RECONFIG_A_MAX_SPACECRAFT],
    /// Control forces `[ux, uy, uz]` per spacecraft per node, FU.
    pub controls_fu: [[[f64; 3]; RECONFIG_A_MAX_NODES]; RECONFIG_A_MAX_SPACECRAFT],
    /// With `RECONFIG_A_INFEASIBLE`: how many of `unmet` are named (0 otherwise).
    pub unmet_count: u8,
    /// 1 when more constraints were unmet than `unmet` holds.
    pub unmet_truncated: u8,
    /// The constraints that cannot be met: keep-out checks first, then control bounds, each
    /// kind by relative shortfall, largest first.
    pub unmet: [ReconfigAUnmet; RECONFIG_A_MAX_UNMET],
}
