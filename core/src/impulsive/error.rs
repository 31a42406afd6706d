//! Reasons a planner-B request is rejected before iterating. `out` and the workspace are then
//! untouched.

use crate::contract::SettingError;
use serde::{Deserialize, Serialize};

/// Which part of the request an error is about.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[repr(u8)]
pub enum Quantity {
    /// The chief's mean elements.
    Chief = 0,
    /// The initial relative elements.
    Initial = 1,
    /// The target relative elements.
    Target = 2,
    /// An impulse point's argument of latitude.
    ImpulsePoint = 3,
}

/// Which orbit a geometric error is about.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[repr(u8)]
pub enum Orbit {
    /// The chief at the initial epoch.
    Chief = 0,
    /// The deputy at the initial epoch (chief + initial).
    DeputyInitial = 1,
    /// The deputy at the end (chief + target; a, e, i do not drift).
    DeputyTarget = 2,
}

/// Largest magnitude of an input angle (Omega, omega, M, their differences, impulse points),
/// rad. At 1e4 rad an f64 still resolves 2e-12 rad (15 um on a GEO orbit); beyond it the phase
/// loses the precision the millimetre terminal check needs.
pub const MAX_ANGLE_RAD: f64 = 10_000.0;

/// A request the planner refuses to iterate on. Every variant names the field, the value and the
/// limit it broke (limits in the units of the field's name).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[repr(u8)]
pub enum PlanError {
    /// A number is NaN or infinite.
    NotFinite {
        /// Which part of the request.
        what: Quantity,
        /// Element index 0..6 (a, e, i, Omega, omega, M) or impulse index.
        index: u8,
    } = 0,
    /// Eccentricity below `Settings::min_eccentricity`: B's `1/e` terms are singular
    /// (near-circular orbits need non-singular elements, which this planner does not use).
    EccentricityTooSmall {
        /// Which orbit.
        orbit: Orbit,
        /// Its eccentricity.
        ecc: f64,
        /// The threshold (`Settings::min_eccentricity`).
        min: f64,
    } = 1,
    /// Eccentricity not in `[0, 1)`: not an ellipse.
    NotElliptic {
        /// Which orbit.
        orbit: Orbit,
        /// Its eccentricity.
        ecc: f64,
    } = 2,
    /// Semi-major axis not in `(min_km, max_km]`: `min_km` is Earth's radius plus
    /// `Settings::min_perigee_altitude_km`, `max_km` is [`super::MAX_SMA_KM`].
    SemiMajorAxisOutOfRange {
        /// Which orbit.
        orbit: Orbit,
        /// Its semi-major axis, km.
        sma_km: f64,
        /// Lower limit (exclusive), km.
        min_km: f64,
        /// Upper limit (inclusive), km.
        max_km: f64,
    } = 3,
    /// `|sin i|` below `Settings::min_sin_inclination`: B's `1/sin i` terms are singular
    /// (equatorial orbits).
    InclinationSingular {
        /// Which orbit.
        orbit: Orbit,
        /// Its `|sin i|`.
        sin_inc: f64,
        /// The threshold (`Settings::min_sin_inclination`).
        min: f64,
    } = 4,
    /// A revolution count is negative (impulse index; for a search, index 0 is its limit).
    NegativeRevolutions {
        /// Impulse index.
        impulse: u8,
        /// The count given.
        revolutions: i32,
    } = 5,
    /// The revolution counts (or a search's limit) sum above `Settings::max_total_revolutions`.
    RevolutionsOverLimit {
        /// Requested sum, saturated to i32.
        requested: i32,
        /// The limit.
        limit: i32,
    } = 6,
    /// More impulses than [`crate::capacity::MAX_IMPULSES`].
    CapacityExceeded {
        /// Requested impulses.
        requested: u16,
        /// Compiled capacity.
        capacity: u16,
    } = 7,
    /// No impulse in the plan.
    NoImpulses = 8,
    /// A setting is out of its range: the setting, the value and the range.
    InvalidSetting(SettingError<super::SettingId>) = 9,
    /// Perigee altitude `a (1 - e) - Re` below `Settings::min_perigee_altitude_km`: the orbit
    /// enters the atmosphere (or the Earth).
    PerigeeTooLow {
        /// Which orbit.
        orbit: Orbit,
        /// Its perigee altitude, km.
        perigee_altitude_km: f64,
        /// The limit, km.
        min_km: f64,
    } = 10,
    /// Inclination not in `[0, pi]` (classical elements).
    InclinationOutOfRange {
        /// Which orbit.
        orbit: Orbit,
        /// Its inclination, rad.
        inc_rad: f64,
    } = 11,
    /// An angle (or angle difference, or impulse point) above [`MAX_ANGLE_RAD`] in magnitude.
    AngleOutOfRange {
        /// Which part of the request.
        what: Quantity,
        /// Element index 0..6 (a, e, i, Omega, omega, M) or impulse index.
        index: u8,
        /// The angle given, rad.
        value_rad: f64,
        /// The limit on its magnitude, rad ([`MAX_ANGLE_RAD`]).
        limit_rad: f64,
    } = 12,
    /// An orbit or relative state given in another form (equinoctial elements, an osculating
    /// state, ROE) could not be converted to the planner's elements.
    InputForm {
        /// Which part of the request.
        part: super::form_problem::FormPart,
        /// Why.
        error: super::forms::FormError,
    } = 13,
}

