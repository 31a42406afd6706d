//! Planner-B settings: every loop bound, tolerance and threshold of a solve.

use super::elements::EARTH_RADIUS_KM;
use super::error::{SettingsError, MAX_SMA_KM};
use serde::{Deserialize, Serialize};

/// Most local searches the impulse-point search runs (workspace capacity).
pub const MAX_SEARCH_STARTS: usize = 16;

/// Loop bounds, tolerances and thresholds. Plain `Copy` data; every field takes effect per
/// solve (there is no set-up step).
///
/// Worst case of a fixed-point solve (`N <= MAX_IMPULSES` impulses; a "propagation" is N
/// Kepler solves of at most `kepler_max_iter` Newton steps; an "SVD" is at most
/// `svd_max_iter` Jacobi sweeps of 15 rotations on the 6 x 3N matrix F):
/// * minimum-norm phase: `fixed_point_max_iter` x (propagation + F + one Cholesky, or one SVD
///   when Cholesky declines);
/// * min-fuel phase (`min_fuel`): `fixed_point_max_iter` x (propagation + F + Cholesky/SVD +
///   one cone program: a 6-row Gram-Schmidt, then at most `min_fuel_max_iter` interior-point
///   iterations of one 6 x 6 Cholesky and two solves each);
/// * correction (`nonlinear_correction`): one exact propagation, `3N` exact propagations for
///   the finite-difference Jacobian, then `correction_max_iter` x (Cholesky/SVD + exact
///   propagation + rank-one update);
/// * report: one linear propagation and one SVD (rank and condition at the returned plan), one
///   exact propagation (the nonlinear re-check and the transfer arcs' perigees).
///
/// A search runs at most `search_max_evaluations` evaluations, each at most
/// `search_fixed_point_max_iter` linearisations (propagation + F + one Cholesky or SVD) and one
/// cone program (as above), then one full fixed-point solve as above.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct Settings {
    /// Most fixed-point iterations (Wang 2018, section 2), per phase (minimum norm, min fuel).
    pub fixed_point_max_iter: u16,
    /// The fixed point has converged when no impulse component changes by more than this, m/s.
    pub fixed_point_tol_mps: f64,
    /// Replace the minimum-norm impulses by the least `sum_k |dv_k|` subject to `F dv = dY`
    /// (a second-order cone program, exact), iterated jointly with the fixed point.
    pub min_fuel: bool,
    /// Most interior-point iterations of one least-fuel cone program.
    pub min_fuel_max_iter: u16,
    /// The joint min-fuel fixed point has converged when the total changes by less than this
    /// between fixed-point iterations, m/s.
    pub min_fuel_step_tol_mps: f64,
    /// A least-fuel cone program is optimal when its certified gap (feasible total minus the
    /// dual lower bound) is below this, m/s.
    pub min_fuel_tol_mps: f64,
    /// Drive the terminal error of the nonlinear model (exact impulses, J2 secular drift) to
    /// `correction_tol` by Broyden's method started from a finite-difference Jacobian. Off,
    /// the plan is the linear model's fixed point and its status `Linearised { miss_m }`.
    pub nonlinear_correction: bool,
    /// Most nonlinear-correction (Broyden) steps. The paper's points need 2; near-circular
    /// orbits (e = 1e-3) 4-5.
    pub correction_max_iter: u16,
    /// Accepted terminal error: largest of `|da|/a`, `|de|`, `|di|`, `|dOmega|`, `|domega|`,
    /// `|dM|` (dimensionless / rad).
    pub correction_tol: f64,
    /// Most Newton steps for Kepler's equation.
    pub kepler_max_iter: u16,
    /// Most implicit-shift QR steps of one SVD.
    pub svd_max_iter: u16,
    /// Singular values below `rank_rcond * sigma_max` count as zero (rank, pseudo-inverse).
    pub rank_rcond: f64,
    /// Classical set only: reject (and stop at) eccentricities below this (the GVE's `1/e`
    /// terms); the equinoctial set has no such limit.
    pub min_eccentricity: f64,
    /// Reject (and stop at) `|sin i|` below this: the GVE's `1/sin i` terms. In the
    /// equinoctial set, only a retrograde orbit (`cos i < 0`) this close to equatorial is
    /// refused, and a chief with `|sin i|` below it has its impulse points in mean longitude.
    pub min_sin_inclination: f64,
    /// Largest sum of revolution counts accepted, for fixed points and a search's limit.
    pub max_total_revolutions: i32,
    /// Lowest perigee altitude `a (1 - e) - Re` accepted, km: for the chief, the deputy's
    /// initial and target orbits (rejected with `PlanError::PerigeeTooLow`) and every transfer
    /// arc of the returned plan (`SolveStatus::UnsafePerigee`). Also sets the smallest
    /// semi-major axis, `Re + min_perigee_altitude_km`. In `[0, MAX_SMA_KM - Re)`.
    pub min_perigee_altitude_km: f64,
    /// Random impulse-point samples the search evaluates before its local searches.
    pub search_samples: u32,
    /// Local pattern searches, started from the best samples (at most [`MAX_SEARCH_STARTS`]).
    pub search_starts: u8,
    /// Most evaluations of a search (samples plus local searches). A local search that
    /// converges early hands its unused budget to the next start, so a search uses between
    /// `search_samples` and this many; the bound depends on the settings alone.
    pub search_max_evaluations: u32,
    /// Seed of the search's xorshift generator.
    pub search_seed: u64,
    /// First pattern step of a local search, rad of argument of latitude.
    pub search_step_rad: f64,
    /// A local search ends when its step falls below this, rad.
    pub search_min_step_rad: f64,
    /// Linearisations per local-search evaluation (the first at zero impulses, each next one
    /// at the previous one's minimum-norm impulses); samples use one.
    pub search_fixed_point_max_iter: u16,
    /// Least-fuel tolerance of a sample's cone program (screening), m/s.
    pub search_screen_tol_mps: f64,
    /// Least-fuel tolerance of a local-search evaluation's cone program, m/s.
    pub search_tol_mps: f64,
    /// The mean-element set the drift, the impulse matrix, the fixed point and the nonlinear
    /// correction are written in. [`ElementSet::Equinoctial`] (default) is regular at e = 0
    /// and i = 0; [`ElementSet::Classical`] is the paper's set (paper-reproduction mode: its
    /// linearised numbers to the digit), which refuses e < `min_eccentricity` and
    /// `|sin i| < min_sin_inclination`. Corrected plans agree between the two (the exact end
    /// condition does not depend on the coordinates).
    pub element_set: ElementSet,
    /// Work budget of a solve, in work units (`crate::work`): past it the solve stops with
    /// `SolveStatus::BudgetExhausted`. Part of it is kept for the final solve after a search
    /// and for the checks of the returned plan. The default bounds the worst request within
    /// the default limits to 400 M Cortex-M7 instructions (`docs/firmware.md`, "Work budget").
    pub work_budget: u64,
}

