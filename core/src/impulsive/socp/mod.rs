//! Exact least fuel at fixed impulse points: the second-order cone program
//! `min sum_k |x_k|  s.t.  F x = y` (6 equality rows, K <= 6 impulses of 3 components), solved by
//! a bounded primal-dual interior-point method (Nesterov-Todd scaling, Mehrotra
//! predictor-corrector).
//!
//! 1. **Row compression.** The rows of F are equilibrated (km versus rad) and orthonormalised by
//!    pivoted Gram-Schmidt with re-orthogonalisation: `G = C D F` has orthonormal rows, `r` of
//!    them (the numerical rank; rows whose residual falls below `rank_rcond` are dropped). The
//!    constraint becomes `G x = h` with `h` the least-squares coordinates of `D y` in the range
//!    of `D F`: for a consistent `y` (always at full rank) the same feasible set, for a
//!    rank-deficient F with an unreachable `y` the reachable target nearest to it. `G` is
//!    perfectly conditioned, so the interior-point normal matrix (`r x r`) is as well scaled as
//!    it can be, whatever the units of F.
//! 2. **Cone program.** With `h` scaled to unit norm, `min sum_k t_k` over `(t_k, x_k)` in the
//!    second-order cone `|x_k| <= t_k`, `G x = h`; dual `max h.l  s.t.  |G_k^T l| <= 1`. The start
//!    is feasible (`x = G^T h`, `t_k = |x_k| + 1`, dual slack `e`, `l = 0`) and every iterate
//!    keeps the equality rows to rounding. An impulse that goes to zero is the cone's apex, an
//!    ordinary point for the interior-point method (the reweighted least squares it replaces
//!    stalled there).
//! 3. **Certificate.** After every iteration the primal iterate is projected onto `G x = h`
//!    exactly (orthonormal rows) and the dual is scaled into `|G_k^T l| <= 1`: their objectives
//!    are an upper and a lower bound on the optimum, whatever the iteration did. The solve stops
//!    as [`SocpStatus::Optimal`] when the bounds are within the tolerance; at the iteration cap
//!    it returns the best feasible plan with [`SocpStatus::NotConverged`] and the certified gap.
//!
//! No heap, fixed-size arrays, every loop bounded by `max_iter` or a capacity, no fused
//! multiply-add; the returned numbers are finite or the status says why not.

mod cone;
mod rows;

use super::transfer::{FMatrix, MAX_UNKNOWNS};
use crate::capacity::MAX_IMPULSES;
use crate::indexed::IndexedExt as _;
use cone::{arrow_solve, jordan, max_step, Cone, Scaling};
use rows::{compress, dot, factor_regularised, norm, refined_solve};

/// Equality rows of the end condition.
pub(crate) const ROWS: usize = 6;
/// Fraction of the step to the cone boundary an iteration takes.
const STEP_FRACTION: f64 = 0.99;

/// How a least-fuel solve ended.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum SocpStatus {
    /// The certified gap (upper minus lower bound) is within the tolerance.
    Optimal,
    /// The iteration cap was reached first; the plan is feasible, the gap is reported.
    NotConverged,
    /// A non-finite input, or a factorisation that failed: the best feasible plan found so far
    /// (at worst the minimum-norm one) is returned.
    NumericalFailure,
}

/// The result of a least-fuel solve.
#[derive(Clone, Copy, Debug)]
pub struct LeastFuel {
    /// Impulses, 3 per impulse, in the units of `y / F`; zero past the used columns.
    pub x: [f64; MAX_UNKNOWNS],
    /// `sum_k |x_k|` of `x`.
    pub total: f64,
    /// Lower bound on the optimum from the dual certificate (`y . mu`).
    pub lower_bound: f64,
    /// Dual certificate in F's rows: `|F_k^T mu| <= 1` for every impulse, `y . mu` = lower bound.
    pub dual: [f64; ROWS],
    /// Numerical rank of F (rows kept by the compression).
    pub rank: u8,
    /// Equilibrated residual `|D (y - F x)|` (non-zero only for an unreachable `y`).
    pub residual: f64,
    /// Interior-point iterations used.
    pub iterations: u16,
    /// How it ended.
    pub status: SocpStatus,
}

