//! Bounded, deterministic search over the impulse points `(u_k, dN_k)` for the least total dv,
//! scored by the exact least-fuel objective (the on-board replacement for the paper's genetic
//! algorithm, Wang 2018, section 3).
//!
//! The points are searched as cumulative phases `phi_1 <= ... <= phi_N` (rad of mean argument
//! of latitude travelled since the epoch): `u_k = wrap_2pi(u_0 + phi_k)` and
//! `dN_k = (phi_k - phi_{k-1} - wrap_2pi(u_k - u_{k-1})) / 2 pi`, so a revolution count is
//! just a longer gap and the problem is continuous; feasible when the gaps are non-negative and
//! `sum dN_k <= max_revolutions`.
//!
//! Every candidate is scored by the least `sum_k |dv_k|` (the cone program of `socp`) on the
//! linear end condition:
//! * **screening** (the `search_samples` random phase vectors of a seeded xorshift generator):
//!   one linearisation at zero impulses, cone program to `search_screen_tol_mps`;
//! * **local search** (`search_starts` pattern searches from the best samples, kept at least
//!   `search_step_rad` apart so that they start in different basins): `search_fixed_point_max_iter`
//!   linearisations (default 1, at zero impulses; each further one at the previous one's
//!   minimum-norm impulses), cone program to `search_tol_mps`. A move is first bounded below by the incumbent's dual certificate
//!   scaled to be feasible at the candidate (`dY . mu / max_k |F_k^T mu|`): a candidate whose
//!   bound is not below the incumbent cannot improve and skips the cone program.
//!
//! Moves of `+-2 pi` shift one revolution between neighbouring gaps, moves of `+-step` slide one
//! point; the step halves when no move improves, down to `search_min_step_rad`. Every scored
//! candidate counts against `search_max_evaluations`, so the work is bounded by the settings
//! alone, and the same input gives the same answer on every run (fixed seed, no clock, no
//! data-dependent budget).

use super::elements::M_PER_KM;
use super::elements::{wrap_two_pi, TWO_PI};
use super::min_fuel::min_norm;
use super::settings::{Settings, MAX_SEARCH_STARTS};
use super::socp::least_fuel;
use super::transfer::{build_system, propagate, Context, ImpulseModel, Points, Sequence, XVector};
use super::types::ImpulsePoint;
use super::work_units;
use crate::capacity::MAX_IMPULSES;
use crate::indexed::IndexedExt as _;
use core::num::NonZeroU32;

/// Phases of one candidate, rad; the first `n` are used.
pub(super) type Phases = [f64; MAX_IMPULSES];

/// The search's candidate store (lives in the workspace).
#[derive(Clone, Debug)]
pub(crate) struct SearchScratch {
    /// Best samples, best first.
    starts: [Phases; MAX_SEARCH_STARTS],
    /// Their costs, m/s (infinite when unused or infeasible).
    costs: [f64; MAX_SEARCH_STARTS],
}

impl SearchScratch {
    /// Empty.
    pub const fn new() -> Self {
        Self {
            starts: [[0.0; MAX_IMPULSES]; MAX_SEARCH_STARTS],
            costs: [f64::INFINITY; MAX_SEARCH_STARTS],
        }
    }
}

/// xorshift64* (Vigna 2016): small, fast, and the same sequence on every platform.
#[derive(Clone, Copy, Debug)]
pub(crate) struct XorShift64 {
    state: u64,
}

impl XorShift64 {
    /// A generator; seed 0 (a fixed point of xorshift) is replaced by a constant.
    pub(crate) const fn new(seed: u64) -> Self {
        Self {
            state: if seed == 0 {
                0x9E37_79B9_7F4A_7C15
            } else {
                seed
            },
        }
    }

    /// Next 64 random bits.
    pub(crate) fn next_u64(&mut self) -> u64 {
        let mut x = self.state;
        x ^= x >> 12;
        x ^= x << 25;
        x ^= x >> 27;
        self.state = x;
        x.wrapping_mul(0x2545_F491_4F6C_DD1D)
    }

    /// Uniform in `[0, 1)` with 53 random bits.
    pub(crate) fn next_f64(&mut self) -> f64 {
        (self.next_u64() >> 11) as f64 * (1.0 / 9_007_199_254_740_992.0)
    }
}

