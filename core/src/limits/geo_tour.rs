//! GEO-tour limits: ceilings of the loop bounds (Lambert, wells, roots, price, gap and exchange
//! search) and of the client count, tolerances no looser than the defaults, and the least
//! perigee radius of any intermediate orbit. One line per setting in
//! [`Limits::check_settings`]. The paper's rule thresholds and the direct Lambert time choose
//! methods; they change neither the work bound nor a safety check, so any value passes here
//! (the planner validates their ranges).

use super::{at_least, at_most, LimitViolation, Setting};
use crate::geo_tour::{Problem, Settings, MAX_TARGETS};
use serde::{Deserialize, Serialize};

/// GEO-tour limits. Field names are the settings' names; each is the most (for
/// `min_radius_km` the least) a request may ask for. Defaults: the default settings and the
/// compiled capacity.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct Limits {
    /// Most clients of one tour.
    pub targets: u8,
    /// Most whole revolutions of a Lambert transfer.
    pub lambert_max_revolutions: u16,
    /// Most Householder steps per Lambert solve.
    pub lambert_max_iter: u16,
    /// Loosest Lambert tolerance.
    pub lambert_tol: f64,
    /// Most golden-section steps per Lambert well.
    pub well_iterations: u16,
    /// Most steps of every 1-D root.
    pub root_max_iter: u16,
    /// Most steps of the time-price search.
    pub price_max_iter: u16,
    /// Loosest tolerance on the tour's time, s.
    pub time_tol_s: f64,
    /// Most legs tried both ways at the critical price.
    pub gap_max_legs: u8,
    /// Most rounds of the exchange search.
    pub exchange_rounds: u16,
    /// Largest margin under which Lambert wells are refined in the exchange search, m/s.
    pub exchange_margin_mps: f64,
    /// Least distance from Earth's centre of any intermediate orbit, km.
    pub min_radius_km: f64,
}

impl Default for Limits {
    fn default() -> Self {
        let d = Settings::default();
        Self {
            targets: MAX_TARGETS as u8,
            lambert_max_revolutions: d.lambert_max_revolutions,
            lambert_max_iter: d.lambert_max_iter,
            lambert_tol: d.lambert_tol,
            well_iterations: d.well_iterations,
            root_max_iter: d.root_max_iter,
            price_max_iter: d.price_max_iter,
            time_tol_s: d.time_tol_s,
            gap_max_legs: d.gap_max_legs,
            exchange_rounds: d.exchange_rounds,
            exchange_margin_mps: d.exchange_margin_mps,
            min_radius_km: d.min_radius_km,
        }
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
        at_most(Setting::GeoTargets, targets, f64::from(self.targets))?;
        self.check_settings(settings)
    }

    /// Check every setting, one line each.
    ///
    /// # Errors
    /// The first [`LimitViolation`].
    pub fn check_settings(&self, s: &Settings) -> Result<(), LimitViolation> {
        // No `..`: a new setting does not compile until it has its line here.
        let Settings {
            lambert_max_revolutions,
            lambert_max_iter,
            lambert_tol,
            well_iterations,
            root_max_iter,
            price_max_iter,
            time_tol_s,
            gap_max_legs,
            exchange_rounds,
            exchange_margin_mps,
            min_radius_km,
            rule_drift_above_rad: _,   // method choice only
            rule_hohmann_above_rad: _, // method choice only
            rule_radial_above_rad: _,  // method choice only
            lambert_direct_time_s: _,  // method choice only
        } = *s;
        use Setting as S;
        let l = self;
        let n = f64::from;
        at_most(
            S::GeoLambertMaxRevolutions,
            n(lambert_max_revolutions),
            n(l.lambert_max_revolutions),
        )?;
        at_most(
            S::GeoLambertMaxIter,
            n(lambert_max_iter),
            n(l.lambert_max_iter),
        )?;
        at_most(S::GeoLambertTol, lambert_tol, l.lambert_tol)?;
        at_most(
            S::GeoWellIterations,
            n(well_iterations),
            n(l.well_iterations),
        )?;
        at_most(S::GeoRootMaxIter, n(root_max_iter), n(l.root_max_iter))?;
        at_most(S::GeoPriceMaxIter, n(price_max_iter), n(l.price_max_iter))?;
        at_most(S::GeoTimeTolS, time_tol_s, l.time_tol_s)?;
        at_most(
            S::GeoGapMaxLegs,
            f64::from(gap_max_legs),
            f64::from(l.gap_max_legs),
        )?;
        at_most(
            S::GeoExchangeRounds,
            n(exchange_rounds),
            n(l.exchange_rounds),
        )?;
        at_most(
            S::GeoExchangeMarginMps,
            exchange_margin_mps,
            l.exchange_margin_mps,
        )?;
        at_least(S::GeoMinRadiusKm, min_radius_km, l.min_radius_km)
    }
}

#[cfg(test)]
#[allow(clippy::unwrap_used, clippy::float_cmp)]
mod tests {
    use super::*;
    use crate::limits::Rule;

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
            (Setting::GeoExchangeRounds, 60_000.0, 8.0, Rule::AtMost)
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
            (Setting::GeoMinRadiusKm, Rule::AtLeast)
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
            (Setting::GeoTargets, 3.0, 2.0)
        );
    }
}
