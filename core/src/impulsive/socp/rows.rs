//! Row compression of the end condition (equilibration, pivoted Gram-Schmidt, least-squares
//! target coordinates) and the small dense linear algebra of the least-fuel interior point
//! (Cholesky with a regularising shift, iterative refinement).

use super::ROWS;
use crate::impulsive::transfer::{FMatrix, MAX_UNKNOWNS};
use crate::indexed::IndexedExt as _;

/// `a . b`.
pub(super) fn dot(a: &[f64], b: &[f64]) -> f64 {
    let mut s = 0.0;
    for (x, y) in a.iter().zip(b.iter()) {
        s += *x * *y;
    }
    s
}

pub(super) fn norm(a: &[f64]) -> f64 {
    libm::sqrt(dot(a, a))
}

/// `a -= c b`.
pub(super) fn axpy_neg(a: &mut [f64], c: f64, b: &[f64]) {
    for (x, y) in a.iter_mut().zip(b.iter()) {
        *x -= c * *y;
    }
}

/// The end condition with orthonormal rows: `G x = h` (first `rank` rows), and the map back.
pub(super) struct Compressed {
    /// Orthonormal rows, `g[j] = sum_i c[j][i] d_i f_i`.
    pub(super) g: [[f64; MAX_UNKNOWNS]; ROWS],
    /// Row combinations (in equilibrated rows).
    pub(super) c: [[f64; ROWS]; ROWS],
    /// Row equilibration `d_i = 1 / |f_i|` (1 for a zero row).
    pub(super) d: [f64; ROWS],
    /// Target coordinates.
    pub(super) h: [f64; ROWS],
    /// Rows kept.
    pub(super) rank: usize,
    /// `|D y - D F x|` for any `x` with `G x = h`.
    pub(super) residual: f64,
}

