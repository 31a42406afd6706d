//! Equinoctial mean elements, regular at e = 0 and i = 0: the conversions to and from the
//! classical set and the inertial state, the true longitude, and the impulse matrix of the
//! Gauss variational equations in this set.
//!
//! The working 6-vector is `[a_km, lambda_rad, ex, ey, hx, hy]` with the mean longitude
//! `lambda = M + omega + Omega`, `(ex, ey) = e (cos, sin)(omega + Omega)` and
//! `(hx, hy) = tan(i/2) (cos, sin) Omega` (Broucke & Cefola 1972, direct set). Every formula
//! below is a polynomial or a rational function of these with denominators bounded away from
//! zero for e < 1 and i < pi; only i = pi (retrograde equatorial, `tan(i/2)` infinite) is
//! singular, and the validation refuses it by name.

use super::elements::{wrap_pi, Elements, A, ARGP, E, EARTH_MU_KM3_S2, I, MA, RAAN};
use super::kepler::{mean_from_true, true_anomaly};
use crate::vec3::{cross, dot, norm, Vec3};
use nalgebra::SMatrix;

/// Index of the mean longitude lambda in an equinoctial 6-vector.
pub(crate) const LAMBDA: usize = 1;
/// Index of `ex = e cos(omega + Omega)`.
pub(crate) const EX: usize = 2;
/// Index of `ey = e sin(omega + Omega)`.
pub(crate) const EY: usize = 3;
/// Index of `hx = tan(i/2) cos Omega`.
pub(crate) const HX: usize = 4;
/// Index of `hy = tan(i/2) sin Omega`.
pub(crate) const HY: usize = 5;

/// `e^2 = ex^2 + ey^2`.
pub(crate) fn ecc_squared(q: &Elements) -> f64 {
    q[EX] * q[EX] + q[EY] * q[EY]
}

/// `tan^2(i/2) = hx^2 + hy^2`.
pub(crate) fn tan_half_inc_squared(q: &Elements) -> f64 {
    q[HX] * q[HX] + q[HY] * q[HY]
}

/// `cos i = (1 - tan^2(i/2)) / (1 + tan^2(i/2))`.
pub(crate) fn cos_inc(q: &Elements) -> f64 {
    let t2 = tan_half_inc_squared(q);
    (1.0 - t2) / (1.0 + t2)
}

/// The longitude of the node Omega (rad); 0 for an exactly equatorial orbit, where it is not
/// defined (callers use the mean longitude there, see [`super::model`]).
pub(crate) fn raan_rad(q: &Elements) -> f64 {
    libm::atan2(q[HY], q[HX])
}

/// Equinoctial elements of classical ones `[a, e, i, Omega, omega, M]`. `lambda` keeps the
/// classical angles' revolution count (no wrapping).
pub(crate) fn from_classical(el: &Elements) -> Elements {
    let lon_perigee = el[RAAN] + el[ARGP];
    let t = libm::tan(0.5 * el[I]);
    [
        el[A],
        el[MA] + lon_perigee,
        el[E] * libm::cos(lon_perigee),
        el[E] * libm::sin(lon_perigee),
        t * libm::cos(el[RAAN]),
        t * libm::sin(el[RAAN]),
    ]
}

/// Classical elements of equinoctial ones. At e = 0 the argument of perigee and at i = 0 the
/// node are not defined; they are then 0 (`atan2(0, 0)`) and the mean anomaly carries the
/// rest of the mean longitude, so `from_classical(to_classical(q)) == q` up to rounding.
pub(crate) fn to_classical(q: &Elements) -> Elements {
    let raan = raan_rad(q);
    let lon_perigee = libm::atan2(q[EY], q[EX]);
    [
        q[A],
        libm::sqrt(ecc_squared(q)),
        2.0 * libm::atan(libm::sqrt(tan_half_inc_squared(q))),
        raan,
        lon_perigee - raan,
        q[LAMBDA] - lon_perigee,
    ]
}

