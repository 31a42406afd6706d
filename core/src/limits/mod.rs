//! Service-side limits: the most work and the least safety a request may ask for.
//!
//! Every loop of a solve is bounded by a setting of the request (or by a problem size), so a
//! request alone decides how long a worker is held. The flight service, `reconfig solve` and
//! the firmware check each request against one [`Limits`] value before solving: a request may
//! tighten any setting, never loosen it past its limit. A request outside the limits is refused
//! with a [`LimitViolation`] that names the setting, its value and the limit; it is never solved
//! with silently clamped values.
//!
//! The built-in limits ([`Limits::default`]) are each planner's default settings and the
//! compiled capacities: the default request of either planner passes, and nothing may ask for
//! more iterations, looser tolerances or a safety check switched off.
//!
//! Planner settings gain fields over time: [`pseudospectral::Limits::check_settings`] and
//! [`impulsive::Limits::check_settings`] destructure `Settings` without `..`, so a new field
//! fails to compile until it has its one line (and its [`Setting`] name).

pub mod geo_tour;
pub mod impulsive;
mod impulsive_forms;
pub mod leo_tour;
pub mod pseudospectral;

use crate::wire::Request;
use serde::{Deserialize, Serialize};

/// A setting (or problem size) a limit applies to. [`Setting::name`] is the core's field name.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[repr(u8)]
pub enum Setting {
    /// Planner A: spacecraft count M of the problem.
    PsSpacecraftCount = 0,
    /// Planner A: polynomial degree N of the problem.
    PsDegree = 1,
    /// Planner A: `sqp_max_iter`.
    PsSqpMaxIter = 2,
    /// Planner A: `sqp_tol_cost`.
    PsSqpTolCost = 3,
    /// Planner A: `sqp_tol_step_lu`.
    PsSqpTolStepLu = 4,
    /// Planner A: `acceleration_memory`.
    PsAccelerationMemory = 5,
    /// Planner A: `continuous_verification`.
    PsContinuousVerification = 6,
    /// Planner A: `qp_max_iter`.
    PsQpMaxIter = 7,
    /// Planner A: `qp_tol_feas`.
    PsQpTolFeas = 8,
    /// Planner A: `verify_max_rounds`.
    PsVerifyMaxRounds = 9,
    /// Planner A: `verify_tol_lu`.
    PsVerifyTolLu = 10,
    /// Planner A: `keep_out_margin_lu`.
    PsKeepOutMarginLu = 11,
    /// Planner A: `newton_max_iter`.
    PsNewtonMaxIter = 12,
    /// Planner A: `refine_max_iter`.
    PsRefineMaxIter = 13,
    /// Planner A: `work_budget`.
    PsWorkBudget = 14,
    /// Planner B: impulses of the problem (fixed points, or a search's count).
    ImpImpulses = 32,
    /// Planner B: the problem asks for an impulse-point search.
    ImpSearch = 33,
    /// Planner B: `fixed_point_max_iter`.
    ImpFixedPointMaxIter = 34,
    /// Planner B: `fixed_point_tol_mps`.
    ImpFixedPointTolMps = 35,
    /// Planner B: `min_fuel`.
    ImpMinFuel = 36,
    /// Planner B: `min_fuel_max_iter`.
    ImpMinFuelMaxIter = 37,
    /// Planner B: `min_fuel_step_tol_mps`.
    ImpMinFuelStepTolMps = 38,
    /// Planner B: `min_fuel_tol_mps`.
    ImpMinFuelTolMps = 39,
    /// Planner B: `min_perigee_altitude_km`.
    ImpMinPerigeeAltitudeKm = 40,
    /// Planner B: `nonlinear_correction`.
    ImpNonlinearCorrection = 41,
    /// Planner B: `correction_max_iter`.
    ImpCorrectionMaxIter = 42,
    /// Planner B: `correction_tol`.
    ImpCorrectionTol = 43,
    /// Planner B: `kepler_max_iter`.
    ImpKeplerMaxIter = 44,
    /// Planner B: `svd_max_iter`.
    ImpSvdMaxIter = 45,
    /// Planner B: `rank_rcond`.
    ImpRankRcond = 46,
    /// Planner B: `min_eccentricity`.
    ImpMinEccentricity = 47,
    /// Planner B: `min_sin_inclination`.
    ImpMinSinInclination = 48,
    /// Planner B: `max_total_revolutions`.
    ImpMaxTotalRevolutions = 49,
    /// Planner B: `search_samples`.
    ImpSearchSamples = 50,
    /// Planner B: `search_starts`.
    ImpSearchStarts = 51,
    /// Planner B: `search_max_evaluations`.
    ImpSearchMaxEvaluations = 52,
    /// Planner B: `search_seed`.
    ImpSearchSeed = 53,
    /// Planner B: `search_step_rad`.
    ImpSearchStepRad = 54,
    /// Planner B: `search_min_step_rad`.
    ImpSearchMinStepRad = 55,
    /// Planner B: `search_fixed_point_max_iter`.
    ImpSearchFixedPointMaxIter = 56,
    /// Planner B: `search_screen_tol_mps`.
    ImpSearchScreenTolMps = 57,
    /// Planner B: `search_tol_mps`.
    ImpSearchTolMps = 58,
    /// Planner B: `work_budget`.
    ImpWorkBudget = 59,
    /// GEO tour: client count of the problem.
    GeoTargets = 64,
    /// GEO tour: `lambert_max_revolutions`.
    GeoLambertMaxRevolutions = 65,
    /// GEO tour: `lambert_max_iter`.
    GeoLambertMaxIter = 66,
    /// GEO tour: `lambert_tol`.
    GeoLambertTol = 67,
    /// GEO tour: `well_iterations`.
    GeoWellIterations = 68,
    /// GEO tour: `root_max_iter`.
    GeoRootMaxIter = 69,
    /// GEO tour: `price_max_iter`.
    GeoPriceMaxIter = 70,
    /// GEO tour: `time_tol_s`.
    GeoTimeTolS = 71,
    /// GEO tour: `gap_max_legs`.
    GeoGapMaxLegs = 72,
    /// GEO tour: `exchange_rounds`.
    GeoExchangeRounds = 73,
    /// GEO tour: `exchange_margin_mps`.
    GeoExchangeMarginMps = 74,
    /// GEO tour: `min_radius_km`.
    GeoMinRadiusKm = 75,
    /// Planner B, input forms: eccentricity of the chief as given (the osculating conic of an
    /// ECI state, or the equinoctial mean elements' `sqrt(ex^2 + ey^2)`).
    ImpChiefEccentricity = 96,
    /// Planner B, input forms: perigee altitude of the chief as given, km.
    ImpChiefPerigeeAltitudeKm = 97,
    /// Planner B, input forms: eccentricity of the deputy's initial orbit as given.
    ImpDeputyInitialEccentricity = 98,
    /// Planner B, input forms: perigee altitude of the deputy's initial orbit as given, km.
    ImpDeputyInitialPerigeeAltitudeKm = 99,
    /// Planner B, input forms: eccentricity of the deputy's target orbit as given.
    ImpDeputyTargetEccentricity = 100,
    /// Planner B, input forms: perigee altitude of the deputy's target orbit as given, km.
    ImpDeputyTargetPerigeeAltitudeKm = 101,
    /// Planner B, input forms: `|sin i|` of the chief a relative state in ROE is given on.
    ImpRoeChiefSinInclination = 102,
    /// LEO tour arc: impulse count M of the arc.
    LeoImpulses = 128,
    /// LEO tour arc: `step_s`.
    LeoStepS = 129,
    /// LEO tour arc: `max_steps`.
    LeoMaxSteps = 130,
    /// LEO tour arc: `lambert_max_iter`.
    LeoLambertMaxIter = 131,
    /// LEO tour arc: `lambert_tol`.
    LeoLambertTol = 132,
    /// LEO tour arc: `max_revolutions`.
    LeoMaxRevolutions = 133,
    /// LEO tour arc: `shoot_max_iter`.
    LeoShootMaxIter = 134,
    /// LEO tour arc: `arrival_tol_km`.
    LeoArrivalTolKm = 135,
    /// LEO tour arc: `grid_points`.
    LeoGridPoints = 136,
    /// LEO tour arc: `candidates`.
    LeoCandidates = 137,
    /// LEO tour arc: `hop_rounds`.
    LeoHopRounds = 138,
    /// LEO tour arc: `search_max_evals`.
    LeoSearchMaxEvals = 139,
    /// LEO tour arc: `search_min_step_s`.
    LeoSearchMinStepS = 140,
    /// LEO tour arc: `work_budget`.
    LeoWorkBudget = 141,
    /// LEO tour arc: `polish_max_evals`.
    LeoPolishMaxEvals = 142,
    /// LEO tour sequencing: `max_arcs`.
    LeoMaxArcs = 143,
    /// LEO tour sequencing: the bound's `band_margin_km`.
    LeoBandMarginKm = 144,
    /// LEO tour sequencing: the bound's `band_margin_rad`.
    LeoBandMarginRad = 145,
    /// LEO tour sequencing: the bound's `margin`.
    LeoBoundMargin = 146,
    /// LEO tour sequencing: the client count.
    LeoClients = 147,
}

