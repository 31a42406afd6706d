//! Planner-B settings: every loop bound, tolerance and threshold of a solve.

use crate::astro::EARTH_RADIUS_KM;
use crate::contract::{check_range, Range, SettingError, SettingValue};
use serde::{Deserialize, Serialize};

/// Largest semi-major axis accepted, km. Beyond 100 000 km (about 2.4 GEO radii) the Moon's and
/// the Sun's gravity exceed J2 by orders of magnitude and the J2-only model no longer describes
/// the motion; the limit also keeps `a^7` (the J2 rate) far from overflow.
pub const MAX_SMA_KM: f64 = 100_000.0;

/// Most local searches the impulse-point search runs (workspace capacity).
pub const MAX_SEARCH_STARTS: usize = 16;

crate::settings_table! {
    /// Loop bounds, tolerances and thresholds. Plain `Copy` data; every field takes effect per
    /// solve (there is no set-up step).
    ///
    /// Worst case of a fixed-point solve (`N <= MAX_IMPULSES` impulses; a "propagation" is N
    /// Kepler solves of at most `kepler_max_iter` Newton steps; an "SVD" is at most
    /// `svd_max_iter` Jacobi sweeps of 15 rotations on the 6 x 3N matrix F):
    /// * minimum-norm phase: `fixed_point_max_iter` x (propagation + F + one Cholesky, or one
    ///   SVD when Cholesky declines);
    /// * min-fuel phase (`min_fuel`): `fixed_point_max_iter` x (propagation + F + Cholesky/SVD +
    ///   one cone program: a 6-row Gram-Schmidt, then at most `min_fuel_max_iter`
    ///   interior-point iterations of one 6 x 6 Cholesky and two solves each);
    /// * correction (`nonlinear_correction`): one exact propagation, `3N` exact propagations for
    ///   the finite-difference Jacobian, then `correction_max_iter` x (Cholesky/SVD + exact
    ///   propagation + rank-one update);
    /// * report: one linear propagation and one SVD (rank and condition at the returned plan),
    ///   one exact propagation (the nonlinear re-check and the transfer arcs' perigees).
    ///
    /// A search runs at most `search_max_evaluations` evaluations, each at most
    /// `search_fixed_point_max_iter` linearisations (propagation + F + one Cholesky or SVD) and
    /// one cone program (as above), then one full fixed-point solve as above.
    pub struct Settings;
    /// Planner B's settings, by name (stable codes on the wire and in the C interface).
    pub enum SettingId for Impulsive;
    {
        /// Most fixed-point iterations (Wang 2018, section 2), per phase (minimum norm, min
        /// fuel).
        fixed_point_max_iter, FixedPointMaxIter = 0: u16 = 60,
        unit "", range Range::at_least(1.0), limit AtMost;
        /// The fixed point has converged when no impulse component changes by more than this,
        /// m/s.
        fixed_point_tol_mps, FixedPointTolMps = 1: f64 = 1e-7,
        unit "m/s", range Range::positive(), limit AtMost;
        /// Replace the minimum-norm impulses by the least `sum_k |dv_k|` subject to `F dv = dY`
        /// (a second-order cone program, exact), iterated jointly with the fixed point. The
        /// limit says whether a request may switch this work on.
        min_fuel, MinFuel = 2: bool = true,
        unit "", range Range::any(), limit MustBeOff;
        /// Most interior-point iterations of one least-fuel cone program.
        min_fuel_max_iter, MinFuelMaxIter = 3: u16 = 40,
        unit "", range Range::at_least(1.0), limit AtMost;
        /// The joint min-fuel fixed point has converged when the total changes by less than
        /// this between fixed-point iterations, m/s.
        min_fuel_step_tol_mps, MinFuelStepTolMps = 4: f64 = 1e-8,
        unit "m/s", range Range::positive(), limit AtMost;
        /// A least-fuel cone program is optimal when its certified gap (feasible total minus
        /// the dual lower bound) is below this, m/s.
        min_fuel_tol_mps, MinFuelTolMps = 5: f64 = 1e-9,
        unit "m/s", range Range::positive(), limit AtMost;
        /// Drive the terminal error of the nonlinear model (exact impulses, J2 secular drift)
        /// to `correction_tol` by Broyden's method started from a finite-difference Jacobian.
        /// Off, the plan is the linear model's fixed point and its status
        /// `Linearised { miss_m }`.
        nonlinear_correction, NonlinearCorrection = 6: bool = true,
        unit "", range Range::any(), limit MustBeOn;
        /// Most nonlinear-correction (Broyden) steps. The paper's points need 2; near-circular
        /// orbits (e = 1e-3) 4-5.
        correction_max_iter, CorrectionMaxIter = 7: u16 = 12,
        unit "", range Range::at_least(1.0), limit AtMost;
        /// Accepted terminal error: largest of `|da|/a`, `|de|`, `|di|`, `|dOmega|`,
        /// `|domega|`, `|dM|` (dimensionless / rad).
        correction_tol, CorrectionTol = 8: f64 = 1e-12,
        unit "", range Range::positive(), limit AtMost;
        /// Most Newton steps for Kepler's equation: no accepted orbit needs more than
        /// `kepler::WORST_NEWTON_STEPS` (10); a transfer arc beyond the accepted eccentricities
        /// that needs more is a `Kepler` failure, not unbounded work.
        kepler_max_iter, KeplerMaxIter = 9: u16 = 12,
        unit "", range Range::at_least(1.0), limit AtMost;
        /// Most Jacobi sweeps of one SVD (one-sided Jacobi converges quadratically: the cases
        /// take 4; 200 until 27 Nov). Each sweep is charged, and the final reserve keeps SVDs at
        /// this many.
        svd_max_iter, SvdMaxIter = 10: u16 = 30,
        unit "", range Range::at_least(1.0), limit AtMost;
        /// Singular values below `rank_rcond * sigma_max` count as zero (rank, pseudo-inverse).
        rank_rcond, RankRcond = 11: f64 = 1e-10,
        unit "", range Range::open(0.0, 1.0), limit AtLeast;
        /// Classical set only: reject (and stop at) eccentricities below this (the GVE's `1/e`
        /// terms); the equinoctial set has no such limit.
        min_eccentricity, MinEccentricity = 12: f64 = 1e-4,
        unit "", range Range::open(0.0, 1.0), limit AtLeast;
        /// Reject (and stop at) `|sin i|` below this: the GVE's `1/sin i` terms. In the
        /// equinoctial set, only a retrograde orbit (`cos i < 0`) this close to equatorial is
        /// refused, and a chief with `|sin i|` below it has its impulse points in mean
        /// longitude.
        min_sin_inclination, MinSinInclination = 13: f64 = 1e-3,
        unit "", range Range::open(0.0, 1.0), limit AtLeast;
        /// Largest sum of revolution counts accepted, for fixed points and a search's limit.
        max_total_revolutions, MaxTotalRevolutions = 14: i32 = 100,
        unit "", range Range::at_least(0.0), limit AtMost;
        /// Lowest perigee altitude `a (1 - e) - Re` accepted, km: for the chief, the deputy's
        /// initial and target orbits (rejected with `PlanError::PerigeeTooLow`) and every
        /// transfer arc of the returned plan (`SolveStatus::UnsafePerigee`). Also sets the
        /// smallest semi-major axis, `Re + min_perigee_altitude_km`.
        min_perigee_altitude_km, MinPerigeeAltitudeKm = 15: f64 = 100.0,
        unit "km", range Range::closed_open(0.0, MAX_SMA_KM - EARTH_RADIUS_KM), limit AtLeast;
        /// Random impulse-point samples the search evaluates before its local searches (at
        /// least `search_starts`, below `search_max_evaluations`).
        search_samples, SearchSamples = 16: u32 = 400,
        unit "", range Range::any(), limit AtMost;
        /// Local pattern searches, started from the best samples (at most
        /// [`MAX_SEARCH_STARTS`]).
        search_starts, SearchStarts = 17: u8 = 8,
        unit "", range Range::closed(1.0, MAX_SEARCH_STARTS as f64), limit AtMost;
        /// Most evaluations of a search (samples plus local searches). A local search that
        /// converges early hands its unused budget to the next start, so a search uses between
        /// `search_samples` and this many; the bound depends on the settings alone.
        search_max_evaluations, SearchMaxEvaluations = 18: u32 = 1_800,
        unit "", range Range::at_least(1.0), limit AtMost;
        /// Seed of the search's xorshift generator (any seed: it picks samples, not how many).
        search_seed, SearchSeed = 19: u64 = 0x5741_4e47_2018_0006,
        unit "", range Range::any(), limit Free;
        /// First pattern step of a local search, rad of argument of latitude.
        search_step_rad, SearchStepRad = 20: f64 = 0.25,
        unit "rad", range Range::positive(), limit AtMost;
        /// A local search ends when its step falls below this, rad.
        search_min_step_rad, SearchMinStepRad = 21: f64 = 1e-4,
        unit "rad", range Range::positive(), limit AtMost;
        /// Linearisations per local-search evaluation (the first at zero impulses, each next
        /// one at the previous one's minimum-norm impulses); samples use one.
        search_fixed_point_max_iter, SearchFixedPointMaxIter = 22: u16 = 1,
        unit "", range Range::at_least(1.0), limit AtMost;
        /// Least-fuel tolerance of a sample's cone program (screening), m/s.
        search_screen_tol_mps, SearchScreenTolMps = 23: f64 = 1e-3,
        unit "m/s", range Range::positive(), limit AtMost;
        /// Least-fuel tolerance of a local-search evaluation's cone program, m/s.
        search_tol_mps, SearchTolMps = 24: f64 = 1e-7,
        unit "m/s", range Range::positive(), limit AtMost;
        /// The mean-element set the drift, the impulse matrix, the fixed point and the
        /// nonlinear correction are written in. [`ElementSet::Equinoctial`] (default) is
        /// regular at e = 0 and i = 0; [`ElementSet::Classical`] is the paper's set
        /// (paper-reproduction mode: its linearised numbers to the digit), which refuses
        /// e < `min_eccentricity` and `|sin i| < min_sin_inclination`. Corrected plans agree
        /// between the two (the exact end condition does not depend on the coordinates).
        element_set, ElementSet = 25: ElementSet = ElementSet::Equinoctial,
        unit "", range Range::any(), limit Free;
        /// Work budget of a solve, in work units (`crate::work`): past it the solve stops with
        /// `SolveStatus::BudgetExhausted`. Part of it is kept for the final solve after a
        /// search and for the checks of the returned plan. The default bounds the worst request
        /// within the default limits to 400 M Cortex-M7 instructions (`docs/firmware.md`,
        /// "Work budget").
        work_budget, WorkBudget = 26: u64 = DEFAULT_WORK_BUDGET,
        unit "units", range Range::any(), limit AtMost;
    }
}

