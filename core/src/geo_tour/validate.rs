//! Every input checked against its documented range before planning.

use super::error::{check, Field, PlanError};
use super::types::Problem;
use crate::indexed::IndexedExt as _;
use core::f64::consts::PI;

/// Longest mission accepted, s (10 years).
pub const MAX_MISSION_TIME_S: f64 = 3.2e8;
/// Largest per-burn cap accepted, m/s.
pub const MAX_BURN_CAP_MPS: f64 = 1.0e4;

/// Check the request.
pub(crate) fn problem(p: &Problem) -> Result<(), PlanError> {
    check(
        Field::StartLongitude,
        0,
        p.start_lon_rad,
        -2.0 * PI,
        2.0 * PI,
    )?;
    if p.targets_lon_rad.is_empty() {
        return Err(PlanError::NoTargets);
    }
    for (i, &lon) in p.targets_lon_rad.iter().indexed() {
        let idx = u8::try_from(i).unwrap_or(u8::MAX);
        check(Field::TargetLongitude, idx, lon, -2.0 * PI, 2.0 * PI)?;
    }
    check(
        Field::MissionTime,
        0,
        p.mission_time_s,
        1.0,
        MAX_MISSION_TIME_S,
    )?;
    check(Field::MaxBurn, 0, p.max_burn_mps, 1e-6, MAX_BURN_CAP_MPS)?;
    Ok(())
}
