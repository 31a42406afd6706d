//! Lower-triangular matrices stored packed by rows (`L[i][j]`, `j <= i`, at `i (i + 1) / 2 + j`).
//!
//! Why: the QP's Gram factor is lower triangular, so a square array wastes half its memory.
//! Packed, the factor of `MAX_ACTIVE` rows takes `MAX_ACTIVE (MAX_ACTIVE + 1) / 2` numbers
//! (12.8 KB instead of 25.1 KB), and the same buffer doubles as the dual table of the QP's
//! capacity-free fallback (`qp_dual.rs`).

use crate::indexed::IndexedExt as _;

/// Numbers a packed lower triangle of order `n` takes.
pub(crate) const fn packed_len(n: usize) -> usize {
    n.saturating_mul(n.saturating_add(1)) / 2
}

/// Position of `L[i][j]` (`j <= i`).
fn at(i: usize, j: usize) -> usize {
    (i.saturating_mul(i.saturating_add(1)) / 2).saturating_add(j)
}

/// `L[i][j]`, 0 outside the buffer.
pub(crate) fn get<const S: usize>(l: &[f64; S], i: usize, j: usize) -> f64 {
    l.get(at(i, j)).copied().unwrap_or(0.0)
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

/// Cholesky-factor the packed symmetric matrix (lower triangle given) of order `n` in place.
/// Returns the index of the first pivot that is not positive, or `None` on success.
pub(crate) fn cholesky<const S: usize>(a: &mut [f64; S], n: usize) -> Option<usize> {
    if !fits::<S>(n) {
        return Some(0);
    }
    for j in 0..n {
        let mut diag = get(a, j, j);
        for k in 0..j {
            let l = get(a, j, k);
            diag -= l * l;
        }
        if diag.is_nan() || diag <= 0.0 {
            return Some(j);
        }
        let pivot = libm::sqrt(diag);
        set(a, j, j, pivot);
        // Row j's first j entries, copied out so rows i > j can be updated beside them (the
        // same products in the same order as indexing both rows).
        let mut row_j = [0.0; crate::capacity::MAX_ACTIVE];
        let start_j = at(j, 0);
        if let (Some(dst), Some(src)) = (
            row_j.get_mut(..j),
            a.get(start_j..start_j.saturating_add(j)),
        ) {
            // Element by element: `copy_from_slice` panics on a length mismatch the compiler
            // cannot rule out here (both are `j` long).
            for (d, s) in dst.iter_mut().zip(src) {
                *d = *s;
            }
        } else {
            for (k, slot) in row_j.iter_mut().indexed().take(j) {
                *slot = get(a, j, k);
            }
        }
        for i in (j.saturating_add(1))..n {
            let mut value = get(a, i, j);
            let start_i = at(i, 0);
            match a.get(start_i..start_i.saturating_add(j)) {
                Some(row_i) if j <= row_j.len() => {
                    for (x, y) in row_i.iter().zip(row_j.iter()) {
                        value -= x * y;
                    }
                }
                _ => {
                    for k in 0..j {
                        value -= get(a, i, k) * get(a, j, k);
                    }
                }
            }
            set(a, i, j, value / pivot);
        }
    }
    None
}

/// Solve `L x = b` in place (forward substitution).
pub(crate) fn solve_lower<const S: usize, const C: usize>(
    l: &[f64; S],
    n: usize,
    b: &mut [f64; C],
) {
    for i in 0..n.min(C) {
        let mut value = b.get(i).copied().unwrap_or(0.0);
        // Row i of L is contiguous: walk it beside b (the same products, in order).
        let start = at(i, 0);
        match l.get(start..start.saturating_add(i)) {
            Some(row) => {
                for (lk, bk) in row.iter().zip(b.iter()) {
                    value -= lk * bk;
                }
            }
            None => {
                for (k, bk) in b.iter().indexed().take(i) {
                    value -= get(l, i, k) * bk;
                }
            }
        }
        if let Some(slot) = b.get_mut(i) {
            *slot = value / get(l, i, i);
        }
    }
}

/// Solve `L^T x = b` in place (back substitution).
pub(crate) fn solve_lower_transposed<const S: usize, const C: usize>(
    l: &[f64; S],
    n: usize,
    b: &mut [f64; C],
) {
    let n = n.min(C);
    for i in (0..n).rev() {
        let mut value = b.get(i).copied().unwrap_or(0.0);
        // Column i below the diagonal: L[k][i] sits k + 1 numbers after L[k - 1][i].
        let mut index = at(i.saturating_add(1), i);
        for (k, bk) in b.iter().indexed().take(n).skip(i.saturating_add(1)) {
            value -= l.get(index).copied().unwrap_or(0.0) * bk;
            index = index.saturating_add(k).saturating_add(1);
        }
        if let Some(slot) = b.get_mut(i) {
            *slot = value / get(l, i, i);
        }
    }
}

#[cfg(test)]
#[allow(clippy::indexing_slicing, clippy::needless_range_loop)]
mod tests {
    use super::*;

    #[test]
    fn packed_cholesky_solves_an_spd_system() {
        let dense = [[4.0, 2.0, 0.4], [2.0, 5.0, 1.0], [0.4, 1.0, 3.0]];
        let mut a = [0.0; 6];
        for i in 0..3 {
            for j in 0..=i {
                set(&mut a, i, j, dense[i][j]);
            }
        }
        assert_eq!(cholesky(&mut a, 3), None);
        let mut x = [1.0, 2.0, 3.0];
        solve_lower(&a, 3, &mut x);
        solve_lower_transposed(&a, 3, &mut x);
        for i in 0..3 {
            let row: f64 = (0..3).map(|j| dense[i][j] * x[j]).sum();
            assert!((row - [1.0, 2.0, 3.0][i]).abs() < 1e-14);
        }
    }

    #[test]
    fn packed_cholesky_reports_the_failing_pivot_and_a_short_buffer() {
        let mut a = [1.0, 2.0, 1.0];
        assert_eq!(cholesky(&mut a, 2), Some(1));
        let mut short = [1.0, 0.0];
        assert_eq!(cholesky(&mut short, 2), Some(0));
    }
}
