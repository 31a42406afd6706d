//! J2 secular drift of equinoctial mean elements (the rates of Wang 2018, eq. 4-5, in the set
//! of [`super::equinoctial`]), its closed-form flow and the flow's Jacobian.
//!
//! With the classical rates `Omega' = -C cos i`, `omega' = C (5 cos^2 i - 1) / 2`,
//! `M' = n + C eta (3 cos^2 i - 1) / 2` (C as in [`super::secular`]), which depend on
//! (a, e^2, cos i) only and so are constants of the flow, the drift over `dt` is: a fixed,
//! `lambda += (n + M'_J2 + omega' + Omega') dt`, `(ex, ey)` turned by `(omega' + Omega') dt`,
//! `(hx, hy)` turned by `Omega' dt`. The same flow as the classical linear drift, written in
//! regular coordinates.

use super::elements::{mean_motion_rad_s, Elements, A, EARTH_J2, EARTH_MU_KM3_S2, EARTH_RADIUS_KM};
use super::equinoctial::{cos_inc, ecc_squared, tan_half_inc_squared, EX, EY, HX, HY, LAMBDA};
use nalgebra::{RowSVector, SMatrix};

/// The secular rates of one orbit, rad/s, with their partial derivatives with respect to
/// (a km, e^2, tan^2(i/2)).
#[derive(Clone, Copy, Debug)]
pub(crate) struct Rates {
    /// Mean longitude rate `n + M'_J2 + omega' + Omega'`.
    pub lambda: f64,
    /// Longitude of perigee rate `omega' + Omega'`.
    pub perigee: f64,
    /// Node rate `Omega'`.
    pub node: f64,
    /// Mean argument of latitude rate `n + M'_J2 + omega'` (lambda minus node).
    pub arg_latitude: f64,
    /// d(lambda, perigee, node)/d(a, e^2, t^2), row per rate.
    pub partials: [[f64; 3]; 3],
}

/// The rates of `q`.
pub(crate) fn rates(q: &Elements) -> Rates {
    let a = q[A];
    let e2 = ecc_squared(q);
    let t2 = tan_half_inc_squared(q);
    let c = cos_inc(q);
    let one_minus_e2 = 1.0 - e2;
    let a2 = a * a;
    let a7 = a2 * a2 * a2 * a;
    let big_c = 3.0 * EARTH_J2 * EARTH_RADIUS_KM * EARTH_RADIUS_KM
        / (2.0 * one_minus_e2 * one_minus_e2)
        * libm::sqrt(EARTH_MU_KM3_S2 / a7);
    let eta = libm::sqrt(one_minus_e2);
    let n = mean_motion_rad_s(a);
    let node = -big_c * c;
    let argp = 0.5 * big_c * (5.0 * c * c - 1.0);
    let mean_j2 = 0.5 * big_c * eta * (3.0 * c * c - 1.0);
    // d cos i / d t^2.
    let dc = -2.0 / ((1.0 + t2) * (1.0 + t2));
    // C ~ a^-3.5 (1 - e^2)^-2.
    let d_node = [-3.5 * node / a, 2.0 * node / one_minus_e2, -big_c * dc];
    let d_argp = [
        -3.5 * argp / a,
        2.0 * argp / one_minus_e2,
        5.0 * big_c * c * dc,
    ];
    let d_mean = [
        -1.5 * n / a - 3.5 * mean_j2 / a,
        1.5 * mean_j2 / one_minus_e2,
        3.0 * big_c * eta * c * dc,
    ];
    let sum3 = |x: &[f64; 3], y: &[f64; 3], z: &[f64; 3]| {
        [x[0] + y[0] + z[0], x[1] + y[1] + z[1], x[2] + y[2] + z[2]]
    };
    let d_perigee = [
        d_argp[0] + d_node[0],
        d_argp[1] + d_node[1],
        d_argp[2] + d_node[2],
    ];
    Rates {
        lambda: n + mean_j2 + argp + node,
        perigee: argp + node,
        node,
        arg_latitude: n + mean_j2 + argp,
        partials: [sum3(&d_mean, &d_argp, &d_node), d_perigee, d_node],
    }
}

/// `(x, y)` turned by `angle`.
fn rotate(x: f64, y: f64, angle: f64) -> (f64, f64) {
    let (s, c) = (libm::sin(angle), libm::cos(angle));
    (c * x - s * y, s * x + c * y)
}

/// `q` drifted for `dt_s` with the rates `r` (its own, or another orbit's: the target of a
/// formation drifts with the chief's).
pub(crate) fn flow_with(q: &Elements, r: &Rates, dt_s: f64) -> Elements {
    let (ex, ey) = rotate(q[EX], q[EY], r.perigee * dt_s);
    let (hx, hy) = rotate(q[HX], q[HY], r.node * dt_s);
    [q[A], q[LAMBDA] + r.lambda * dt_s, ex, ey, hx, hy]
}

