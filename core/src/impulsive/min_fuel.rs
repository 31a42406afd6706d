//! Least fuel at fixed impulse points: minimise `sum_k |dv_k|` subject to `F dX = dY` over the
//! null space of eq. 13, by iteratively reweighted least squares.
//!
//! Each step solves `min sum_k |x_k|^2 / w_k  s.t.  F x = y` with `w_k = max(|x_k|, floor)`
//! from the previous iterate, i.e. `x = W^(1/2) (F W^(1/2))^+ y`. This is a majorise-minimise
//! step for the sum of norms, so the total never increases (up to the floor); it starts from
//! the minimum-norm solution. Bounded by `Settings::min_fuel_max_iter`.

use super::pinv::{solve_full_row_rank, solve_min_norm};
use super::settings::Settings;
use super::status::Stage;
use super::transfer::{FMatrix, XVector};
use nalgebra::SVector;

/// `F^+ y` by the equilibrated Cholesky fast path, or the SVD when it declines.
///
/// # Errors
/// [`Stage::Svd`] from the SVD.
pub(crate) fn min_norm(
    f: &FMatrix,
    columns: usize,
    y: &SVector<f64, 6>,
    settings: &Settings,
) -> Result<XVector, Stage> {
    match solve_full_row_rank(f, y) {
        Some(x) => Ok(x),
        None => {
            solve_min_norm(f, columns, y, settings.rank_rcond, settings.svd_max_iter).map(|r| r.0)
        }
    }
}

/// Euclidean norm of one impulse block.
fn norm3(b: &[f64]) -> f64 {
    let mut s = 0.0;
    for v in b {
        s += *v * *v;
    }
    libm::sqrt(s)
}

/// `sum_k |x_k|` over the impulse blocks, in the units of `x`.
pub(crate) fn total(x: &XVector) -> f64 {
    x.as_slice().chunks_exact(3).map(norm3).sum()
}

/// Refine `start` (which must satisfy `F x = y`) towards least `sum_k |x_k|`.
/// Returns the refined impulses, the conditioning of the last weighted solve and the steps used.
///
/// # Errors
/// [`Stage::Svd`] from the weighted pseudo-inverse.
pub(crate) fn refine(
    f: &FMatrix,
    columns: usize,
    y: &SVector<f64, 6>,
    start: &XVector,
    settings: &Settings,
) -> Result<(XVector, u16), Stage> {
    // Work in km/s like F; the floor and tolerance are given in m/s.
    let floor = settings.min_fuel_floor_mps * 1e-3;
    let tol = settings.min_fuel_tol_mps * 1e-3;
    let mut x = *start;
    let mut cost = total(&x);
    let mut steps = 0u16;
    for _ in 0..settings.min_fuel_max_iter {
        let mut scale = XVector::zeros();
        for (s_block, x_block) in scale
            .as_mut_slice()
            .chunks_exact_mut(3)
            .zip(x.as_slice().chunks_exact(3))
        {
            let mag = norm3(x_block);
            let w = libm::sqrt(if mag > floor { mag } else { floor });
            for s in s_block.iter_mut() {
                *s = w;
            }
        }
        let mut g = *f;
        for (mut col, s) in g.column_iter_mut().zip(scale.iter()) {
            col.scale_mut(*s);
        }
        let z = min_norm(&g, columns, y, settings)?;
        let next = z.component_mul(&scale);
        let next_cost = total(&next);
        steps = steps.saturating_add(1);
        let done = libm::fabs(cost - next_cost) <= tol;
        // Keep the better iterate: reweighting is monotone up to the floor and rounding.
        if next_cost <= cost {
            x = next;
            cost = next_cost;
        }
        if done {
            break;
        }
    }
    Ok((x, steps))
}

#[cfg(test)]
#[allow(clippy::unwrap_used, clippy::indexing_slicing, clippy::float_cmp)]
mod tests {
    use super::*;

    #[test]
    fn prefers_one_impulse_when_it_is_cheaper() {
        // Three impulses that each reach y along the same direction with different gains:
        // min sum |x_k| puts everything on the largest gain; minimum norm spreads it.
        let mut f = FMatrix::zeros();
        let gains = [1.0, 2.0, 3.0];
        for (k, g) in gains.iter().enumerate() {
            for r in 0..3 {
                f[(r, 3 * k + r)] = *g;
            }
            // Rows 3..6 repeat rows 0..3 scaled: F has rank 3 and y is consistent with it.
            f[(3, 3 * k)] = *g * 0.5;
            f[(4, 3 * k + 1)] = *g * 0.25;
            f[(5, 3 * k + 2)] = *g * 0.125;
        }
        let y = SVector::<f64, 6>::new(3.0, 0.0, 0.0, 1.5, 0.0, 0.0);
        let (x0, _) = solve_min_norm(&f, 9, &y, 1e-12, 200).unwrap();
        let settings = Settings {
            min_fuel_max_iter: 200,
            ..Settings::default()
        };
        let (x, steps) = refine(&f, 9, &y, &x0, &settings).unwrap();
        assert!(steps > 1);
        assert!(total(&x) <= total(&x0));
        assert!((f * x - y).norm() < 1e-9, "{}", (f * x - y).norm());
        // Optimum: all on the gain-3 impulse, |x| = 1.
        assert!((total(&x) - 1.0).abs() < 1e-6, "{}", total(&x));
        assert!(total(&x0) > 1.0 + 1e-3);
    }
}