impl LeastFuel {
    const fn zero(status: SocpStatus) -> Self {
        Self {
            x: [0.0; MAX_UNKNOWNS],
            total: 0.0,
            lower_bound: 0.0,
            dual: [0.0; ROWS],
            rank: 0,
            residual: 0.0,
            iterations: 0,
            status,
        }
    }
}

/// The interior-point iterate.
struct Iterate {
    z: [Cone; MAX_IMPULSES],
    s: [Cone; MAX_IMPULSES],
    l: [f64; ROWS],
}

/// Block k of `G` (3 columns) as row-major `r x 3`.
fn block(g: &[[f64; MAX_UNKNOWNS]; ROWS], k: usize) -> [[f64; 3]; ROWS] {
    let mut b = [[0.0; 3]; ROWS];
    let c = k.saturating_mul(3);
    for (bi, gi) in b.iter_mut().zip(g.iter()) {
        if let Some(src) = gi.get(c..c.saturating_add(3)) {
            bi.copy_from_slice(src);
        }
    }
    b
}

/// `G_k^T l` (3-vector).
fn gkt(gk: &[[f64; 3]; ROWS], l: &[f64; ROWS], r: usize) -> [f64; 3] {
    let mut out = [0.0; 3];
    for (row, li) in gk.iter().zip(l.iter()).take(r) {
        for (o, g) in out.iter_mut().zip(row.iter()) {
            *o += *g * *li;
        }
    }
    out
}

/// `G_k u` (an `r`-vector) for a 3-vector `u`.
fn gkt_rows(gk: &[[f64; 3]; ROWS], u: &[f64; 3], r: usize) -> [f64; ROWS] {
    let mut out = [0.0; ROWS];
    for (o, row) in out.iter_mut().zip(gk.iter()).take(r) {
        *o = dot(row, u);
    }
    out
}

/// Certified bounds at an iterate: the primal projected onto `G x = h`, the dual scaled into
/// its constraints. Returns (upper, lower, projected x, scaled dual).
fn certify(
    blocks: &[[[f64; 3]; ROWS]; MAX_IMPULSES],
    k_used: usize,
    r: usize,
    h: &[f64; ROWS],
    it: &Iterate,
) -> (f64, f64, [f64; MAX_UNKNOWNS], [f64; ROWS]) {
    let mut x = [0.0; MAX_UNKNOWNS];
    for (xk, zk) in x.chunks_exact_mut(3).zip(it.z.iter()).take(k_used) {
        xk.copy_from_slice(&[zk[1], zk[2], zk[3]]);
    }
    // Residual h - G x, then x += G^T (h - G x) (exact projection: G G^T = I).
    let mut res = *h;
    for (gk, xk) in blocks.iter().zip(x.chunks_exact(3)).take(k_used) {
        for (ri, row) in res.iter_mut().zip(gk.iter()).take(r) {
            *ri -= dot(row, xk);
        }
    }
    for (gk, xk) in blocks.iter().zip(x.chunks_exact_mut(3)).take(k_used) {
        let d = gkt(gk, &res, r);
        for (xi, di) in xk.iter_mut().zip(d.iter()) {
            *xi += *di;
        }
    }
    let mut upper = 0.0;
    for xk in x.chunks_exact(3).take(k_used) {
        upper += norm(xk);
    }
    let mut worst = 0.0f64;
    for gk in blocks.iter().take(k_used) {
        worst = worst.max(norm(&gkt(gk, &it.l, r)));
    }
    let scale = if worst > 1.0 { 1.0 / worst } else { 1.0 };
    let mut l = it.l;
    for v in l.iter_mut() {
        *v *= scale;
    }
    // The first r (the rank, <= ROWS) entries are the compressed rows in use.
    let lower = h
        .iter()
        .zip(l.iter())
        .take(r)
        .fold(0.0, |acc, (a, b)| acc + *a * *b);
    (upper, lower, x, l)
}

/// Least `sum_k |x_k|` subject to `F x = y` for a row-major `f` (6 rows, the first `columns`
/// columns used, 3 per impulse): the cone program the planner runs at every least-fuel
/// fixed-point iteration, exposed so that it can be checked against an independent solver.
/// Arguments and result as for the planner's internal call (see the module docs).
pub fn least_fuel_rows(
    f: &[[f64; MAX_UNKNOWNS]; ROWS],
    columns: usize,
    y: &[f64; ROWS],
    tol: f64,
    rank_rcond: f64,
    max_iter: u16,
) -> Option<LeastFuel> {
    let mut m = FMatrix::zeros();
    for (i, row) in f.iter().indexed() {
        for (j, v) in row.iter().indexed() {
            if let Some(x) = m.get_mut((i, j)) {
                *x = *v;
            }
        }
    }
    least_fuel(&m, columns, y, tol, rank_rcond, max_iter)
}

