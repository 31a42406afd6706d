//! Reasons a planner-B request is rejected before iterating. `out` and the workspace are then
//! untouched.

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

/// A request the planner refuses to iterate on.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
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
    } = 1,
    /// Eccentricity not in `[0, 1)`: not an ellipse.
    NotElliptic {
        /// Which orbit.
        orbit: Orbit,
    } = 2,
    /// Semi-major axis at or below Earth's radius.
    BelowEarthRadius {
        /// Which orbit.
        orbit: Orbit,
    } = 3,
    /// `|sin i|` below `Settings::min_sin_inclination`: B's `1/sin i` terms are singular
    /// (equatorial orbits).
    InclinationSingular {
        /// Which orbit.
        orbit: Orbit,
    } = 4,
    /// A revolution count is negative (impulse index; for a search, index 0 is its limit).
    NegativeRevolutions {
        /// Impulse index.
        impulse: u8,
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
    /// A setting is out of range.
    InvalidSettings(SettingsError) = 9,
}

/// A setting out of its documented range.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[repr(u8)]
pub enum SettingsError {
    /// An iteration or evaluation limit is zero.
    ZeroIterationLimit = 0,
    /// A tolerance is not finite and positive.
    BadTolerance = 1,
    /// A singularity threshold or limit is out of range.
    BadThreshold = 2,
    /// The search budget cannot hold its samples and starts, or asks for too many starts.
    BadSearchBudget = 3,
}

impl core::fmt::Display for PlanError {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        match self {
            Self::NotFinite { what, index } => {
                write!(f, "{what:?} value {index} is NaN or infinite")
            }
            Self::EccentricityTooSmall { orbit } => write!(
                f,
                "{orbit:?} eccentricity is below the threshold (1/e terms of the GVE are singular)"
            ),
            Self::NotElliptic { orbit } => write!(f, "{orbit:?} eccentricity is not in [0, 1)"),
            Self::BelowEarthRadius { orbit } => {
                write!(f, "{orbit:?} semi-major axis is at or below Earth's radius")
            }
            Self::InclinationSingular { orbit } => write!(
                f,
                "{orbit:?} |sin i| is below the threshold (1/sin i terms of the GVE are singular)"
            ),
            Self::NegativeRevolutions { impulse } => {
                write!(f, "revolution count of impulse {impulse} is negative")
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
            Self::InvalidSettings(e) => write!(f, "invalid settings: {e:?}"),
        }
    }
}

#[cfg(test)]
#[allow(
    clippy::unwrap_used,
    clippy::indexing_slicing,
    clippy::float_cmp,
    clippy::arithmetic_side_effects
)]
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

    #[test]
    fn display_names_the_problem() {
        let mut buf = Buf {
            text: [0; 160],
            len: 0,
        };
        write!(
            buf,
            "{}",
            PlanError::InclinationSingular {
                orbit: Orbit::Chief
            }
        )
        .unwrap();
        let s = core::str::from_utf8(&buf.text[..buf.len]).unwrap();
        assert!(s.contains("Chief") && s.contains("sin i"), "{s}");
        let mut buf = Buf {
            text: [0; 160],
            len: 0,
        };
        write!(
            buf,
            "{}",
            PlanError::CapacityExceeded {
                requested: 7,
                capacity: 6
            }
        )
        .unwrap();
        let s = core::str::from_utf8(&buf.text[..buf.len]).unwrap();
        assert!(s.contains('7') && s.contains('6'), "{s}");
    }
}
