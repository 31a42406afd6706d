//! GEO-tour limits: the client count and the settings' limits (each setting's rule is in its
//! settings table, `geo_tour::SettingId::limit_rule`: ceilings of the loop bounds, tolerances
//! no looser than the defaults, the least perigee radius; the paper's rule thresholds and the
//! direct Lambert time choose methods and have no limit).

use super::{at_most, LimitViolation, ProblemLimit, Setting};
use crate::geo_tour::{Problem, Settings, MAX_TARGETS};
use serde::{Deserialize, Serialize};

planner_limits! {
    /// GEO-tour limits. Defaults: the compiled capacity and the default settings.
    pub struct Limits {
        /// Most clients of one tour.
        targets: u8 = MAX_TARGETS as u8,
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
        // The client list's capacity is in its type; the limit may be lower.
        let targets = problem.targets_lon_rad.len() as f64;
        at_most(
            Setting::Problem(ProblemLimit::Targets),
            targets,
            f64::from(self.targets),
        )?;
        settings
            .check_limits(&self.settings)
            .map_err(|v| v.naming(Setting::from))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::contract::Rule;
    use crate::geo_tour::SettingId;

    impl Limits {
        fn check_settings(&self, s: &Settings) -> Result<(), LimitViolation> {
            s.check_limits(&self.settings)
                .map_err(|v| v.naming(Setting::from))
        }
    }

    #[test]
    fn defaults_pass_and_a_loosened_setting_is_named() {
        let l = Limits::default();
        assert_eq!(l.check_settings(&Settings::default()), Ok(()));
        let e = l
            .check_settings(&Settings {
                exchange_rounds: 60_000,
                ..Settings::default()
            })
            .unwrap_err();
        assert_eq!(
            (e.setting, e.value, e.limit, e.rule),
            (
                Setting::GeoTour(SettingId::ExchangeRounds),
                60_000.0,
                8.0,
                Rule::AtMost
            )
        );
        assert_eq!(e.setting.name(), "exchange_rounds");
        let e = l
            .check_settings(&Settings {
                min_radius_km: 6378.0,
                ..Settings::default()
            })
            .unwrap_err();
        assert_eq!(
            (e.setting, e.rule),
            (Setting::GeoTour(SettingId::MinRadiusKm), Rule::AtLeast)
        );
        let tighter = Settings {
            lambert_max_revolutions: 1,
            price_max_iter: 20,
            min_radius_km: 7000.0,
            ..Settings::default()
        };
        assert_eq!(l.check_settings(&tighter), Ok(()));
    }

    #[test]
    fn client_count_above_the_limit_is_named() {
        let l = Limits {
            targets: 2,
            ..Limits::default()
        };
        let mut targets = heapless::Vec::new();
        for lon in [0.1, 0.2, 0.3] {
            targets.push(lon).unwrap();
        }
        let p = Problem {
            start_lon_rad: 0.0,
            targets_lon_rad: targets,
            mission_time_s: 86_400.0 * 60.0,
            max_burn_mps: 5.0,
            sweep: crate::geo_tour::SweepChoice::Cheaper,
            policy: crate::geo_tour::MethodPolicy::ByCost,
        };
        let e = l.check(&p, &Settings::default()).unwrap_err();
        assert_eq!(
            (e.setting, e.value, e.limit),
            (Setting::Problem(ProblemLimit::Targets), 3.0, 2.0)
        );
    }
}
