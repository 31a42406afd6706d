//! The few dense kernels planner A needs, on fixed-size square arrays: Cholesky factorisation
//! and triangular solves on the leading `n x n` block. No allocation, no panics.
//!
//! Only the lower triangle is read. Rows are walked as slices split at the diagonal and columns
//! as walks over the rows (`column`), so no entry is read through an index that could
//! miss; a row that a split cannot reach (`n` beyond the array) ends the kernel with a failure
//! its caller acts on, never with a made-up entry.

use crate::indexed::IndexedExt as _;

/// `start - x_1 y_1 - x_2 y_2 - ...`, subtracted in order: the inner step of every kernel here
/// and in `packed.rs`, so the dense and the packed kernels round alike.
pub(crate) fn minus_products(start: f64, pairs: impl IntoIterator<Item = (f64, f64)>) -> f64 {
    let mut value = start;
    for (x, y) in pairs {
        value -= x * y;
    }
    value
}

/// Entry `i` of `b` and the entries after it (back substitution's unknown and the solved
/// ones), `None` past the end.
pub(crate) fn slot_and_later(b: &mut [f64], i: usize) -> Option<(&mut f64, &mut [f64])> {
    b.split_at_mut_checked(i)
        .and_then(|(_, rest)| rest.split_first_mut())
}

/// Column `j` of `a` from row `from` down: `a[from][j], a[from + 1][j], ...`.
fn column<const C: usize>(
    a: &[[f64; C]; C],
    j: usize,
    from: usize,
) -> impl Iterator<Item = f64> + '_ {
    // Each row's entry `j` (a row has none only when `j` is outside the array: then the
    // column is empty). Not `flatten().step_by(C)`: `StepBy::nth` divides, and its
    // division-by-zero check is a panic path the abort-proof C library must not link.
    a.iter()
        .skip(from)
        .filter_map(move |row| row.get(j).copied())
}

/// Cholesky-factor the leading `n x n` block of `a` in place (lower triangle holds L, the
/// strict upper triangle is left untouched). Returns the index of the first pivot that is not
/// positive (the matrix is not numerically positive definite there, or `n` exceeds the array),
/// or `None` on success.
pub(crate) fn cholesky_in_place<const C: usize>(a: &mut [[f64; C]; C], n: usize) -> Option<usize> {
    for j in 0..n {
        let Some((head, below)) = a.split_at_mut_checked(j.saturating_add(1)) else {
            return Some(j);
        };
        let Some((left, diagonal)) = head.last_mut().and_then(|row| split_at_diagonal(row, j))
        else {
            return Some(j);
        };
        let diag = minus_products(*diagonal, left.iter().map(|&l| (l, l)));
        if diag.is_nan() || diag <= 0.0 {
            return Some(j);
        }
        let pivot = libm::sqrt(diag);
        *diagonal = pivot;
        for row in below.iter_mut().take(n.saturating_sub(j.saturating_add(1))) {
            let Some((row_left, entry)) = split_at_diagonal(row, j) else {
                return Some(j);
            };
            *entry =
                minus_products(*entry, row_left.iter().copied().zip(left.iter().copied())) / pivot;
        }
    }
    None
}

/// Row `row` split at entry `i`: the entries left of it, and the entry.
fn split_at_diagonal<const C: usize>(
    row: &mut [f64; C],
    i: usize,
) -> Option<(&mut [f64], &mut f64)> {
    let (left, right) = row.split_at_mut_checked(i)?;
    Some((left, right.first_mut()?))
}

/// Solve `L x = b` in place (forward substitution) with L in the lower triangle of `l`.
/// Returns false (with `b` partly solved) when `n` exceeds the arrays.
#[must_use]
pub(crate) fn solve_lower<const C: usize>(l: &[[f64; C]; C], n: usize, b: &mut [f64; C]) -> bool {
    for (i, row) in l.iter().take(n).indexed() {
        let (Some((left, right)), Some((solved, rest))) =
            (row.split_at_checked(i), b.split_at_mut_checked(i))
        else {
            return false;
        };
        let (Some(&diagonal), Some(slot)) = (right.first(), rest.first_mut()) else {
            return false;
        };
        *slot = minus_products(*slot, left.iter().copied().zip(solved.iter().copied())) / diagonal;
    }
    true
}

/// Solve `L^T x = b` in place (back substitution) with L in the lower triangle of `l`.
/// Returns false (with `b` partly solved) when `n` exceeds the arrays.
#[must_use]
pub(crate) fn solve_lower_transposed<const C: usize>(
    l: &[[f64; C]; C],
    n: usize,
    b: &mut [f64; C],
) -> bool {
    let n = n.min(C);
    for i in (0..n).rev() {
        let Some((slot, later)) = slot_and_later(b, i) else {
            return false;
        };
        // Column i from the diagonal down: L[i][i], then L[k][i] for k > i.
        let mut below = column(l, i, i);
        let Some(diagonal) = below.next() else {
            return false;
        };
        let later = later.iter().copied();
        let pairs = below.zip(later).take(n.saturating_sub(i.saturating_add(1)));
        *slot = minus_products(*slot, pairs) / diagonal;
    }
    true
}

#[cfg(test)]
pub(super) mod tests {
    use super::*;

    /// The SPD test matrix of the dense and the packed Cholesky, and its right-hand side.
    pub(in crate::pseudospectral) const SPD: [[f64; 3]; 3] =
        [[4.0, 2.0, 0.4], [2.0, 5.0, 1.0], [0.4, 1.0, 3.0]];
    pub(in crate::pseudospectral) const RHS: [f64; 3] = [1.0, 2.0, 3.0];

    /// `solve` (both triangular solves of a factor of `SPD`) turns `RHS` into `x` with
    /// `SPD x = RHS` to 1e-14.
    pub(in crate::pseudospectral) fn assert_solves_spd(solve: impl FnOnce(&mut [f64; 3]) -> bool) {
        let mut x = RHS;
        assert!(solve(&mut x));
        for i in 0..3 {
            let row: f64 = (0..3).map(|j| SPD[i][j] * x[j]).sum();
            assert!((row - RHS[i]).abs() < 1e-14);
        }
    }

    #[test]
    fn cholesky_solves_spd_system() {
        let mut a = SPD;
        assert_eq!(cholesky_in_place(&mut a, 3), None);
        assert_solves_spd(|x| solve_lower(&a, 3, x) && solve_lower_transposed(&a, 3, x));
    }

    #[test]
    fn cholesky_reports_failing_pivot() {
        let mut a = [[1.0, 2.0], [2.0, 1.0]];
        assert_eq!(cholesky_in_place(&mut a, 2), Some(1));
    }

    #[test]
    fn an_order_beyond_the_array_is_a_failure() {
        let mut a = [[4.0, 0.0], [0.0, 4.0]];
        assert_eq!(cholesky_in_place(&mut a, 3), Some(2));
    }
}
