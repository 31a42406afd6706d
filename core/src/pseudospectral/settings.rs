//! Planner-A settings: every loop bound and tolerance of a solve.

use super::error::SettingsError;
use serde::{Deserialize, Serialize};

/// Most verification rounds a solve may be set to.
pub const MAX_VERIFY_ROUNDS: u8 = 8;

/// Default work budget, in units (`docs/firmware.md`, "Work budget").
pub const DEFAULT_WORK_BUDGET: u64 = 40_000_000;

/// Loop bounds and tolerances. Plain `Copy` data; all fields take effect per solve.
///
/// The worst case of a solve is bounded by
/// `(verify_max_rounds + 1) * sqp_max_iter * qp_max_iter` QP steps, each
/// `O(MAX_ACTIVE^2 + M N (N - 3))` flops; see the README for measured figures.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct Settings {
    /// Most convex subproblems (SQP / convex-concave iterations) per verification round.
    pub sqp_max_iter: u16,
    /// Stop when the cost decreases by less than this, relative (`|dJ| <= tol (1 + J)`), between
    /// iterations.
    pub sqp_tol_cost: f64,
    /// Or stop when the largest coefficient change (position scale) is below this, in LU.
    pub sqp_tol_step_lu: f64,
    /// Anderson-acceleration memory of the convex-concave iteration (0 = plain iteration, at
    /// most 1).
    pub acceleration_memory: u8,
    /// Follow each near-contact pair's continuous separation minimum with a moving check, and
    /// run the verification rounds. Off, the solver enforces keep-out only at the nodes and
    /// test points, as the paper does (the continuous minimum is still measured and reported).
    pub continuous_verification: bool,
    /// Most active-set changes per QP. Worst case: every candidate constraint enters once per
    /// drop, bounded by this number.
    pub qp_max_iter: u16,
    /// Constraint violation a QP accepts as satisfied, in the constraint's units (LU or FU).
    pub qp_tol_feas: f64,
    /// Rounds of continuous verification: each finds the true minimum separation of every pair
    /// and adds a keep-out point where it is below d (while the pair has point capacity left,
    /// `MAX_VERIFY_POINTS_PER_PAIR - 1`; one is the moving check) or, where a dip persists,
    /// raises that pair's keep-out by the dip; then re-solves. At most `MAX_VERIFY_ROUNDS` (8).
    pub verify_max_rounds: u8,
    /// Continuous separation accepted as meeting the keep-out: `>= d - verify_tol_lu`.
    pub verify_tol_lu: f64,
    /// Enlarge the keep-out used in the constraints by this, in LU, so that the continuous
    /// minimum between check points stays at or above d.
    pub keep_out_margin_lu: f64,
    /// Newton iterations for LGL nodes and for the root-finds of the Pontryagin guess.
    pub newton_max_iter: u16,
    /// Bisection / Newton steps when refining a separation minimum between check points.
    pub refine_max_iter: u16,
    /// Work budget of a solve, in work units (`crate::work`): past it the solve stops with
    /// `SolveStatus::BudgetExhausted`. Part of it is kept for the checks of the returned
    /// answer. The default bounds the worst request within the default limits to 400 M
    /// Cortex-M7 instructions (`docs/firmware.md`, "Work budget").
    pub work_budget: u64,
}

impl Default for Settings {
    fn default() -> Self {
        Self {
            sqp_max_iter: 60,
            sqp_tol_cost: 1e-8,
            sqp_tol_step_lu: 1e-10,
            acceleration_memory: 1,
            continuous_verification: true,
            qp_max_iter: 400,
            qp_tol_feas: 1e-12,
            verify_max_rounds: 4,
            verify_tol_lu: 1e-7,
            keep_out_margin_lu: 0.0,
            newton_max_iter: 60,
            refine_max_iter: 80,
            work_budget: DEFAULT_WORK_BUDGET,
        }
    }
}

impl Settings {
    /// Check every field against its documented range.
    ///
    /// # Errors
    /// [`SettingsError`] naming the first field class out of range.
    pub fn validate(&self) -> Result<(), SettingsError> {
        if self.sqp_max_iter == 0
            || self.qp_max_iter == 0
            || self.newton_max_iter == 0
            || self.refine_max_iter == 0
        {
            return Err(SettingsError::ZeroIterationLimit);
        }
        let positive = |v: f64| v.is_finite() && v > 0.0;
        if !positive(self.sqp_tol_cost)
            || !positive(self.sqp_tol_step_lu)
            || !positive(self.qp_tol_feas)
            || !positive(self.verify_tol_lu)
            || !self.keep_out_margin_lu.is_finite()
            || self.keep_out_margin_lu < 0.0
        {
            return Err(SettingsError::BadTolerance);
        }
        if usize::from(self.acceleration_memory) > super::anderson::MAX_MEMORY {
            return Err(SettingsError::AccelerationMemory);
        }
        if self.verify_max_rounds > MAX_VERIFY_ROUNDS {
            return Err(SettingsError::TooManyVerifyRounds);
        }
        Ok(())
    }
}