impl Setting {
    /// The core's name of the setting (the key in a fixture's `[settings]` table and in a
    /// limits file); problem sizes are named after their fixture keys.
    pub const fn name(self) -> &'static str {
        match self {
            Self::PsSpacecraftCount => "spacecraft",
            Self::PsDegree => "nodes",
            Self::PsSqpMaxIter => "sqp_max_iter",
            Self::PsSqpTolCost => "sqp_tol_cost",
            Self::PsSqpTolStepLu => "sqp_tol_step_lu",
            Self::PsAccelerationMemory => "acceleration_memory",
            Self::PsContinuousVerification => "continuous_verification",
            Self::PsQpMaxIter => "qp_max_iter",
            Self::PsQpTolFeas => "qp_tol_feas",
            Self::PsVerifyMaxRounds => "verify_max_rounds",
            Self::PsVerifyTolLu => "verify_tol_lu",
            Self::PsKeepOutMarginLu => "keep_out_margin_lu",
            Self::PsNewtonMaxIter => "newton_max_iter",
            Self::PsRefineMaxIter => "refine_max_iter",
            Self::PsWorkBudget => "work_budget",
            Self::ImpImpulses => "impulses",
            Self::ImpSearch => "search",
            Self::ImpFixedPointMaxIter => "fixed_point_max_iter",
            Self::ImpFixedPointTolMps => "fixed_point_tol_mps",
            Self::ImpMinFuel => "min_fuel",
            Self::ImpMinFuelMaxIter => "min_fuel_max_iter",
            Self::ImpMinFuelStepTolMps => "min_fuel_step_tol_mps",
            Self::ImpMinFuelTolMps => "min_fuel_tol_mps",
            Self::ImpMinPerigeeAltitudeKm => "min_perigee_altitude_km",
            Self::ImpNonlinearCorrection => "nonlinear_correction",
            Self::ImpCorrectionMaxIter => "correction_max_iter",
            Self::ImpCorrectionTol => "correction_tol",
            Self::ImpKeplerMaxIter => "kepler_max_iter",
            Self::ImpSvdMaxIter => "svd_max_iter",
            Self::ImpRankRcond => "rank_rcond",
            Self::ImpMinEccentricity => "min_eccentricity",
            Self::ImpMinSinInclination => "min_sin_inclination",
            Self::ImpMaxTotalRevolutions => "max_total_revolutions",
            Self::ImpSearchSamples => "search_samples",
            Self::ImpSearchStarts => "search_starts",
            Self::ImpSearchMaxEvaluations => "search_max_evaluations",
            Self::ImpSearchSeed => "search_seed",
            Self::ImpSearchStepRad => "search_step_rad",
            Self::ImpSearchMinStepRad => "search_min_step_rad",
            Self::ImpSearchFixedPointMaxIter => "search_fixed_point_max_iter",
            Self::ImpSearchScreenTolMps => "search_screen_tol_mps",
            Self::ImpSearchTolMps => "search_tol_mps",
            Self::ImpWorkBudget => "work_budget",
            Self::GeoTargets => "targets",
            Self::GeoLambertMaxRevolutions => "lambert_max_revolutions",
            Self::GeoLambertMaxIter => "lambert_max_iter",
            Self::GeoLambertTol => "lambert_tol",
            Self::GeoWellIterations => "well_iterations",
            Self::GeoRootMaxIter => "root_max_iter",
            Self::GeoPriceMaxIter => "price_max_iter",
            Self::GeoTimeTolS => "time_tol_s",
            Self::GeoGapMaxLegs => "gap_max_legs",
            Self::GeoExchangeRounds => "exchange_rounds",
            Self::GeoExchangeMarginMps => "exchange_margin_mps",
            Self::GeoMinRadiusKm => "min_radius_km",
            Self::ImpChiefEccentricity => "chief.eccentricity",
            Self::ImpChiefPerigeeAltitudeKm => "chief.perigee_altitude_km",
            Self::ImpDeputyInitialEccentricity => "deputy.initial.eccentricity",
            Self::ImpDeputyInitialPerigeeAltitudeKm => "deputy.initial.perigee_altitude_km",
            Self::ImpDeputyTargetEccentricity => "deputy.target.eccentricity",
            Self::ImpDeputyTargetPerigeeAltitudeKm => "deputy.target.perigee_altitude_km",
            Self::ImpRoeChiefSinInclination => "relative.roe chief |sin i|",
            Self::LeoImpulses => "impulses",
            Self::LeoStepS => "step_s",
            Self::LeoMaxSteps => "max_steps",
            Self::LeoLambertMaxIter => "lambert_max_iter",
            Self::LeoLambertTol => "lambert_tol",
            Self::LeoMaxRevolutions => "max_revolutions",
            Self::LeoShootMaxIter => "shoot_max_iter",
            Self::LeoArrivalTolKm => "arrival_tol_km",
            Self::LeoGridPoints => "grid_points",
            Self::LeoCandidates => "candidates",
            Self::LeoHopRounds => "hop_rounds",
            Self::LeoSearchMaxEvals => "search_max_evals",
            Self::LeoSearchMinStepS => "search_min_step_s",
            Self::LeoWorkBudget => "work_budget",
            Self::LeoPolishMaxEvals => "polish_max_evals",
            Self::LeoMaxArcs => "max_arcs",
            Self::LeoBandMarginKm => "bound.band_margin_km",
            Self::LeoBandMarginRad => "bound.band_margin_rad",
            Self::LeoBoundMargin => "bound.margin",
            Self::LeoClients => "clients",
        }
    }

    /// The planner the setting belongs to.
    pub const fn planner(self) -> crate::wire::Planner {
        match self as u8 {
            0..=31 => crate::wire::Planner::Pseudospectral,
            32..=63 | 96..=127 => crate::wire::Planner::Impulsive,
            64..=95 => crate::wire::Planner::GeoTour,
            128..=142 => crate::wire::Planner::LeoArc,
            _ => crate::wire::Planner::LeoSequence,
        }
    }
}