/// Least `sum_k |x_k|` subject to `F x = y` over the first `columns` columns of `f` (3 per
/// impulse), at most `max_iter` interior-point iterations, stopping when the certified gap is
/// below `tol` (absolute, in the units of `x`). Rows whose Gram-Schmidt residual (after row
/// equilibration) is below `rank_rcond` count as dependent. `None` when `f` or `y` is not
/// finite (no feasible point can be formed).
pub(crate) fn least_fuel(
    f: &FMatrix,
    columns: usize,
    y: &[f64; ROWS],
    tol: f64,
    rank_rcond: f64,
    max_iter: u16,
) -> Option<LeastFuel> {
    let columns = columns.min(MAX_UNKNOWNS);
    let k_used = columns / 3;
    let finite_f =
        (0..ROWS).all(|i| (0..columns).all(|j| f.get((i, j)).is_some_and(|v| v.is_finite())));
    if !finite_f || !y.iter().all(|v| v.is_finite()) {
        return None;
    }
    let cmp = compress(f, columns, y, rank_rcond);
    let r = cmp.rank;
    let rho = libm::sqrt(cmp.h.iter().take(r).fold(0.0, |acc, a| acc + *a * *a));
    let mut out = LeastFuel::zero(SocpStatus::Optimal);
    out.rank = u8::try_from(r).unwrap_or(u8::MAX);
    out.residual = cmp.residual;
    if !(rho.is_finite() && rho > 0.0) {
        // Nothing to reach (or nothing reachable, see the residual): no impulse.
        if !rho.is_finite() {
            out.status = SocpStatus::NumericalFailure;
        }
        return Some(out);
    }
    let mut h = [0.0; ROWS];
    for (hi, ci) in h.iter_mut().zip(cmp.h.iter()).take(r) {
        *hi = *ci / rho;
    }
    let mut blocks = [[[0.0; 3]; ROWS]; MAX_IMPULSES];
    for (k, b) in blocks.iter_mut().indexed().take(k_used) {
        *b = block(&cmp.g, k);
    }
    // Feasible start: minimum-norm x = G^T h, t_k = |x_k| + 1; s = e, l = 0.
    let mut it = Iterate {
        z: [[0.0; 4]; MAX_IMPULSES],
        s: [[0.0; 4]; MAX_IMPULSES],
        l: [0.0; ROWS],
    };
    for ((zk, sk), gk) in
        it.z.iter_mut()
            .zip(it.s.iter_mut())
            .zip(blocks.iter())
            .take(k_used)
    {
        let x = gkt(gk, &h, r);
        *zk = [norm(&x) + 1.0, x[0], x[1], x[2]];
        *sk = [1.0, 0.0, 0.0, 0.0];
    }
    // G_k G_k^T per impulse, fixed over the iterations.
    let mut gram = [[[0.0; ROWS]; ROWS]; MAX_IMPULSES];
    for (pk, gk) in gram.iter_mut().zip(blocks.iter()).take(k_used) {
        for (pi, gi) in pk.iter_mut().zip(gk.iter()).take(r) {
            for (pij, gj) in pi.iter_mut().zip(gk.iter()).take(r) {
                *pij = dot(gi, gj);
            }
        }
    }
    let tol_unit = tol / rho;
    let (mut best_upper, mut best_lower, mut best_x, mut best_l) =
        certify(&blocks, k_used, r, &h, &it);
    let mut status = SocpStatus::NotConverged;
    let mut iterations = 0u16;
    let k_f = k_used as f64;
    for _ in 0..max_iter {
        // The iterates keep the equality rows, so z.s is the duality gap up to rounding: the
        // certificate (a projection and K norms) is computed only once it can succeed.
        let mut gap_now = 0.0;
        for (zk, sk) in it.z.iter().zip(it.s.iter()).take(k_used) {
            gap_now += dot(zk, sk);
        }
        if gap_now <= 2.0 * tol_unit {
            let (upper, lower, x, l) = certify(&blocks, k_used, r, &h, &it);
            if upper.is_finite() && upper < best_upper {
                best_upper = upper;
                best_x = x;
            }
            if lower.is_finite() && lower > best_lower {
                best_lower = lower;
                best_l = l;
            }
        }
        if best_upper - best_lower <= tol_unit {
            status = SocpStatus::Optimal;
            break;
        }
        // Scalings, scaled points v = W z = W^-1 s, and the normal matrix
        // sum_k G_k W_k^-2 G_k^T = sum_k (G_k G_k^T + c_k (G_k qbar_k)(G_k qbar_k)^T) / eta_k^2.
        let mut sc = [Scaling::default(); MAX_IMPULSES];
        let mut v = [[0.0; 4]; MAX_IMPULSES];
        let mut m = [[0.0; ROWS]; ROWS];
        let mut ok = true;
        for k in 0..k_used {
            let (Some(zk), Some(sk), Some(gk), Some(pk)) =
                (it.z.get(k), it.s.get(k), blocks.get(k), gram.get(k))
            else {
                ok = false;
                break;
            };
            let Some(w) = Scaling::new(zk, sk) else {
                ok = false;
                break;
            };
            let (inv_eta2, c) = w.inv_squared_block();
            let wq = gkt_rows(gk, &[w.q[1], w.q[2], w.q[3]], r);
            for ((mi, pi), wi) in m.iter_mut().zip(pk.iter()).zip(wq.iter()).take(r) {
                for ((mij, pij), wj) in mi.iter_mut().zip(pi.iter()).zip(wq.iter()).take(r) {
                    *mij += inv_eta2 * (*pij + c * *wi * *wj);
                }
            }
            if let (Some(slot), Some(vk)) = (sc.get_mut(k), v.get_mut(k)) {
                *vk = w.apply(zk);
                *slot = w;
            }
        }
        if !ok {
            status = SocpStatus::NumericalFailure;
            break;
        }
        // Near the optimum the normal matrix mixes scales of 1/mu and mu (an impulse at the
        // cone's apex, another on the boundary) and can lose definiteness to rounding: factor
        // it with a small diagonal shift when needed and recover the accuracy by iterative
        // refinement against the unshifted matrix.
        let m0 = m;
        let Some(shift) = factor_regularised(&mut m, r) else {
            status = SocpStatus::NumericalFailure;
            break;
        };
        // Residuals: r_p = h - G x, r_d,k = e - A_k^T l - s_k.
        let mut rp = h;
        for (gk, zk) in blocks.iter().zip(it.z.iter()).take(k_used) {
            for (ri, row) in rp.iter_mut().zip(gk.iter()).take(r) {
                *ri -= row[0] * zk[1] + row[1] * zk[2] + row[2] * zk[3];
            }
        }
        let mut rd = [[0.0; 4]; MAX_IMPULSES];
        for ((rdk, gk), sk) in rd
            .iter_mut()
            .zip(blocks.iter())
            .zip(it.s.iter())
            .take(k_used)
        {
            let g = gkt(gk, &it.l, r);
            *rdk = [1.0 - sk[0], -g[0] - sk[1], -g[1] - sk[2], -g[2] - sk[3]];
        }
        let mut gap = 0.0;
        for (zk, sk) in it.z.iter().zip(it.s.iter()).take(k_used) {
            gap += dot(zk, sk);
        }
        let mu = gap / k_f;
        // Newton direction for a complementarity right-hand side rc (per cone).
        let direction = |rc: &[Cone; MAX_IMPULSES]| {
            let mut d = [[0.0; 4]; MAX_IMPULSES];
            let mut rhs = rp;
            for k in 0..k_used {
                let (Some(vk), Some(rck), Some(w), Some(rdk), Some(gk), Some(dk)) = (
                    v.get(k),
                    rc.get(k),
                    sc.get(k),
                    rd.get(k),
                    blocks.get(k),
                    d.get_mut(k),
                ) else {
                    continue;
                };
                *dk = arrow_solve(vk, rck);
                // rhs += A_k (W^-2 r_d - W^-1 d)
                let a = w.apply_inv(&w.apply_inv(rdk));
                let b = w.apply_inv(dk);
                for (ri, row) in rhs.iter_mut().zip(gk.iter()).take(r) {
                    *ri += row[0] * (a[1] - b[1]) + row[1] * (a[2] - b[2]) + row[2] * (a[3] - b[3]);
                }
            }
            let dl = refined_solve(&m0, &m, r, shift, &rhs);
            let mut dz = [[0.0; 4]; MAX_IMPULSES];
            let mut ds = [[0.0; 4]; MAX_IMPULSES];
            for k in 0..k_used {
                let (Some(w), Some(rdk), Some(gk), Some(dk), Some(dzk), Some(dsk)) = (
                    sc.get(k),
                    rd.get(k),
                    blocks.get(k),
                    d.get(k),
                    dz.get_mut(k),
                    ds.get_mut(k),
                ) else {
                    continue;
                };
                let g = gkt(gk, &dl, r);
                // ds = r_d - A^T dl; dz = W^-1 d - W^-2 ds.
                *dsk = [rdk[0], rdk[1] - g[0], rdk[2] - g[1], rdk[3] - g[2]];
                let a = w.apply_inv(dk);
                let b = w.apply_inv(&w.apply_inv(dsk));
                for (o, (ai, bi)) in dzk.iter_mut().zip(a.iter().zip(b.iter())) {
                    *o = *ai - *bi;
                }
            }
            (dz, ds, dl)
        };
        let step_of = |dz: &[Cone; MAX_IMPULSES], ds: &[Cone; MAX_IMPULSES]| {
            let mut a = f64::INFINITY;
            for ((zk, sk), (dzk, dsk)) in
                it.z.iter()
                    .zip(it.s.iter())
                    .zip(dz.iter().zip(ds.iter()))
                    .take(k_used)
            {
                a = a.min(max_step(zk, dzk)).min(max_step(sk, dsk));
            }
            a
        };
        // Predictor (affine scaling): rc = -v o v.
        let mut rc = [[0.0; 4]; MAX_IMPULSES];
        for (rck, vk) in rc.iter_mut().zip(v.iter()).take(k_used) {
            let vv = jordan(vk, vk);
            *rck = [-vv[0], -vv[1], -vv[2], -vv[3]];
        }
        let (dz_a, ds_a, _) = direction(&rc);
        let alpha_a = step_of(&dz_a, &ds_a).min(1.0);
        let sigma = {
            let t = 1.0 - alpha_a;
            t * t * t
        };
        // Corrector: rc = sigma mu e - v o v - (W^-1 ds_a) o (W dz_a).
        for k in 0..k_used {
            let (Some(rck), Some(w), Some(dzk), Some(dsk)) =
                (rc.get_mut(k), sc.get(k), dz_a.get(k), ds_a.get(k))
            else {
                continue;
            };
            let corr = jordan(&w.apply_inv(dsk), &w.apply(dzk));
            for (x, c) in rck.iter_mut().zip(corr.iter()) {
                *x -= *c;
            }
            rck[0] += sigma * mu;
        }
        let (dz, ds, dl) = direction(&rc);
        let alpha = (STEP_FRACTION * step_of(&dz, &ds)).min(1.0);
        let finite = dz.iter().chain(ds.iter()).flatten().all(|x| x.is_finite())
            && dl.iter().all(|x| x.is_finite())
            && alpha.is_finite();
        if !(finite && alpha > 0.0) {
            status = SocpStatus::NumericalFailure;
            break;
        }
        for ((zk, sk), (dzk, dsk)) in
            it.z.iter_mut()
                .zip(it.s.iter_mut())
                .zip(dz.iter().zip(ds.iter()))
                .take(k_used)
        {
            for (x, d) in zk.iter_mut().zip(dzk.iter()) {
                *x += alpha * *d;
            }
            for (x, d) in sk.iter_mut().zip(dsk.iter()) {
                *x += alpha * *d;
            }
        }
        for (x, d) in it.l.iter_mut().zip(dl.iter()).take(r) {
            *x += alpha * *d;
        }
        iterations = iterations.saturating_add(1);
    }
    if status != SocpStatus::Optimal {
        // The last iterate (the one before a failure, or at the cap) is certified too.
        let (upper, lower, x, l) = certify(&blocks, k_used, r, &h, &it);
        if upper.is_finite() && upper < best_upper {
            best_upper = upper;
            best_x = x;
        }
        if lower.is_finite() && lower > best_lower {
            best_lower = lower;
            best_l = l;
        }
    }
    if status == SocpStatus::NotConverged && best_upper - best_lower <= tol_unit {
        status = SocpStatus::Optimal;
    }
    // Back to the caller's units: x scales with rho; the dual in F's rows is D C^T l.
    for (o, xi) in out.x.iter_mut().zip(best_x.iter()).take(columns) {
        *o = *xi * rho;
    }
    let mut dual = [0.0; ROWS];
    for (j, (cj, lj)) in cmp.c.iter().zip(best_l.iter()).indexed().take(r) {
        let _ = j;
        for (di, ci) in dual.iter_mut().zip(cj.iter()) {
            *di += *ci * *lj;
        }
    }
    for (di, e) in dual.iter_mut().zip(cmp.d.iter()) {
        *di *= *e;
    }
    out.dual = dual;
    out.total = best_upper * rho;
    out.lower_bound = best_lower * rho;
    out.iterations = iterations;
    out.status = status;
    Some(out)
}

