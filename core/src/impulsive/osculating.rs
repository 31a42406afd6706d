//! Osculating <-> mean elements by first-order J2 averaging (Kozai's method of averaging,
//! first order in J2, short-period terms only): the osculating elements are the mean ones plus
//! the zero-mean periodic part of the J2 variation over one revolution,
//! `q_osc = q_mean + (1/n) * integral (q'(lambda) - <q'>) d lambda`, evaluated on the mean
//! two-body orbit. `q'` is the Gauss variational equations of [`super::equinoctial`] applied
//! to the J2 acceleration, plus the Keplerian `-3n/(2a) delta_a` for the mean longitude; the
//! integral is taken term by term on a discrete Fourier series in the mean longitude
//! ([`SAMPLES`] points, exact for the harmonics it resolves). In equinoctial elements, so it is
//! regular at e = 0 and i = 0. Long-period terms (second order in J2 for a, first order but
//! slow for e and omega near the critical inclination) are outside this theory.
//!
//! Bounded: [`SAMPLES`] states and Kepler solves per evaluation, `SAMPLES^2 / 2` Fourier
//! products per element; the inverse runs at most `max_iter` evaluations.

use super::elements::{mean_motion_rad_s, Elements, A, EARTH_J2, EARTH_MU_KM3_S2, EARTH_RADIUS_KM};
use super::equinoctial::{impulse_matrix, state, true_longitude, LAMBDA};
use crate::indexed::IndexedExt as _;
use crate::vec3::dot;

/// Samples per revolution of the Fourier quadrature (harmonics up to 31 in the mean
/// longitude; the J2 short-period terms of a near-circular orbit live in harmonics 1-3, and
/// harmonic k of an orbit with eccentricity e decays like e^(k-3)).
pub const SAMPLES: usize = 64;

/// The J2 acceleration at `pos_km`, km/s^2 (inertial).
fn j2_acceleration(pos_km: &[f64; 3]) -> [f64; 3] {
    let r2 = dot(pos_km, pos_km);
    let r = libm::sqrt(r2);
    let z2 = pos_km[2] * pos_km[2] / r2;
    let k = -1.5 * EARTH_J2 * EARTH_MU_KM3_S2 * EARTH_RADIUS_KM * EARTH_RADIUS_KM / (r2 * r2 * r);
    [
        k * pos_km[0] * (1.0 - 5.0 * z2),
        k * pos_km[1] * (1.0 - 5.0 * z2),
        k * pos_km[2] * (3.0 - 5.0 * z2),
    ]
}

/// The element rates `q'` (per s) under J2 of `q` moved to mean longitude `lambda_rad`, without
/// the Keplerian `n`. `None` when Kepler's equation does not converge.
fn j2_rates(q: &Elements, lambda_rad: f64, kepler_max_iter: u16) -> Option<Elements> {
    let mut at = *q;
    at[LAMBDA] = lambda_rad;
    let (l, ok) = true_longitude(&at, kepler_max_iter);
    if !ok {
        return None;
    }
    let s = state(&at, l);
    let acc = j2_acceleration(&s.pos_km);
    let rtn = [
        dot(&acc, &s.radial),
        dot(&acc, &s.along),
        dot(&acc, &s.normal),
    ];
    let b = impulse_matrix(&at, l);
    let mut qdot = nalgebra::SVector::<f64, 6>::zeros();
    qdot.gemv(1.0, &b, &nalgebra::SVector::<f64, 3>::from(rtn), 0.0);
    let mut out = [0.0; 6];
    for (o, x) in out.iter_mut().zip(qdot.iter()) {
        *o = *x;
    }
    Some(out)
}

/// Harmonics of the quadrature, 1 to `SAMPLES / 2 - 1`.
const HARMONICS: usize = SAMPLES / 2 - 1;

/// Fourier coefficients per harmonic and element.
type Coefficients = [[f64; 6]; HARMONICS];

/// `(A_k, B_k) = (1/N) sum_j f_j (cos, sin)(k theta_j)` of the rows `f_j` (each an element
/// vector), `theta_j = 2 pi j / N`; the angles advance by a rotation per sample.
fn fourier(rows: &[Elements; SAMPLES]) -> (Coefficients, Coefficients) {
    let step = core::f64::consts::TAU / SAMPLES as f64;
    let mut cos_coef = [[0.0; 6]; HARMONICS];
    let mut sin_coef = [[0.0; 6]; HARMONICS];
    for (k, (ak, bk)) in cos_coef.iter_mut().zip(sin_coef.iter_mut()).indexed() {
        let kf = k as f64 + 1.0;
        let (ck, sk) = (libm::cos(kf * step), libm::sin(kf * step));
        let (mut c, mut s) = (1.0, 0.0);
        for row in rows {
            for ((a, b), v) in ak.iter_mut().zip(bk.iter_mut()).zip(row.iter()) {
                *a += *v * c;
                *b += *v * s;
            }
            (c, s) = (c * ck - s * sk, s * ck + c * sk);
        }
        for (a, b) in ak.iter_mut().zip(bk.iter_mut()) {
            *a /= SAMPLES as f64;
            *b /= SAMPLES as f64;
        }
    }
    (cos_coef, sin_coef)
}