/// Pivoted Gram-Schmidt (each accepted row orthogonalised twice) on the equilibrated rows of F,
/// then the least-squares target coordinates.
pub(super) fn compress(f: &FMatrix, columns: usize, y: &[f64; ROWS], rcond: f64) -> Compressed {
    let mut out = Compressed {
        g: [[0.0; MAX_UNKNOWNS]; ROWS],
        c: [[0.0; ROWS]; ROWS],
        d: [0.0; ROWS],
        h: [0.0; ROWS],
        rank: 0,
        residual: 0.0,
    };
    // Working rows (equilibrated) and their combinations.
    let mut w = [[0.0; MAX_UNKNOWNS]; ROWS];
    let mut wc = [[0.0; ROWS]; ROWS];
    let mut fe = [[0.0; MAX_UNKNOWNS]; ROWS];
    let mut ye = [0.0; ROWS];
    for ((i, ((wi, wci), (fei, (di, (yei, yi))))), f_row) in w
        .iter_mut()
        .zip(wc.iter_mut())
        .zip(
            fe.iter_mut()
                .zip(out.d.iter_mut().zip(ye.iter_mut().zip(y.iter()))),
        )
        .indexed()
        .zip(f.row_iter())
    {
        for (x, fv) in wi.iter_mut().zip(f_row.iter()).take(columns) {
            *x = *fv;
        }
        let n = norm(wi);
        // A zero row stays zero (unit scale), so an unreachable y_i shows in the residual.
        *di = if n > 0.0 { 1.0 / n } else { 1.0 };
        for x in wi.iter_mut() {
            *x *= *di;
        }
        *fei = *wi;
        *yei = *yi * *di;
        if let Some(ci) = wci.get_mut(i) {
            *ci = 1.0;
        }
    }
    let mut taken = [false; ROWS];
    for j in 0..ROWS {
        // Pivot: the untaken row with the largest residual.
        let mut best: Option<(usize, f64)> = None;
        for (i, (wi, t)) in w.iter().zip(taken.iter()).indexed() {
            let n = norm(wi);
            if !*t && best.is_none_or(|(_, b)| n > b) {
                best = Some((i, n));
            }
        }
        let Some((p, n)) = best else { break };
        if n.is_nan() || n <= rcond {
            break;
        }
        if let Some(t) = taken.get_mut(p) {
            *t = true;
        }
        let (Some(&wp), Some(&wcp)) = (w.get(p), wc.get(p)) else {
            break;
        };
        let mut row = wp;
        let mut comb = wcp;
        // Second orthogonalisation against the accepted rows ("twice is enough").
        for (gl, cl) in out.g.iter().zip(out.c.iter()).take(j) {
            let a = dot(&row, gl);
            axpy_neg(&mut row, a, gl);
            axpy_neg(&mut comb, a, cl);
        }
        let n = norm(&row);
        if n.is_nan() || n <= rcond {
            break;
        }
        for x in row.iter_mut() {
            *x /= n;
        }
        for x in comb.iter_mut() {
            *x /= n;
        }
        // Orthogonalise the untaken rows against it.
        for (wi, (wci, t)) in w.iter_mut().zip(wc.iter_mut().zip(taken.iter())) {
            if !*t {
                let a = dot(wi, &row);
                axpy_neg(wi, a, &row);
                axpy_neg(wci, a, &comb);
            }
        }
        if let (Some(gj), Some(cj)) = (out.g.get_mut(j), out.c.get_mut(j)) {
            *gj = row;
            *cj = comb;
        }
        out.rank = j.saturating_add(1);
    }
    // Least-squares coordinates h = argmin |L h - D y|, L = (D F) G^T (6 x rank), by
    // Gram-Schmidt on L's columns (twice), then back substitution.
    let r = out.rank;
    let mut q = [[0.0; ROWS]; ROWS]; // q[j] = column j of Q
    let mut rr = [[0.0; ROWS]; ROWS]; // rr[l][j] = R_lj
    for j in 0..r {
        let mut col = [0.0; ROWS];
        if let Some(gj) = out.g.get(j) {
            for (ci, fei) in col.iter_mut().zip(fe.iter()) {
                *ci = dot(fei, gj);
            }
        }
        for _ in 0..2 {
            for l in 0..j {
                if let Some(ql) = q.get(l) {
                    let a = dot(&col, ql);
                    axpy_neg(&mut col, a, ql);
                    if let Some(x) = rr.get_mut(l).and_then(|row| row.get_mut(j)) {
                        *x += a;
                    }
                }
            }
        }
        let n = norm(&col);
        if let Some(x) = rr.get_mut(j).and_then(|row| row.get_mut(j)) {
            *x = n;
        }
        if n > 0.0 {
            for x in col.iter_mut() {
                *x /= n;
            }
        }
        if let Some(qj) = q.get_mut(j) {
            *qj = col;
        }
    }
    let mut qty = [0.0; ROWS];
    let mut proj = ye;
    for (v, qj) in qty.iter_mut().zip(q.iter()).take(r) {
        *v = dot(qj, &ye);
        axpy_neg(&mut proj, *v, qj);
    }
    out.residual = norm(&proj);
    // Back substitution R h = Q^T D y, row j of R against the entries of h after j.
    for (j, (rj, qj)) in rr.iter().zip(qty.iter()).indexed().take(r).rev() {
        let Some((hj, h_after)) = out.h.get_mut(j..).and_then(<[_]>::split_first_mut) else {
            break;
        };
        let Some((rjj, r_after)) = rj.get(j..).and_then(<[_]>::split_first) else {
            break;
        };
        let mut s = *qj;
        let later = r.saturating_sub(j.saturating_add(1));
        for (rjl, hl) in r_after.iter().zip(h_after.iter()).take(later) {
            s -= *rjl * *hl;
        }
        // rjj >= singular value of L restricted, bounded below by the rank threshold; a zero
        // column (rjj = 0) has no coordinate.
        *hj = if *rjj > 0.0 { s / *rjj } else { 0.0 };
    }
    out
}