/// `q` drifted for `dt_s` with its own rates (the planner drifts through `Model::drift`).
#[cfg(test)]
pub(crate) fn flow(q: &Elements, dt_s: f64) -> Elements {
    flow_with(q, &rates(q), dt_s)
}

/// The Jacobian of [`flow`] with respect to `q`, at `q`, for `dt_s`.
pub(crate) fn flow_jacobian(q: &Elements, dt_s: f64) -> SMatrix<f64, 6, 6> {
    let r = rates(q);
    let out = flow_with(q, &r, dt_s);
    // d(a, e^2, t^2)/dq: a; e^2 = ex^2 + ey^2; t^2 = hx^2 + hy^2.
    let grad = |row: &[f64; 3]| -> [f64; 6] {
        [
            row[0] * dt_s,
            0.0,
            2.0 * q[EX] * row[1] * dt_s,
            2.0 * q[EY] * row[1] * dt_s,
            2.0 * q[HX] * row[2] * dt_s,
            2.0 * q[HY] * row[2] * dt_s,
        ]
    };
    let [d_lambda, d_perigee, d_node] = r.partials;
    let (g_lambda, g_perigee, g_node) = (grad(&d_lambda), grad(&d_perigee), grad(&d_node));
    let (sp, cp) = (libm::sin(r.perigee * dt_s), libm::cos(r.perigee * dt_s));
    let (sn, cn) = (libm::sin(r.node * dt_s), libm::cos(r.node * dt_s));
    // The rotation of each pair, plus the change of its angle: d(R v)/d angle = (-y', x').
    let row = |k: f64, g: &[f64; 6]| -> [f64; 6] {
        [k * g[0], k * g[1], k * g[2], k * g[3], k * g[4], k * g[5]]
    };
    let mut r_lambda = g_lambda;
    r_lambda[LAMBDA] += 1.0;
    let mut r_ex = row(-out[EY], &g_perigee);
    r_ex[EX] += cp;
    r_ex[EY] -= sp;
    let mut r_ey = row(out[EX], &g_perigee);
    r_ey[EX] += sp;
    r_ey[EY] += cp;
    let mut r_hx = row(-out[HY], &g_node);
    r_hx[HX] += cn;
    r_hx[HY] -= sn;
    let mut r_hy = row(out[HX], &g_node);
    r_hy[HX] += sn;
    r_hy[HY] += cn;
    let r_a = [1.0, 0.0, 0.0, 0.0, 0.0, 0.0];
    SMatrix::<f64, 6, 6>::from_rows(&[
        RowSVector::<f64, 6>::from(r_a),
        RowSVector::<f64, 6>::from(r_lambda),
        RowSVector::<f64, 6>::from(r_ex),
        RowSVector::<f64, 6>::from(r_ey),
        RowSVector::<f64, 6>::from(r_hx),
        RowSVector::<f64, 6>::from(r_hy),
    ])
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::impulsive::equinoctial::{from_classical, to_classical};
    use crate::impulsive::secular;

    #[test]
    fn same_flow_as_the_classical_drift() {
        let cl = [7178.137, 0.0678, 1.107_148_7, 1.954_769_3, 0.3, 2.0];
        let dt = 5.0e4;
        let d = secular::rates(&cl);
        let mut moved = cl;
        for (x, r) in moved.iter_mut().zip(d.iter()) {
            *x += *r * dt;
        }
        let q = flow(&from_classical(&cl), dt);
        let want = from_classical(&moved);
        for k in 0..6 {
            assert!(
                (q[k] - want[k]).abs() < 1e-11 * want[k].abs().max(1.0),
                "{k}"
            );
        }
        assert!((to_classical(&q)[0] - cl[0]).abs() < 1e-12);
        let r = rates(&from_classical(&cl));
        assert!((r.arg_latitude - secular::arg_latitude_rate_rad_s(&cl)).abs() < 1e-18);
    }

    #[test]
    fn jacobian_matches_central_differences() {
        for q in [
            from_classical(&[7178.137, 0.0678, 1.1, 1.9, 0.3, 2.0]),
            [7078.137, 0.7, 0.0, 0.0, 1.15, 0.4],
            [42164.17, 2.0, 0.0, 0.0, 0.0, 0.0],
            [8000.0, -1.0, 1e-3, -2e-3, 1e-4, 3e-5],
        ] {
            let dt = 3.0e5;
            let j = flow_jacobian(&q, dt);
            for (col, step) in [
                (0, 1e-3),
                (1, 1e-6),
                (2, 1e-6),
                (3, 1e-6),
                (4, 1e-6),
                (5, 1e-6),
            ] {
                let mut p = q;
                let mut m = q;
                p[col] += step;
                m[col] -= step;
                let (fp, fm) = (flow(&p, dt), flow(&m, dt));
                for row in 0..6 {
                    let fd = (fp[row] - fm[row]) / (2.0 * step);
                    assert!(
                        (j[(row, col)] - fd).abs() < 1e-5 * fd.abs() + 1e-7,
                        "row {row} col {col}: {} vs {fd}",
                        j[(row, col)]
                    );
                }
            }
        }
    }
}