#[cfg(test)]
#[allow(clippy::needless_range_loop)]
mod tests {
    use super::*;

    fn lcg(seed: &mut u64) -> f64 {
        *seed = seed
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        ((*seed >> 11) as f64 / (1u64 << 53) as f64) - 0.5
    }

    fn residual(f: &FMatrix, x: &[f64; MAX_UNKNOWNS], y: &[f64; ROWS]) -> f64 {
        let mut r = 0.0f64;
        for i in 0..ROWS {
            let mut s = -y[i];
            for j in 0..MAX_UNKNOWNS {
                s += f[(i, j)] * x[j];
            }
            r = r.max(s.abs());
        }
        r
    }

    /// The dual certificate in F's rows: `|F_k^T mu| <= 1` and `y . mu` equals the lower bound.
    fn check_dual(f: &FMatrix, k: usize, y: &[f64; ROWS], lf: &LeastFuel) {
        for b in 0..k {
            let mut g = [0.0; 3];
            for (c, gc) in g.iter_mut().enumerate() {
                for i in 0..ROWS {
                    *gc += f[(i, 3 * b + c)] * lf.dual[i];
                }
            }
            assert!(norm(&g) <= 1.0 + 1e-12, "{}", norm(&g));
        }
        let lb: f64 = (0..ROWS).map(|i| y[i] * lf.dual[i]).sum();
        assert!(
            (lb - lf.lower_bound).abs() < 1e-9 * (1.0 + lf.total),
            "{lb} {}",
            lf.lower_bound
        );
    }