/// True longitude `L = omega + Omega + f` from the mean longitude (rad, unwrapped like lambda):
/// Kepler's equation solved on `lambda - varpi`, which is regular as e -> 0 because the
/// correction `L - lambda` is O(e) whatever `varpi = atan2(ey, ex)` is. `(L, converged)`.
pub(crate) fn true_longitude(q: &Elements, max_iter: u16) -> (f64, bool) {
    let e = libm::sqrt(ecc_squared(q));
    let lon_perigee = libm::atan2(q[EY], q[EX]);
    let m = wrap_pi(q[LAMBDA] - lon_perigee);
    let (f, ok) = true_anomaly(m, e, max_iter);
    // lambda + (f - M): the same revolution count as lambda.
    (q[LAMBDA] + wrap_pi(f - m), ok)
}

/// The equinoctial frame: unit vectors `f_hat`, `g_hat` in the orbit plane (`f_hat` toward the
/// origin of longitudes carried by the node) and the orbit normal `w_hat`.
fn frame(q: &Elements) -> (Vec3, Vec3, Vec3) {
    let (p, r) = (q[HY], q[HX]);
    let s2 = 1.0 + p * p + r * r;
    let f_hat = [(1.0 - p * p + r * r) / s2, 2.0 * p * r / s2, -2.0 * p / s2];
    let g_hat = [2.0 * p * r / s2, (1.0 + p * p - r * r) / s2, 2.0 * r / s2];
    let w_hat = [2.0 * p / s2, -2.0 * r / s2, (1.0 - p * p - r * r) / s2];
    (f_hat, g_hat, w_hat)
}

/// `a x + b y`.
fn combine(a: f64, x: &Vec3, b: f64, y: &Vec3) -> Vec3 {
    [
        a * x[0] + b * y[0],
        a * x[1] + b * y[1],
        a * x[2] + b * y[2],
    ]
}

/// Position (km), velocity (km/s) and the local frame of equinoctial elements `q` at true
/// longitude `L` (rad).
pub(crate) fn state(q: &Elements, true_longitude_rad: f64) -> super::nonlinear::State {
    let (f_hat, g_hat, normal) = frame(q);
    let (sin_l, cos_l) = (libm::sin(true_longitude_rad), libm::cos(true_longitude_rad));
    let p = q[A] * (1.0 - ecc_squared(q));
    let w = 1.0 + q[EX] * cos_l + q[EY] * sin_l;
    let r = p / w;
    let vp = libm::sqrt(EARTH_MU_KM3_S2 / p);
    let radial = combine(cos_l, &f_hat, sin_l, &g_hat);
    let along = combine(-sin_l, &f_hat, cos_l, &g_hat);
    let pos_km = crate::vec3::scale(&radial, r);
    let vel_km_s = combine(-vp * (q[EY] + sin_l), &f_hat, vp * (q[EX] + cos_l), &g_hat);
    super::nonlinear::State {
        pos_km,
        vel_km_s,
        radial,
        along,
        normal,
    }
}

