//! Classical orbital elements to an inertial state (the fixtures give the clients as
//! osculating classical elements at the tour epoch).

use super::j2::{join, State};
use crate::vec3::{add, scale};

/// Osculating classical elements.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct Classical {
    /// Semi-major axis, km.
    pub a_km: f64,
    /// Eccentricity (< 1).
    pub e: f64,
    /// Inclination, rad.
    pub i_rad: f64,
    /// Right ascension of the ascending node, rad.
    pub raan_rad: f64,
    /// Argument of perigee, rad.
    pub argp_rad: f64,
    /// True anomaly, rad.
    pub nu_rad: f64,
}

/// The inertial state of `el` (km, km/s); `None` for a non-elliptic or non-finite orbit.
pub fn state_of(mu_km3_s2: f64, el: &Classical) -> Option<State> {
    let ok = [el.a_km, el.e, el.i_rad, el.raan_rad, el.argp_rad, el.nu_rad]
        .iter()
        .all(|v| v.is_finite())
        && el.a_km > 0.0
        && (0.0..1.0).contains(&el.e);
    if !ok {
        return None;
    }
    let p = el.a_km * (1.0 - el.e * el.e);
    let (sn, cn) = libm::sincos(el.nu_rad);
    let r = p / (1.0 + el.e * cn);
    let k = libm::sqrt(mu_km3_s2 / p);
    // Perifocal frame, then rotated by argp, i, raan.
    let (so, co) = libm::sincos(el.raan_rad);
    let (si, ci) = libm::sincos(el.i_rad);
    let (sw, cw) = libm::sincos(el.argp_rad);
    let pv = [co * cw - so * sw * ci, so * cw + co * sw * ci, sw * si];
    let qv = [-co * sw - so * cw * ci, -so * sw + co * cw * ci, cw * si];
    let pos = add(&scale(&pv, r * cn), &scale(&qv, r * sn));
    let vel = add(&scale(&pv, -k * sn), &scale(&qv, k * (el.e + cn)));
    let s = join(&pos, &vel);
    s.iter().all(|v| v.is_finite()).then_some(s)
}