/// Symmetric positive definite `m` (first `r` rows/columns): Cholesky in place. The factor `L`
/// is written to the lower triangle and, transposed, to the upper one, so that both triangular
/// solves of [`cholesky_solve`] read it by rows (the upper triangle of `m` is not read here:
/// every entry it holds is written before [`cholesky_solve`] reads it).
pub(super) fn cholesky(m: &mut [[f64; ROWS]; ROWS], r: usize) -> bool {
    for j in 0..r {
        // Row j (its left part is L's row j so far), and the rows below it.
        let Some((row_j, below)) = m.get_mut(j..).and_then(<[_]>::split_first_mut) else {
            return false;
        };
        let Some((left_j, diag_right)) = row_j.split_at_mut_checked(j) else {
            return false;
        };
        let Some((djj_slot, right_j)) = diag_right.split_first_mut() else {
            return false;
        };
        let mut djj = *djj_slot;
        for v in left_j.iter() {
            djj -= *v * *v;
        }
        if !(djj.is_finite() && djj > 0.0) {
            return false;
        }
        let ljj = libm::sqrt(djj);
        *djj_slot = ljj;
        let below_rows = r.saturating_sub(j.saturating_add(1));
        for (row_i, upper) in below.iter_mut().zip(right_j.iter_mut()).take(below_rows) {
            let Some((left_i, rest_i)) = row_i.split_at_mut_checked(j) else {
                return false;
            };
            let Some(x) = rest_i.first_mut() else {
                return false;
            };
            let mut v = *x;
            for (a, b) in left_i.iter().zip(left_j.iter()) {
                v -= *a * *b;
            }
            *x = v / ljj;
            *upper = *x;
        }
    }
    true
}

/// Solve `L L^T x = b` in place (first `r` entries), `l` as [`cholesky`] leaves it.
pub(super) fn cholesky_solve(l: &[[f64; ROWS]; ROWS], r: usize, b: &mut [f64; ROWS]) {
    // L y = b: row i of the lower triangle against the entries already solved.
    for (i, row) in l.iter().indexed().take(r) {
        let Some((done, rest)) = b.split_at_mut_checked(i) else {
            return;
        };
        let (Some((left, diag)), Some(bi)) = (row.split_at_checked(i), rest.first_mut()) else {
            return;
        };
        let Some(lii) = diag.first() else {
            return;
        };
        let mut v = *bi;
        for (lij, bj) in left.iter().zip(done.iter()) {
            v -= *lij * *bj;
        }
        *bi = v / *lii;
    }
    // L^T x = y: row i of the upper triangle (L's column i) against the entries after i.
    for (i, row) in l.iter().indexed().take(r).rev() {
        let Some((bi, after)) = b.get_mut(i..).and_then(<[_]>::split_first_mut) else {
            return;
        };
        let Some((lii, right)) = row.get(i..).and_then(<[_]>::split_first) else {
            return;
        };
        let mut v = *bi;
        let later = r.saturating_sub(i.saturating_add(1));
        for (lji, bj) in right.iter().zip(after.iter()).take(later) {
            v -= *lji * *bj;
        }
        *bi = v / *lii;
    }
}

/// Cholesky of `m + delta I` with the least `delta` in `0, 1e-14 tr, 1e-12 tr, 1e-10 tr` that
/// factors; the shift used, or `None` when none does (`m` then holds garbage).
pub(super) fn factor_regularised(m: &mut [[f64; ROWS]; ROWS], r: usize) -> Option<f64> {
    let m0 = *m;
    let mut trace = 0.0;
    for (j, row) in m0.iter().indexed().take(r) {
        // The diagonal entry of row j (j < ROWS: one entry).
        for x in row.iter().skip(j).take(1) {
            trace += *x;
        }
    }
    for rel in [0.0, 1e-14, 1e-12, 1e-10] {
        *m = m0;
        let delta = rel * trace;
        for (j, row) in m.iter_mut().indexed().take(r) {
            for x in row.iter_mut().skip(j).take(1) {
                *x += delta;
            }
        }
        if cholesky(m, r) {
            return Some(delta);
        }
    }
    None
}

/// Solve `m0 x = b` with the factor `l` of `m0 + shift I`: one solve, then (when shifted) three
/// steps of iterative refinement.
pub(super) fn refined_solve(
    m0: &[[f64; ROWS]; ROWS],
    l: &[[f64; ROWS]; ROWS],
    r: usize,
    shift: f64,
    b: &[f64; ROWS],
) -> [f64; ROWS] {
    let mut x = *b;
    cholesky_solve(l, r, &mut x);
    if shift > 0.0 {
        for _ in 0..3 {
            // Residual b - m0 x (m0 is stored in full).
            let mut res = *b;
            for (ri, m0i) in res.iter_mut().zip(m0.iter()).take(r) {
                for (m0ij, xj) in m0i.iter().zip(x.iter()).take(r) {
                    *ri -= *m0ij * *xj;
                }
            }
            cholesky_solve(l, r, &mut res);
            for (xi, d) in x.iter_mut().zip(res.iter()).take(r) {
                *xi += *d;
            }
        }
    }
    x
}