/// Equinoctial elements of a position and velocity, with lambda chosen within pi of `near`'s.
/// `None` when the state is not a non-degenerate ellipse or its normal points to -z within
/// rounding (retrograde equatorial, outside the set's domain).
pub(crate) fn from_state(pos_km: &Vec3, vel_km_s: &Vec3, near: &Elements) -> Option<Elements> {
    let r = norm(pos_km);
    let v2 = dot(vel_km_s, vel_km_s);
    let h = cross(pos_km, vel_km_s);
    let hn = norm(&h);
    let energy_term = 2.0 / r - v2 / EARTH_MU_KM3_S2;
    if !(r > 0.0 && hn > 0.0 && energy_term > 0.0) {
        return None;
    }
    let w = [h[0] / hn, h[1] / hn, h[2] / hn];
    let denom = 1.0 + w[2];
    if denom.partial_cmp(&1e-12) != Some(core::cmp::Ordering::Greater) {
        return None;
    }
    let hy = w[0] / denom;
    let hx = -w[1] / denom;
    let a = 1.0 / energy_term;
    let rv = dot(pos_km, vel_km_s);
    let mut ecc_vec = [0.0; 3];
    for ((o, p), v) in ecc_vec.iter_mut().zip(pos_km.iter()).zip(vel_km_s.iter()) {
        *o = ((v2 - EARTH_MU_KM3_S2 / r) * *p - rv * *v) / EARTH_MU_KM3_S2;
    }
    let mut q = [a, 0.0, 0.0, 0.0, hx, hy];
    let (f_hat, g_hat, _) = frame(&q);
    let (ex, ey) = (dot(&ecc_vec, &f_hat), dot(&ecc_vec, &g_hat));
    let e = libm::sqrt(ex * ex + ey * ey);
    if e.is_nan() || e >= 1.0 {
        return None;
    }
    let true_lon = libm::atan2(dot(pos_km, &g_hat), dot(pos_km, &f_hat));
    let lon_perigee = libm::atan2(ey, ex);
    let lambda = lon_perigee + mean_from_true(true_lon - lon_perigee, e);
    q[LAMBDA] = near[LAMBDA] + wrap_pi(lambda - near[LAMBDA]);
    q[EX] = ex;
    q[EY] = ey;
    if q.iter().all(|x| x.is_finite()) {
        Some(q)
    } else {
        None
    }
}

/// The elements after an impulse `dv_rtn` (km/s: radial, along-track, normal) applied exactly
/// at true longitude `L`.
pub(crate) fn apply_impulse(q: &Elements, true_longitude_rad: f64, dv: &Vec3) -> Option<Elements> {
    let s = state(q, true_longitude_rad);
    from_state(&s.pos_km, &s.velocity_after(dv), q)
}