    #[test]
    fn puts_everything_on_the_best_impulse_and_zeroes_the_others() {
        // Three impulses that each reach y along the same direction with gains 1, 2, 3; rows 3..6
        // repeat rows 0..3 scaled, so F has rank 3. The optimum puts |x| = 1 on the gain-3
        // impulse and nothing on the others: two impulses at the cone's apex, where reweighted
        // least squares stalled.
        let mut f = FMatrix::zeros();
        for (k, g) in [1.0, 2.0, 3.0].iter().enumerate() {
            for r in 0..3 {
                f[(r, 3 * k + r)] = *g;
            }
            f[(3, 3 * k)] = *g * 0.5;
            f[(4, 3 * k + 1)] = *g * 0.25;
            f[(5, 3 * k + 2)] = *g * 0.125;
        }
        let y = [3.0, 0.0, 0.0, 1.5, 0.0, 0.0];
        let lf = least_fuel(&f, 9, &y, 1e-12, 1e-10, 50).unwrap();
        assert_eq!(lf.status, SocpStatus::Optimal);
        assert_eq!(lf.rank, 3);
        assert!((lf.total - 1.0).abs() < 1e-11, "{}", lf.total);
        assert!(lf.total - lf.lower_bound <= 1e-12);
        assert!(lf.residual < 1e-14);
        assert!(residual(&f, &lf.x, &y) < 1e-12);
        assert!((lf.x[6] - 1.0).abs() < 1e-10);
        assert!(norm(&lf.x[0..6]) < 1e-10, "{:?}", &lf.x[0..6]);
        check_dual(&f, 3, &y, &lf);
    }