/// Impulse points of a phase vector, or `None` when infeasible.
pub(crate) fn points_of(
    phi: &Phases,
    n: usize,
    u0: f64,
    max_revolutions: i32,
    out: &mut Points,
) -> Option<()> {
    let mut prev_phi = 0.0;
    let mut prev_u = wrap_two_pi(u0);
    let mut sum: i64 = 0;
    for (p, point) in phi.iter().zip(out.at.iter_mut()).take(n) {
        let gap = *p - prev_phi;
        if gap.is_nan() || gap < 0.0 {
            return None;
        }
        let u = wrap_two_pi(u0 + *p);
        let revs = libm::round((gap - wrap_two_pi(u - prev_u)) / TWO_PI);
        let revs = if revs > 0.0 { revs } else { 0.0 };
        // revs <= gap / 2 pi + 1 is finite and small here: gaps are bounded by the sampler.
        let revs = if revs < f64::from(i32::MAX) {
            revs as i32
        } else {
            return None;
        };
        sum = sum.saturating_add(i64::from(revs));
        *point = ImpulsePoint {
            arg_latitude_rad: u,
            revolutions: revs,
        };
        prev_phi = *p;
        prev_u = u;
    }
    if sum > i64::from(max_revolutions) {
        return None;
    }
    out.n = n;
    Some(())
}

/// A scored candidate: least-fuel total (m/s, infinite when infeasible or failed) and its dual
/// certificate in F's rows (km/s units of dY per unit of dv).
#[derive(Clone, Copy, Debug)]
pub(super) struct Score {
    pub(super) cost: f64,
    pub(super) dual: [f64; 6],
}

const INFEASIBLE: Score = Score {
    cost: f64::INFINITY,
    dual: [0.0; 6],
};

/// What a search evaluation needs besides the candidate.
pub(super) struct Scorer<'a> {
    pub(super) ctx: &'a Context,
    pub(super) settings: &'a Settings,
    pub(super) n: usize,
    pub(super) u0: f64,
    pub(super) max_revolutions: i32,
}

impl Scorer<'_> {
    /// Least-fuel total of `phi` after `linearisations` fixed-point linearisations (the first at
    /// zero impulses, the next at the minimum-norm impulses of the previous one), the cone
    /// program solved to `tol_mps`. With `incumbent = (dual, cost)`, a candidate whose dual
    /// lower bound is not below `cost` is returned as that bound without the cone program.
    pub(super) fn score(
        &self,
        phi: &Phases,
        linearisations: u16,
        tol_mps: f64,
        incumbent: Option<&Score>,
        seq: &mut Sequence,
        pts: &mut Points,
    ) -> Score {
        if points_of(phi, self.n, self.u0, self.max_revolutions, pts).is_none() {
            return INFEASIBLE;
        }
        if !seq
            .work
            .spend(work_units::evaluation(self.n, linearisations))
        {
            return INFEASIBLE;
        }
        let columns = self.n.saturating_mul(3);
        let mut dv = XVector::zeros();
        for j in 0..linearisations.max(1) {
            if propagate(self.ctx, pts, &dv, ImpulseModel::Linear, self.settings, seq).is_err() {
                return INFEASIBLE;
            }
            build_system(self.ctx, pts, seq);
            if j.saturating_add(1) < linearisations {
                match min_norm(&seq.f, columns, &seq.dy, self.settings, &mut seq.work) {
                    Ok(x) => dv = x,
                    Err(_) => return INFEASIBLE,
                }
            }
        }
        if let Some(inc) = incumbent {
            if let Some(bound) = dual_bound(&seq.f, columns, &seq.dy, &inc.dual) {
                if bound * M_PER_KM >= inc.cost {
                    return Score {
                        cost: bound * M_PER_KM,
                        dual: inc.dual,
                    };
                }
            }
        }
        let mut y = [0.0; 6];
        y.copy_from_slice(seq.dy.as_slice());
        let Some(lf) = least_fuel(
            &seq.f,
            columns,
            &y,
            tol_mps / M_PER_KM,
            self.settings.rank_rcond,
            self.settings.min_fuel_max_iter,
        ) else {
            return INFEASIBLE;
        };
        seq.work
            .charge(work_units::cone_program(self.n, lf.iterations));
        // Rank-deficient points cannot reach the target; a failed cone program still returns a
        // feasible plan, whose total is an honest (upper) score.
        let cost = lf.total * M_PER_KM;
        if lf.rank == 6 && cost.is_finite() {
            Score {
                cost,
                dual: lf.dual,
            }
        } else {
            INFEASIBLE
        }
    }
}

