//! What a planner-A solve produced: status and counters.

use serde::{Deserialize, Serialize};

crate::status_enum! {
    /// The state of the returned iterate: a promise about the trajectory in the solution.
    ///
    /// Only `Solved` and `Feasible` promise anything about the returned trajectory, and both are
    /// checked on it by the code that returns them (`solver.rs`, `certificate.rs`):
    ///
    /// * feasible: keep-out `>= d - verify_tol_lu` on the **continuous** trajectory (global
    ///   branch-and-bound minimum per pair, certified), every node control within
    ///   `Umax + CONTROL_TOL_FU`, and the dynamics check (eq. 29) below `DYNAMICS_TOL`;
    /// * certified: additionally the certificate in `Solution::certificate` meets the first- and
    ///   second-order tolerances of [`super::Certificate`].
    ///
    /// Every other status makes **no** feasibility promise: the trajectory returned with it may
    /// violate the keep-out or the control bound (`max_violation` and `min_separation_lu` say by
    /// how much).
    #[derive(Eq)]
    pub enum SolveStatus {
        /// Feasible (as above) and certified a local optimum: stationary, complementary, and the
        /// reduced Hessian of the Lagrangian positive on the active constraints' null space, each
        /// within the certificate's tolerances.
        Solved = 1,
        /// The iteration ended but the continuous separation is below `d - verify_tol_lu`
        /// somewhere; the solution says where. Not feasible.
        SeparationNotVerified = 2,
        /// The SQP iteration limit was reached and the last iterate is not verified feasible.
        MaxIterations = 3,
        /// A subproblem's l1-elastic QP kept a positive slack: at the last answer no step within
        /// the control bound meets the linearised keep-out of the checks `Solution::unseparated`
        /// names (pairs, times, shortfalls). Not feasible; not a proof that no plan exists (the
        /// linearisation is an inner approximation of the keep-out).
        Infeasible = 4,
        /// A QP hit its iteration limit (never its active-set capacity: past it the QP continues
        /// without a factor) and the last iterate is not verified feasible.
        QpLimit = 5,
        /// A factorisation failed; the stage says where. Not feasible.
        NumericalFailure(Stage) = 6,
        /// Verified feasible (as above) but not certified optimal within the budget: the iteration
        /// limit was reached, a QP stopped early, or the certificate missed a tolerance (for
        /// example a saddle the escape could not leave). May be flown; it may cost more than a
        /// local optimum.
        Feasible = 7,
        /// The work budget (`Settings::work_budget`) ran out before the iteration ended. The
        /// returned trajectory is the last QP solution (or the guess), checked like any other with
        /// the budget kept for it: `verified` says whether it passed the feasibility checks above
        /// (then it may be flown, not certified optimal); otherwise it makes no promise.
        BudgetExhausted {
            /// The returned trajectory is verified feasible (as above).
            verified: bool,
        } = 8,
    }
    usable: [Self::Solved | Self::Feasible | Self::BudgetExhausted { verified: true }];
    budget: BudgetExhausted;
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
    /// The trajectory is also certified a local optimum (`Solved`).
    pub fn is_certified(&self) -> bool {
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
    /// Saddle escapes tried (a step along negative reduced curvature, then the iteration
    /// again); at most `MAX_SADDLE_ESCAPES` (2).
    pub saddle_escapes: u8,
    /// Subproblems the active-set QP found infeasible and solved again in l1-elastic form.
    pub elastic_subproblems: u8,
    /// Work units used (`Settings::work_budget`), the final checks included.
    pub work_units: u64,
}
