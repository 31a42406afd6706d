//! What a planner-B solve produced: status and counters.

use serde::{Deserialize, Serialize};

crate::status_enum! {
    /// The state of the returned plan. Checked in this order: numerical failure, unsafe perigee,
    /// rank deficiency (at the returned plan), nonlinear correction not converged, fixed point not
    /// converged, linearised (correction off), solved. Every number in a returned [`Solution`] is
    /// finite whatever the status: a value a failed stage could not compute is absent (`None`),
    /// and a plan whose own numbers are not finite is not returned (`NumericalFailure(NonFinite)`,
    /// no impulses).
    ///
    /// [`Solution`]: super::Solution
    pub enum SolveStatus {
        /// The returned impulses, flown with the exact impulse model and J2 secular drift, reach
        /// the target within `correction_tol` (re-checked on the returned plan), F has full rank
        /// there, and every transfer arc's perigee is above `min_perigee_altitude_km`. Needs
        /// `nonlinear_correction`.
        Solved = 1,
        /// `F` has rank below 6 (for example coincident impulse points): the least-squares
        /// minimum-norm impulses are returned; they do not reach the target.
        RankDeficient = 2,
        /// The fixed-point iteration hit `fixed_point_max_iter` (correction disabled); the last
        /// iterate is returned.
        MaxIterations = 3,
        /// The nonlinear defect correction hit `correction_max_iter` above `correction_tol`.
        CorrectionNotConverged = 4,
        /// A numerical step failed; the stage says where. The best plan so far is returned.
        NumericalFailure(Stage) = 5,
        /// The plan's transfer arc `arc` (1-based: arc k follows impulse k, arc N is the final
        /// orbit) has its perigee below `Settings::min_perigee_altitude_km`: not flyable.
        UnsafePerigee {
            /// The arc, 1..=N.
            arc: u8,
            /// Its perigee altitude `a (1 - e) - Re`, km (exact impulse model).
            perigee_altitude_km: f64,
        } = 6,
        /// The linear-model fixed point (Wang 2018, eq. 14) converged, full rank, safe perigees,
        /// but the nonlinear correction was off: flown with exact impulses the plan misses the
        /// target by `miss_m` (deputy position at the last impulse). Not usable as a plan to fly.
        Linearised {
            /// Position miss of the nonlinear check, m.
            miss_m: f64,
        } = 7,
        /// The work budget (`Settings::work_budget`) ran out: the search, the fixed point or the
        /// correction stopped early. The returned plan (the best points found, solved with the
        /// budget kept for it) was checked like any other: `verified` says whether it met every
        /// condition of `Solved` (then it may be flown; a longer search might find less fuel).
        BudgetExhausted {
            /// The returned plan reaches the target and has safe perigees (as `Solved`).
            verified: bool,
        } = 8,
    }
    usable: [Self::Solved | Self::BudgetExhausted { verified: true }];
    budget: BudgetExhausted;
}

/// Where a numerical failure happened.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[repr(u8)]
pub enum Stage {
    /// Kepler's equation did not converge within `kepler_max_iter`.
    #[default]
    Kepler = 0,
    /// The SVD did not converge within `svd_max_iter`, or produced a non-finite value.
    Svd = 1,
    /// An iterate left the valid domain (e or sin i under threshold, e >= 1, a <= Re).
    SingularState = 2,
    /// A number of the returned plan came out NaN or infinite: no plan is returned.
    NonFinite = 3,
}

/// Counters and measures of one solve.
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct SolveInfo {
    /// Outcome.
    pub status: SolveStatus,
    /// Fixed-point iterations (minimum-norm phase plus min-fuel phase) of the returned plan.
    pub iterations: u16,
    /// Interior-point iterations of the least-fuel cone programs, all told.
    pub min_fuel_iterations: u16,
    /// Nonlinear defect-correction steps.
    pub correction_iterations: u16,
    /// Numerical rank of `F` at the returned plan (6 when full), from an SVD of F rebuilt there.
    pub rank: u8,
    /// 2-norm condition number of `F` at the returned plan (ratio of extreme singular values);
    /// absent when rank-deficient (the smallest singular value being zero) or not computed.
    pub condition_number: Option<f64>,
    /// The min-fuel refinement was run and lowered the total (else the minimum-norm plan).
    pub min_fuel_used: bool,
    /// The nonlinear defect correction was applied to the returned impulses.
    pub correction_used: bool,
    /// Fixed-point solves evaluated (1 for fixed points; the search's count otherwise).
    pub evaluations: u32,
    /// Certified optimality gap of the least-fuel impulses on the final linearisation (upper
    /// minus dual lower bound), m/s; 0 when the least-fuel plan was not used.
    pub min_fuel_gap_mps: f64,
    /// Work units used (`Settings::work_budget`), the final checks included.
    pub work_units: u64,
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn default_is_unsolved_and_only_solved_is_usable() {
        assert_eq!(SolveStatus::default(), SolveStatus::Unsolved);
        assert!(SolveStatus::Solved.is_usable());
        for s in [
            SolveStatus::Unsolved,
            SolveStatus::RankDeficient,
            SolveStatus::MaxIterations,
            SolveStatus::CorrectionNotConverged,
            SolveStatus::NumericalFailure(Stage::Svd),
            SolveStatus::UnsafePerigee {
                arc: 1,
                perigee_altitude_km: 50.0,
            },
            SolveStatus::Linearised { miss_m: 150.0 },
            SolveStatus::BudgetExhausted { verified: false },
        ] {
            assert!(!s.is_usable(), "{s:?}");
        }
        assert_eq!(SolveInfo::default().status, SolveStatus::Unsolved);
    }
}
