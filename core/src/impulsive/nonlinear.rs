//! Exact (nonlinear) impulse update of mean elements and positions, for verification beyond
//! the paper: elements -> position and velocity, add the impulse in the local frame, velocity
//! -> elements. Mean elements are treated as osculating two-body elements at the impulse
//! instant; J2 enters only through the secular drift between impulses.

use super::elements::wrap_pi;
use super::elements::{Elements, A, ARGP, E, EARTH_MU_KM3_S2, I, MA, RAAN};
use super::kepler::mean_from_true;

pub(crate) use crate::vec3::Vec3;
use crate::vec3::{cross, dot, norm};

/// Position (km), velocity (km/s) and the local frame (radial, along-track, normal unit
/// vectors) of elements `el` at true anomaly `f` (rad).
pub(crate) struct State {
    /// Inertial position, km.
    pub pos_km: Vec3,
    /// Inertial velocity, km/s.
    pub vel_km_s: Vec3,
    /// Radial unit vector.
    pub radial: Vec3,
    /// Along-track unit vector (normal x radial).
    pub along: Vec3,
    /// Orbit-normal unit vector.
    pub normal: Vec3,
}

impl State {
    /// The inertial velocity just after an impulse `dv_rtn_km_s` (km/s: radial, along-track,
    /// normal) applied at this state.
    pub(crate) fn velocity_after(&self, dv_rtn_km_s: &Vec3) -> Vec3 {
        let mut vel = self.vel_km_s;
        for (((v, r), t), n) in vel
            .iter_mut()
            .zip(self.radial.iter())
            .zip(self.along.iter())
            .zip(self.normal.iter())
        {
            *v += dv_rtn_km_s[0] * *r + dv_rtn_km_s[1] * *t + dv_rtn_km_s[2] * *n;
        }
        vel
    }
}

/// The two-body state of `el` at true anomaly `f`.
pub(crate) fn state(el: &Elements, true_anomaly_rad: f64) -> State {
    let (a, e, i, raan, w) = (el[A], el[E], el[I], el[RAAN], el[ARGP]);
    let f = true_anomaly_rad;
    let theta = w + f;
    let (so, co) = (libm::sin(raan), libm::cos(raan));
    let (si, ci) = (libm::sin(i), libm::cos(i));
    let (st, ct) = (libm::sin(theta), libm::cos(theta));
    let radial = [co * ct - so * st * ci, so * ct + co * st * ci, st * si];
    let normal = [so * si, -co * si, ci];
    let along = cross(&normal, &radial);
    let p = a * (1.0 - e * e);
    let r = p / (1.0 + e * libm::cos(f));
    let vp = libm::sqrt(EARTH_MU_KM3_S2 / p);
    let vr = vp * e * libm::sin(f);
    let vt = vp * (1.0 + e * libm::cos(f));
    let mut pos_km = [0.0; 3];
    let mut vel_km_s = [0.0; 3];
    for ((p_out, v_out), (rad, alo)) in pos_km
        .iter_mut()
        .zip(vel_km_s.iter_mut())
        .zip(radial.iter().zip(along.iter()))
    {
        *p_out = r * *rad;
        *v_out = vr * *rad + vt * *alo;
    }
    State {
        pos_km,
        vel_km_s,
        radial,
        along,
        normal,
    }
}

/// Two-body elements of a position and velocity, with the angles (Omega, omega, M) chosen
/// within pi of those of `near` so that secular angle counts carry on. `None` when the state is
/// not a non-degenerate ellipse.
pub(crate) fn elements_from_state(
    pos_km: &Vec3,
    vel_km_s: &Vec3,
    near: &Elements,
) -> Option<Elements> {
    elements_from_state_with(EARTH_MU_KM3_S2, pos_km, vel_km_s, near)
}

/// [`elements_from_state`] with the gravitational parameter `mu_km3_s2`.
pub(crate) fn elements_from_state_with(
    mu_km3_s2: f64,
    pos_km: &Vec3,
    vel_km_s: &Vec3,
    near: &Elements,
) -> Option<Elements> {
    elements_and_true_anomaly_with(mu_km3_s2, pos_km, vel_km_s, near).map(|(el, _)| el)
}

