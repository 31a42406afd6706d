//! The astrodynamics floor every planner stands on: Earth's constants, the J2 gravity model's
//! constants as one value, unit factors and angle wrapping. Defined once here, below the
//! planners; no planner defines its own copy.
//!
//! Units (stated once for the orbital planners B, GEO and LEO): lengths in km, times in s,
//! angles in rad, velocities in km/s; impulses leave the core in m/s (`*_mps`).

/// Earth's gravitational parameter mu, km^3/s^2 (Wang 2018, section 1.2; the servicing
/// digests use the same value).
pub const EARTH_MU_KM3_S2: f64 = 398_600.441_8;
/// Earth's equatorial radius Re, km (Wang 2018, eq. 4; WGS-84).
pub const EARTH_RADIUS_KM: f64 = 6378.137;
/// Earth's second zonal harmonic J2 (unnormalised, dimensionless).
pub const EARTH_J2: f64 = 1.082_63e-3;
/// Earth's sidereal rotation rate, rad/s: the geostationary ring's mean motion.
pub const EARTH_ROTATION_RAD_S: f64 = 7.292_115_9e-5;
/// Metres per kilometre (km/s to m/s, km to m).
pub const M_PER_KM: f64 = 1000.0;
/// 2 pi.
pub const TWO_PI: f64 = core::f64::consts::TAU;

/// The constants of a two-body + J2 gravity model.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Gravity {
    /// Gravitational parameter, km^3/s^2.
    pub mu_km3_s2: f64,
    /// Equatorial radius, km.
    pub re_km: f64,
    /// Second zonal harmonic (unnormalised), dimensionless.
    pub j2: f64,
}

impl Gravity {
    /// Earth: [`EARTH_MU_KM3_S2`], [`EARTH_RADIUS_KM`], [`EARTH_J2`].
    pub const EARTH: Self = Self {
        mu_km3_s2: EARTH_MU_KM3_S2,
        re_km: EARTH_RADIUS_KM,
        j2: EARTH_J2,
    };
}

/// `x` wrapped into `[0, 2 pi)`.
pub fn wrap_two_pi(x: f64) -> f64 {
    let r = libm::fmod(x, TWO_PI);
    let r = if r < 0.0 { r + TWO_PI } else { r };
    // fmod of a tiny negative value plus 2 pi can round up to exactly 2 pi.
    if r >= TWO_PI {
        0.0
    } else {
        r
    }
}

/// `x` wrapped into `[-pi, pi]` (IEEE remainder).
pub fn wrap_pi(x: f64) -> f64 {
    libm::remainder(x, TWO_PI)
}

#[cfg(test)]
mod tests {
    use super::*;
    use core::f64::consts::PI;

    #[test]
    fn wrapping() {
        assert_eq!(wrap_two_pi(0.0), 0.0);
        assert!((wrap_two_pi(-0.5) - (TWO_PI - 0.5)).abs() < 1e-15);
        assert!((wrap_two_pi(7.0) - (7.0 - TWO_PI)).abs() < 1e-15);
        assert_eq!(wrap_two_pi(-1e-300), 0.0);
        assert!(wrap_two_pi(-1e-17) < TWO_PI);
        assert!((wrap_pi(3.0 * PI / 2.0) + PI / 2.0).abs() < 1e-15);
        assert!((wrap_pi(-3.0 * PI / 2.0) - PI / 2.0).abs() < 1e-15);
        // Exact in the ranges the planners use: x in [2 pi, 4 pi) and (-2 pi, 0).
        for x in [2.5 * PI, 3.999 * PI, -0.001, -1.999 * PI] {
            let floor_form = x - TWO_PI * libm::floor(x / TWO_PI);
            assert_eq!(wrap_two_pi(x), floor_form, "{x}");
        }
    }

    #[test]
    fn geostationary_radius_from_the_constants() {
        // a = (mu / n^2)^(1/3) = 42164.17 km for the sidereal day.
        let n = EARTH_ROTATION_RAD_S;
        let a = libm::cbrt(EARTH_MU_KM3_S2 / (n * n));
        assert!((a - 42_164.17).abs() < 0.01, "{a}");
        // Units: mu in km^3/s^2 gives the LEO circular speed in km/s.
        let v = libm::sqrt(EARTH_MU_KM3_S2 / (EARTH_RADIUS_KM + 400.0));
        assert!((v - 7.6686).abs() < 1e-3, "{v}");
        assert_eq!(Gravity::EARTH.j2, EARTH_J2);
    }
}
