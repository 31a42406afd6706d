//! Planner-B limits: ceilings of the loop bounds and of the search, floors of the singularity
//! thresholds, the nonlinear correction required. One line per setting in
//! [`Limits::check_settings`].

use super::{allowed, at_least, at_most, must_be_on, LimitViolation, Setting};
use crate::capacity::MAX_IMPULSES;
use crate::impulsive::{ImpulsePlan, Problem, Settings};
use serde::{Deserialize, Serialize};

/// Planner-B limits. Field names are the settings' names; each is the most (for
/// `rank_rcond`, `min_eccentricity` and `min_sin_inclination` the least) a request may ask for;
/// flags say whether a request may switch the work on (`min_fuel`, `search`) or must keep the
/// check on (`nonlinear_correction`). Defaults: the default
/// settings and the compiled capacity.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct Limits {
    /// Most impulses (fixed points, or a search's count).
    pub impulses: u8,
    /// A request may ask for an impulse-point search.
    pub search: bool,
    /// Most fixed-point iterations per phase.
    pub fixed_point_max_iter: u16,
    /// Loosest fixed-point tolerance, m/s.
    pub fixed_point_tol_mps: f64,
    /// A request may ask for the least-fuel refinement.
    pub min_fuel: bool,
    /// Most interior-point iterations of one least-fuel cone program.
    pub min_fuel_max_iter: u16,
    /// Loosest joint min-fuel step tolerance, m/s.
    pub min_fuel_step_tol_mps: f64,
    /// Loosest certified gap of a least-fuel cone program, m/s.
    pub min_fuel_tol_mps: f64,
    /// The nonlinear defect correction must be on.
    pub nonlinear_correction: bool,
    /// Most defect-correction steps.
    pub correction_max_iter: u16,
    /// Loosest accepted terminal error of the nonlinear model.
    pub correction_tol: f64,
    /// Most Newton steps for Kepler's equation.
    pub kepler_max_iter: u16,
    /// Most QR steps of one SVD.
    pub svd_max_iter: u16,
    /// Least relative singular-value threshold (a smaller one admits ill-conditioned
    /// directions).
    pub rank_rcond: f64,
    /// Least eccentricity accepted as non-singular.
    pub min_eccentricity: f64,
    /// Least `|sin i|` accepted as non-singular.
    pub min_sin_inclination: f64,
    /// Largest sum of revolution counts.
    pub max_total_revolutions: i32,
    /// Least minimum perigee altitude of every orbit and transfer arc, km (a request may
    /// raise it, never lower it).
    pub min_perigee_altitude_km: f64,
    /// Most random samples of a search.
    pub search_samples: u32,
    /// Most local searches.
    pub search_starts: u8,
    /// Most evaluations of a search.
    pub search_max_evaluations: u32,
    /// Largest first pattern step, rad.
    pub search_step_rad: f64,
    /// Loosest final pattern step, rad.
    pub search_min_step_rad: f64,
    /// Most linearisations per search evaluation.
    pub search_fixed_point_max_iter: u16,
    /// Loosest least-fuel gap when screening search samples, m/s.
    pub search_screen_tol_mps: f64,
    /// Loosest least-fuel gap in the search's local moves, m/s.
    pub search_tol_mps: f64,
    /// Largest work budget, in work units.
    pub work_budget: u64,
}