    #[test]
    fn square_system_has_the_unique_solution() {
        // Two impulses, 6 x 6: the only feasible point is F^-1 y.
        let mut seed = 3u64;
        let mut f = FMatrix::zeros();
        for i in 0..6 {
            for j in 0..6 {
                f[(i, j)] = lcg(&mut seed) + if i == j { 2.0 } else { 0.0 };
            }
        }
        let y = [1.0, -0.5, 0.25, 0.0, 2.0, -1.0];
        let lf = least_fuel(&f, 6, &y, 1e-12, 1e-10, 50).unwrap();
        assert_eq!(lf.status, SocpStatus::Optimal);
        assert!(residual(&f, &lf.x, &y) < 1e-12);
        let x_ref = f
            .fixed_view::<6, 6>(0, 0)
            .into_owned()
            .lu()
            .solve(&nalgebra::SVector::<f64, 6>::from(y))
            .unwrap();
        for j in 0..6 {
            assert!((lf.x[j] - x_ref[j]).abs() < 1e-10);
        }
    }

    #[test]
    fn random_instances_are_certified_and_optimal_against_perturbations() {
        // Badly scaled rows (km versus rad) as in F; 2 to 6 impulses.
        let mut seed = 11u64;
        for case in 0..200 {
            let k = 2 + case % 5;
            let mut f = FMatrix::zeros();
            for i in 0..6 {
                let scale = if i == 0 { 3e3 } else { 0.2 };
                for j in 0..3 * k {
                    f[(i, j)] = scale * lcg(&mut seed);
                }
            }
            let mut y = [0.0; 6];
            for (i, v) in y.iter_mut().enumerate() {
                *v = (if i == 0 { 1.0 } else { 1e-4 }) * lcg(&mut seed);
            }
            let lf = least_fuel(&f, 3 * k, &y, 1e-13, 1e-10, 60).unwrap();
            assert_eq!(lf.status, SocpStatus::Optimal, "case {case}: {lf:?}");
            assert!(lf.total - lf.lower_bound <= 1e-13);
            let sum: f64 = lf.x.chunks_exact(3).map(norm).sum();
            assert!((sum - lf.total).abs() < 1e-15 + 1e-12 * sum);
            assert!(residual(&f, &lf.x, &y) < 1e-12 * (1.0 + f.amax()));
            check_dual(&f, k, &y, &lf);
            assert!(lf.iterations < 40, "{}", lf.iterations);
        }
    }