/// The working mean-element set of planner B (see `Settings::element_set`).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
#[repr(u8)]
pub enum ElementSet {
    /// `[a, e, i, Omega, omega, M]`, Wang 2018's sigma: singular at e = 0 and sin i = 0.
    Classical = 0,
    /// `[a, lambda, e cos(omega + Omega), e sin(omega + Omega), tan(i/2) cos Omega,
    /// tan(i/2) sin Omega]`: regular except at i = pi.
    Equinoctial = 1,
}

impl SettingValue for ElementSet {
    fn to_f64(self) -> f64 {
        f64::from(self as u8)
    }
    fn from_f64(value: f64) -> Option<Self> {
        match u8::from_f64(value)? {
            0 => Some(Self::Classical),
            1 => Some(Self::Equinoctial),
            _ => None,
        }
    }
}

/// Default work budget, in units (`docs/firmware.md`, "Work budget").
pub const DEFAULT_WORK_BUDGET: u64 = 18_900_000;

impl Settings {
    /// The paper-reproduction settings: the paper's classical elements, with the defaults
    /// otherwise (combine with [`Settings::fixed_point_only`]'s switches for the paper's
    /// linearised numbers).
    pub fn paper_classical() -> Self {
        Self {
            element_set: ElementSet::Classical,
            ..Self::default()
        }
    }

