//! Mean orbital elements as a working 6-vector.
//!
//! Units are the orbital planners' ([`crate::astro`]): km, s, rad, km/s; impulses leave the
//! core in m/s (`*_mps`). The Earth constants and the angle wrapping are [`crate::astro`]'s.

use super::types::{MeanElements, RelativeElements};
pub(crate) use crate::astro::{
    wrap_pi, wrap_two_pi, EARTH_J2, EARTH_MU_KM3_S2, EARTH_RADIUS_KM, M_PER_KM, TWO_PI,
};

/// Index of a in an element 6-vector.
pub(crate) const A: usize = 0;
/// Index of e.
pub(crate) const E: usize = 1;
/// Index of i.
pub(crate) const I: usize = 2;
/// Index of Omega (RAAN).
pub(crate) const RAAN: usize = 3;
/// Index of omega (argument of perigee).
pub(crate) const ARGP: usize = 4;
/// Index of M (mean anomaly).
pub(crate) const MA: usize = 5;

/// Elements `[a_km, e, i_rad, raan_rad, argp_rad, mean_anomaly_rad]` (Wang 2018's sigma).
pub(crate) type Elements = [f64; 6];

/// The 6-vector of mean elements.
pub(crate) fn from_mean(el: &MeanElements) -> Elements {
    [
        el.sma_km,
        el.ecc,
        el.inc_rad,
        el.raan_rad,
        el.argp_rad,
        el.mean_anomaly_rad,
    ]
}

/// The 6-vector of a relative-element difference.
pub(crate) fn from_relative(el: &RelativeElements) -> Elements {
    [
        el.dsma_km,
        el.decc,
        el.dinc_rad,
        el.draan_rad,
        el.dargp_rad,
        el.dmean_anomaly_rad,
    ]
}

/// The typed relative elements of a 6-vector.
pub(crate) fn to_relative(v: &Elements) -> RelativeElements {
    RelativeElements {
        dsma_km: v[A],
        decc: v[E],
        dinc_rad: v[I],
        draan_rad: v[RAAN],
        dargp_rad: v[ARGP],
        dmean_anomaly_rad: v[MA],
    }
}

/// `a + b` componentwise.
pub(crate) fn add(a: &Elements, b: &Elements) -> Elements {
    let mut out = *a;
    for (o, x) in out.iter_mut().zip(b.iter()) {
        *o += *x;
    }
    out
}

/// `a - b` componentwise.
pub(crate) fn sub(a: &Elements, b: &Elements) -> Elements {
    let mut out = *a;
    for (o, x) in out.iter_mut().zip(b.iter()) {
        *o -= *x;
    }
    out
}

/// Mean motion `n = sqrt(mu / a^3)`, rad/s.
pub(crate) fn mean_motion_rad_s(sma_km: f64) -> f64 {
    libm::sqrt(EARTH_MU_KM3_S2 / (sma_km * sma_km * sma_km))
}

/// Mean argument of latitude `u = omega + M`, rad (not wrapped).
pub(crate) fn mean_arg_latitude_rad(el: &Elements) -> f64 {
    el[ARGP] + el[MA]
}

/// Each of `got`'s six elements within `rel` of `want`'s (relative to `max(|want|, 1)`): the
/// round trips' check.
#[cfg(test)]
pub(crate) fn assert_elements_close(got: &Elements, want: &Elements, rel: f64) {
    for k in 0..6 {
        assert!(
            (got[k] - want[k]).abs() < rel * want[k].abs().max(1.0),
            "{k}: {} vs {}",
            got[k],
            want[k]
        );
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn constants_and_mean_motion() {
        // 800 km altitude: period about 6052 s.
        let n = mean_motion_rad_s(7178.137);
        assert!((TWO_PI / n - 6052.0).abs() < 2.0);
        assert_eq!(M_PER_KM * 1.0e-3, 1.0);
    }

    #[test]
    fn round_trip_relative() {
        let v = [1.0, 2.0, 3.0, 4.0, 5.0, 6.0];
        assert_eq!(from_relative(&to_relative(&v)), v);
        assert_eq!(sub(&add(&v, &v), &v), v);
    }
}
