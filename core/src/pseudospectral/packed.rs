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

/// Delete row and column `index` of the factored matrix `L L^T` of order `n`, leaving in place
/// the factor of what remains (order `n - 1`): the rows above `index` are unchanged, the rows
/// below move up one place without their entry in column `index`, and that column's part below
/// the diagonal (`x`, kept in `scratch`) goes back into the trailing block as a rank-one
/// update, `L33 L33^T + x x^T` (the rotations of the LINPACK update: an update, not a
/// downdate, so it cannot fail on a positive factor and loses no accuracy). O(n^2) where
/// forming and factoring the Gram matrix again is O(n^2 free + n^3). Returns false (the buffer
/// then unspecified) when `index >= n`, the buffer or `scratch` does not hold the triangle, or
/// a pivot is not positive and finite.
pub(crate) fn delete_row<const S: usize>(
    l: &mut [f64; S],
    n: usize,
    index: usize,
    scratch: &mut [f64],
) -> bool {
    if index >= n || !fits::<S>(n) {
        return false;
    }
    let below = n.saturating_sub(index).saturating_sub(1);
    let Some(x) = scratch.get_mut(..below) else {
        return false;
    };
    // Move the rows below `index` up one place, dropping their entry in column `index` (kept
    // in `x`). A new row ends before the old row it is read from starts, so a forward copy
    // reads every entry before it is overwritten.
    for (r, x_r) in (index..n.saturating_sub(1)).zip(x.iter_mut()) {
        let from = at(r.saturating_add(1), 0);
        let to = at(r, 0);
        let Some(&removed) = l.get(from.saturating_add(index)) else {
            return false;
        };
        *x_r = removed;
        for c in 0..=r {
            // Old column c (left of `index`) or c + 1 (right of it).
            let old = if c < index { c } else { c.saturating_add(1) };
            let Some(&value) = l.get(from.saturating_add(old)) else {
                return false;
            };
            let Some(slot) = l.get_mut(to.saturating_add(c)) else {
                return false;
            };
            *slot = value;
        }
    }
    // Rank-one update of the trailing block (rows and columns `index..n - 1`) by `x`.
    for j in 0..below {
        let jj = index.saturating_add(j);
        let (Some(&d), Some(&xj)) = (l.get(at(jj, jj)), x.get(j)) else {
            return false;
        };
        let r = libm::hypot(d, xj);
        if !(d > 0.0 && r.is_finite()) {
            return false;
        }
        let (c, s) = (r / d, xj / d);
        set(l, jj, jj, r);
        let Some(rest) = x.get_mut(j.saturating_add(1)..) else {
            return false;
        };
        for (i, x_i) in rest.iter_mut().indexed() {
            let ii = jj.saturating_add(1).saturating_add(i);
            let Some(entry) = l.get_mut(at(ii, jj)) else {
                return false;
            };
            let updated = (*entry + s * *x_i) / c;
            *x_i = c * *x_i - s * updated;
            *entry = updated;
        }
    }
    true
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

    /// A symmetric positive definite matrix of order `N` from a deterministic generator
    /// (`B B^T + I` with `B`'s entries from a linear congruential sequence in [-1, 1]).
    fn spd<const N: usize>(seed: u64) -> [[f64; N]; N] {
        let mut state = seed;
        let mut b = [[0.0; N]; N];
        for row in b.iter_mut() {
            for v in row.iter_mut() {
                state = state
                    .wrapping_mul(6_364_136_223_846_793_005)
                    .wrapping_add(1_442_695_040_888_963_407);
                *v = (state >> 11) as f64 / (1u64 << 53) as f64 * 2.0 - 1.0;
            }
        }
        let mut a = [[0.0; N]; N];
        for i in 0..N {
            for j in 0..N {
                a[i][j] = (0..N).map(|k| b[i][k] * b[j][k]).sum::<f64>();
            }
            a[i][i] += 1.0;
        }
        a
    }

    #[test]
    fn deleting_a_row_leaves_the_factor_of_the_rest() {
        // Every row of an order-9 matrix deleted from its factor, against the factor of the
        // matrix without that row and column, formed and factored again.
        const N: usize = 9;
        const S: usize = N * (N + 1) / 2;
        let a = spd::<N>(7);
        for index in 0..N {
            let mut factor = [0.0; S];
            for i in 0..N {
                for j in 0..=i {
                    set(&mut factor, i, j, a[i][j]);
                }
            }
            assert_eq!(cholesky(&mut factor, N), None);
            let mut scratch = [f64::NAN; N];
            assert!(delete_row(&mut factor, N, index, &mut scratch));
            let kept: heapless::Vec<usize, N> = (0..N).filter(|&i| i != index).collect();
            let mut fresh = [0.0; S];
            for (i, &ki) in kept.iter().enumerate() {
                for (j, &kj) in kept.iter().enumerate().take(i + 1) {
                    set(&mut fresh, i, j, a[ki][kj]);
                }
            }
            assert_eq!(cholesky(&mut fresh, N - 1), None);
            for k in 0..packed_len(N - 1) {
                assert!(
                    (factor[k] - fresh[k]).abs() <= 1e-12 * (1.0 + fresh[k].abs()),
                    "row {index} deleted, entry {k}: {} against {}",
                    factor[k],
                    fresh[k]
                );
            }
        }
    }

    #[test]
    fn deleting_a_row_outside_the_triangle_or_with_short_scratch_fails() {
        let mut factor = [4.0, 2.0, 3.0];
        assert!(!delete_row(&mut factor, 2, 2, &mut [0.0; 2]));
        assert!(!delete_row(&mut factor, 3, 0, &mut [0.0; 2]));
        assert!(!delete_row(&mut factor, 2, 0, &mut []));
        // The last row needs no scratch: the leading block is the factor.
        assert!(delete_row(&mut factor, 2, 1, &mut []));
        assert_eq!(factor[0], 4.0);
    }
}