impl Default for Limits {
    fn default() -> Self {
        let d = Settings::default();
        Self {
            impulses: MAX_IMPULSES as u8,
            search: true,
            fixed_point_max_iter: d.fixed_point_max_iter,
            fixed_point_tol_mps: d.fixed_point_tol_mps,
            min_fuel: true,
            min_fuel_max_iter: d.min_fuel_max_iter,
            min_fuel_step_tol_mps: d.min_fuel_step_tol_mps,
            min_fuel_tol_mps: d.min_fuel_tol_mps,
            nonlinear_correction: d.nonlinear_correction,
            correction_max_iter: d.correction_max_iter,
            correction_tol: d.correction_tol,
            kepler_max_iter: d.kepler_max_iter,
            svd_max_iter: d.svd_max_iter,
            rank_rcond: d.rank_rcond,
            min_eccentricity: d.min_eccentricity,
            min_sin_inclination: d.min_sin_inclination,
            max_total_revolutions: d.max_total_revolutions,
            min_perigee_altitude_km: d.min_perigee_altitude_km,
            search_samples: d.search_samples,
            search_starts: d.search_starts,
            search_max_evaluations: d.search_max_evaluations,
            search_step_rad: d.search_step_rad,
            search_min_step_rad: d.search_min_step_rad,
            search_fixed_point_max_iter: d.search_fixed_point_max_iter,
            search_screen_tol_mps: d.search_screen_tol_mps,
            search_tol_mps: d.search_tol_mps,
            work_budget: d.work_budget,
        }
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
                allowed(Setting::ImpSearch, true, self.search)?;
                // Above the capacity the planner refuses the request itself, naming it.
                if usize::from(*impulses) > MAX_IMPULSES {
                    return Ok(());
                }
                f64::from(*impulses)
            }
        };
        at_most(Setting::ImpImpulses, impulses, f64::from(self.impulses))
    }

    /// Check every setting, one line each.
    ///
    /// # Errors
    /// The first [`LimitViolation`].
    pub fn check_settings(&self, s: &Settings) -> Result<(), LimitViolation> {
        // No `..`: a new setting does not compile until it has its line here.
        let Settings {
            fixed_point_max_iter,
            fixed_point_tol_mps,
            min_fuel,
            min_fuel_max_iter,
            min_fuel_step_tol_mps,
            min_fuel_tol_mps,
            nonlinear_correction,
            correction_max_iter,
            correction_tol,
            kepler_max_iter,
            svd_max_iter,
            rank_rcond,
            min_eccentricity,
            min_sin_inclination,
            max_total_revolutions,
            min_perigee_altitude_km,
            search_samples,
            search_starts,
            search_max_evaluations,
            search_seed: _, // any seed: it picks samples, not how many
            search_step_rad,
            search_min_step_rad,
            search_fixed_point_max_iter,
            search_screen_tol_mps,
            search_tol_mps,
            element_set: _, // either set: the same loops and bounds
            work_budget,
        } = *s;
        use Setting as S;
        let l = self;
        let n = f64::from;
        at_most(
            S::ImpFixedPointMaxIter,
            n(fixed_point_max_iter),
            n(l.fixed_point_max_iter),
        )?;
        at_most(
            S::ImpFixedPointTolMps,
            fixed_point_tol_mps,
            l.fixed_point_tol_mps,
        )?;
        allowed(S::ImpMinFuel, min_fuel, l.min_fuel)?;
        at_most(
            S::ImpMinFuelMaxIter,
            n(min_fuel_max_iter),
            n(l.min_fuel_max_iter),
        )?;
        at_most(
            S::ImpMinFuelStepTolMps,
            min_fuel_step_tol_mps,
            l.min_fuel_step_tol_mps,
        )?;
        at_most(S::ImpMinFuelTolMps, min_fuel_tol_mps, l.min_fuel_tol_mps)?;
        must_be_on(
            S::ImpNonlinearCorrection,
            nonlinear_correction,
            l.nonlinear_correction,
        )?;
        at_most(
            S::ImpCorrectionMaxIter,
            n(correction_max_iter),
            n(l.correction_max_iter),
        )?;
        at_most(S::ImpCorrectionTol, correction_tol, l.correction_tol)?;
        at_most(
            S::ImpKeplerMaxIter,
            n(kepler_max_iter),
            n(l.kepler_max_iter),
        )?;
        at_most(S::ImpSvdMaxIter, n(svd_max_iter), n(l.svd_max_iter))?;
        at_least(S::ImpRankRcond, rank_rcond, l.rank_rcond)?;
        at_least(S::ImpMinEccentricity, min_eccentricity, l.min_eccentricity)?;
        at_least(
            S::ImpMinSinInclination,
            min_sin_inclination,
            l.min_sin_inclination,
        )?;
        at_most(
            S::ImpMaxTotalRevolutions,
            f64::from(max_total_revolutions),
            f64::from(l.max_total_revolutions),
        )?;
        at_least(
            S::ImpMinPerigeeAltitudeKm,
            min_perigee_altitude_km,
            l.min_perigee_altitude_km,
        )?;
        at_most(
            S::ImpSearchSamples,
            f64::from(search_samples),
            f64::from(l.search_samples),
        )?;
        at_most(
            S::ImpSearchStarts,
            f64::from(search_starts),
            f64::from(l.search_starts),
        )?;
        at_most(
            S::ImpSearchMaxEvaluations,
            f64::from(search_max_evaluations),
            f64::from(l.search_max_evaluations),
        )?;
        at_most(S::ImpSearchStepRad, search_step_rad, l.search_step_rad)?;
        at_most(
            S::ImpSearchMinStepRad,
            search_min_step_rad,
            l.search_min_step_rad,
        )?;
        at_most(
            S::ImpSearchFixedPointMaxIter,
            n(search_fixed_point_max_iter),
            n(l.search_fixed_point_max_iter),
        )?;
        at_most(
            S::ImpSearchScreenTolMps,
            search_screen_tol_mps,
            l.search_screen_tol_mps,
        )?;
        at_most(S::ImpSearchTolMps, search_tol_mps, l.search_tol_mps)?;
        // Exact below 2^53 units (far above any budget).
        at_most(S::ImpWorkBudget, work_budget as f64, l.work_budget as f64)
    }
}

#[cfg(test)]
#[allow(clippy::unwrap_used, clippy::float_cmp)]
mod tests {
    use super::*;
    use crate::limits::Rule;

    #[test]
    fn defaults_pass_and_the_issue_request_is_named() {
        let l = Limits::default();
        assert_eq!(l.check_settings(&Settings::default()), Ok(()));
        assert_eq!(
            l.check_settings(&Settings::fixed_point_only()),
            Err(LimitViolation {
                setting: Setting::ImpNonlinearCorrection,
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
            (Setting::ImpSearchSamples, 2e6, 400.0, Rule::AtMost)
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
            (Setting::ImpMinEccentricity, Rule::AtLeast)
        );
        let e = l
            .check_settings(&Settings {
                min_perigee_altitude_km: 50.0,
                ..Settings::default()
            })
            .unwrap_err();
        assert_eq!(
            (e.setting, e.value, e.limit, e.rule),
            (Setting::ImpMinPerigeeAltitudeKm, 50.0, 100.0, Rule::AtLeast)
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
        let zero = crate::impulsive::RelativeElements {
            dsma_km: 0.0,
            decc: 0.0,
            dinc_rad: 0.0,
            draan_rad: 0.0,
            dargp_rad: 0.0,
            dmean_anomaly_rad: 0.0,
        };
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
        assert_eq!((e.setting, e.rule), (Setting::ImpSearch, Rule::MustBeOff));
        assert_eq!(Limits::default().check_problem(&p), Ok(()));
    }
}