/// How a value must relate to its limit.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[repr(u8)]
pub enum Rule {
    /// At most the limit (loop bounds, tolerances).
    AtMost = 0,
    /// At least the limit (margins and singularity thresholds).
    AtLeast = 1,
    /// Must be on (a safety check); value and limit are 0 (off) or 1 (on).
    MustBeOn = 2,
    /// Must be off (extra work the limits do not allow); value and limit are 0 or 1.
    MustBeOff = 3,
    /// Strictly below the limit (an eccentricity below 1).
    Below = 4,
}

/// A request outside the limits: which setting, the requested value, the limit and the rule.
/// Integers and flags are carried as `f64` (exact up to 2^53; flags as 0 / 1).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct LimitViolation {
    /// The setting.
    pub setting: Setting,
    /// The value the request asked for.
    pub value: f64,
    /// The limit it broke.
    pub limit: f64,
    /// How the value must relate to the limit.
    pub rule: Rule,
}

impl core::fmt::Display for LimitViolation {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        let name = self.setting.name();
        let onoff = |v: f64| if v > 0.5 { "on" } else { "off" };
        match self.rule {
            Rule::AtMost => write!(
                f,
                "{name} = {} is above the limit {}",
                self.value, self.limit
            ),
            Rule::AtLeast => write!(
                f,
                "{name} = {} is below the limit {}",
                self.value, self.limit
            ),
            Rule::Below => write!(
                f,
                "{name} = {} is not below the limit {}",
                self.value, self.limit
            ),
            Rule::MustBeOn | Rule::MustBeOff => write!(
                f,
                "{name} = {}: the limits require it {}",
                onoff(self.value),
                onoff(self.limit)
            ),
        }
    }
}

