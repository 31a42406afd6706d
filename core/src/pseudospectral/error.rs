//! Reasons a planner-A request is rejected before iterating. The workspace is untouched.

use crate::contract::SettingError;
use serde::{Deserialize, Serialize};

/// Which input quantity an error is about.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[repr(u8)]
pub enum Quantity {
    /// The horizon T.
    Horizon = 0,
    /// The control bound Umax.
    MaxControl = 1,
    /// The keep-out distance d.
    KeepOut = 2,
    /// A spacecraft mass.
    Mass = 3,
    /// A boundary state component.
    BoundaryState = 4,
    /// A settings value.
    Setting = 5,
    /// A warm-start value.
    WarmStart = 6,
}

/// Which capacity an error is about.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[repr(u8)]
pub enum Capacity {
    /// Spacecraft count M.
    Spacecraft = 0,
    /// Polynomial degree N.
    Degree = 1,
}

/// Which end of the horizon a boundary error is about.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[repr(u8)]
pub enum Boundary {
    /// t = 0.
    Initial = 0,
    /// t = T.
    Final = 1,
}

/// A request the planner refuses to iterate on.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[repr(u8)]
pub enum PlanError {
    /// A number is NaN or infinite.
    NotFinite {
        /// Which quantity.
        what: Quantity,
        /// Spacecraft index where it applies, else 0.
        spacecraft: u8,
        /// The value given (NaN or an infinity, as the caller gave it).
        value: f64,
    } = 0,
    /// A quantity that must be positive is zero or negative.
    NotPositive {
        /// Which quantity.
        what: Quantity,
        /// Spacecraft index where it applies, else 0.
        spacecraft: u8,
        /// The value given.
        value: f64,
    } = 1,
    /// A size is above the compiled capacity.
    CapacityExceeded {
        /// Which capacity.
        what: Capacity,
        /// Requested size.
        requested: u16,
        /// Compiled capacity.
        capacity: u16,
    } = 2,
    /// The degree N is below the minimum (4): no free coefficient would remain.
    DegreeTooLow {
        /// Requested degree.
        requested: u16,
    } = 3,
    /// No spacecraft in the request.
    NoSpacecraft = 4,
    /// Two spacecraft start or end closer than the keep-out distance.
    BoundaryTooClose {
        /// First spacecraft.
        first: u8,
        /// Second spacecraft.
        second: u8,
        /// Start or end.
        boundary: Boundary,
    } = 5,
    /// Even bang-bang control at Umax cannot meet one axis's boundary conditions in T.
    ManoeuvreInfeasible {
        /// Spacecraft index.
        spacecraft: u8,
        /// Axis 0 = x, 1 = y, 2 = z.
        axis: u8,
    } = 6,
    /// A setting is out of its range: the setting, the value and the range.
    InvalidSetting(SettingError<super::SettingId>) = 7,
    /// The warm start does not match the problem (spacecraft count or degree).
    WarmStartMismatch = 8,
    /// A number is outside the range the planner is built for: every magnitude at most
    /// [`MAX_MAGNITUDE`], and T, Umax, d and masses at least [`MIN_POSITIVE`] (normalised
    /// units keep real problems near 1; beyond this range squares and costs would overflow).
    OutOfRange {
        /// Which quantity.
        what: Quantity,
        /// Spacecraft index where it applies, else 0.
        spacecraft: u8,
        /// The value given.
        value: f64,
        /// The end of the accepted range it is beyond: [`MAX_MAGNITUDE`] for a magnitude,
        /// [`MIN_POSITIVE`] for a positive quantity below it.
        limit: f64,
    } = 9,
}

/// Largest magnitude of any input number (normalised units).
pub const MAX_MAGNITUDE: f64 = 1e9;
/// Smallest accepted T, Umax, d and mass (normalised units).
pub const MIN_POSITIVE: f64 = 1e-9;

impl core::fmt::Display for PlanError {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        match self {
            Self::NotFinite {
                what,
                spacecraft,
                value,
            } => {
                write!(f, "{what:?} = {value} is NaN or infinite")?;
                per_spacecraft(f, *what, *spacecraft)
            }
            Self::NotPositive {
                what,
                spacecraft,
                value,
            } => {
                write!(f, "{what:?} = {value} must be positive")?;
                per_spacecraft(f, *what, *spacecraft)
            }
            Self::CapacityExceeded {
                what,
                requested,
                capacity,
            } => write!(f, "{what:?} {requested} exceeds capacity {capacity}"),
            Self::DegreeTooLow { requested } => {
                write!(f, "degree N = {requested} is below the minimum of 4")
            }
            Self::NoSpacecraft => write!(f, "no spacecraft in the problem"),
            Self::BoundaryTooClose {
                first,
                second,
                boundary,
            } => write!(
                f,
                "spacecraft index {first} and {second} are closer than the keep-out distance at the {boundary:?} boundary"
            ),
            Self::ManoeuvreInfeasible { spacecraft, axis } => write!(
                f,
                "spacecraft index {spacecraft} cannot meet its boundary conditions on the {} axis within Umax in T",
                match axis { 0 => "x", 1 => "y", _ => "z" }
            ),
            Self::InvalidSetting(e) => write!(f, "{e}"),
            Self::WarmStartMismatch => write!(f, "warm start does not match the problem"),
            Self::OutOfRange {
                what,
                spacecraft,
                value,
                limit,
            } => {
                write!(
                    f,
                    "{what:?} = {value:e} is outside the accepted range (beyond {limit:e}: magnitude at most {MAX_MAGNITUDE:e}, positive quantities at least {MIN_POSITIVE:e})"
                )?;
                per_spacecraft(f, *what, *spacecraft)
            }
        }
    }
}

/// Name the spacecraft (zero-based index) where the quantity belongs to one.
fn per_spacecraft(
    f: &mut core::fmt::Formatter<'_>,
    what: Quantity,
    spacecraft: u8,
) -> core::fmt::Result {
    match what {
        Quantity::Mass | Quantity::BoundaryState | Quantity::WarmStart => {
            write!(f, " (spacecraft index {spacecraft})")
        }
        _ => Ok(()),
    }
}

impl core::error::Error for PlanError {}
