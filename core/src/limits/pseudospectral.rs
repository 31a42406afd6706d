//! Planner-A limits: ceilings of the problem sizes, and the settings' limits (each setting's
//! rule is in its settings table, `pseudospectral::SettingId::limit_rule`).

use super::{at_most, LimitViolation, ProblemLimit, Setting};
use crate::capacity::{MAX_DEGREE, MAX_SPACECRAFT};
use crate::pseudospectral::{Problem, Settings};
use serde::{Deserialize, Serialize};

planner_limits! {
    /// Planner-A limits. Defaults: the compiled capacities and the default settings.
    pub struct Limits {
        /// Most spacecraft M.
        spacecraft: u8 = MAX_SPACECRAFT as u8,
        /// Highest polynomial degree N.
        nodes: u16 = MAX_DEGREE as u16,
        /// The most work and the least safety a request's settings may ask for, each by its
        /// setting's rule.
        settings: Settings = Settings::DEFAULT,
    }
}

impl Limits {
    /// Check a request's problem sizes and settings.
    ///
    /// # Errors
    /// The first [`LimitViolation`]: sizes first, then settings in declaration order.
    pub fn check(&self, problem: &Problem, settings: &Settings) -> Result<(), LimitViolation> {
        self.check_problem(problem)?;
        settings
            .check_limits(&self.settings)
            .map_err(|v| v.naming(Setting::from))
    }

    /// Check the problem sizes that bound a solve's loops (M and N), up to the compiled
    /// capacities.
    ///
    /// # Errors
    /// The first [`LimitViolation`].
    pub fn check_problem(&self, problem: &Problem) -> Result<(), LimitViolation> {
        at_most(
            Setting::Problem(ProblemLimit::Spacecraft),
            problem.spacecraft.len() as f64,
            f64::from(self.spacecraft),
        )?;
        // Above the compiled capacity the planner refuses the request itself, naming the
        // capacity (`CapacityExceeded`); a limit is the service's ceiling below it.
        if usize::from(problem.degree) > MAX_DEGREE {
            return Ok(());
        }
        at_most(
            Setting::Problem(ProblemLimit::Degree),
            f64::from(problem.degree),
            f64::from(self.nodes),
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::contract::Rule;
    use crate::pseudospectral::SettingId;

    fn check_settings(s: &Settings) -> Result<(), LimitViolation> {
        s.check_limits(&Limits::default().settings)
            .map_err(|v| v.naming(Setting::from))
    }

    #[test]
    fn defaults_pass_and_each_loosening_is_named() {
        assert_eq!(check_settings(&Settings::default()), Ok(()));
        let tighter = Settings {
            sqp_max_iter: 10,
            sqp_tol_cost: 1e-12,
            keep_out_margin_lu: 0.01,
            ..Settings::default()
        };
        assert_eq!(check_settings(&tighter), Ok(()));
        let e = check_settings(&Settings {
            qp_max_iter: 401,
            ..Settings::default()
        })
        .unwrap_err();
        assert_eq!(e.setting, Setting::Pseudospectral(SettingId::QpMaxIter));
        assert_eq!((e.value, e.limit, e.rule), (401.0, 400.0, Rule::AtMost));
        let e = check_settings(&Settings {
            continuous_verification: false,
            ..Settings::default()
        })
        .unwrap_err();
        assert_eq!(
            e.setting,
            Setting::Pseudospectral(SettingId::ContinuousVerification)
        );
        assert_eq!(e.rule, Rule::MustBeOn);
        let e = check_settings(&Settings {
            verify_tol_lu: 1e-3,
            ..Settings::default()
        })
        .unwrap_err();
        assert_eq!(
            (e.setting, e.value),
            (Setting::Pseudospectral(SettingId::VerifyTolLu), 1e-3)
        );
        // The audit's C request: a huge tolerance is refused by name (issue 33).
        let e = check_settings(&Settings {
            verify_tol_lu: 1e308,
            ..Settings::default()
        })
        .unwrap_err();
        assert_eq!(e.setting.name(), "verify_tol_lu");
        assert_eq!(e.limit, 1e-7);
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
            (Setting::Problem(ProblemLimit::Degree), 20.0, 16.0)
        );
        p.degree = 16;
        assert_eq!(l.check_problem(&p), Ok(()));
        // Over the capacity: left to the planner's own CapacityExceeded.
        p.degree = 25;
        assert_eq!(l.check_problem(&p), Ok(()));
    }
}
