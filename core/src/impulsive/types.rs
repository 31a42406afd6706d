//! Planner-B public types. (Contract shared with the host harness and the firmware: field names
//! here are relied on outside the core.)

use crate::capacity::MAX_IMPULSES;
use serde::{Deserialize, Serialize};

/// Mean classical orbital elements.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct MeanElements {
    /// Semi-major axis a, km.
    pub sma_km: f64,
    /// Eccentricity e (dimensionless), 0 < e < 1.
    pub ecc: f64,
    /// Inclination i, rad.
    pub inc_rad: f64,
    /// Right ascension of the ascending node, rad.
    pub raan_rad: f64,
    /// Argument of perigee, rad.
    pub argp_rad: f64,
    /// Mean anomaly, rad.
    pub mean_anomaly_rad: f64,
}

/// Mean equinoctial elements (Broucke & Cefola's direct set), regular at e = 0 and i = 0:
/// `lambda = M + omega + Omega`, `(ex, ey) = e (cos, sin)(omega + Omega)`,
/// `(hx, hy) = tan(i/2) (cos, sin) Omega`. Also used for differences of two such sets.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct EquinoctialElements {
    /// Semi-major axis a, km.
    pub sma_km: f64,
    /// Mean longitude lambda, rad.
    pub mean_longitude_rad: f64,
    /// `e cos(omega + Omega)`.
    pub ex: f64,
    /// `e sin(omega + Omega)`.
    pub ey: f64,
    /// `tan(i/2) cos Omega`.
    pub hx: f64,
    /// `tan(i/2) sin Omega`.
    pub hy: f64,
}

impl EquinoctialElements {
    /// The six numbers in declaration order.
    pub const fn as_array(&self) -> [f64; 6] {
        [
            self.sma_km,
            self.mean_longitude_rad,
            self.ex,
            self.ey,
            self.hx,
            self.hy,
        ]
    }
}

/// Deputy-minus-chief mean elements, same order and units as [`MeanElements`]. The default is
/// no difference (the deputy on the chief's elements).
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct RelativeElements {
    /// Delta a, km.
    pub dsma_km: f64,
    /// Delta e.
    pub decc: f64,
    /// Delta i, rad.
    pub dinc_rad: f64,
    /// Delta RAAN, rad.
    pub draan_rad: f64,
    /// Delta argument of perigee, rad.
    pub dargp_rad: f64,
    /// Delta mean anomaly, rad.
    pub dmean_anomaly_rad: f64,
}

impl RelativeElements {
    /// The six numbers in declaration order.
    pub const fn as_array(&self) -> [f64; 6] {
        [
            self.dsma_km,
            self.decc,
            self.dinc_rad,
            self.draan_rad,
            self.dargp_rad,
            self.dmean_anomaly_rad,
        ]
    }
}

/// Where one impulse is applied: mean argument of latitude and whole revolutions since the
/// previous impulse (Wang 2018, eq. 7). For an equatorial chief in the equinoctial set the
/// angle is the mean longitude instead (see [`super::point_phase`]); the field keeps its name on
/// the wire.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct ImpulsePoint {
    /// Mean argument of latitude u_k = omega + M at the impulse, rad (mean longitude
    /// `M + omega + Omega` when [`super::point_phase`] says so).
    pub arg_latitude_rad: f64,
    /// Whole revolutions dN_k added to the phase from the previous impulse (negative is an error).
    pub revolutions: i32,
}

/// Fixed impulse points, or a bounded search over them.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub enum ImpulsePlan {
    /// Impulses at these points.
    Fixed(heapless::Vec<ImpulsePoint, MAX_IMPULSES>),
    /// Search the points for the least total dv.
    Search {
        /// Number of impulses.
        impulses: u8,
        /// Limit on the sum of revolution counts.
        max_revolutions: i32,
    },
}

/// A reconfiguration request.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Problem {
    /// The chief's mean elements at the initial epoch.
    pub chief: MeanElements,
    /// Deputy minus chief at the initial epoch.
    pub initial: RelativeElements,
    /// Deputy minus chief wanted after the last impulse.
    pub target: RelativeElements,
    /// Impulse points or a search.
    pub plan: ImpulsePlan,
}

#[cfg(test)]
impl MeanElements {
    /// The paper's chief (Wang 2018): Molniya-like inclination, e = 0.0678.
    pub(crate) fn test_paper_chief() -> Self {
        Self {
            sma_km: 7178.137,
            ecc: 0.0678,
            inc_rad: 63.4349f64.to_radians(),
            raan_rad: 112f64.to_radians(),
            argp_rad: 0.0,
            mean_anomaly_rad: 0.0,
        }
    }

    /// The tests' sun-synchronous chief: 700 km, e = 1e-3, i = 98.2 deg.
    pub(crate) fn test_sso_chief() -> Self {
        Self {
            sma_km: 7078.137,
            ecc: 1e-3,
            inc_rad: 98.2f64.to_radians(),
            raan_rad: 0.5,
            argp_rad: 0.3,
            mean_anomaly_rad: 1.0,
        }
    }
}
