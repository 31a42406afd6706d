//! Refuse a request before planning: each refusal names the field, the value and the limit.

use super::types::{ArcProblem, Field, PlanError, SettingId, Settings, MAX_IMPULSES};
use crate::contract::{check_range, Range};

fn range(field: Field, value: f64, min: f64, max: f64) -> Result<(), PlanError> {
    if value.is_finite() && (min..=max).contains(&value) {
        Ok(())
    } else {
        Err(PlanError::OutOfRange {
            field,
            value,
            min,
            max,
        })
    }
}

/// Check `problem` and `settings`.
///
/// # Errors
/// The first field outside its range: the problem's, then the settings' in declaration order,
/// then the least gap between impulses against the arc (at most an eighth of it).
pub fn check(problem: &ArcProblem, settings: &Settings) -> Result<(), PlanError> {
    for (field, s) in [(Field::From, &problem.from), (Field::To, &problem.to)] {
        for v in s {
            range(field, *v, -1e6, 1e6)?;
        }
    }
    range(Field::Duration, problem.duration_s, 600.0, 3e6)?;
    range(
        Field::Impulses,
        f64::from(problem.impulses),
        2.0,
        MAX_IMPULSES as f64,
    )?;
    settings.check_ranges().map_err(PlanError::InvalidSetting)?;
    check_range(
        SettingId::MinGapS,
        settings.min_gap_s,
        Range::closed(0.0, problem.duration_s / 8.0),
    )
    .map_err(PlanError::InvalidSetting)
}