/// `(1/n)` times the zero-mean antiderivative of the series at `theta` (rad from the first
/// sample): `sum_k (2/k) (A_k sin k theta - B_k cos k theta) / n`.
fn antiderivative(coef: &(Coefficients, Coefficients), theta: f64, n: f64) -> Elements {
    let mut out = [0.0; 6];
    for (k, (ak, bk)) in coef.0.iter().zip(coef.1.iter()).indexed() {
        let kf = k as f64 + 1.0;
        let (sin_k, cos_k) = (libm::sin(kf * theta), libm::cos(kf * theta));
        for ((o, a), b) in out.iter_mut().zip(ak.iter()).zip(bk.iter()) {
            *o += 2.0 / kf * (*a * sin_k - *b * cos_k);
        }
    }
    for o in out.iter_mut() {
        *o /= n;
    }
    out
}

/// The short-period part `q_osc - q_mean` at the mean elements `q`, equinoctial. `None` when
/// Kepler's equation does not converge at a sample.
pub(crate) fn short_period(q: &Elements, kepler_max_iter: u16) -> Option<Elements> {
    let n = mean_motion_rad_s(q[A]);
    let step = core::f64::consts::TAU / SAMPLES as f64;
    let mut rates = [[0.0; 6]; SAMPLES];
    for (j, slot) in rates.iter_mut().indexed() {
        *slot = j2_rates(q, q[LAMBDA] + step * j as f64, kepler_max_iter)?;
    }
    // a's periodic part at every sample drives the Keplerian term of lambda.
    let coef = fourier(&rates);
    for (j, r) in rates.iter_mut().indexed() {
        let delta_a = antiderivative(&coef, step * j as f64, n)[A];
        r[LAMBDA] += -1.5 * n / q[A] * delta_a;
    }
    Some(antiderivative(&fourier(&rates), 0.0, n))
}

/// Osculating equinoctial elements of mean ones.
pub(crate) fn mean_to_osculating(q: &Elements, kepler_max_iter: u16) -> Option<Elements> {
    let d = short_period(q, kepler_max_iter)?;
    Some(super::elements::add(q, &d))
}

/// Mean equinoctial elements of osculating ones: `q_mean = q_osc - sp(q_mean)` by fixed-point
/// iteration from `q_osc` (a contraction of ratio O(J2)), at most `max_iter` steps, until the
/// largest change (a scaled by itself) is below `tol`. `(q_mean, converged, steps)`: `steps`
/// short-period evaluations were made (the work meter charges them).
pub(crate) fn osculating_to_mean(
    osc: &Elements,
    kepler_max_iter: u16,
    max_iter: u16,
    tol: f64,
) -> Option<(Elements, bool, u16)> {
    let mut mean = *osc;
    for step in 1..=max_iter {
        let d = short_period(&mean, kepler_max_iter)?;
        let next = super::elements::sub(osc, &d);
        let mut change = libm::fabs(next[A] - mean[A]) / osc[A];
        for (x, y) in next.iter().zip(mean.iter()).skip(1) {
            change = change.max(libm::fabs(*x - *y));
        }
        mean = next;
        if change <= tol {
            return Some((mean, true, step));
        }
    }
    Some((mean, false, max_iter))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::impulsive::equinoctial::from_classical;

    #[test]
    fn circular_semi_major_axis_oscillation_is_the_textbook_one() {
        // Circular orbit: a_osc - a_mean = (3/2) J2 Re^2 / a sin^2 i cos 2u (first order).
        let (a, inc) = (7078.137, 98.2f64.to_radians());
        for u_deg in [0.0, 30.0, 45.0, 90.0, 137.0] {
            let u = f64::to_radians(u_deg);
            let q = from_classical(&[a, 0.0, inc, 0.5, 0.0, u]);
            let d = short_period(&q, 30).unwrap();
            let want = 1.5 * EARTH_J2 * EARTH_RADIUS_KM * EARTH_RADIUS_KM / a
                * libm::sin(inc)
                * libm::sin(inc)
                * libm::cos(2.0 * u);
            assert!((d[A] - want).abs() < 1e-9, "u {u_deg}: {} vs {want}", d[A]);
        }
    }

    #[test]
    fn round_trip_mean_osculating_mean() {
        for cl in [
            [7078.137, 0.0, 98.2f64.to_radians(), 0.5, 0.0, 1.0],
            [7178.137, 0.0678, 1.107_148_7, 1.954_769_3, 0.3, 2.0],
            [42164.17, 0.0, 0.0, 0.0, 0.0, 0.7],
            [7000.0, 1e-3, 1e-4, 2.0, 1.0, 3.0],
        ] {
            let q = from_classical(&cl);
            let osc = mean_to_osculating(&q, 30).unwrap();
            let (back, ok, _) = osculating_to_mean(&osc, 30, 30, 1e-14).unwrap();
            assert!(ok);
            crate::impulsive::elements::assert_elements_close(&back, &q, 1e-12);
        }
    }
}
