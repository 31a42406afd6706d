//! What a planner-A solve produced: status and counters.

use serde::{Deserialize, Serialize};

/// The state of the returned iterate.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[repr(u8)]
pub enum SolveStatus {
    /// No solve has written this solution.
    #[default]
    Unsolved = 0,
    /// Converged; keep-out holds on the continuous trajectory within `verify_tol_lu`.
    Solved = 1,
    /// Converged at the check points, but continuous verification ran out of rounds or points
    /// with the separation still below d; the solution says where.
    SeparationNotVerified = 2,
    /// The SQP iteration limit was reached; the best feasible iterate is returned.
    MaxIterations = 3,
    /// A QP subproblem was infeasible (the linearised keep-out and control bounds conflict).
    Infeasible = 4,
    /// A QP hit its active-set capacity or iteration limit.
    QpLimit = 5,
    /// A factorisation failed; the stage says where.
    NumericalFailure(Stage) = 6,
}

/// Where a numerical failure happened.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[repr(u8)]
pub enum Stage {
    /// Building the LGL nodes and matrices.
    #[default]
    Transcription = 0,
    /// The cost-metric basis of the free coefficients.
    Basis = 1,
    /// The QP's Gram-matrix factorisation.
    QpFactor = 2,
}

impl SolveStatus {
    /// The trajectory meets every constraint and may be flown.
    pub fn is_usable(&self) -> bool {
        matches!(self, Self::Solved)
    }
}

/// Counters and measures of one solve.
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct SolveInfo {
    /// Outcome.
    pub status: SolveStatus,
    /// Convex subproblems solved, over all verification rounds.
    pub sqp_iterations: u16,
    /// Active-set changes over all QPs.
    pub qp_iterations: u32,
    /// Continuous verification rounds that added points.
    pub verify_rounds: u8,
    /// Keep-out check points added by verification.
    pub verify_points_added: u16,
    /// Keep-out constraints (node, test and verification points) checked in the last QP.
    pub keep_out_checks: u16,
    /// Largest active set any QP held (capacity `MAX_ACTIVE`).
    pub max_active: u16,
    /// The warm start was supplied and accepted as the first linearisation point.
    pub warm_start_used: bool,
    /// Largest violation of a checked constraint at the returned iterate.
    pub max_violation: f64,
}
