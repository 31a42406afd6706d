//! Earth gravity acceleration from a spherical-harmonic field, in the Earth-fixed frame, by the
//! recursion of Cunningham (1970) for the functions `V_nm`, `W_nm` (Montenbruck & Gill,
//! *Satellite Orbits*, 2000, section 3.2.4): no trigonometric function and no division by
//! `cos(latitude)`, so the poles are ordinary points.

use super::gravity_model::{GravityModel, MAX_DEGREE};

/// Rows of the `V`, `W` tables: the acceleration of degree n needs degree n + 1.
const VW_ROWS: usize = MAX_DEGREE + 2;

/// Which terms of the field to evaluate.
#[derive(Clone, Copy, Debug, PartialEq, Eq, serde::Serialize)]
pub struct FieldTerms {
    /// Highest degree (0 = the central term alone), at most [`MAX_DEGREE`].
    pub degree: usize,
    /// Highest order, at most `degree` (0 = zonal terms only).
    pub order: usize,
}

impl FieldTerms {
    /// The central term alone (two-body).
    pub const CENTRAL: Self = Self {
        degree: 0,
        order: 0,
    };
    /// The central term and J2 (degree 2, zonal).
    pub const J2: Self = Self {
        degree: 2,
        order: 0,
    };
    /// The whole vendored field, degree and order [`MAX_DEGREE`].
    pub const FULL: Self = Self {
        degree: MAX_DEGREE,
        order: MAX_DEGREE,
    };
}

/// Acceleration (km/s^2, Earth-fixed) of the field `model` at the Earth-fixed position
/// `r_km`, with the terms `terms` (degree clamped to [`MAX_DEGREE`], order to the degree).
/// With `terms = J2` only `C20` is used: `C21`, `S21` (about 1e-9, the pole's mean offset) are
/// order-1 terms and left out.
pub fn acceleration_km_s2(model: &GravityModel, terms: FieldTerms, r_km: &[f64; 3]) -> [f64; 3] {
    let n_max = terms.degree.min(MAX_DEGREE);
    let m_max = terms.order.min(n_max);
    let [x, y, z] = *r_km;
    let re = model.radius_km;
    let r2 = x * x + y * y + z * z;
    let rho = re * re / r2;
    let (x0, y0, z0) = (re * x / r2, re * y / r2, re * z / r2);
    let mut v = [[0.0; VW_ROWS]; VW_ROWS];
    let mut w = [[0.0; VW_ROWS]; VW_ROWS];
    // V_mm, W_mm along the diagonal, then V_nm, W_nm up each column: degrees to n_max + 1,
    // orders to m_max + 1 (the acceleration of order m needs orders m - 1 and m + 1).
    v[0][0] = re / r2.sqrt();
    for m in 0..=(m_max + 1).min(n_max + 1) {
        if m > 0 {
            let k = (2 * m - 1) as f64;
            v[m][m] = k * (x0 * v[m - 1][m - 1] - y0 * w[m - 1][m - 1]);
            w[m][m] = k * (x0 * w[m - 1][m - 1] + y0 * v[m - 1][m - 1]);
        }
        if m < n_max + 1 {
            v[m + 1][m] = (2 * m + 1) as f64 * z0 * v[m][m];
            w[m + 1][m] = (2 * m + 1) as f64 * z0 * w[m][m];
        }
        for n in (m + 2)..=(n_max + 1) {
            let a = (2 * n - 1) as f64 / (n - m) as f64;
            let b = (n + m - 1) as f64 / (n - m) as f64;
            v[n][m] = a * z0 * v[n - 1][m] - b * rho * v[n - 2][m];
            w[n][m] = a * z0 * w[n - 1][m] - b * rho * w[n - 2][m];
        }
    }
    let (mut ax, mut ay, mut az) = (0.0, 0.0, 0.0);
    for n in 0..=n_max {
        for m in 0..=m_max.min(n) {
            let (c, s) = (model.c[n][m], model.s[n][m]);
            if c == 0.0 && s == 0.0 {
                continue;
            }
            if m == 0 {
                ax -= c * v[n + 1][1];
                ay -= c * w[n + 1][1];
            } else {
                // (n - m + 2)! / (n - m)!
                let f = ((n - m + 1) * (n - m + 2)) as f64;
                ax += 0.5
                    * ((-c * v[n + 1][m + 1] - s * w[n + 1][m + 1])
                        + f * (c * v[n + 1][m - 1] + s * w[n + 1][m - 1]));
                ay += 0.5
                    * ((-c * w[n + 1][m + 1] + s * v[n + 1][m + 1])
                        + f * (-c * w[n + 1][m - 1] + s * v[n + 1][m - 1]));
            }
            az += (n - m + 1) as f64 * (-c * v[n + 1][m] - s * w[n + 1][m]);
        }
    }
    let k = model.gm_km3_s2 / (re * re);
    [k * ax, k * ay, k * az]
}