/// `dY . mu / max(1, max_k |F_k^T mu|)`: a lower bound on the least fuel of `(F, dY)` from any
/// `mu` (weak duality); `None` when not finite.
fn dual_bound(
    f: &super::transfer::FMatrix,
    columns: usize,
    dy: &nalgebra::SVector<f64, 6>,
    mu: &[f64; 6],
) -> Option<f64> {
    let mut worst = 1.0f64;
    // Columns come in threes, one impulse each: |F_k^T mu| over each impulse k in use.
    let mut s = 0.0;
    let mut in_impulse = 0u8;
    for col in f.column_iter().take(columns) {
        let mut g = 0.0;
        for (fv, m) in col.iter().zip(mu.iter()) {
            g += *fv * *m;
        }
        s += g * g;
        in_impulse = in_impulse.saturating_add(1);
        if in_impulse == 3 {
            worst = worst.max(libm::sqrt(s));
            s = 0.0;
            in_impulse = 0;
        }
    }
    if in_impulse > 0 {
        worst = worst.max(libm::sqrt(s));
    }
    let mut b = 0.0;
    for (d, m) in dy.iter().zip(mu.iter()) {
        b += *d * *m;
    }
    let b = b / worst;
    if b.is_finite() {
        Some(b)
    } else {
        None
    }
}

/// Largest `|phi_k - psi_k|` over the first `n` phases.
fn distance(phi: &Phases, psi: &Phases, n: usize) -> f64 {
    let mut d = 0.0f64;
    for (a, b) in phi.iter().zip(psi.iter()).take(n) {
        d = d.max(libm::fabs(*a - *b));
    }
    d
}

/// Insert `(phi, cost)` into the sorted top list of length `keep` (stable: earlier wins ties),
/// keeping its entries more than `separation` apart: a candidate that close to a better entry
/// is dropped, and one that beats a close entry replaces it (starts in different basins).
fn insert_top(
    scratch: &mut SearchScratch,
    keep: usize,
    n: usize,
    separation: f64,
    phi: &Phases,
    cost: f64,
) {
    let keep = keep.min(MAX_SEARCH_STARTS);
    let Some(pos) = scratch.costs.iter().take(keep).index_of(|c| cost < *c) else {
        return;
    };
    // A better entry nearby: same basin, drop.
    let near_better = scratch
        .starts
        .iter()
        .zip(scratch.costs.iter())
        .take(pos)
        .any(|(s, c)| c.is_finite() && distance(s, phi, n) <= separation);
    if near_better {
        return;
    }
    // A worse entry nearby: the candidate takes its place (the entries below it move up).
    let near_worse = scratch
        .starts
        .iter()
        .zip(scratch.costs.iter())
        .indexed()
        .take(keep)
        .skip(pos)
        .find(|(_, (s, c))| c.is_finite() && distance(s, phi, n) <= separation)
        .map(|(j, _)| j);
    let last = near_worse.unwrap_or(keep.saturating_sub(1));
    let mut j = last;
    while j > pos {
        let below = j.saturating_sub(1);
        if let (Some(&c), Some(&p)) = (scratch.costs.get(below), scratch.starts.get(below)) {
            if let Some(slot) = scratch.costs.get_mut(j) {
                *slot = c;
            }
            if let Some(slot) = scratch.starts.get_mut(j) {
                *slot = p;
            }
        }
        j = below;
    }
    if let Some(slot) = scratch.costs.get_mut(pos) {
        *slot = cost;
    }
    if let Some(slot) = scratch.starts.get_mut(pos) {
        *slot = *phi;
    }
}

