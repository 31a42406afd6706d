//! Row compression of the end condition (equilibration, pivoted Gram-Schmidt, least-squares
//! target coordinates) and the small dense linear algebra of the least-fuel interior point
//! (Cholesky with a regularising shift, iterative refinement).

use super::ROWS;
use crate::impulsive::transfer::{FMatrix, MAX_UNKNOWNS};

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
    for (i, ((wi, wci), (fei, (di, yei)))) in w
        .iter_mut()
        .zip(wc.iter_mut())
        .zip(fe.iter_mut().zip(out.d.iter_mut().zip(ye.iter_mut())))
        .enumerate()
    {
        for (j, x) in wi.iter_mut().enumerate().take(columns) {
            *x = f.get((i, j)).copied().unwrap_or(0.0);
        }
        let n = norm(wi);
        // A zero row stays zero (unit scale), so an unreachable y_i shows in the residual.
        *di = if n > 0.0 { 1.0 / n } else { 1.0 };
        for x in wi.iter_mut() {
            *x *= *di;
        }
        *fei = *wi;
        *yei = y.get(i).copied().unwrap_or(0.0) * *di;
        if let Some(ci) = wci.get_mut(i) {
            *ci = 1.0;
        }
    }
    let mut taken = [false; ROWS];
    for j in 0..ROWS {
        // Pivot: the untaken row with the largest residual.
        let mut best: Option<(usize, f64)> = None;
        for (i, (wi, t)) in w.iter().zip(taken.iter()).enumerate() {
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
    for j in (0..r).rev() {
        let mut s = qty.get(j).copied().unwrap_or(0.0);
        for l in j.saturating_add(1)..r {
            let rjl = rr.get(j).and_then(|row| row.get(l)).copied().unwrap_or(0.0);
            s -= rjl * out.h.get(l).copied().unwrap_or(0.0);
        }
        let rjj = rr.get(j).and_then(|row| row.get(j)).copied().unwrap_or(0.0);
        if let Some(hj) = out.h.get_mut(j) {
            // rjj >= singular value of L restricted, bounded below by the rank threshold.
            *hj = if rjj > 0.0 { s / rjj } else { 0.0 };
        }
    }
    out
}

/// Symmetric positive definite `m` (first `r` rows/columns): Cholesky in place, lower triangle.
pub(super) fn cholesky(m: &mut [[f64; ROWS]; ROWS], r: usize) -> bool {
    for j in 0..r {
        let mut djj = m.get(j).and_then(|row| row.get(j)).copied().unwrap_or(0.0);
        for l in 0..j {
            let v = m.get(j).and_then(|row| row.get(l)).copied().unwrap_or(0.0);
            djj -= v * v;
        }
        if !(djj.is_finite() && djj > 0.0) {
            return false;
        }
        let ljj = libm::sqrt(djj);
        if let Some(x) = m.get_mut(j).and_then(|row| row.get_mut(j)) {
            *x = ljj;
        }
        for i in j.saturating_add(1)..r {
            let mut v = m.get(i).and_then(|row| row.get(j)).copied().unwrap_or(0.0);
            for l in 0..j {
                let a = m.get(i).and_then(|row| row.get(l)).copied().unwrap_or(0.0);
                let b = m.get(j).and_then(|row| row.get(l)).copied().unwrap_or(0.0);
                v -= a * b;
            }
            if let Some(x) = m.get_mut(i).and_then(|row| row.get_mut(j)) {
                *x = v / ljj;
            }
        }
    }
    true
}

/// Solve `L L^T x = b` in place (first `r` entries).
pub(super) fn cholesky_solve(l: &[[f64; ROWS]; ROWS], r: usize, b: &mut [f64; ROWS]) {
    for i in 0..r {
        let mut v = b.get(i).copied().unwrap_or(0.0);
        for j in 0..i {
            v -= l.get(i).and_then(|row| row.get(j)).copied().unwrap_or(0.0)
                * b.get(j).copied().unwrap_or(0.0);
        }
        if let Some(x) = b.get_mut(i) {
            *x = v / l.get(i).and_then(|row| row.get(i)).copied().unwrap_or(1.0);
        }
    }
    for i in (0..r).rev() {
        let mut v = b.get(i).copied().unwrap_or(0.0);
        for j in i.saturating_add(1)..r {
            v -= l.get(j).and_then(|row| row.get(i)).copied().unwrap_or(0.0)
                * b.get(j).copied().unwrap_or(0.0);
        }
        if let Some(x) = b.get_mut(i) {
            *x = v / l.get(i).and_then(|row| row.get(i)).copied().unwrap_or(1.0);
        }
    }
}

/// Cholesky of `m + delta I` with the least `delta` in `0, 1e-14 tr, 1e-12 tr, 1e-10 tr` that
/// factors; the shift used, or `None` when none does (`m` then holds garbage).
pub(super) fn factor_regularised(m: &mut [[f64; ROWS]; ROWS], r: usize) -> Option<f64> {
    let m0 = *m;
    let mut trace = 0.0;
    for (j, row) in m0.iter().enumerate().take(r) {
        trace += row.get(j).copied().unwrap_or(0.0);
    }
    for rel in [0.0, 1e-14, 1e-12, 1e-10] {
        *m = m0;
        let delta = rel * trace;
        for (j, row) in m.iter_mut().enumerate().take(r) {
            if let Some(x) = row.get_mut(j) {
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
            for (i, ri) in res.iter_mut().enumerate().take(r) {
                for (j, xj) in x.iter().enumerate().take(r) {
                    *ri -= m0.get(i).and_then(|row| row.get(j)).copied().unwrap_or(0.0) * *xj;
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