/// `B(q)` at true longitude `L`: rows (a km, lambda rad, ex, ey, hx, hy) per km/s of (radial,
/// along-track, normal) impulse. The Gauss equations of Walker et al. (1985) for (ex, ey, hx,
/// hy), with a from vis-viva and lambda = M + omega + Omega summed from the classical rows,
/// where the `1/e` and `1/sin i` terms cancel (`(eta - 1)/e = -e/(1 + eta)`,
/// `(1 - cos i)/sin i = tan(i/2)`).
pub(crate) fn impulse_matrix(q: &Elements, true_longitude_rad: f64) -> SMatrix<f64, 6, 3> {
    let a = q[A];
    let (ex, ey, hx, hy) = (q[EX], q[EY], q[HX], q[HY]);
    let e2 = ecc_squared(q);
    let p = a * (1.0 - e2);
    let h = libm::sqrt(EARTH_MU_KM3_S2 * p);
    let eta = libm::sqrt(1.0 - e2);
    let (sin_l, cos_l) = (libm::sin(true_longitude_rad), libm::cos(true_longitude_rad));
    let w = 1.0 + ex * cos_l + ey * sin_l;
    let r = p / w;
    let ph = p / h;
    // e sin f and e cos f in this set.
    let e_sin_f = ex * sin_l - ey * cos_l;
    let e_cos_f = w - 1.0;
    let s2 = 1.0 + hx * hx + hy * hy;
    let node_term = hx * sin_l - hy * cos_l;
    let one_eta = h * (1.0 + eta);
    // Rows a, lambda, ex, ey, hx, hy; columns radial, along-track, normal.
    #[rustfmt::skip]
    let b = SMatrix::<f64, 6, 3>::new(
        2.0 * a * a * e_sin_f / h, 2.0 * a * a * w / h, 0.0,
        -p * e_cos_f / one_eta - 2.0 * r * eta / h, (p + r) * e_sin_f / one_eta, r * node_term / h,
        ph * sin_l, ph * ((w + 1.0) * cos_l + ex) / w, -ph * node_term * ey / w,
        -ph * cos_l, ph * ((w + 1.0) * sin_l + ey) / w, ph * node_term * ex / w,
        0.0, 0.0, ph * s2 * cos_l / (2.0 * w),
        0.0, 0.0, ph * s2 * sin_l / (2.0 * w),
    );
    b
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::impulsive::nonlinear;

    const CLASSICAL: Elements = [7178.137, 0.0678, 1.107_148_7, 1.954_769_3, 0.3, 2.0];

    fn orbits() -> [Elements; 4] {
        [
            from_classical(&CLASSICAL),
            // Circular sun-synchronous.
            [7078.137, 0.7, 0.0, 0.0, 1.15, 0.4],
            // Circular equatorial (GEO).
            [42164.17, 2.0, 0.0, 0.0, 0.0, 0.0],
            // Slightly eccentric, slightly inclined.
            [8000.0, -1.0, 1e-3, -2e-3, 1e-4, 3e-5],
        ]
    }

    #[test]
    fn classical_round_trip() {
        let q = from_classical(&CLASSICAL);
        let back = to_classical(&q);
        for k in 0..6 {
            assert!((back[k] - CLASSICAL[k]).abs() < 1e-13 * CLASSICAL[k].abs().max(1.0));
        }
    }

    #[test]
    fn state_agrees_with_classical_and_round_trips() {
        let (f, _) = true_anomaly(CLASSICAL[MA], CLASSICAL[E], 50);
        let cs = nonlinear::state(&CLASSICAL, f);
        let q = from_classical(&CLASSICAL);
        let (l, ok) = true_longitude(&q, 50);
        assert!(ok);
        let es = state(&q, l);
        for k in 0..3 {
            assert!((cs.pos_km[k] - es.pos_km[k]).abs() < 1e-9);
            assert!((cs.vel_km_s[k] - es.vel_km_s[k]).abs() < 1e-12);
            assert!((cs.along[k] - es.along[k]).abs() < 1e-13);
            assert!((cs.normal[k] - es.normal[k]).abs() < 1e-13);
        }
        for q in orbits() {
            let (l, _) = true_longitude(&q, 50);
            let s = state(&q, l);
            let back = from_state(&s.pos_km, &s.vel_km_s, &q).unwrap();
            crate::impulsive::elements::assert_elements_close(&back, &q, 1e-12);
        }
    }

    #[test]
    fn impulse_matrix_is_the_derivative_of_the_exact_impulse() {
        for q in orbits() {
            let (l, _) = true_longitude(&q, 50);
            let b = impulse_matrix(&q, l);
            for axis in 0..3 {
                let step = 1e-7; // 0.1 mm/s
                let mut dp = [0.0; 3];
                let mut dm = [0.0; 3];
                dp[axis] = step;
                dm[axis] = -step;
                let (up, um) = (
                    apply_impulse(&q, l, &dp).unwrap(),
                    apply_impulse(&q, l, &dm).unwrap(),
                );
                for k in 0..6 {
                    let fd = (up[k] - um[k]) / (2.0 * step);
                    let scale = b.row(k).amax().max(1e-3);
                    assert!(
                        (b[(k, axis)] - fd).abs() < 1e-6 * scale,
                        "orbit {q:?} axis {axis} row {k}: {} vs {fd}",
                        b[(k, axis)]
                    );
                }
            }
        }
    }

    #[test]
    fn classical_gve_maps_to_equinoctial_gve() {
        // Away from the singularities B_eq = (d eq / d classical) B_classical.
        let (f, _) = true_anomaly(CLASSICAL[MA], CLASSICAL[E], 50);
        let bc = crate::impulsive::gve::impulse_matrix(&CLASSICAL, f);
        let q = from_classical(&CLASSICAL);
        let (l, _) = true_longitude(&q, 50);
        let be = impulse_matrix(&q, l);
        for axis in 0..3 {
            let h = 1e-7;
            let mut p = CLASSICAL;
            let mut m = CLASSICAL;
            for k in 0..6 {
                p[k] += h * bc[(k, axis)];
                m[k] -= h * bc[(k, axis)];
            }
            let (qp, qm) = (from_classical(&p), from_classical(&m));
            for k in 0..6 {
                let fd = (qp[k] - qm[k]) / (2.0 * h);
                assert!((be[(k, axis)] - fd).abs() < 1e-6 * be.column(axis).amax());
            }
        }
    }
}