    /// The fixed-point plan alone: the defaults without the least-fuel refinement and without
    /// the nonlinear defect correction (Wang 2018's eq. 14 iterated to its fixed point). This is
    /// the plan the on-board instruction budget (2 M) is set for.
    pub fn fixed_point_only() -> Self {
        Self {
            min_fuel: false,
            nonlinear_correction: false,
            ..Self::default()
        }
    }
}

impl Settings {
    /// Check every field against its range, then the search's counts against each other
    /// (`search_starts <= search_samples < search_max_evaluations`).
    ///
    /// # Errors
    /// [`SettingError`] naming the first setting out of range, its value and its range.
    pub fn validate(&self) -> Result<(), SettingError<SettingId>> {
        self.check_ranges()?;
        check_range(
            SettingId::SearchSamples,
            f64::from(self.search_samples),
            Range::closed_open(
                f64::from(self.search_starts),
                f64::from(self.search_max_evaluations),
            ),
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The refused setting and its value.
    fn refused(s: &Settings) -> (SettingId, f64) {
        let e = s.validate().unwrap_err();
        (e.setting, e.value)
    }

    #[test]
    fn default_is_valid_and_each_refusal_is_named() {
        assert_eq!(Settings::default().validate(), Ok(()));
        let s = Settings {
            kepler_max_iter: 0,
            ..Settings::default()
        };
        assert_eq!(refused(&s), (SettingId::KeplerMaxIter, 0.0));
        let s = Settings {
            correction_tol: f64::NAN,
            ..Settings::default()
        };
        let e = s.validate().unwrap_err();
        assert_eq!(e.setting, SettingId::CorrectionTol);
        assert!(e.value.is_nan());
        let s = Settings {
            min_eccentricity: 0.0,
            ..Settings::default()
        };
        assert_eq!(refused(&s), (SettingId::MinEccentricity, 0.0));
        for bad in [-1.0, f64::INFINITY, 1e6] {
            let s = Settings {
                min_perigee_altitude_km: bad,
                ..Settings::default()
            };
            assert_eq!(refused(&s), (SettingId::MinPerigeeAltitudeKm, bad));
        }
        let s = Settings {
            search_starts: 200,
            ..Settings::default()
        };
        let e = s.validate().unwrap_err();
        assert_eq!((e.setting, e.value), (SettingId::SearchStarts, 200.0));
        assert_eq!(e.range.max, MAX_SEARCH_STARTS as f64);
        let s = Settings {
            search_samples: 20_000,
            ..Settings::default()
        };
        let e = s.validate().unwrap_err();
        assert_eq!(
            (e.setting, e.value, e.range.max),
            (SettingId::SearchSamples, 20_000.0, 1800.0)
        );
    }

    #[test]
    fn every_setting_round_trips_through_its_number() {
        let d = Settings {
            // The default seed is above 2^53, where f64 no longer holds every integer.
            search_seed: 12_345,
            ..Settings::default()
        };
        for &id in SettingId::ALL {
            let mut s = d;
            assert!(s.set(id, d.value(id)), "{}", id.name());
            assert_eq!(s, d, "{}", id.name());
            assert_eq!(SettingId::from_code(id as u8), Some(id));
        }
    }
}