    #[test]
    fn unreachable_target_of_a_rank_deficient_f_is_projected() {
        // One impulse: rank 3, y has a component outside the range.
        let mut f = FMatrix::zeros();
        for r in 0..3 {
            f[(r, r)] = 2.0;
            f[(r + 3, r)] = 1.0;
        }
        let y = [2.0, 0.0, 0.0, 0.0, 0.0, 0.0];
        let lf = least_fuel(&f, 3, &y, 1e-12, 1e-10, 50).unwrap();
        assert_eq!(lf.rank, 3);
        assert!(lf.residual > 0.1);
        // Least squares on the equilibrated rows: x = 2 * 1/sqrt5 ... the projection of
        // (1, 0, 0, 0, 0, 0) onto the range of (e_0 / ..) gives x_0 = 0.5 (rows 0 and 3 equal
        // after equilibration).
        assert!((lf.x[0] - 0.5).abs() < 1e-12, "{:?}", lf.x);
        assert!(lf.x[1].abs() < 1e-12 && lf.x[2].abs() < 1e-12);
    }

    #[test]
    fn non_finite_input_is_refused_and_the_cap_is_honoured() {
        let mut f = FMatrix::zeros();
        f[(0, 0)] = f64::NAN;
        assert!(least_fuel(&f, 3, &[1.0; 6], 1e-12, 1e-10, 10).is_none());
        let mut seed = 5u64;
        let mut f = FMatrix::zeros();
        for i in 0..6 {
            for j in 0..12 {
                f[(i, j)] = lcg(&mut seed);
            }
        }
        let y = [1.0, 0.5, -0.5, 0.2, 0.1, 0.0];
        let lf = least_fuel(&f, 12, &y, 1e-12, 1e-10, 2).unwrap();
        assert_eq!(lf.status, SocpStatus::NotConverged);
        assert_eq!(lf.iterations, 2);
        assert!(lf.total.is_finite() && lf.total > lf.lower_bound);
        assert!(residual(&f, &lf.x, &y) < 1e-12);
        let zero = least_fuel(&f, 12, &[0.0; 6], 1e-12, 1e-10, 10).unwrap();
        assert_eq!(zero.status, SocpStatus::Optimal);
        assert_eq!(zero.total, 0.0);
    }
}