impl core::fmt::Display for PlanError {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        match self {
            Self::NotFinite { what, index } => {
                write!(f, "{what:?} value {index} is NaN or infinite")
            }
            Self::EccentricityTooSmall { orbit, ecc, min } => write!(
                f,
                "{orbit:?} eccentricity {ecc:e} is below the threshold {min:e} (1/e terms of the GVE are singular)"
            ),
            Self::NotElliptic { orbit, ecc } => {
                write!(f, "{orbit:?} eccentricity {ecc} is not in [0, 1)")
            }
            Self::SemiMajorAxisOutOfRange {
                orbit,
                sma_km,
                min_km,
                max_km,
            } => write!(
                f,
                "{orbit:?} semi-major axis {sma_km} km is not in ({min_km}, {max_km}] km"
            ),
            Self::InclinationSingular {
                orbit,
                sin_inc,
                min,
            } => write!(
                f,
                "{orbit:?} |sin i| = {sin_inc:e} is below the threshold {min:e} (1/sin i terms of the GVE are singular)"
            ),
            Self::NegativeRevolutions {
                impulse,
                revolutions,
            } => {
                write!(
                    f,
                    "revolution count {revolutions} of impulse {impulse} is negative"
                )
            }
            Self::RevolutionsOverLimit { requested, limit } => {
                write!(
                    f,
                    "revolutions sum to {requested}, over the limit of {limit}"
                )
            }
            Self::CapacityExceeded {
                requested,
                capacity,
            } => {
                write!(f, "{requested} impulses exceed the capacity of {capacity}")
            }
            Self::NoImpulses => write!(f, "the plan has no impulses"),
            Self::InvalidSetting(e) => write!(f, "{e}"),
            Self::PerigeeTooLow {
                orbit,
                perigee_altitude_km,
                min_km,
            } => write!(
                f,
                "{orbit:?} perigee altitude {perigee_altitude_km} km is below the minimum of {min_km} km"
            ),
            Self::InclinationOutOfRange { orbit, inc_rad } => {
                write!(f, "{orbit:?} inclination {inc_rad} rad is not in [0, pi]")
            }
            Self::AngleOutOfRange {
                what,
                index,
                value_rad,
                limit_rad,
            } => write!(
                f,
                "{what:?} angle {index} = {value_rad} rad exceeds {limit_rad} rad in magnitude"
            ),
            Self::InputForm { part, error } => {
                write!(f, "{part:?} cannot be converted: {error}")
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use core::fmt::Write;

    struct Buf {
        text: [u8; 160],
        len: usize,
    }

    impl Write for Buf {
        fn write_str(&mut self, s: &str) -> core::fmt::Result {
            for b in s.bytes() {
                if self.len < self.text.len() {
                    self.text[self.len] = b;
                    self.len += 1;
                }
            }
            Ok(())
        }
    }

    /// `e` as displayed (its first 160 bytes), handed to `check`.
    fn displayed(e: PlanError, check: impl FnOnce(&str)) {
        let mut buf = Buf {
            text: [0; 160],
            len: 0,
        };
        write!(buf, "{e}").unwrap();
        check(core::str::from_utf8(&buf.text[..buf.len]).unwrap());
    }

    #[test]
    fn display_names_the_problem() {
        let singular = PlanError::InclinationSingular {
            orbit: Orbit::Chief,
            sin_inc: 1e-4,
            min: 1e-3,
        };
        displayed(singular, |s| {
            assert!(s.contains("Chief") && s.contains("sin i"), "{s}");
        });
        let full = PlanError::CapacityExceeded {
            requested: 7,
            capacity: 6,
        };
        displayed(full, |s| assert!(s.contains('7') && s.contains('6'), "{s}"));
    }
}
