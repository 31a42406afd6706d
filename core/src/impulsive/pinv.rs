//! Minimum-norm least-squares solution `x = F^+ y` by a one-sided Jacobi (Hestenes) SVD of
//! `F^T`, with the numerical rank and the 2-norm condition number (Wang 2018, eq. 13-14).
//!
//! Why not nalgebra's SVD: nalgebra 0.35's `SVD` returned singular vectors that do not
//! reconstruct rank-deficient inputs (see `nalgebra_svd_is_unreliable_when_rank_deficient`
//! below), which is exactly the case (coincident impulse points) that must be solved in the
//! least-squares sense and reported. One-sided Jacobi is rank-revealing, accurate for small
//! singular values, needs only rotations (no FMA), and its sweeps are bounded by a setting.

use super::status::Stage;
use super::transfer::{FMatrix, XVector, MAX_UNKNOWNS};
use crate::indexed::IndexedExt as _;
use nalgebra::{Cholesky, SMatrix, SVector};

/// Rank and conditioning of one pseudo-inverse.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub(crate) struct Conditioning {
    /// Singular values above `rcond * sigma_max`.
    pub rank: u8,
    /// `sigma_max / sigma_min` over the `min(6, columns)` largest singular values (infinite
    /// when rank-deficient).
    pub condition_number: f64,
}

fn dot(a: &[f64], b: &[f64]) -> f64 {
    let mut s = 0.0;
    for (x, y) in a.iter().zip(b.iter()) {
        s += *x * *y;
    }
    s
}

/// Rotate columns `p`, `q`: `p' = c p - s q`, `q' = s p + c q`.
fn rotate(p: &mut [f64], q: &mut [f64], c: f64, s: f64) {
    for (x, y) in p.iter_mut().zip(q.iter_mut()) {
        let (xp, yq) = (*x, *y);
        *x = c * xp - s * yq;
        *y = s * xp + c * yq;
    }
}

/// `x = F^+ y` with singular values below `rcond * sigma_max` treated as zero. `columns` is the
/// number of unknowns in use (3 per impulse); the remaining columns of `f` are ignored and the
/// matching entries of `x` are zero. At most `max_sweeps` Jacobi sweeps of 15 rotations;
/// `sweeps` is set to the sweeps made (the caller charges them, `work_units::svd`).
///
/// # Errors
/// [`Stage::Svd`] when the sweeps do not converge or a value is not finite.
pub(crate) fn solve_min_norm(
    f: &FMatrix,
    columns: usize,
    y: &SVector<f64, 6>,
    rcond: f64,
    max_sweeps: u16,
    sweeps: &mut u16,
) -> Result<(XVector, Conditioning), Stage> {
    *sweeps = 0;
    let used = columns.clamp(1, MAX_UNKNOWNS);
    // w[j] = row j of F = column j of A = F^T; v accumulates the right rotations (A V = W).
    let mut w = [[0.0f64; MAX_UNKNOWNS]; 6];
    for (row, f_row) in w.iter_mut().zip(f.row_iter()) {
        for (x, fv) in row.iter_mut().zip(f_row.iter()).take(used) {
            *x = *fv;
        }
    }
    if !w.iter().flatten().all(|v| v.is_finite()) || !y.iter().all(|v| v.is_finite()) {
        return Err(Stage::Svd);
    }
    let mut v = [[0.0f64; 6]; 6];
    for (j, col) in v.iter_mut().indexed() {
        if let Some(x) = col.get_mut(j) {
            *x = 1.0;
        }
    }
    // Columns below this squared norm are numerical zeros (rank deficiency): rotating them
    // against each other would never settle.
    let mut scale2 = 0.0f64;
    for col in w.iter() {
        scale2 = scale2.max(col.iter().take(used).fold(0.0, |acc, x| acc + *x * *x));
    }
    let negligible = 16.0 * f64::EPSILON * f64::EPSILON * scale2;
    // Off-diagonal test relative to the column norms, scaled with the row count as usual for
    // one-sided Jacobi (a plain epsilon can cycle on rounding).
    let orthogonal = f64::EPSILON * (used as f64);
    let mut converged = false;
    for _ in 0..max_sweeps {
        *sweeps = sweeps.saturating_add(1);
        let mut rotated = false;
        for p in 0..6usize {
            for q in p.saturating_add(1)..6 {
                let (head, tail) = w.split_at_mut(q);
                let (Some(wp), Some(wq)) = (head.get_mut(p), tail.first_mut()) else {
                    continue;
                };
                let (Some(wp), Some(wq)) = (wp.get_mut(..used), wq.get_mut(..used)) else {
                    continue;
                };
                let alpha = dot(wp, wp);
                let beta = dot(wq, wq);
                let gamma = dot(wp, wq);
                if alpha <= negligible
                    || beta <= negligible
                    || libm::fabs(gamma) <= orthogonal * libm::sqrt(alpha * beta)
                {
                    continue;
                }
                rotated = true;
                let zeta = (beta - alpha) / (2.0 * gamma);
                let t =
                    libm::copysign(1.0, zeta) / (libm::fabs(zeta) + libm::sqrt(1.0 + zeta * zeta));
                let c = 1.0 / libm::sqrt(1.0 + t * t);
                let s = c * t;
                rotate(wp, wq, c, s);
                let (vh, vt) = v.split_at_mut(q);
                if let (Some(vp), Some(vq)) = (vh.get_mut(p), vt.first_mut()) {
                    rotate(vp, vq, c, s);
                }
            }
        }
        if !rotated {
            converged = true;
            break;
        }
    }
    if !converged {
        return Err(Stage::Svd);
    }
    let mut sigma = [0.0f64; 6];
    for (s, col) in sigma.iter_mut().zip(w.iter()) {
        *s = libm::sqrt(col.iter().take(used).fold(0.0, |acc, x| acc + *x * *x));
    }
    let mut sorted = sigma;
    sorted.sort_unstable_by(|a, b| b.total_cmp(a));
    let sigma_max = sorted[0];
    // The smallest of the `used` (>= 1) values in use: the last of the first `used` sorted ones.
    let sigma_min = sorted.iter().take(used).fold(sigma_max, |_, s| *s);
    let threshold = rcond * sigma_max;
    // F = V diag(sigma) U^T with W = U diag(sigma), so F^+ y = sum_j w_j (v_j . y) / sigma_j^2.
    let mut x = XVector::zeros();
    let mut rank = 0u8;
    for ((col, vj), s) in w.iter().zip(v.iter()).zip(sigma.iter()) {
        if sigma_max > 0.0 && *s > threshold {
            rank = rank.saturating_add(1);
            let coeff = dot(vj, y.as_slice()) / (*s * *s);
            for (xi, wi) in x.iter_mut().zip(col.iter()).take(used) {
                *xi += coeff * *wi;
            }
        }
    }
    if !x.iter().all(|v| v.is_finite()) {
        return Err(Stage::Svd);
    }
    let condition_number = if sigma_min > threshold && sigma_min > 0.0 {
        sigma_max / sigma_min
    } else {
        f64::INFINITY
    };
    Ok((
        x,
        Conditioning {
            rank,
            condition_number,
        },
    ))
}

