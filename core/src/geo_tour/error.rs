//! Reasons a GEO tour request is refused before planning: every one names the field, the
//! value and the limit.

use crate::contract::SettingError;
use serde::{Deserialize, Serialize};

/// A field of the request (a setting is named by its [`super::SettingId`]).
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
    /// A setting is out of its range: the setting, the value and the range.
    InvalidSetting(SettingError<super::SettingId>),
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
            Self::InvalidSetting(e) => write!(f, "{e}"),
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