/// Search the impulse points; writes the best into `pts` and returns the evaluations used.
pub(crate) fn search(
    ctx: &Context,
    n: usize,
    max_revolutions: i32,
    settings: &Settings,
    seq: &mut Sequence,
    pts: &mut Points,
    scratch: &mut SearchScratch,
) -> u32 {
    let n = n.clamp(1, MAX_IMPULSES);
    let scorer = Scorer {
        ctx,
        settings,
        n,
        u0: ctx.model.phase_rad(&ctx.deputy0),
        max_revolutions,
    };
    let budget = settings.search_max_evaluations;
    let starts = usize::from(settings.search_starts).min(MAX_SEARCH_STARTS);
    let mut rng = XorShift64::new(settings.search_seed);
    let mut evaluations: u32 = 0;
    *scratch = SearchScratch::new();
    let revs = f64::from(max_revolutions);
    let n_f = n as f64;
    let span = TWO_PI * (revs + n_f);
    let shrink = (revs + 1.0) / (revs + n_f);

    // Phase 1: random samples, screened by the least fuel at one linearisation.
    for _ in 0..settings.search_samples.min(budget) {
        if seq.work.exhausted() {
            break;
        }
        let mut phi = [0.0; MAX_IMPULSES];
        for p in phi.iter_mut().take(n) {
            *p = rng.next_f64() * span;
        }
        if let Some(head) = phi.get_mut(..n) {
            head.sort_unstable_by(f64::total_cmp);
        }
        if points_of(&phi, n, scorer.u0, max_revolutions, pts).is_none() {
            // Shrinking to phi_N < 2 pi (max_revolutions + 1) always makes it feasible.
            for p in phi.iter_mut().take(n) {
                *p *= shrink;
            }
        }
        let c = scorer
            .score(&phi, 1, settings.search_screen_tol_mps, None, seq, pts)
            .cost;
        evaluations = evaluations.saturating_add(1);
        insert_top(scratch, starts, n, settings.search_step_rad, &phi, c);
    }

    // Phase 2: pattern searches from the best samples; unused budget carries to the next start.
    let lin = settings.search_fixed_point_max_iter;
    let tol = settings.search_tol_mps;
    let mut best_phi = scratch.starts[0];
    let mut best_cost = f64::INFINITY;
    // Start j shares what is left of the budget with the starts after it: `left` counts them
    // with itself, so it is at least 1 and the division is by a NonZeroU32.
    for (j, left) in (0..starts).zip((1..=starts).rev()) {
        let (Some(&start), Some(&start_cost)) = (scratch.starts.get(j), scratch.costs.get(j))
        else {
            break;
        };
        let Some(left) = u32::try_from(left).ok().and_then(NonZeroU32::new) else {
            break;
        };
        if !start_cost.is_finite() {
            continue;
        }
        let allowance = budget.saturating_sub(evaluations) / left;
        if allowance == 0 {
            break;
        }
        let mut used: u32 = 1;
        let mut phi = start;
        let mut inc = scorer.score(&phi, lin, tol, None, seq, pts);
        let mut step = settings.search_step_rad;
        while used < allowance && step >= settings.search_min_step_rad && !seq.work.exhausted() {
            let mut improved = false;
            for k in 0..n {
                for delta in [TWO_PI, -TWO_PI, step, -step] {
                    if used >= allowance {
                        break;
                    }
                    let mut cand = phi;
                    if let Some(p) = cand.get_mut(k) {
                        *p += delta;
                    }
                    if points_of(&cand, n, scorer.u0, max_revolutions, pts).is_none() {
                        continue;
                    }
                    let sc = scorer.score(&cand, lin, tol, Some(&inc), seq, pts);
                    used = used.saturating_add(1);
                    if sc.cost < inc.cost {
                        phi = cand;
                        inc = sc;
                        improved = true;
                        break;
                    }
                }
            }
            if !improved {
                step *= 0.5;
            }
        }
        evaluations = evaluations.saturating_add(used);
        if inc.cost < best_cost {
            best_cost = inc.cost;
            best_phi = phi;
        }
    }
    if points_of(&best_phi, n, scorer.u0, max_revolutions, pts).is_none() {
        // Only when no sample was feasible and finite: fall back to evenly spread points.
        let mut phi = [0.0; MAX_IMPULSES];
        for (k, p) in phi.iter_mut().take(n).indexed() {
            *p = TWO_PI * (revs + 1.0) * (k as f64 + 0.5) / n_f;
        }
        let _ = points_of(&phi, n, scorer.u0, max_revolutions, pts);
    }
    evaluations
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn xorshift_is_reproducible_and_uniform() {
        let mut a = XorShift64::new(42);
        let mut b = XorShift64::new(42);
        let mut sum = 0.0;
        for _ in 0..10_000 {
            let x = a.next_f64();
            assert_eq!(x, b.next_f64());
            assert!((0.0..1.0).contains(&x));
            sum += x;
        }
        assert!((sum / 10_000.0 - 0.5).abs() < 0.01);
        assert_ne!(XorShift64::new(0).next_u64(), 0);
    }

    #[test]
    fn phases_map_to_points() {
        let mut pts = Points::new();
        let u0 = 0.1;
        // Two revolutions plus 1 rad, then 0.5 rad later.
        let phi = [2.0 * TWO_PI + 1.0, 2.0 * TWO_PI + 1.5, 0.0, 0.0, 0.0, 0.0];
        points_of(&phi, 2, u0, 14, &mut pts).unwrap();
        assert_eq!(pts.at[0].revolutions, 2);
        assert!((pts.at[0].arg_latitude_rad - 1.1).abs() < 1e-12);
        assert_eq!(pts.at[1].revolutions, 0);
        assert!((pts.at[1].arg_latitude_rad - 1.6).abs() < 1e-12);
        // Over the revolution limit, or decreasing: infeasible.
        assert!(points_of(&phi, 2, u0, 1, &mut pts).is_none());
        let bad = [1.0, 0.5, 0.0, 0.0, 0.0, 0.0];
        assert!(points_of(&bad, 2, u0, 14, &mut pts).is_none());
    }

    #[test]
    fn top_list_keeps_starts_apart() {
        let mut s = SearchScratch::new();
        let at = |a: f64, b: f64| [a, b, 0.0, 0.0, 0.0, 0.0];
        insert_top(&mut s, 3, 2, 0.25, &at(1.0, 2.0), 5.0);
        // Near a better entry: the same basin, dropped.
        insert_top(&mut s, 3, 2, 0.25, &at(1.1, 2.1), 6.0);
        assert!(s.costs[1].is_infinite());
        // Near a worse entry: replaces it.
        insert_top(&mut s, 3, 2, 0.25, &at(1.05, 2.0), 4.0);
        assert_eq!(s.costs[0], 4.0);
        assert_eq!(s.starts[0][0], 1.05);
        assert!(s.costs[1].is_infinite());
        // Far away: kept, in cost order.
        insert_top(&mut s, 3, 2, 0.25, &at(3.0, 4.0), 4.5);
        insert_top(&mut s, 3, 2, 0.25, &at(5.0, 6.0), 3.0);
        assert_eq!(s.costs[..3], [3.0, 4.0, 4.5]);
    }

    #[test]
    fn dual_bound_is_a_lower_bound_and_tight_at_its_own_problem() {
        use crate::impulsive::socp::least_fuel;
        let mut seed = 9u64;
        let mut next = || {
            seed = seed
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            ((seed >> 11) as f64 / (1u64 << 53) as f64) - 0.5
        };
        let mut f = crate::impulsive::transfer::FMatrix::zeros();
        for i in 0..6 {
            for j in 0..12 {
                f[(i, j)] = next();
            }
        }
        let y = nalgebra::SVector::<f64, 6>::new(0.3, -0.1, 0.2, 0.05, -0.4, 0.1);
        let mut yy = [0.0; 6];
        yy.copy_from_slice(y.as_slice());
        let lf = least_fuel(&f, 12, &yy, 1e-12, 1e-10, 60).unwrap();
        let own = dual_bound(&f, 12, &y, &lf.dual).unwrap();
        assert!((own - lf.total).abs() < 1e-10, "{own} {}", lf.total);
        // At a perturbed problem the same certificate still bounds the optimum from below.
        for _ in 0..20 {
            let mut g = f;
            for v in g.iter_mut().take(72) {
                *v += 0.05 * next();
            }
            let mut yg = [0.0; 6];
            yg.copy_from_slice(y.as_slice());
            let opt = least_fuel(&g, 12, &yg, 1e-12, 1e-10, 60).unwrap().total;
            let bound = dual_bound(&g, 12, &y, &lf.dual).unwrap();
            assert!(bound <= opt + 1e-12, "{bound} > {opt}");
            assert!(bound > 0.5 * opt);
        }
    }
}