/// `x = F^T (F F^T)^-1 y` on the row-equilibrated F, by Cholesky: the same minimum-norm
/// solution as [`solve_min_norm`] when F has full row rank (row scaling `D` leaves
/// `(D F)^+ D y = F^+ y` unchanged then), at a fraction of the cost. Equilibration removes the
/// km-versus-rad row scaling that makes F's condition number ~4e4, so the normal equations
/// stay accurate. `None` when a row is zero or a Cholesky pivot falls below `1e-6` (the
/// equilibrated Gram matrix has a unit diagonal): the caller then uses the SVD.
pub(crate) fn solve_full_row_rank(f: &FMatrix, y: &SVector<f64, 6>) -> Option<XVector> {
    let mut fs = *f;
    let mut ys = *y;
    for (mut row, yi) in fs.row_iter_mut().zip(ys.iter_mut()) {
        let norm = libm::sqrt(row.dot(&row));
        if !(norm > 0.0 && norm.is_finite()) {
            return None;
        }
        row.scale_mut(1.0 / norm);
        *yi /= norm;
    }
    let fst = fs.transpose();
    let mut gram = SMatrix::<f64, 6, 6>::zeros();
    gram.gemm_tr(1.0, &fst, &fst, 0.0);
    let chol = Cholesky::new(gram)?;
    if !chol.l_dirty().diagonal().iter().all(|d| *d > 1e-6) {
        return None;
    }
    let z = chol.solve(&ys);
    let mut x = XVector::zeros();
    x.gemv(1.0, &fst, &z, 0.0);
    if x.iter().all(|v| v.is_finite()) {
        Some(x)
    } else {
        None
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn minimum_norm_of_an_underdetermined_system() {
        // Deterministic well-conditioned 6 x 9 matrix.
        let mut f = FMatrix::zeros();
        let mut seed = 1u64;
        for c in 0..9 {
            for r in 0..6 {
                seed = seed
                    .wrapping_mul(6364136223846793005)
                    .wrapping_add(1442695040888963407);
                f[(r, c)] = ((seed >> 11) as f64 / (1u64 << 53) as f64) - 0.5;
            }
        }
        let y = SVector::<f64, 6>::new(1.0, -2.0, 0.5, 0.3, 0.0, 1.5);
        let (x, cond) = solve_min_norm(&f, 9, &y, 1e-12, 200, &mut 0).unwrap();
        assert_eq!(cond.rank, 6);
        assert!(cond.condition_number.is_finite() && cond.condition_number > 1.0);
        // Solves the system.
        let r = f * x - y;
        assert!(r.norm() < 1e-12);
        // Minimum norm: x lies in the row space of F, i.e. x = F^T z.
        let z = (f * f.transpose()).try_inverse().unwrap() * y;
        let x_ref = f.transpose() * z;
        assert!((x - x_ref).norm() < 1e-12);
        for k in 9..18 {
            assert_eq!(x[k], 0.0);
        }
    }

    #[test]
    fn rank_deficient_reports_rank() {
        let mut f = FMatrix::zeros();
        // Two identical 6x3 blocks of rank 3: F has rank 3.
        for r in 0..6 {
            for c in 0..3 {
                let v = ((r * 3 + c) as f64 * 0.37).sin() + if r == c { 2.0 } else { 0.0 };
                f[(r, c)] = v;
                f[(r, c + 3)] = v;
            }
        }
        let y = SVector::<f64, 6>::new(1.0, 1.0, 1.0, 1.0, 1.0, 1.0);
        let (x, cond) = solve_min_norm(&f, 6, &y, 1e-10, 200, &mut 0).unwrap();
        assert_eq!(cond.rank, 3);
        assert!(cond.condition_number.is_infinite());
        // Least squares: the residual is orthogonal to the range of F.
        let r = f * x - y;
        assert!((f.transpose() * r).norm() < 1e-10);
        // Symmetric split between the identical blocks (minimum norm).
        for c in 0..3 {
            assert!((x[c] - x[c + 3]).abs() < 1e-12);
        }
    }

    #[test]
    fn nalgebra_svd_is_unreliable_when_rank_deficient() {
        // The case that made us write our own: a consistent rank-3 system with scaled blocks.
        let mut f = FMatrix::zeros();
        for (k, g) in [0.1, 0.2, 0.3].iter().enumerate() {
            for r in 0..3 {
                f[(r, 3 * k + r)] = *g * if k == 0 { 0.1 } else { 1.0 };
            }
            f[(3, 3 * k)] = *g * 0.5 * if k == 0 { 0.1 } else { 1.0 };
            f[(4, 3 * k + 1)] = *g * 0.25 * if k == 0 { 0.1 } else { 1.0 };
            f[(5, 3 * k + 2)] = *g * 0.125 * if k == 0 { 0.1 } else { 1.0 };
        }
        let y = SVector::<f64, 6>::new(3.0, 0.0, 0.0, 1.5, 0.0, 0.0);
        let (x, cond) = solve_min_norm(&f, 9, &y, 1e-10, 60, &mut 0).unwrap();
        assert_eq!(cond.rank, 3);
        assert!((f * x - y).norm() < 1e-12, "{}", (f * x - y).norm());
    }

    #[test]
    fn cholesky_path_agrees_with_the_svd_and_declines_rank_deficiency() {
        let mut f = FMatrix::zeros();
        let mut seed = 7u64;
        for c in 0..9 {
            for r in 0..6 {
                seed = seed
                    .wrapping_mul(6364136223846793005)
                    .wrapping_add(1442695040888963407);
                // Rows on very different scales, like F (km vs rad).
                let scale = if r == 0 { 2e3 } else { 0.1 };
                f[(r, c)] = scale * (((seed >> 11) as f64 / (1u64 << 53) as f64) - 0.5);
            }
        }
        let y = SVector::<f64, 6>::new(1.0, -2.0e-4, 5e-5, 3e-5, 0.0, 1.5e-4);
        let (x_svd, _) = solve_min_norm(&f, 9, &y, 1e-12, 200, &mut 0).unwrap();
        let x = solve_full_row_rank(&f, &y).unwrap();
        assert!(
            (x - x_svd).norm() < 1e-12 * x_svd.norm(),
            "{}",
            (x - x_svd).norm()
        );
        let mut g = FMatrix::zeros();
        for r in 0..6 {
            for c in 0..3 {
                g[(r, c)] = ((r * 3 + c) as f64 * 0.37).sin() + if r == c { 2.0 } else { 0.0 };
                g[(r, c + 3)] = g[(r, c)];
            }
        }
        assert!(solve_full_row_rank(&g, &y).is_none());
    }

    #[test]
    fn non_finite_is_an_svd_failure() {
        let mut f = FMatrix::zeros();
        f[(0, 0)] = f64::NAN;
        let y = SVector::<f64, 6>::zeros();
        assert_eq!(
            solve_min_norm(&f, 3, &y, 1e-10, 50, &mut 0),
            Err(Stage::Svd)
        );
    }
}
