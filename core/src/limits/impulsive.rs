//! Planner-B limits: the impulse count, whether a search is allowed, and the settings'
//! limits (each setting's rule is in its settings table, `impulsive::SettingId::limit_rule`:
//! ceilings of the loop bounds and of the search, floors of the singularity thresholds, the
//! nonlinear correction required, the least-fuel refinement allowed or not).

use super::{allowed, at_most, LimitViolation, ProblemLimit, Setting};
use crate::capacity::MAX_IMPULSES;
use crate::impulsive::{ImpulsePlan, Problem, Settings};
use serde::{Deserialize, Serialize};

planner_limits! {
    /// Planner-B limits. Defaults: the compiled capacity, searches allowed, the default settings.
    pub struct Limits {
        /// Most impulses (fixed points, or a search's count).
        impulses: u8 = MAX_IMPULSES as u8,
        /// A request may ask for an impulse-point search.
        search: bool = true,
        /// The most work and the least safety a request's settings may ask for.
        settings: Settings = Settings::DEFAULT,
    }
}

impl Limits {
    /// Check a request's problem and settings.
    ///
    /// # Errors
    /// The first [`LimitViolation`]: the problem first, then settings in declaration order.
    pub fn check(&self, problem: &Problem, settings: &Settings) -> Result<(), LimitViolation> {
        self.check_problem(problem)?;
        self.check_settings(settings)
    }

    /// Check the impulse count and whether a search is allowed.
    ///
    /// # Errors
    /// The first [`LimitViolation`].
    pub fn check_problem(&self, problem: &Problem) -> Result<(), LimitViolation> {
        self.check_plan(&problem.plan)
    }

    /// Check a plan's impulse count and whether a search is allowed.
    ///
    /// # Errors
    /// The first [`LimitViolation`].
    pub fn check_plan(&self, plan: &ImpulsePlan) -> Result<(), LimitViolation> {
        let impulses = match plan {
            ImpulsePlan::Fixed(points) => points.len() as f64,
            ImpulsePlan::Search { impulses, .. } => {
                allowed(Setting::Problem(ProblemLimit::Search), true, self.search)?;
                // Above the capacity the planner refuses the request itself, naming it.
                if usize::from(*impulses) > MAX_IMPULSES {
                    return Ok(());
                }
                f64::from(*impulses)
            }
        };
        at_most(
            Setting::Problem(ProblemLimit::Impulses),
            impulses,
            f64::from(self.impulses),
        )
    }

    /// Check every setting against its limit.
    ///
    /// # Errors
    /// The first [`LimitViolation`], in declaration order.
    pub fn check_settings(&self, s: &Settings) -> Result<(), LimitViolation> {
        s.check_limits(&self.settings)
            .map_err(|v| v.naming(Setting::from))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::contract::Rule;
    use crate::impulsive::SettingId;

    #[test]
    fn defaults_pass_and_the_issue_request_is_named() {
        let l = Limits::default();
        assert_eq!(l.check_settings(&Settings::default()), Ok(()));
        assert_eq!(
            l.check_settings(&Settings::fixed_point_only()),
            Err(LimitViolation {
                setting: Setting::Impulsive(SettingId::NonlinearCorrection),
                value: 0.0,
                limit: 1.0,
                rule: Rule::MustBeOn,
            })
        );
        let e = l
            .check_settings(&Settings {
                search_samples: 2_000_000,
                search_max_evaluations: 4_000_000,
                ..Settings::default()
            })
            .unwrap_err();
        assert_eq!(
            (e.setting, e.value, e.limit, e.rule),
            (
                Setting::Impulsive(SettingId::SearchSamples),
                2e6,
                400.0,
                Rule::AtMost
            )
        );
        let e = l
            .check_settings(&Settings {
                search_max_evaluations: u32::MAX,
                ..Settings::default()
            })
            .unwrap_err();
        assert_eq!(e.value, 4_294_967_295.0);
        let e = l
            .check_settings(&Settings {
                min_eccentricity: 1e-9,
                ..Settings::default()
            })
            .unwrap_err();
        assert_eq!(
            (e.setting, e.rule),
            (
                Setting::Impulsive(SettingId::MinEccentricity),
                Rule::AtLeast
            )
        );
        let e = l
            .check_settings(&Settings {
                min_perigee_altitude_km: 50.0,
                ..Settings::default()
            })
            .unwrap_err();
        assert_eq!(
            (e.setting, e.value, e.limit, e.rule),
            (
                Setting::Impulsive(SettingId::MinPerigeeAltitudeKm),
                50.0,
                100.0,
                Rule::AtLeast
            )
        );
        let tighter = Settings {
            fixed_point_max_iter: 5,
            correction_tol: 1e-14,
            min_fuel: false,
            search_samples: 100,
            search_max_evaluations: 200,
            min_perigee_altitude_km: 300.0,
            ..Settings::default()
        };
        assert_eq!(l.check_settings(&tighter), Ok(()));
    }

    #[test]
    fn searches_can_be_forbidden() {
        let l = Limits {
            search: false,
            ..Limits::default()
        };
        let zero = crate::impulsive::RelativeElements::default();
        let p = Problem {
            chief: crate::impulsive::MeanElements {
                sma_km: 7000.0,
                ecc: 0.01,
                inc_rad: 1.0,
                raan_rad: 0.0,
                argp_rad: 0.0,
                mean_anomaly_rad: 0.0,
            },
            initial: zero,
            target: zero,
            plan: ImpulsePlan::Search {
                impulses: 3,
                max_revolutions: 10,
            },
        };
        let e = l.check_problem(&p).unwrap_err();
        assert_eq!(
            (e.setting, e.rule),
            (Setting::Problem(ProblemLimit::Search), Rule::MustBeOff)
        );
        assert_eq!(Limits::default().check_problem(&p), Ok(()));
    }
}
