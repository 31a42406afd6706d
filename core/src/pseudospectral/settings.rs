//! Planner-A settings: every loop bound and tolerance of a solve.

use crate::contract::{Range, SettingError};

/// Largest Anderson-acceleration memory (`acceleration_memory`).
pub const MAX_ACCELERATION_MEMORY: u8 = super::anderson::MAX_MEMORY as u8;

/// Most verification rounds a solve may be set to.
pub const MAX_VERIFY_ROUNDS: u8 = 8;

/// Default work budget, in units: `DEFAULT_WORK_BUDGET x MAX_INSTRUCTIONS_PER_UNIT` <= 400 M
/// Cortex-M7 instructions (`docs/planner-a.md`, "Work budget").
pub const DEFAULT_WORK_BUDGET: u64 = 40_000_000;

crate::settings_table! {
    /// Loop bounds and tolerances. Plain `Copy` data; all fields take effect per solve.
    ///
    /// The worst case of a solve is bounded by
    /// `(verify_max_rounds + 1) * sqp_max_iter * qp_max_iter` QP steps, each
    /// `O(MAX_ACTIVE^2 + M N (N - 3))` flops, and by the work budget (`docs/firmware.md`).
    pub struct Settings;
    /// Planner A's settings, by name (stable codes on the wire and in the C interface).
    pub enum SettingId for Pseudospectral;
    {
        /// Most convex subproblems (SQP / convex-concave iterations) per verification round.
        sqp_max_iter, SqpMaxIter = 0: u16 = 60,
        unit "", range Range::at_least(1.0), limit AtMost;
        /// Stop when the cost decreases by less than this, relative (`|dJ| <= tol (1 + J)`),
        /// between iterations.
        sqp_tol_cost, SqpTolCost = 1: f64 = 1e-8,
        unit "", range Range::positive(), limit AtMost;
        /// Or stop when the largest coefficient change (position scale) is below this, in LU.
        sqp_tol_step_lu, SqpTolStepLu = 2: f64 = 1e-10,
        unit "LU", range Range::positive(), limit AtMost;
        /// Anderson-acceleration memory of the convex-concave iteration (0 = plain iteration,
        /// at most 1).
        acceleration_memory, AccelerationMemory = 3: u8 = 1,
        unit "", range Range::closed(0.0, MAX_ACCELERATION_MEMORY as f64), limit AtMost;
        /// Follow each near-contact pair's continuous separation minimum with a moving check,
        /// and run the verification rounds. Off, the solver enforces keep-out only at the nodes
        /// and test points, as the paper does (the continuous minimum is still measured and
        /// reported).
        continuous_verification, ContinuousVerification = 4: bool = true,
        unit "", range Range::any(), limit MustBeOn;
        /// Most active-set changes per QP. Worst case: every candidate constraint enters once
        /// per drop, bounded by this number.
        qp_max_iter, QpMaxIter = 5: u16 = 400,
        unit "", range Range::at_least(1.0), limit AtMost;
        /// Constraint violation a QP accepts as satisfied, in the constraint's units (LU or FU).
        qp_tol_feas, QpTolFeas = 6: f64 = 1e-12,
        unit "", range Range::positive(), limit AtMost;
        /// Rounds of continuous verification: each finds the true minimum separation of every
        /// pair and adds a keep-out point where it is below d (while the pair has point
        /// capacity left, `MAX_VERIFY_POINTS_PER_PAIR - 1`; one is the moving check) or, where
        /// a dip persists, raises that pair's keep-out by the dip; then re-solves. At most
        /// `MAX_VERIFY_ROUNDS` (8).
        verify_max_rounds, VerifyMaxRounds = 7: u8 = 4,
        unit "", range Range::closed(0.0, MAX_VERIFY_ROUNDS as f64), limit AtMost;
        /// Continuous separation accepted as meeting the keep-out: `>= d - verify_tol_lu`.
        verify_tol_lu, VerifyTolLu = 8: f64 = 1e-7,
        unit "LU", range Range::positive(), limit AtMost;
        /// Enlarge the keep-out used in the constraints by this, in LU, so that the continuous
        /// minimum between check points stays at or above d.
        keep_out_margin_lu, KeepOutMarginLu = 9: f64 = 0.0,
        unit "LU", range Range::at_least(0.0), limit AtLeast;
        /// Newton iterations for LGL nodes and for the root-finds of the Pontryagin guess.
        newton_max_iter, NewtonMaxIter = 10: u16 = 60,
        unit "", range Range::at_least(1.0), limit AtMost;
        /// Bisection / Newton steps when refining a separation minimum between check points.
        refine_max_iter, RefineMaxIter = 11: u16 = 80,
        unit "", range Range::at_least(1.0), limit AtMost;
        /// Work budget of a solve, in work units (`crate::work`): past it the solve stops with
        /// `SolveStatus::BudgetExhausted`. Part of it is kept for the checks of the returned
        /// answer. No charged step costs more than `MAX_INSTRUCTIONS_PER_UNIT` (10) Cortex-M7
        /// instructions per unit, so the default bounds a solve to 400 M instructions
        /// (`docs/planner-a.md`, "Work budget").
        work_budget, WorkBudget = 12: u64 = DEFAULT_WORK_BUDGET,
        unit "units", range Range::any(), limit AtMost;
    }
}

impl Settings {
    /// Check every field against its documented range.
    ///
    /// # Errors
    /// [`SettingError`] naming the first setting out of range, its value and its range.
    pub fn validate(&self) -> Result<(), SettingError<SettingId>> {
        self.check_ranges()
    }
}