/// The working mean-element set of planner B (see `Settings::element_set`).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum ElementSet {
    /// `[a, e, i, Omega, omega, M]`, Wang 2018's sigma: singular at e = 0 and sin i = 0.
    Classical,
    /// `[a, lambda, e cos(omega + Omega), e sin(omega + Omega), tan(i/2) cos Omega,
    /// tan(i/2) sin Omega]`: regular except at i = pi.
    Equinoctial,
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

impl Default for Settings {
    fn default() -> Self {
        Self {
            fixed_point_max_iter: 60,
            fixed_point_tol_mps: 1e-7,
            min_fuel: true,
            min_fuel_max_iter: 40,
            min_fuel_step_tol_mps: 1e-8,
            min_fuel_tol_mps: 1e-9,
            nonlinear_correction: true,
            correction_max_iter: 12,
            correction_tol: 1e-12,
            kepler_max_iter: 30,
            svd_max_iter: 200,
            rank_rcond: 1e-10,
            min_eccentricity: 1e-4,
            min_sin_inclination: 1e-3,
            max_total_revolutions: 100,
            min_perigee_altitude_km: 100.0,
            search_samples: 400,
            search_starts: 8,
            search_max_evaluations: 1_800,
            search_seed: 0x5741_4e47_2018_0006,
            search_step_rad: 0.25,
            search_min_step_rad: 1e-4,
            search_fixed_point_max_iter: 1,
            search_screen_tol_mps: 1e-3,
            search_tol_mps: 1e-7,
            element_set: ElementSet::Equinoctial,
            work_budget: DEFAULT_WORK_BUDGET,
        }
    }
}

