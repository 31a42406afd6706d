//! Planner-A limits: ceilings of the loop bounds and problem sizes, floors of the safety
//! settings. One line per setting in [`Limits::check_settings`].

use super::{at_least, at_most, must_be_on, LimitViolation, Setting};
use crate::capacity::{MAX_DEGREE, MAX_SPACECRAFT};
use crate::pseudospectral::{Problem, Settings};
use serde::{Deserialize, Serialize};

/// Planner-A limits. Field names are the settings' names; each is the most (or, for
/// `keep_out_margin_lu`, the least) a request may ask for. Defaults: the default settings and
/// the compiled capacities.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct Limits {
    /// Most spacecraft M.
    pub spacecraft: u8,
    /// Highest polynomial degree N.
    pub nodes: u16,
    /// Most SQP iterations per verification round.
    pub sqp_max_iter: u16,
    /// Loosest relative cost tolerance.
    pub sqp_tol_cost: f64,
    /// Loosest step tolerance, LU.
    pub sqp_tol_step_lu: f64,
    /// Most Anderson-acceleration memory.
    pub acceleration_memory: u8,
    /// Continuous verification must be on.
    pub continuous_verification: bool,
    /// Most active-set changes per QP.
    pub qp_max_iter: u16,
    /// Loosest QP feasibility tolerance.
    pub qp_tol_feas: f64,
    /// Most verification rounds.
    pub verify_max_rounds: u8,
    /// Loosest accepted continuous separation shortfall, LU.
    pub verify_tol_lu: f64,
    /// Least keep-out margin, LU.
    pub keep_out_margin_lu: f64,
    /// Most Newton iterations (LGL nodes, guess root-finds).
    pub newton_max_iter: u16,
    /// Most refinement steps of a separation minimum.
    pub refine_max_iter: u16,
    /// Largest work budget, in work units.
    pub work_budget: u64,
}

impl Default for Limits {
    fn default() -> Self {
        let d = Settings::default();
        Self {
            spacecraft: MAX_SPACECRAFT as u8,
            nodes: MAX_DEGREE as u16,
            sqp_max_iter: d.sqp_max_iter,
            sqp_tol_cost: d.sqp_tol_cost,
            sqp_tol_step_lu: d.sqp_tol_step_lu,
            acceleration_memory: d.acceleration_memory,
            continuous_verification: d.continuous_verification,
            qp_max_iter: d.qp_max_iter,
            qp_tol_feas: d.qp_tol_feas,
            verify_max_rounds: d.verify_max_rounds,
            verify_tol_lu: d.verify_tol_lu,
            keep_out_margin_lu: d.keep_out_margin_lu,
            newton_max_iter: d.newton_max_iter,
            refine_max_iter: d.refine_max_iter,
            work_budget: d.work_budget,
        }
    }
}

impl Limits {
    /// Check a request's problem sizes and settings.
    ///
    /// # Errors
    /// The first [`LimitViolation`]: sizes first, then settings in declaration order.
    pub fn check(&self, problem: &Problem, settings: &Settings) -> Result<(), LimitViolation> {
        self.check_problem(problem)?;
        self.check_settings(settings)
    }

    /// Check the problem sizes that bound a solve's loops (M and N), up to the compiled
    /// capacities.
    ///
    /// # Errors
    /// The first [`LimitViolation`].
    pub fn check_problem(&self, problem: &Problem) -> Result<(), LimitViolation> {
        at_most(
            Setting::PsSpacecraftCount,
            problem.spacecraft.len() as f64,
            f64::from(self.spacecraft),
        )?;
        // Above the compiled capacity the planner refuses the request itself, naming the
        // capacity (`CapacityExceeded`); a limit is the service's ceiling below it.
        if usize::from(problem.degree) > MAX_DEGREE {
            return Ok(());
        }
        at_most(
            Setting::PsDegree,
            f64::from(problem.degree),
            f64::from(self.nodes),
        )
    }

