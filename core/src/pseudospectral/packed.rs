//! Lower-triangular matrices stored packed by rows (`L[i][j]`, `j <= i`, at `i (i + 1) / 2 + j`).
//!
//! Why: the QP's Gram factor is lower triangular, so a square array wastes half its memory.
//! Packed, the factor of `MAX_ACTIVE` rows takes `MAX_ACTIVE (MAX_ACTIVE + 1) / 2` numbers
//! (12.8 KB instead of 25.1 KB), and the same buffer doubles as the dual table of the QP's
//! capacity-free fallback (`qp_dual.rs`).

use super::linalg::{minus_products, slot_and_later};
use crate::indexed::IndexedExt as _;

/// Numbers a packed lower triangle of order `n` takes.
pub(crate) const fn packed_len(n: usize) -> usize {
    n.saturating_mul(n.saturating_add(1)) / 2
}

/// Position of `L[i][j]` (`j <= i`).
fn at(i: usize, j: usize) -> usize {
    (i.saturating_mul(i.saturating_add(1)) / 2).saturating_add(j)
}

/// `L[i][j] = value`, ignored outside the buffer.
pub(crate) fn set<const S: usize>(l: &mut [f64; S], i: usize, j: usize, value: f64) {
    if let Some(slot) = l.get_mut(at(i, j)) {
        *slot = value;
    }
}

/// Whether a triangle of order `n` fits in a buffer of `S` numbers.
pub(crate) const fn fits<const S: usize>(n: usize) -> bool {
    packed_len(n) <= S
}

/// Row `i` of the triangle in `rest`, which starts at row `i`: `L[i][..i]` and `L[i][i]`, and
/// the rows after it (`None` when the buffer ends first).
fn split_row(rest: &mut [f64], i: usize) -> Option<(&mut [f64], &mut f64, &mut [f64])> {
    let (row, after) = rest.split_at_mut_checked(i.checked_add(1)?)?;
    let (diagonal, left) = row.split_last_mut()?;
    Some((left, diagonal, after))
}

/// Cholesky-factor the packed symmetric matrix (lower triangle given) of order `n` in place.
/// Returns the index of the first pivot that is not positive, or `None` on success.
pub(crate) fn cholesky<const S: usize>(a: &mut [f64; S], n: usize) -> Option<usize> {
    if !fits::<S>(n) {
        return Some(0);
    }
    // Row j, then the rows below it in order, each split off the buffer (so row j is read
    // beside the rows it updates, the same products in the same order as indexing both).
    let mut rest: &mut [f64] = a;
    for j in 0..n {
        let Some((left, diagonal, below)) = split_row(rest, j) else {
            return Some(j);
        };
        let diag = minus_products(*diagonal, left.iter().map(|&l| (l, l)));
        if diag.is_nan() || diag <= 0.0 {
            return Some(j);
        }
        let pivot = libm::sqrt(diag);
        *diagonal = pivot;
        let mut lower: &mut [f64] = &mut *below;
        for i in (j.saturating_add(1))..n {
            // Row i: its first j entries beside row j's, then entry j.
            let Some((row_i, _, after)) = split_row(lower, i) else {
                return Some(j);
            };
            let Some((head, tail)) = row_i.split_at_mut_checked(j) else {
                return Some(j);
            };
            let Some(entry) = tail.first_mut() else {
                return Some(j);
            };
            *entry = minus_products(*entry, head.iter().copied().zip(left.iter().copied())) / pivot;
            lower = after;
        }
        rest = below;
    }
    None
}

/// Solve `L x = b` in place (forward substitution). Returns false (with `b` partly solved) when
/// the buffer does not hold a triangle of order `min(n, C)`.
#[must_use]
pub(crate) fn solve_lower<const S: usize, const C: usize>(
    l: &[f64; S],
    n: usize,
    b: &mut [f64; C],
) -> bool {
    let mut rows: &[f64] = l;
    for i in 0..n.min(C) {
        // Row i of L is contiguous: walk it beside b (the same products, in order).
        let Some((row, after)) = rows.split_at_checked(i.saturating_add(1)) else {
            return false;
        };
        let (Some((&diagonal, left)), Some((solved, unsolved))) =
            (row.split_last(), b.split_at_mut_checked(i))
        else {
            return false;
        };
        let Some(slot) = unsolved.first_mut() else {
            return false;
        };
        *slot = minus_products(*slot, left.iter().copied().zip(solved.iter().copied())) / diagonal;
        rows = after;
    }
    true
}

/// Solve `L^T x = b` in place (back substitution). Returns false (with `b` partly solved) when
/// the buffer does not hold a triangle of order `min(n, C)`.
#[must_use]
pub(crate) fn solve_lower_transposed<const S: usize, const C: usize>(
    l: &[f64; S],
    n: usize,
    b: &mut [f64; C],
) -> bool {
    let n = n.min(C);
    for i in (0..n).rev() {
        let Some((slot, later)) = slot_and_later(b, i) else {
            return false;
        };
        let Some(&diagonal) = l.get(at(i, i)) else {
            return false;
        };
        let mut value = *slot;
        // Column i below the diagonal: L[k][i] sits k + 1 numbers after L[k - 1][i].
        let mut index = at(i.saturating_add(1), i);
        for (k, bk) in later
            .iter()
            .take(n.saturating_sub(i.saturating_add(1)))
            .indexed()
        {
            let Some(&lki) = l.get(index) else {
                return false;
            };
            value -= lki * bk;
            index = index
                .saturating_add(i.saturating_add(1).saturating_add(k))
                .saturating_add(1);
        }
        *slot = value / diagonal;
    }
    true
}

#[cfg(test)]
#[allow(clippy::needless_range_loop)]
mod tests {
    use super::*;

    #[test]
    fn packed_cholesky_solves_an_spd_system() {
        use crate::pseudospectral::linalg::tests::{assert_solves_spd, SPD};
        let mut a = [0.0; 6];
        for i in 0..3 {
            for j in 0..=i {
                set(&mut a, i, j, SPD[i][j]);
            }
        }
        assert_eq!(cholesky(&mut a, 3), None);
        assert_solves_spd(|x| solve_lower(&a, 3, x) && solve_lower_transposed(&a, 3, x));
    }

    #[test]
    fn packed_cholesky_reports_the_failing_pivot_and_a_short_buffer() {
        let mut a = [1.0, 2.0, 1.0];
        assert_eq!(cholesky(&mut a, 2), Some(1));
        let mut short = [1.0, 0.0];
        assert_eq!(cholesky(&mut short, 2), Some(0));
    }
}