impl core::error::Error for LimitViolation {}

/// The limits of every planner.
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct Limits {
    /// Planner A.
    pub pseudospectral: pseudospectral::Limits,
    /// Planner B.
    pub impulsive: impulsive::Limits,
    /// The GEO servicing tour.
    pub geo_tour: geo_tour::Limits,
    /// The LEO tour's per-arc rendezvous.
    pub leo_tour: leo_tour::Limits,
}

impl Limits {
    /// Check a request against the limits of its planner.
    ///
    /// # Errors
    /// The first [`LimitViolation`], in the order the settings are declared.
    pub fn check(&self, request: &Request) -> Result<(), LimitViolation> {
        match request {
            Request::Pseudospectral { problem, settings } => {
                self.pseudospectral.check(problem, settings)
            }
            Request::Impulsive { problem, settings } => self.impulsive.check(problem, settings),
            Request::GeoTour { problem, settings } => self.geo_tour.check(problem, settings),
            Request::LeoArc { problem, settings } => self.leo_tour.check(problem, settings),
            Request::LeoSequence {
                clients,
                impulses,
                settings,
                arc_settings,
            } => self
                .leo_tour
                .check_sequence(clients.len(), *impulses, settings, arc_settings),
            Request::ImpulsiveForm { problem, settings } => {
                self.impulsive.check_form(problem, settings)
            }
        }
    }
}

