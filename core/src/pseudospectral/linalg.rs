//! The few dense kernels planner A needs, on fixed-size square arrays: Cholesky factorisation
//! and triangular solves on the leading `n x n` block. No allocation, no panics.

/// Cholesky-factor the leading `n x n` block of `a` in place (lower triangle holds L, the
/// strict upper triangle is left untouched). Returns the index of the first pivot that is not
/// positive (the matrix is not numerically positive definite there), or `None` on success.
pub(crate) fn cholesky_in_place<const C: usize>(a: &mut [[f64; C]; C], n: usize) -> Option<usize> {
    for j in 0..n.min(C) {
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
        for i in (j.saturating_add(1))..n.min(C) {
            let mut value = get(a, i, j);
            for k in 0..j {
                value -= get(a, i, k) * get(a, j, k);
            }
            set(a, i, j, value / pivot);
        }
    }
    None
}

/// Solve `L x = b` in place (forward substitution) with L in the lower triangle of `l`.
pub(crate) fn solve_lower<const C: usize>(l: &[[f64; C]; C], n: usize, b: &mut [f64; C]) {
    for i in 0..n.min(C) {
        let mut value = b.get(i).copied().unwrap_or(0.0);
        for k in 0..i {
            value -= get(l, i, k) * b.get(k).copied().unwrap_or(0.0);
        }
        if let Some(slot) = b.get_mut(i) {
            *slot = value / get(l, i, i);
        }
    }
}

/// Solve `L^T x = b` in place (back substitution) with L in the lower triangle of `l`.
pub(crate) fn solve_lower_transposed<const C: usize>(
    l: &[[f64; C]; C],
    n: usize,
    b: &mut [f64; C],
) {
    let n = n.min(C);
    for i in (0..n).rev() {
        let mut value = b.get(i).copied().unwrap_or(0.0);
        for k in (i.saturating_add(1))..n {
            value -= get(l, k, i) * b.get(k).copied().unwrap_or(0.0);
        }
        if let Some(slot) = b.get_mut(i) {
            *slot = value / get(l, i, i);
        }
    }
}

/// `a[i][j]`, 0 outside.
pub(crate) fn get<const R: usize, const C: usize>(a: &[[f64; C]; R], i: usize, j: usize) -> f64 {
    a.get(i).and_then(|row| row.get(j)).copied().unwrap_or(0.0)
}

/// `a[i][j] = value`, ignored outside.
pub(crate) fn set<const R: usize, const C: usize>(
    a: &mut [[f64; C]; R],
    i: usize,
    j: usize,
    value: f64,
) {
    if let Some(slot) = a.get_mut(i).and_then(|row| row.get_mut(j)) {
        *slot = value;
    }
}

#[cfg(test)]
#[allow(clippy::indexing_slicing)]
mod tests {
    use super::*;

    #[test]
    fn cholesky_solves_spd_system() {
        let mut a = [[4.0, 2.0, 0.4], [2.0, 5.0, 1.0], [0.4, 1.0, 3.0]];
        let original = a;
        assert_eq!(cholesky_in_place(&mut a, 3), None);
        let mut x = [1.0, 2.0, 3.0];
        solve_lower(&a, 3, &mut x);
        solve_lower_transposed(&a, 3, &mut x);
        for i in 0..3 {
            let row: f64 = (0..3).map(|j| original[i][j] * x[j]).sum();
            assert!((row - [1.0, 2.0, 3.0][i]).abs() < 1e-14);
        }
    }

    #[test]
    fn cholesky_reports_failing_pivot() {
        let mut a = [[1.0, 2.0], [2.0, 1.0]];
        assert_eq!(cholesky_in_place(&mut a, 2), Some(1));
    }
}