impl Settings {
    /// Check every field against its documented range.
    ///
    /// # Errors
    /// [`SettingsError`] naming the first class of field out of range.
    pub fn validate(&self) -> Result<(), SettingsError> {
        if self.fixed_point_max_iter == 0
            || self.min_fuel_max_iter == 0
            || self.correction_max_iter == 0
            || self.kepler_max_iter == 0
            || self.svd_max_iter == 0
            || self.search_fixed_point_max_iter == 0
            || self.search_max_evaluations == 0
        {
            return Err(SettingsError::ZeroIterationLimit);
        }
        let positive = |v: f64| v.is_finite() && v > 0.0;
        if !positive(self.fixed_point_tol_mps)
            || !positive(self.min_fuel_tol_mps)
            || !positive(self.min_fuel_step_tol_mps)
            || !positive(self.correction_tol)
            || !positive(self.search_step_rad)
            || !positive(self.search_min_step_rad)
            || !positive(self.search_screen_tol_mps)
            || !positive(self.search_tol_mps)
            || !(self.rank_rcond.is_finite() && self.rank_rcond > 0.0 && self.rank_rcond < 1.0)
        {
            return Err(SettingsError::BadTolerance);
        }
        let in_unit = |v: f64| v.is_finite() && v > 0.0 && v < 1.0;
        if !in_unit(self.min_eccentricity)
            || !in_unit(self.min_sin_inclination)
            || self.max_total_revolutions < 0
            || !(0.0..MAX_SMA_KM - EARTH_RADIUS_KM).contains(&self.min_perigee_altitude_km)
        {
            return Err(SettingsError::BadThreshold);
        }
        if self.search_starts == 0
            || usize::from(self.search_starts) > MAX_SEARCH_STARTS
            || self.search_samples < u32::from(self.search_starts)
            || self.search_samples >= self.search_max_evaluations
        {
            return Err(SettingsError::BadSearchBudget);
        }
        Ok(())
    }
}

#[cfg(test)]
#[allow(clippy::unwrap_used, clippy::indexing_slicing, clippy::float_cmp)]
mod tests {
    use super::*;

    #[test]
    fn default_is_valid_and_each_class_is_caught() {
        assert_eq!(Settings::default().validate(), Ok(()));
        let s = Settings {
            kepler_max_iter: 0,
            ..Settings::default()
        };
        assert_eq!(s.validate(), Err(SettingsError::ZeroIterationLimit));
        let s = Settings {
            correction_tol: f64::NAN,
            ..Settings::default()
        };
        assert_eq!(s.validate(), Err(SettingsError::BadTolerance));
        let s = Settings {
            min_eccentricity: 0.0,
            ..Settings::default()
        };
        assert_eq!(s.validate(), Err(SettingsError::BadThreshold));
        for bad in [-1.0, f64::NAN, f64::INFINITY, 1e6] {
            let s = Settings {
                min_perigee_altitude_km: bad,
                ..Settings::default()
            };
            assert_eq!(s.validate(), Err(SettingsError::BadThreshold), "{bad}");
        }
        let s = Settings {
            search_starts: 200,
            ..Settings::default()
        };
        assert_eq!(s.validate(), Err(SettingsError::BadSearchBudget));
        let s = Settings {
            search_samples: 20_000,
            ..Settings::default()
        };
        assert_eq!(s.validate(), Err(SettingsError::BadSearchBudget));
    }
}