/// `value <= limit`. A NaN passes here: the planner's own validation names it.
fn at_most(setting: Setting, value: f64, limit: f64) -> Result<(), LimitViolation> {
    if value > limit {
        Err(LimitViolation {
            setting,
            value,
            limit,
            rule: Rule::AtMost,
        })
    } else {
        Ok(())
    }
}

/// `value >= limit`. A NaN passes here: the planner's own validation names it.
fn at_least(setting: Setting, value: f64, limit: f64) -> Result<(), LimitViolation> {
    if value < limit {
        Err(LimitViolation {
            setting,
            value,
            limit,
            rule: Rule::AtLeast,
        })
    } else {
        Ok(())
    }
}

/// `value < limit`. A NaN passes here: the planner's own validation names it.
fn below(setting: Setting, value: f64, limit: f64) -> Result<(), LimitViolation> {
    if value >= limit {
        Err(LimitViolation {
            setting,
            value,
            limit,
            rule: Rule::Below,
        })
    } else {
        Ok(())
    }
}

/// A safety flag: when `required`, `value` must be on.
fn must_be_on(setting: Setting, value: bool, required: bool) -> Result<(), LimitViolation> {
    if required && !value {
        Err(LimitViolation {
            setting,
            value: 0.0,
            limit: 1.0,
            rule: Rule::MustBeOn,
        })
    } else {
        Ok(())
    }
}

/// A work-adding flag: unless `allowed`, `value` must be off.
fn allowed(setting: Setting, value: bool, allowed: bool) -> Result<(), LimitViolation> {
    if value && !allowed {
        Err(LimitViolation {
            setting,
            value: 1.0,
            limit: 0.0,
            rule: Rule::MustBeOff,
        })
    } else {
        Ok(())
    }
}
