//! The Jacobian of the canonical system, `A = df/dy` (14×14): the matrix of the variational
//! equations `Φ' = A Φ` whose solution is the shooting's state-transition matrix
//! (SPEC-hybrid.md eq. 19–21, with the digest's corrections: `−Gᵀ` in the `λv` column of the
//! `λr` row, `Ω4 = +|λv| T/(2ε m²)`, and the third-derivative block written out). Derived here
//! from the canonical system directly (the throttle's dependence on `m`, `λv`, `λm` through
//! the switching function, where it is between its bounds), and checked against finite
//! differences in the tests.

use super::dynamics::{primer, Augmented, Model, Throttle};
use nalgebra::{Matrix3, SMatrix, Vector3};

/// The 14×14 Jacobian.
pub type Jacobian = SMatrix<f64, 14, 14>;

/// Where each block of the state starts: `[r, v, m, λr, λv, λm]`.
const R: usize = 0;
const V: usize = 3;
const M: usize = 6;
const LR: usize = 7;
const LV: usize = 10;
const LM: usize = 13;

fn matrix3(a: &[[f64; 3]; 3]) -> Matrix3<f64> {
    Matrix3::new(
        a[0][0], a[0][1], a[0][2], a[1][0], a[1][1], a[1][2], a[2][0], a[2][1], a[2][2],
    )
}

// nalgebra's f64 matrices: the integer-overflow lint does not apply.
#[allow(clippy::arithmetic_side_effects)]
/// `df/dy` at `y` under `law`. Where `λv = 0` the thrust direction is undefined; its terms are
/// left zero there (the shooting never reaches it: `|λv|` is the primer's length).
pub fn jacobian(model: &Model, law: Throttle, y: &Augmented) -> Jacobian {
    let mut a = Jacobian::zeros();
    let t = model.thrust_fu;
    let c = model.exhaust_vu;
    let m = y.m_mu;
    let lv = Vector3::from(y.lambda_v);
    let (l, alpha) = primer(&y.lambda_v);
    let alpha = Vector3::from(alpha);
    let s = model.switching(y);
    let u = law.of(s);
    let du_ds = law.slope(s);
    let g = matrix3(&model.gravity_gradient(&y.r_lu));
    let coriolis = Matrix3::new(0.0, 2.0, 0.0, -2.0, 0.0, 0.0, 0.0, 0.0, 0.0);

    // r' = v; v' = g + h + u T α/m (gravity and Coriolis parts).
    a.fixed_view_mut::<3, 3>(R, V)
        .copy_from(&Matrix3::identity());
    a.fixed_view_mut::<3, 3>(V, R).copy_from(&g);
    a.fixed_view_mut::<3, 3>(V, V).copy_from(&coriolis);
    // λr' = −G λv; λv' = −λr − Hᵀ λv.
    let third = matrix3(&model.gravity_gradient_along(&y.r_lu, &y.lambda_v));
    a.fixed_view_mut::<3, 3>(LR, R).copy_from(&(-third));
    a.fixed_view_mut::<3, 3>(LR, LV)
        .copy_from(&(-g.transpose()));
    a.fixed_view_mut::<3, 3>(LV, LR)
        .copy_from(&(-Matrix3::identity()));
    a.fixed_view_mut::<3, 3>(LV, LV)
        .copy_from(&(-coriolis.transpose()));
    if l <= 0.0 {
        return a;
    }

    // The throttle's gradient through S = 1 − |λv| c/m − λm (zero on a bound).
    let du_dm = du_ds * l * c / (m * m);
    let du_dlv = lv * (-du_ds * c / (m * l));
    let du_dlm = -du_ds;
    // dα/dλv = −(I/|λv| − λv λvᵀ/|λv|³).
    let dalpha = -(Matrix3::identity() / l - lv * lv.transpose() / (l * l * l));

    // The thrust acceleration u T α/m.
    let da_dm = alpha * (t / m * du_dm - u * t / (m * m));
    let da_dlv = (alpha * du_dlv.transpose() + dalpha * u) * (t / m);
    let da_dlm = alpha * (t / m * du_dlm);
    a.fixed_view_mut::<3, 1>(V, M).copy_from(&da_dm);
    a.fixed_view_mut::<3, 3>(V, LV).copy_from(&da_dlv);
    a.fixed_view_mut::<3, 1>(V, LM).copy_from(&da_dlm);

    // m' = −u T/c.
    let k = -t / c;
    a.fixed_view_mut::<1, 1>(M, M).fill(k * du_dm);
    a.fixed_view_mut::<1, 3>(M, LV)
        .copy_from(&(du_dlv.transpose() * k));
    a.fixed_view_mut::<1, 1>(M, LM).fill(k * du_dlm);

    // λm' = −u T |λv|/m².
    let tl = t * l / (m * m);
    a.fixed_view_mut::<1, 1>(LM, M)
        .fill(-tl * du_dm + 2.0 * u * t * l / (m * m * m));
    let dlm_dlv = (du_dlv * l + lv * (u / l)) * (-t / (m * m));
    a.fixed_view_mut::<1, 3>(LM, LV)
        .copy_from(&dlm_dlv.transpose());
    a.fixed_view_mut::<1, 1>(LM, LM).fill(-tl * du_dlm);
    a
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::hybrid::dynamics::tests::sample;

    /// Every column of `df/dy` against central differences of the canonical system, with the
    /// throttle off, full, in between (ε = 0.4), and for minimum time.
    #[test]
    fn the_jacobian_is_the_derivative_of_the_canonical_system() {
        let model = Model::paper();
        let s0 = model.switching(&sample(0.0));
        let smoothed = Throttle::Smoothed { epsilon: 0.4 };
        for (law, target_s) in [
            (smoothed, 0.9),
            (smoothed, -0.9),
            (smoothed, 0.1),
            (smoothed, -0.3),
            (Throttle::Full, 0.1),
        ] {
            let y = sample(s0 - target_s);
            let a = jacobian(&model, law, &y);
            let base = y.to_array();
            for col in 0..14 {
                let f_at = |dx: f64| {
                    let mut z = base;
                    z[col] += dx;
                    model.derivative(law, &Augmented::from_array(&z)).to_array()
                };
                let h = 1e-6 * (1.0 + base[col].abs());
                let (plus, minus) = (f_at(h), f_at(-h));
                for row in 0..14 {
                    let fd = (plus[row] - minus[row]) / (2.0 * h);
                    let scale = 1.0 + fd.abs();
                    assert!(
                        (a[(row, col)] - fd).abs() < 1e-5 * scale,
                        "{law:?} S {target_s}: A[{row}][{col}] = {} against {fd}",
                        a[(row, col)]
                    );
                }
            }
        }
    }
}
