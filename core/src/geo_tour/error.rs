//! Reasons a GEO tour request is refused before planning: every one names the field, the
//! value and the limit.

use serde::{Deserialize, Serialize};

/// A field of the request or of the settings.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[repr(u8)]
pub enum Field {
    /// `Problem::start_lon_rad`.
    StartLongitude = 0,
    /// `Problem::targets_lon_rad[index]`.
    TargetLongitude = 1,
    /// `Problem::mission_time_s`.
    MissionTime = 2,
    /// `Problem::max_burn_mps`.
    MaxBurn = 3,
    /// `Settings::lambert_max_revolutions`.
    LambertMaxRevolutions = 4,
    /// `Settings::lambert_max_iter`.
    LambertMaxIter = 5,
    /// `Settings::lambert_tol`.
    LambertTol = 6,
    /// `Settings::well_iterations`.
    WellIterations = 7,
    /// `Settings::root_max_iter`.
    RootMaxIter = 8,
    /// `Settings::price_max_iter`.
    PriceMaxIter = 9,
    /// `Settings::time_tol_s`.
    TimeTol = 10,
    /// `Settings::gap_max_legs`.
    GapMaxLegs = 11,
    /// `Settings::min_radius_km`.
    MinRadius = 12,
    /// `Settings::rule_drift_above_rad`.
    RuleDriftAbove = 13,
    /// `Settings::rule_hohmann_above_rad`.
    RuleHohmannAbove = 14,
    /// `Settings::rule_radial_above_rad`.
    RuleRadialAbove = 15,
    /// `Settings::lambert_direct_time_s`.
    LambertDirectTime = 16,
    /// `Settings::exchange_rounds`.
    ExchangeRounds = 17,
    /// `Settings::exchange_margin_mps`.
    ExchangeMargin = 18,
}

/// A request the planner refuses.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub enum PlanError {
    /// A value is NaN, infinite or outside `[min, max]` (`index`: the target, else 0).
    OutOfRange {
        /// Which field.
        field: Field,
        /// Target index, else 0.
        index: u8,
        /// The value given (NaN stays NaN here: it is the caller's).
        value: f64,
        /// Smallest accepted.
        min: f64,
        /// Largest accepted.
        max: f64,
    },
    /// No clients.
    NoTargets,
}

impl core::fmt::Display for PlanError {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        match self {
            Self::OutOfRange {
                field,
                index,
                value,
                min,
                max,
            } => write!(
                f,
                "{field:?}[{index}] = {value} is outside [{min}, {max}] (or not finite)"
            ),
            Self::NoTargets => write!(f, "the tour has no clients"),
        }
    }
}

/// Check `value` in `[min, max]` and finite.
pub(crate) fn check(
    field: Field,
    index: u8,
    value: f64,
    min: f64,
    max: f64,
) -> Result<(), PlanError> {
    if value.is_finite() && value >= min && value <= max {
        Ok(())
    } else {
        Err(PlanError::OutOfRange {
            field,
            index,
            value,
            min,
            max,
        })
    }
}
