//! J2 secular drift of mean elements, `D(sigma)` (Wang 2018, eq. 4-5), and its Jacobian `dD`
//! (the paper's `M_3x3` block, eq. 8).

use super::elements::{mean_motion_rad_s, Elements, A, ARGP, E, I, MA, RAAN};
use crate::astro::Gravity;
use nalgebra::SMatrix;

// The constants of the secular theory (gravitational parameter, equatorial radius, J2):
// planner B uses the Earth's (`Gravity::EARTH`); the LEO tour its settings'.

/// `C = 3 J2 Re^2 / (2 (1 - e^2)^2) sqrt(mu / a^7)`, rad/s.
fn j2_coefficient(k: &Gravity, sma_km: f64, ecc: f64) -> f64 {
    let one_minus_e2 = 1.0 - ecc * ecc;
    let a2 = sma_km * sma_km;
    let a7 = a2 * a2 * a2 * sma_km;
    3.0 * k.j2 * k.re_km * k.re_km / (2.0 * one_minus_e2 * one_minus_e2)
        * libm::sqrt(k.mu_km3_s2 / a7)
}

/// `D(sigma) = [0, 0, 0, n_Omega, n_omega, n + n_M]`, rad/s in the angle rows.
pub(crate) fn rates(el: &Elements) -> Elements {
    rates_with(&Gravity::EARTH, el)
}

/// [`rates`] with the constants `k`: the first-order secular J2 rates of mean elements.
pub(crate) fn rates_with(k: &Gravity, el: &Elements) -> Elements {
    let (a, e, i) = (el[A], el[E], el[I]);
    let c = j2_coefficient(k, a, e);
    let cos_i = libm::cos(i);
    let cos2 = cos_i * cos_i;
    let eta = libm::sqrt(1.0 - e * e);
    let mut d = [0.0; 6];
    d[RAAN] = -c * cos_i;
    d[ARGP] = 0.5 * c * (5.0 * cos2 - 1.0);
    d[MA] = libm::sqrt(k.mu_km3_s2 / (a * a * a)) + 0.5 * c * eta * (3.0 * cos2 - 1.0);
    d
}

/// `n_J2 = n + n_omega + n_M`: the rate of the mean argument of latitude, rad/s.
pub(crate) fn arg_latitude_rate_rad_s(el: &Elements) -> f64 {
    let d = rates(el);
    d[ARGP] + d[MA]
}

/// The 6x6 Jacobian `dD/dsigma`: zero except rows (Omega, omega, M) x columns (a, e, i),
/// which hold the paper's `M_3x3` (checked against finite differences in the tests).
pub(crate) fn rates_jacobian(el: &Elements) -> SMatrix<f64, 6, 6> {
    let (a, e, i) = (el[A], el[E], el[I]);
    let c = j2_coefficient(&Gravity::EARTH, a, e);
    let one_minus_e2 = 1.0 - e * e;
    let eta = libm::sqrt(one_minus_e2);
    let (sin_i, cos_i) = (libm::sin(i), libm::cos(i));
    let sin2 = sin_i * sin_i;
    let n = mean_motion_rad_s(a);
    let omega_factor = 2.0 - 2.5 * sin2;
    let m_factor = 1.0 - 1.5 * sin2;
    // Rows a, e, i, Omega, omega, M; columns a, e, i, Omega, omega, M.
    #[rustfmt::skip]
    let j =     SMatrix::<f64, 6, 6>::new(
        0.0, 0.0, 0.0, 0.0, 0.0, 0.0,
        0.0, 0.0, 0.0, 0.0, 0.0, 0.0,
        0.0, 0.0, 0.0, 0.0, 0.0, 0.0,
        3.5 * c / a * cos_i, -4.0 * e * c * cos_i / one_minus_e2, c * sin_i, 0.0, 0.0, 0.0,
        -3.5 * c / a * omega_factor, 4.0 * e * c / one_minus_e2 * omega_factor, -5.0 * c * sin_i * cos_i, 0.0, 0.0, 0.0,
        -1.5 * n / a - 3.5 * c * eta / a * m_factor, 3.0 * e * c / eta * m_factor, -3.0 * c * eta * sin_i * cos_i, 0.0, 0.0, 0.0,
    );
    j
}

#[cfg(test)]
mod tests {
    use super::*;

    fn chief() -> Elements {
        [
            7178.137,
            0.0678,
            63.4349f64.to_radians(),
            112f64.to_radians(),
            0.0,
            0.0,
        ]
    }

    #[test]
    fn critical_inclination_freezes_perigee() {
        let d = rates(&chief());
        assert!(d[ARGP].abs() < 1e-8 * d[MA]);
        assert!(d[RAAN] < 0.0);
        assert_eq!(d[A], 0.0);
        // n_Omega at 800 km, 63.4 deg: about -2.97 deg/day.
        let deg_per_day = d[RAAN].to_degrees() * 86400.0;
        assert!((-3.1..-2.8).contains(&deg_per_day), "{deg_per_day}");
    }

    #[test]
    fn jacobian_matches_central_differences() {
        for el in [
            chief(),
            [7000.0, 0.3, 0.4, 1.0, 2.0, 3.0],
            [8000.0, 0.01, 2.0, 0.0, 0.0, 0.0],
        ] {
            let j = rates_jacobian(&el);
            for (col, step) in [(A, 1e-2), (E, 1e-5), (I, 1e-5)] {
                let mut p = el;
                let mut m = el;
                p[col] += step;
                m[col] -= step;
                let (dp, dm) = (rates(&p), rates(&m));
                for row in 0..6 {
                    let fd = (dp[row] - dm[row]) / (2.0 * step);
                    let scale = fd.abs().max(1e-12);
                    assert!(
                        (j[(row, col)] - fd).abs() < 1e-6 * scale,
                        "row {row} col {col}: {} vs {fd}",
                        j[(row, col)]
                    );
                }
            }
            for col in 3..6 {
                for row in 0..6 {
                    assert_eq!(j[(row, col)], 0.0);
                }
            }
        }
    }
}