/// [`elements_from_state_with`] and the true anomaly (rad, not wrapped) it converted to the
/// mean anomaly: a caller that needs both skips solving Kepler's equation back.
pub(crate) fn elements_and_true_anomaly_with(
    mu_km3_s2: f64,
    pos_km: &Vec3,
    vel_km_s: &Vec3,
    near: &Elements,
) -> Option<(Elements, f64)> {
    let r = norm(pos_km);
    let v2 = dot(vel_km_s, vel_km_s);
    let h = cross(pos_km, vel_km_s);
    let hn = norm(&h);
    let energy_term = 2.0 / r - v2 / mu_km3_s2;
    if !(r > 0.0 && hn > 0.0 && energy_term > 0.0) {
        return None;
    }
    let a = 1.0 / energy_term;
    let rv = dot(pos_km, vel_km_s);
    let mut ecc_vec = [0.0; 3];
    for ((o, p), v) in ecc_vec.iter_mut().zip(pos_km.iter()).zip(vel_km_s.iter()) {
        *o = ((v2 - mu_km3_s2 / r) * *p - rv * *v) / mu_km3_s2;
    }
    let e = norm(&ecc_vec);
    if e.is_nan() || e >= 1.0 {
        return None;
    }
    let i = libm::atan2(libm::sqrt(h[0] * h[0] + h[1] * h[1]), h[2]);
    let raan = libm::atan2(h[0], -h[1]);
    let node = [libm::cos(raan), libm::sin(raan), 0.0];
    let h_unit = [h[0] / hn, h[1] / hn, h[2] / hn];
    let ahead = cross(&h_unit, &node);
    let theta = libm::atan2(dot(pos_km, &ahead), dot(pos_km, &node));
    let w = libm::atan2(dot(&ecc_vec, &ahead), dot(&ecc_vec, &node));
    let nu = theta - w;
    let m = mean_from_true(nu, e);
    let el = [
        a,
        e,
        i,
        near[RAAN] + wrap_pi(raan - near[RAAN]),
        near[ARGP] + wrap_pi(w - near[ARGP]),
        near[MA] + wrap_pi(m - near[MA]),
    ];
    if el.iter().all(|x| x.is_finite()) && nu.is_finite() {
        Some((el, nu))
    } else {
        None
    }
}

/// The elements after an impulse `dv_rtn` (km/s: radial, along-track, normal) applied exactly
/// at true anomaly `f`.
pub(crate) fn apply_impulse(
    el: &Elements,
    true_anomaly_rad: f64,
    dv_rtn_km_s: &Vec3,
) -> Option<Elements> {
    let s = state(el, true_anomaly_rad);
    elements_from_state(&s.pos_km, &s.velocity_after(dv_rtn_km_s), el)
}

/// Position difference `b - a` in the local frame of `a` (radial, along-track, normal), km.
pub(crate) fn relative_position_rtn(a: &State, b: &State) -> Vec3 {
    let d = [
        b.pos_km[0] - a.pos_km[0],
        b.pos_km[1] - a.pos_km[1],
        b.pos_km[2] - a.pos_km[2],
    ];
    [dot(&d, &a.radial), dot(&d, &a.along), dot(&d, &a.normal)]
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::impulsive::gve::impulse_matrix;
    use crate::impulsive::kepler::true_anomaly;

    const EL: Elements = [7178.137, 0.0678, 1.107_148_7, 1.954_769_3, 0.3, 2.0];

    #[test]
    fn state_round_trip() {
        let (f, _) = true_anomaly(EL[MA], EL[E], 50);
        let s = state(&EL, f);
        let back = elements_from_state(&s.pos_km, &s.vel_km_s, &EL).unwrap();
        crate::impulsive::elements::assert_elements_close(&back, &EL, 1e-11);
        // Frame is orthonormal and right-handed.
        let c = cross(&s.radial, &s.along);
        for (x, n) in c.iter().zip(s.normal.iter()) {
            assert!((x - n).abs() < 1e-15);
        }
    }

    #[test]
    fn exact_impulse_agrees_with_gve_to_first_order() {
        let (f, _) = true_anomaly(EL[MA], EL[E], 50);
        let b = impulse_matrix(&EL, f);
        for axis in 0..3 {
            let mut dv = [0.0; 3];
            dv[axis] = 1e-6; // 1 mm/s
            let after = apply_impulse(&EL, f, &dv).unwrap();
            for k in 0..6 {
                let exact = after[k] - EL[k];
                let linear = b[(k, axis)] * 1e-6;
                // Second-order remainder: relative dv / (2 v_r) ~ 1e-6 for the radial row of a.
                assert!(
                    (exact - linear).abs() < 1e-5 * linear.abs() + 5e-10,
                    "axis {axis} row {k}: {exact} vs {linear}"
                );
            }
        }
    }
}
