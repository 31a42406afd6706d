//! The shootings' Newton step: `A x = b` for the small square systems of the shootings (7 and
//! 9 unknowns) by Gaussian elimination with full pivoting, written so that no path can panic
//! (every element reached through `get`, rows swapped by copies): nalgebra's `full_piv_lu`
//! carries bounds-check panics that survive optimisation, which a flight image must not link
//! (the C interface's abort-free link check found them).

use crate::indexed::IndexedExt as _;
use nalgebra::{SMatrix, SVector};

/// Pivots at or below this fraction of the matrix's largest element count as zero: the
/// system is singular to working precision.
const SINGULAR_REL: f64 = 1e-14;

/// Swap rows `i` and `j` of `rows` (copies: no two mutable borrows, no slice panics).
fn swap<T: Copy>(rows: &mut [T], i: usize, j: usize) -> Option<()> {
    let (ri, rj) = (*rows.get(i)?, *rows.get(j)?);
    *rows.get_mut(i)? = rj;
    *rows.get_mut(j)? = ri;
    Some(())
}

/// Solve `a x = b`; `None` when `a` is singular to working precision (or holds a non-finite
/// number).
pub(crate) fn solve<const K: usize>(
    a: &SMatrix<f64, K, K>,
    b: &SVector<f64, K>,
) -> Option<SVector<f64, K>> {
    // Rows of `a`, the right-hand side, and which unknown each column now stands for.
    let mut m = [[0.0; K]; K];
    for (i, row) in m.iter_mut().indexed() {
        for (j, x) in row.iter_mut().indexed() {
            *x = *a.get((i, j))?;
        }
    }
    let mut rhs = [0.0; K];
    for (i, x) in rhs.iter_mut().indexed() {
        *x = *b.get(i)?;
    }
    let mut unknown = [0usize; K];
    for (j, u) in unknown.iter_mut().indexed() {
        *u = j;
    }
    let scale = m
        .iter()
        .flat_map(|row| row.iter())
        .fold(0.0f64, |s, x| s.max(libm::fabs(*x)));
    if !scale.is_finite() || scale <= 0.0 {
        return None;
    }
    for col in 0..K {
        // The largest remaining element.
        let mut best = (col, col, -1.0f64);
        for (r, row) in m.iter().indexed().skip(col) {
            for (c, x) in row.iter().indexed().skip(col) {
                if libm::fabs(*x) > best.2 {
                    best = (r, c, libm::fabs(*x));
                }
            }
        }
        let (pr, pc, size) = best;
        if size <= SINGULAR_REL * scale {
            return None;
        }
        swap(&mut m, col, pr)?;
        swap(&mut rhs, col, pr)?;
        if pc != col {
            for row in &mut m {
                swap(row, col, pc)?;
            }
            swap(&mut unknown, col, pc)?;
        }
        let pivot_row = *m.get(col)?;
        let pivot = *pivot_row.get(col)?;
        let pivot_rhs = *rhs.get(col)?;
        for (row, r) in m.iter_mut().zip(rhs.iter_mut()).skip(col.saturating_add(1)) {
            let factor = *row.get(col)? / pivot;
            for (x, p) in row.iter_mut().zip(pivot_row.iter()).skip(col) {
                *x -= factor * p;
            }
            *r -= factor * pivot_rhs;
        }
    }
    // Back substitution in the permuted unknowns.
    let mut y = [0.0; K];
    for i in (0..K).rev() {
        let row = m.get(i)?;
        let tail: f64 = row
            .iter()
            .zip(y.iter())
            .skip(i.saturating_add(1))
            .map(|(a, x)| a * x)
            .sum();
        *y.get_mut(i)? = (*rhs.get(i)? - tail) / *row.get(i)?;
    }
    let mut x = SVector::<f64, K>::zeros();
    for (value, &u) in y.iter().zip(unknown.iter()) {
        *x.get_mut(u)? = *value;
    }
    x.iter().all(|v| v.is_finite()).then_some(x)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn it_solves_what_nalgebra_solves_and_refuses_a_singular_system() {
        // A badly scaled system with a zero on the diagonal: full pivoting needed.
        let a = SMatrix::<f64, 4, 4>::from_row_slice(&[
            0.0, 2.0, 1e-6, 3.0, //
            4.0, 1.0, 0.0, -2.0, //
            1e3, -7.0, 2.0, 0.5, //
            0.25, 0.0, -1e-3, 9.0,
        ]);
        let b = SVector::<f64, 4>::from([1.0, -2.0, 3.0, 0.5]);
        let x = solve(&a, &b).expect("regular");
        let reference = a.full_piv_lu().solve(&b).expect("regular");
        for (u, v) in x.iter().zip(reference.iter()) {
            assert!(
                (u - v).abs() <= 1e-12 * (1.0 + v.abs()),
                "{x} against {reference}"
            );
        }
        let residual = a * x - b;
        assert!(residual.amax() < 1e-12, "{residual}");
        // Two equal rows: singular.
        let mut s = a;
        s.set_row(3, &a.row(1));
        assert_eq!(solve(&s, &b), None);
        // A NaN: refused, not propagated.
        let mut n = a;
        n[(2, 2)] = f64::NAN;
        assert_eq!(solve(&n, &b), None);
    }
}
