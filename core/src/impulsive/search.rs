//! Bounded, deterministic search over the impulse points `(u_k, dN_k)` for the least total dv,
//! with the fixed-point solve inside (the on-board replacement for the paper's genetic
//! algorithm, Wang 2018, section 3).
//!
//! The points are searched as cumulative phases `phi_1 <= ... <= phi_N` (rad of mean argument
//! of latitude travelled since the epoch): `u_k = wrap_2pi(u_0 + phi_k)` and
//! `dN_k = (phi_k - phi_{k-1} - wrap_2pi(u_k - u_{k-1})) / 2 pi`, so a revolution count is
//! just a longer gap and the problem is continuous; feasible when the gaps are non-negative and
//! `sum dN_k <= max_revolutions`. Phase 1 scores `search_samples` random phase vectors from a
//! seeded xorshift generator; phase 2 runs `search_starts` pattern searches from the best of
//! them (moves of `+-2 pi` shift one revolution between neighbouring gaps, moves of `+-step`
//! slide one point; the step halves when no move improves). Every evaluation counts against
//! `search_max_evaluations`, so the work is bounded by the settings alone, and the same input
//! gives the same answer on every run (fixed seed, no clock, no data-dependent budget).

use super::elements::{mean_arg_latitude_rad, wrap_two_pi, TWO_PI};
use super::min_fuel::total;
use super::settings::{Settings, MAX_SEARCH_STARTS};
use super::solver::fixed_point;
use super::transfer::{Context, Points, Sequence, XVector};
use super::types::ImpulsePoint;
use crate::capacity::MAX_IMPULSES;

/// Phases of one candidate, rad; the first `n` are used.
type Phases = [f64; MAX_IMPULSES];

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

#[allow(clippy::too_many_arguments)]
/// Cost of a phase vector: the fixed-point total in m/s (infinite when infeasible or failed).
fn cost_of(
    phi: &Phases,
    n: usize,
    u0: f64,
    max_revolutions: i32,
    ctx: &Context,
    settings: &Settings,
    seq: &mut Sequence,
    pts: &mut Points,
) -> f64 {
    if points_of(phi, n, u0, max_revolutions, pts).is_none() {
        return f64::INFINITY;
    }
    let mut dv = XVector::zeros();
    match fixed_point(
        ctx,
        pts,
        settings,
        seq,
        &mut dv,
        settings.search_min_fuel,
        settings.search_fixed_point_max_iter,
    ) {
        Ok(fp) if fp.conditioning.rank == 6 => {
            let t = total(&dv) * super::elements::M_PER_KM;
            if t.is_finite() {
                t
            } else {
                f64::INFINITY
            }
        }
        _ => f64::INFINITY,
    }
}

/// Insert `(phi, cost)` into the sorted top list of length `keep` (stable: earlier wins ties).
fn insert_top(scratch: &mut SearchScratch, keep: usize, phi: &Phases, cost: f64) {
    let keep = keep.min(MAX_SEARCH_STARTS);
    let Some(pos) = scratch.costs.iter().take(keep).position(|c| cost < *c) else {
        return;
    };
    let last = keep.saturating_sub(1);
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
    let u0 = mean_arg_latitude_rad(&ctx.deputy0);
    let budget = settings.search_max_evaluations;
    let starts = usize::from(settings.search_starts).min(MAX_SEARCH_STARTS);
    let mut rng = XorShift64::new(settings.search_seed);
    let mut evaluations: u32 = 0;
    *scratch = SearchScratch::new();
    let revs = f64::from(max_revolutions);
    let n_f = n as f64;
    let span = TWO_PI * (revs + n_f);
    let shrink = (revs + 1.0) / (revs + n_f);

    // Phase 1: random samples.
    for _ in 0..settings.search_samples.min(budget) {
        let mut phi = [0.0; MAX_IMPULSES];
        for p in phi.iter_mut().take(n) {
            *p = rng.next_f64() * span;
        }
        if let Some(head) = phi.get_mut(..n) {
            head.sort_unstable_by(f64::total_cmp);
        }
        if points_of(&phi, n, u0, max_revolutions, pts).is_none() {
            // Shrinking to phi_N < 2 pi (max_revolutions + 1) always makes it feasible.
            for p in phi.iter_mut().take(n) {
                *p *= shrink;
            }
        }
        let c = cost_of(&phi, n, u0, max_revolutions, ctx, settings, seq, pts);
        evaluations = evaluations.saturating_add(1);
        insert_top(scratch, starts, &phi, c);
    }

    // Phase 2: pattern searches from the best samples; unused budget carries to the next start.
    let mut best_phi = scratch.starts[0];
    let mut best_cost = scratch.costs[0];
    for j in 0..starts {
        let (Some(&start), Some(&start_cost)) = (scratch.starts.get(j), scratch.costs.get(j))
        else {
            break;
        };
        if !start_cost.is_finite() {
            continue;
        }
        let remaining_starts = u32::try_from(starts.saturating_sub(j)).unwrap_or(1).max(1);
        let allowance = budget
            .saturating_sub(evaluations)
            .checked_div(remaining_starts)
            .unwrap_or(0);
        let mut used: u32 = 0;
        let mut phi = start;
        let mut cost = start_cost;
        let mut step = settings.search_step_rad;
        while used < allowance && step >= settings.search_min_step_rad {
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
                    if points_of(&cand, n, u0, max_revolutions, pts).is_none() {
                        continue;
                    }
                    let c = cost_of(&cand, n, u0, max_revolutions, ctx, settings, seq, pts);
                    used = used.saturating_add(1);
                    if c < cost {
                        phi = cand;
                        cost = c;
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
        if cost < best_cost {
            best_cost = cost;
            best_phi = phi;
        }
    }
    if points_of(&best_phi, n, u0, max_revolutions, pts).is_none() {
        // Only when no sample was feasible and finite: fall back to evenly spread points.
        let mut phi = [0.0; MAX_IMPULSES];
        for (k, p) in phi.iter_mut().take(n).enumerate() {
            *p = TWO_PI * (revs + 1.0) * (k as f64 + 0.5) / n_f;
        }
        let _ = points_of(&phi, n, u0, max_revolutions, pts);
    }
    evaluations
}

#[cfg(test)]
#[allow(clippy::unwrap_used, clippy::indexing_slicing, clippy::float_cmp)]
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
}