/// The field's potential (km^2/s^2) at `r_km` with `terms`, less the central term `GM / r`
/// (so that a difference quotient of it is not lost in the rounding of `GM / r`): the tests
/// differentiate it numerically.
#[cfg(test)]
#[allow(clippy::needless_range_loop)]
pub fn noncentral_potential_km2_s2(
    model: &GravityModel,
    terms: FieldTerms,
    r_km: &[f64; 3],
) -> f64 {
    // Legendre functions by the textbook recursion in latitude and longitude, independent of
    // the Cartesian recursion above.
    let n_max = terms.degree.min(MAX_DEGREE);
    let m_max = terms.order.min(n_max);
    let [x, y, z] = *r_km;
    let r = (x * x + y * y + z * z).sqrt();
    let sin_phi = z / r;
    let cos_phi = (x * x + y * y).sqrt() / r;
    let lambda = y.atan2(x);
    // Un-normalised associated Legendre functions P_nm(sin phi), no Condon-Shortley phase.
    let mut p = [[0.0; VW_ROWS]; VW_ROWS];
    p[0][0] = 1.0;
    for m in 0..=n_max {
        if m > 0 {
            p[m][m] = (2 * m - 1) as f64 * cos_phi * p[m - 1][m - 1];
        }
        if m < n_max {
            p[m + 1][m] = (2 * m + 1) as f64 * sin_phi * p[m][m];
        }
        for n in (m + 2)..=n_max {
            p[n][m] = ((2 * n - 1) as f64 * sin_phi * p[n - 1][m]
                - (n + m - 1) as f64 * p[n - 2][m])
                / (n - m) as f64;
        }
    }
    let mut u = 0.0;
    for n in 1..=n_max {
        let radial = (model.radius_km / r).powi(n as i32);
        for m in 0..=m_max.min(n) {
            let ml = m as f64 * lambda;
            u += radial * p[n][m] * (model.c[n][m] * ml.cos() + model.s[n][m] * ml.sin());
        }
    }
    model.gm_km3_s2 / r * u
}

#[cfg(test)]
#[allow(clippy::unwrap_used)]
mod tests {
    use super::*;

    fn model() -> GravityModel {
        GravityModel::jgm3().unwrap()
    }

    #[test]
    fn the_central_term_is_two_body() {
        let g = model();
        let r = [6000.0, -3000.0, 2500.0];
        let a = acceleration_km_s2(&g, FieldTerms::CENTRAL, &r);
        let rn = (r[0] * r[0] + r[1] * r[1] + r[2] * r[2]).sqrt();
        for k in 0..3 {
            let want = -g.gm_km3_s2 * r[k] / rn.powi(3);
            assert!((a[k] - want).abs() < 1e-15 * g.gm_km3_s2 / rn / rn, "{k}");
        }
    }

    #[test]
    fn j2_alone_is_the_closed_form() {
        let g = model();
        let r = [5000.0, 4000.0, 3000.0];
        let a = acceleration_km_s2(&g, FieldTerms::J2, &r);
        let (x, y, z) = (r[0], r[1], r[2]);
        let rn = (x * x + y * y + z * z).sqrt();
        let k = 1.5 * g.j2() * g.gm_km3_s2 * g.radius_km.powi(2) / rn.powi(5);
        let zr = 5.0 * z * z / (rn * rn);
        let want = [
            -g.gm_km3_s2 * x / rn.powi(3) + k * x * (zr - 1.0),
            -g.gm_km3_s2 * y / rn.powi(3) + k * y * (zr - 1.0),
            -g.gm_km3_s2 * z / rn.powi(3) + k * z * (zr - 3.0),
        ];
        super::super::assert_close(&a, &want, 1e-17);
    }

    /// The acceleration is the gradient of the potential computed by another recursion
    /// (Legendre functions in latitude): central differences, every term to degree and order 8,
    /// at points off the axes and near a pole.
    #[test]
    fn the_full_field_is_the_gradient_of_its_potential() {
        let g = model();
        for r in [
            [6778.0, 0.0, 0.0],
            [-2100.0, 5400.0, 3900.0],
            [15.0, -20.0, 6900.0],
            [4200.0, 4200.0, -4200.0],
        ] {
            let a = acceleration_km_s2(&g, FieldTerms::FULL, &r);
            let central = acceleration_km_s2(&g, FieldTerms::CENTRAL, &r);
            let h = 1e-2;
            for k in 0..3 {
                let mut plus = r;
                let mut minus = r;
                plus[k] += h;
                minus[k] -= h;
                let grad = (noncentral_potential_km2_s2(&g, FieldTerms::FULL, &plus)
                    - noncentral_potential_km2_s2(&g, FieldTerms::FULL, &minus))
                    / (2.0 * h);
                // The non-central part is ~1e-5 km/s^2; the difference quotient is good to
                // ~1e-14 km/s^2 (rounding of U ~ 0.06 km^2/s^2 over 20 m, and h^2 U''' / 6).
                assert!(
                    (a[k] - central[k] - grad).abs() < 1e-13,
                    "{r:?} axis {k}: {} vs {} (non-central {})",
                    a[k],
                    grad,
                    a[k] - central[k]
                );
            }
        }
    }

    #[test]
    fn the_tesseral_terms_matter() {
        let g = model();
        let r = [-2100.0, 5400.0, 3900.0];
        let zonal = acceleration_km_s2(
            &g,
            FieldTerms {
                degree: 8,
                order: 0,
            },
            &r,
        );
        let full = acceleration_km_s2(&g, FieldTerms::FULL, &r);
        let d = ((0..3).map(|k| (zonal[k] - full[k]).powi(2)).sum::<f64>()).sqrt();
        // C22, S22 dominate: ~3 GM R^2 |C22| / r^4 ~ 3e-8 km/s^2.
        assert!(d > 5e-9 && d < 2e-7, "{d}");
    }
}