    /// Check every setting, one line each.
    ///
    /// # Errors
    /// The first [`LimitViolation`].
    pub fn check_settings(&self, s: &Settings) -> Result<(), LimitViolation> {
        // No `..`: a new setting does not compile until it has its line here.
        let Settings {
            sqp_max_iter,
            sqp_tol_cost,
            sqp_tol_step_lu,
            acceleration_memory,
            continuous_verification,
            qp_max_iter,
            qp_tol_feas,
            verify_max_rounds,
            verify_tol_lu,
            keep_out_margin_lu,
            newton_max_iter,
            refine_max_iter,
            work_budget,
        } = *s;
        use Setting as S;
        let l = self;
        at_most(S::PsSqpMaxIter, sqp_max_iter.into(), l.sqp_max_iter.into())?;
        at_most(S::PsSqpTolCost, sqp_tol_cost, l.sqp_tol_cost)?;
        at_most(S::PsSqpTolStepLu, sqp_tol_step_lu, l.sqp_tol_step_lu)?;
        at_most(
            S::PsAccelerationMemory,
            acceleration_memory.into(),
            l.acceleration_memory.into(),
        )?;
        must_be_on(
            S::PsContinuousVerification,
            continuous_verification,
            l.continuous_verification,
        )?;
        at_most(S::PsQpMaxIter, qp_max_iter.into(), l.qp_max_iter.into())?;
        at_most(S::PsQpTolFeas, qp_tol_feas, l.qp_tol_feas)?;
        at_most(
            S::PsVerifyMaxRounds,
            verify_max_rounds.into(),
            l.verify_max_rounds.into(),
        )?;
        at_most(S::PsVerifyTolLu, verify_tol_lu, l.verify_tol_lu)?;
        at_least(
            S::PsKeepOutMarginLu,
            keep_out_margin_lu,
            l.keep_out_margin_lu,
        )?;
        at_most(
            S::PsNewtonMaxIter,
            newton_max_iter.into(),
            l.newton_max_iter.into(),
        )?;
        at_most(
            S::PsRefineMaxIter,
            refine_max_iter.into(),
            l.refine_max_iter.into(),
        )?;
        // Exact below 2^53 units (far above any budget).
        at_most(S::PsWorkBudget, work_budget as f64, l.work_budget as f64)?;
        Ok(())
    }
}

#[cfg(test)]
#[allow(clippy::unwrap_used, clippy::float_cmp)]
mod tests {
    use super::*;
    use crate::limits::Rule;

    #[test]
    fn defaults_pass_and_each_loosening_is_named() {
        let l = Limits::default();
        assert_eq!(l.check_settings(&Settings::default()), Ok(()));
        let tighter = Settings {
            sqp_max_iter: 10,
            sqp_tol_cost: 1e-12,
            keep_out_margin_lu: 0.01,
            ..Settings::default()
        };
        assert_eq!(l.check_settings(&tighter), Ok(()));
        let e = l
            .check_settings(&Settings {
                qp_max_iter: 401,
                ..Settings::default()
            })
            .unwrap_err();
        assert_eq!(e.setting, Setting::PsQpMaxIter);
        assert_eq!((e.value, e.limit, e.rule), (401.0, 400.0, Rule::AtMost));
        let e = l
            .check_settings(&Settings {
                continuous_verification: false,
                ..Settings::default()
            })
            .unwrap_err();
        assert_eq!(e.setting, Setting::PsContinuousVerification);
        assert_eq!(e.rule, Rule::MustBeOn);
        let e = l
            .check_settings(&Settings {
                verify_tol_lu: 1e-3,
                ..Settings::default()
            })
            .unwrap_err();
        assert_eq!((e.setting, e.value), (Setting::PsVerifyTolLu, 1e-3));
    }

    #[test]
    fn sizes_are_limited() {
        let l = Limits {
            spacecraft: 4,
            nodes: 16,
            ..Limits::default()
        };
        let mut p = Problem {
            horizon_tu: 1.0,
            max_control_fu: 1.0,
            keep_out_lu: 0.1,
            degree: 20,
            test_points: true,
            spacecraft: heapless::Vec::new(),
        };
        let e = l.check_problem(&p).unwrap_err();
        assert_eq!(
            (e.setting, e.value, e.limit),
            (Setting::PsDegree, 20.0, 16.0)
        );
        p.degree = 16;
        assert_eq!(l.check_problem(&p), Ok(()));
        // Over the capacity: left to the planner's own CapacityExceeded.
        p.degree = 25;
        assert_eq!(l.check_problem(&p), Ok(()));
    }
}
