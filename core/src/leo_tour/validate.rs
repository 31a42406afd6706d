//! Refuse a request before planning: each refusal names the field, the value and the limit.

use super::j2::{pos, vel, State};
use super::types::{ArcProblem, Field, PlanError, SettingId, Settings, MAX_IMPULSES};
use crate::contract::{check_range, Range};
use crate::vec3::{cross, dot, norm};

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

/// The least perigee altitude of a client's osculating orbit, km: below it the orbit meets
/// the atmosphere's dense part within a revolution (the Kármán line), or the Earth.
pub const MIN_PERIGEE_ALTITUDE_KM: f64 = 100.0;

/// The perigee altitude (km) of the osculating orbit of `state` about a body of `mu_km3_s2`
/// and radius `re_km`; NaN for a degenerate state (no angular momentum), which then fails
/// the range check.
fn perigee_altitude_km(state: &State, mu_km3_s2: f64, re_km: f64) -> f64 {
    let (r, v) = (pos(state), vel(state));
    let h = norm(&cross(&r, &v));
    let energy = 0.5 * dot(&v, &v) - mu_km3_s2 / norm(&r);
    // e from the energy and the angular momentum: e^2 = 1 + 2 E h^2 / mu^2 (clamped at 0
    // against rounding for a circular orbit).
    let e = libm::sqrt((1.0 + 2.0 * energy * h * h / (mu_km3_s2 * mu_km3_s2)).max(0.0));
    let p = h * h / mu_km3_s2;
    if h > 0.0 {
        p / (1.0 + e) - re_km
    } else {
        f64::NAN
    }
}

/// A client whose osculating perigee is below [`MIN_PERIGEE_ALTITUDE_KM`], or inside the
/// Earth: the refusal of the sequencing and of the schedule (one shape and one message for
/// both).
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct LowPerigee {
    /// Which client (0-based).
    pub index: usize,
    /// Its perigee altitude, km (NaN for a degenerate state).
    pub altitude_km: f64,
    /// The least accepted, km.
    pub min_km: f64,
}

impl core::fmt::Display for LowPerigee {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        write!(
            f,
            "client {}: perigee altitude {} km is below the least {} km",
            self.index, self.altitude_km, self.min_km
        )
    }
}

/// The first of `clients` (index, state) whose perigee altitude is below
/// [`MIN_PERIGEE_ALTITUDE_KM`] (or NaN). The sequencing and the schedule refuse such a
/// request by name before any arc estimate would.
pub(crate) fn first_low_client<'s>(
    clients: impl Iterator<Item = (usize, &'s State)>,
    mu_km3_s2: f64,
    re_km: f64,
) -> Option<LowPerigee> {
    clients
        .map(|(index, s)| LowPerigee {
            index,
            altitude_km: perigee_altitude_km(s, mu_km3_s2, re_km),
            min_km: MIN_PERIGEE_ALTITUDE_KM,
        })
        .find(|c| c.altitude_km.is_nan() || c.altitude_km < c.min_km)
}

/// Check `problem` and `settings`.
///
/// # Errors
/// The first field outside its range: the problem's, then the settings' in declaration order,
/// then each client's perigee altitude (at least [`MIN_PERIGEE_ALTITUDE_KM`], with the
/// settings' Earth), then the least gap between impulses against the arc (at most an eighth of
/// it).
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
    for (field, s) in [
        (Field::FromPerigeeAltitudeKm, &problem.from),
        (Field::ToPerigeeAltitudeKm, &problem.to),
    ] {
        let altitude_km = perigee_altitude_km(s, settings.mu_km3_s2, settings.re_km);
        range(field, altitude_km, MIN_PERIGEE_ALTITUDE_KM, 1e6)?;
    }
    check_range(
        SettingId::MinGapS,
        settings.min_gap_s,
        Range::closed(0.0, problem.duration_s / 8.0),
    )
    .map_err(PlanError::InvalidSetting)
}
