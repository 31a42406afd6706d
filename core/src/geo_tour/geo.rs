//! The geostationary ring: constants, inertial states of a slot, and a first-order dual number
//! for the drift method's derivatives.

use crate::lambert::Vec3;
use crate::vec3;

use crate::astro::{EARTH_MU_KM3_S2, EARTH_ROTATION_RAD_S, TWO_PI};

/// Derived geostationary quantities, computed once per solve.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Geo {
    /// Gravitational parameter, km^3/s^2.
    pub mu: f64,
    /// Mean motion of the ring, rad/s.
    pub n0: f64,
    /// Radius of the ring, km (42 164.17).
    pub a0: f64,
    /// Circular speed on the ring, km/s (3.0747).
    pub v0: f64,
    /// Period of the ring (sidereal day), s.
    pub t0: f64,
}

impl Geo {
    /// The standard ring (mu and Earth's rate above).
    pub fn standard() -> Self {
        let mu = EARTH_MU_KM3_S2;
        let n0 = EARTH_ROTATION_RAD_S;
        let a0 = libm::cbrt(mu / (n0 * n0));
        Self {
            mu,
            n0,
            a0,
            v0: libm::sqrt(mu / a0),
            t0: TWO_PI / n0,
        }
    }

    /// Speed on an orbit of semi-major axis `a_km` at radius `r_km` (vis-viva), km/s.
    pub fn vis_viva(&self, r_km: f64, a_km: f64) -> f64 {
        libm::sqrt(self.mu * (2.0 / r_km - 1.0 / a_km))
    }

    /// Period of an orbit of semi-major axis `a_km`, s.
    pub fn period(&self, a_km: f64) -> f64 {
        TWO_PI * libm::sqrt(a_km * a_km * a_km / self.mu)
    }

    /// Inertial position and velocity of a geostationary slot at Earth-fixed longitude
    /// `lon_rad` at time `t_s` after the mission epoch (inertial x axis = the epoch's
    /// Greenwich meridian; z = Earth's axis).
    pub fn slot_state(&self, lon_rad: f64, t_s: f64) -> (Vec3, Vec3) {
        let th = lon_rad + self.n0 * t_s;
        // One argument reduction for both (the same kernels as `sin` and `cos`, so the same
        // bits).
        let (s, c) = libm::sincos(th);
        (
            [self.a0 * c, self.a0 * s, 0.0],
            [-self.v0 * s, self.v0 * c, 0.0],
        )
    }
}

/// Convert a burn given in the local radial / along-track / normal frame of a state into an
/// inertial velocity change (same units).
pub fn rtn_to_inertial(r: &Vec3, v: &Vec3, rtn: &Vec3) -> Vec3 {
    // Unit vectors by division (not a reciprocal's product): the bits the plans were held to.
    let unit = |a: &Vec3| {
        let n = vec3::norm(a);
        [a[0] / n, a[1] / n, a[2] / n]
    };
    let ir = unit(r);
    let ih = unit(&vec3::cross(r, v));
    let it = vec3::cross(&ih, &ir);
    [
        rtn[0] * ir[0] + rtn[1] * it[0] + rtn[2] * ih[0],
        rtn[0] * ir[1] + rtn[1] * it[1] + rtn[2] * ih[1],
        rtn[0] * ir[2] + rtn[1] * it[2] + rtn[2] * ih[2],
    ]
}

/// Inertial velocity change expressed in the local frame of `(r, v)`: radial, along-track,
/// normal.
pub fn inertial_to_rtn(r: &Vec3, v: &Vec3, dv: &Vec3) -> Vec3 {
    let e = |rtn: Vec3| rtn_to_inertial(r, v, &rtn);
    let (ir, it, ih) = (e([1.0, 0.0, 0.0]), e([0.0, 1.0, 0.0]), e([0.0, 0.0, 1.0]));
    [vec3::dot(&ir, dv), vec3::dot(&it, dv), vec3::dot(&ih, dv)]
}

/// A number with its first derivative (forward-mode automatic differentiation), for the drift
/// method's marginal cost of time.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Dual {
    pub v: f64,
    pub d: f64,
}

impl Dual {
    pub fn var(v: f64) -> Self {
        Self { v, d: 1.0 }
    }
    pub fn cst(v: f64) -> Self {
        Self { v, d: 0.0 }
    }
    pub fn sqrt(self) -> Self {
        let s = libm::sqrt(self.v);
        Self {
            v: s,
            d: self.d / (2.0 * s),
        }
    }
    pub fn recip(self) -> Self {
        Self {
            v: 1.0 / self.v,
            d: -self.d / (self.v * self.v),
        }
    }
}

impl core::ops::Add for Dual {
    type Output = Self;
    fn add(self, o: Self) -> Self {
        Self {
            v: self.v + o.v,
            d: self.d + o.d,
        }
    }
}

impl core::ops::Sub for Dual {
    type Output = Self;
    fn sub(self, o: Self) -> Self {
        Self {
            v: self.v - o.v,
            d: self.d - o.d,
        }
    }
}

impl core::ops::Mul for Dual {
    type Output = Self;
    fn mul(self, o: Self) -> Self {
        Self {
            v: self.v * o.v,
            d: self.d * o.v + self.v * o.d,
        }
    }
}

impl core::ops::Div for Dual {
    type Output = Self;
    fn div(self, o: Self) -> Self {
        let q = self.v / o.v;
        Self {
            v: q,
            d: (self.d - q * o.d) / o.v,
        }
    }
}

impl core::ops::Mul<f64> for Dual {
    type Output = Self;
    fn mul(self, k: f64) -> Self {
        Self {
            v: self.v * k,
            d: self.d * k,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ring_constants() {
        let g = Geo::standard();
        assert!((g.a0 - 42_164.17).abs() < 0.01, "{}", g.a0);
        assert!((g.v0 - 3.074_66).abs() < 1e-5, "{}", g.v0);
        assert!((g.t0 / 86_400.0 - 0.997_27).abs() < 1e-5);
    }

    #[test]
    fn rtn_round_trip() {
        let g = Geo::standard();
        let (r, v) = g.slot_state(0.7, 1234.0);
        let dv = rtn_to_inertial(&r, &v, &[1.0, 2.0, 3.0]);
        let back = inertial_to_rtn(&r, &v, &dv);
        for k in 0..3 {
            assert!((back[k] - [1.0, 2.0, 3.0][k]).abs() < 1e-12);
        }
    }
}
