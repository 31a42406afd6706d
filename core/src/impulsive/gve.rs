//! The impulse matrix B of the Gauss variational equations (Wang 2018, eq. 1-3):
//! `Delta sigma = B(sigma) dv`.
//!
//! Columns are ordered **radial, along-track, normal** (RTN), the order of every `dv_rtn` in
//! planner B; the paper prints them along-track, radial, normal. B holds `1/e` and `1/sin i`:
//! callers reject states under the thresholds in `Settings` before building it.

#[cfg(test)]
use super::elements::MA;
use super::elements::{Elements, A, ARGP, E, EARTH_MU_KM3_S2, I};
use nalgebra::SMatrix;

/// Column of the radial component.
#[cfg(test)]
pub(crate) const RADIAL: usize = 0;
/// Column of the along-track component.
#[cfg(test)]
pub(crate) const ALONG: usize = 1;
/// Column of the normal component.
#[cfg(test)]
pub(crate) const NORMAL: usize = 2;

/// `B(sigma)` at true anomaly `f` (rad): rows (a km, e, i, Omega, omega, M rad) per km/s of
/// (radial, along-track, normal) impulse.
pub(crate) fn impulse_matrix(el: &Elements, true_anomaly_rad: f64) -> SMatrix<f64, 6, 3> {
    let (a, e, i, w) = (el[A], el[E], el[I], el[ARGP]);
    let f = true_anomaly_rad;
    let p = a * (1.0 - e * e);
    let h = libm::sqrt(EARTH_MU_KM3_S2 * p);
    let (sin_f, cos_f) = (libm::sin(f), libm::cos(f));
    let r = p / (1.0 + e * cos_f);
    let theta = w + f;
    let (sin_t, cos_t) = (libm::sin(theta), libm::cos(theta));
    let (sin_i, cos_i) = (libm::sin(i), libm::cos(i));
    let eta = libm::sqrt(1.0 - e * e);
    let he = h * e;
    // Rows a, e, i, Omega, omega, M; columns radial, along-track, normal.
    SMatrix::<f64, 6, 3>::new(
        2.0 * a * a * e * sin_f / h,
        2.0 * a * a * p / (h * r),
        0.0,
        p * sin_f / h,
        ((p + r) * cos_f + r * e) / h,
        0.0,
        0.0,
        0.0,
        r * cos_t / h,
        0.0,
        0.0,
        r * sin_t / (h * sin_i),
        -p * cos_f / he,
        (p + r) * sin_f / he,
        -r * cos_i * sin_t / (h * sin_i),
        eta * (p * cos_f - 2.0 * r * e) / he,
        -eta * (p + r) * sin_f / he,
        0.0,
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn vis_viva_along_track_at_perigee() {
        // At perigee an along-track dv changes a by 2 a^2 v / mu dv (vis-viva).
        let el = [7178.137, 0.0678, 1.0, 0.5, 0.3, 0.0];
        let b = impulse_matrix(&el, 0.0);
        let p = el[0] * (1.0 - el[1] * el[1]);
        let v = libm::sqrt(EARTH_MU_KM3_S2 / p) * (1.0 + el[1]);
        let expected = 2.0 * el[0] * el[0] * v / EARTH_MU_KM3_S2;
        assert!((b[(A, ALONG)] - expected).abs() < 1e-12 * expected);
        assert_eq!(b[(A, RADIAL)], 0.0);
        // A normal impulse leaves the in-plane elements alone.
        for row in [A, E, MA] {
            assert_eq!(b[(row, NORMAL)], 0.0);
        }
    }
}
