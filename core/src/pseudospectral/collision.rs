//! Where keep-out is checked: the pruning window of eq. 23 and the Gaussian test points of
//! eq. 27, both computed on the analytic Pontryagin trajectories.

use super::guess::Track;
use crate::capacity::TEST_POINTS_PER_PAIR;
use crate::indexed::IndexedExt as _;

/// Offsets of the test points in units of sigma (Huang 2012, eq. 27): the boundaries that split
/// the central 95.44 % of a normal distribution into equal parts.
pub(crate) const TEST_POINT_OFFSETS: [f64; TEST_POINTS_PER_PAIR] =
    [-1.07, -0.64, -0.30, 0.0, 0.30, 0.64, 1.07];

/// Positions of spacecraft `i` and `j` on their analytic laws at time `t`, as `r_i - r_j`.
pub(crate) fn analytic_relative(laws_i: &[Track; 3], laws_j: &[Track; 3], t: f64) -> [f64; 3] {
    let mut out = [0.0; 3];
    for (slot, (a, b)) in out.iter_mut().zip(laws_i.iter().zip(laws_j.iter())) {
        *slot = a.state(t).0 - b.state(t).0;
    }
    out
}

fn norm2(v: &[f64; 3]) -> f64 {
    v[0] * v[0] + v[1] * v[1] + v[2] * v[2]
}

/// Earliest time two spacecraft could be within `keep_out` of each other when starting from
/// `relative_position` / `relative_velocity` with relative acceleration at most `accel` (eq. 23):
/// `|dr| >= s0 - v t - a t^2 / 2`.
pub(crate) fn earliest_contact(
    relative_position: [f64; 3],
    relative_velocity: [f64; 3],
    accel: f64,
    keep_out: f64,
) -> f64 {
    let s0 = libm::sqrt(norm2(&relative_position));
    let v = libm::sqrt(norm2(&relative_velocity));
    let gap = s0 - keep_out;
    if gap <= 0.0 {
        return 0.0;
    }
    if accel <= 0.0 {
        return if v > 0.0 { gap / v } else { f64::INFINITY };
    }
    (-v + libm::sqrt(v * v + 2.0 * accel * gap)) / accel
}

/// The closest approach of the analytic trajectories in `[lo, hi]` (TU): a coarse scan then a
/// golden-section refinement, `iterations` steps in all.
pub(crate) fn closest_approach(
    laws_i: &[Track; 3],
    laws_j: &[Track; 3],
    lo: f64,
    hi: f64,
    iterations: u16,
) -> f64 {
    const SCAN: usize = 16;
    let mut best_t = lo;
    let mut best = f64::INFINITY;
    for k in 0..=SCAN {
        let t = lo + (hi - lo) * (k as f64) / (SCAN as f64);
        let d = norm2(&analytic_relative(laws_i, laws_j, t));
        if d < best {
            best = d;
            best_t = t;
        }
    }
    let step = (hi - lo) / (SCAN as f64);
    let (mut a, mut b) = ((best_t - step).max(lo), (best_t + step).min(hi));
    let ratio = 0.5 * (libm::sqrt(5.0) - 1.0);
    let mut c = b - ratio * (b - a);
    let mut d = a + ratio * (b - a);
    let mut fc = norm2(&analytic_relative(laws_i, laws_j, c));
    let mut fd = norm2(&analytic_relative(laws_i, laws_j, d));
    for _ in 0..iterations {
        if b - a < 1e-12 * (1.0 + libm::fabs(hi)) {
            break;
        }
        if fc < fd {
            b = d;
            d = c;
            fd = fc;
            c = b - ratio * (b - a);
            fc = norm2(&analytic_relative(laws_i, laws_j, c));
        } else {
            a = c;
            c = d;
            fc = fd;
            d = a + ratio * (b - a);
            fd = norm2(&analytic_relative(laws_i, laws_j, d));
        }
    }
    let t = 0.5 * (a + b);
    if norm2(&analytic_relative(laws_i, laws_j, t)) <= best {
        t
    } else {
        best_t
    }
}

/// Test-point times (TU) for one pair (eq. 27): `K` = the node of least analytic separation,
/// `mu` = the closest approach between nodes K - 1 and K + 1 (clamped to the horizon's ends),
/// `2 sigma` = the time between those nodes. Points outside `(0, T)` are dropped (the boundary
/// states are already checked); returns the times and how many there are.
pub(crate) fn test_points(
    laws_i: &[Track; 3],
    laws_j: &[Track; 3],
    node_times: &[f64],
    horizon: f64,
    iterations: u16,
) -> ([f64; TEST_POINTS_PER_PAIR], usize) {
    let mut best_node = 0usize;
    let mut best = f64::INFINITY;
    for (h, &t) in node_times.iter().indexed() {
        let d = norm2(&analytic_relative(laws_i, laws_j, t));
        if d < best {
            best = d;
            best_node = h;
        }
    }
    let last = node_times.len().saturating_sub(1);
    let lo = node_times
        .get(best_node.saturating_sub(1))
        .copied()
        .unwrap_or(0.0);
    let hi = node_times
        .get(best_node.saturating_add(1).min(last))
        .copied()
        .unwrap_or(horizon);
    let mu = closest_approach(laws_i, laws_j, lo, hi, iterations);
    let sigma = 0.5 * (hi - lo);
    let mut out = [0.0; TEST_POINTS_PER_PAIR];
    let mut count = 0usize;
    for offset in TEST_POINT_OFFSETS {
        let t = mu + offset * sigma;
        if t > 0.0 && t < horizon {
            if let Some(slot) = out.get_mut(count) {
                *slot = t;
                count = count.saturating_add(1);
            }
        }
    }
    (out, count)
}
