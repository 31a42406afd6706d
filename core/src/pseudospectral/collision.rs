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
    analytic_relative_motion(laws_i, laws_j, t).0
}

/// Relative position and velocity `(r_i - r_j, v_i - v_j)` on the analytic laws at `t`, each
/// axis law evaluated once for both.
pub(crate) fn analytic_relative_motion(
    laws_i: &[Track; 3],
    laws_j: &[Track; 3],
    t: f64,
) -> ([f64; 3], [f64; 3]) {
    let (mut relative, mut velocity) = ([0.0; 3], [0.0; 3]);
    for ((r, v), (a, b)) in relative
        .iter_mut()
        .zip(velocity.iter_mut())
        .zip(laws_i.iter().zip(laws_j.iter()))
    {
        let ((pa, va), (pb, vb)) = (a.state(t), b.state(t));
        *r = pa - pb;
        *v = va - vb;
    }
    (relative, velocity)
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

/// `|r|^2 / 2`'s first and second time derivatives for the pair at `t`: `r . v` and
/// `v . v + r . a`, with `r`, `v`, `a` the relative position, velocity and acceleration on the
/// analytic laws.
fn separation_slope(laws_i: &[Track; 3], laws_j: &[Track; 3], t: f64) -> (f64, f64) {
    let (relative, velocity) = analytic_relative_motion(laws_i, laws_j, t);
    let (mut slope, mut curvature) = (0.0, 0.0);
    for (((a, b), r), v) in laws_i
        .iter()
        .zip(laws_j.iter())
        .zip(relative.iter())
        .zip(velocity.iter())
    {
        slope += r * v;
        curvature += v * v + r * (a.acceleration(t) - b.acceleration(t));
    }
    (slope, curvature)
}

/// The closest approach of the analytic trajectories in `[lo, hi]` (TU): a coarse scan, then
/// Newton's method on `d|r|^2/dt = 0` inside the scan's bracket around its least sample
/// (bisection where a step would leave the bracket), at most `iterations` steps. Was a
/// golden-section search on `|r|^2`: about 55 steps to 1e-12 TU, each as costly as a Newton
/// step, and no better than `sqrt(eps)` in time where `|r|^2` is flat.
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
    // A minimum inside the bracket has the slope negative at its left end, positive at its
    // right; otherwise the least sample stands (a minimum at an end of [lo, hi]).
    if !(separation_slope(laws_i, laws_j, a).0 < 0.0 && separation_slope(laws_i, laws_j, b).0 > 0.0)
    {
        return best_t;
    }
    let tol = 1e-12 * (1.0 + libm::fabs(hi));
    let mut t = best_t;
    for _ in 0..iterations {
        let (slope, curvature) = separation_slope(laws_i, laws_j, t);
        if slope < 0.0 {
            a = t;
        } else if slope > 0.0 {
            b = t;
        } else {
            break;
        }
        let newton = t - slope / curvature;
        let next = if curvature > 0.0 && newton > a && newton < b {
            newton
        } else {
            0.5 * (a + b)
        };
        let moved = libm::fabs(next - t);
        t = next;
        if moved <= tol || b - a <= tol {
            break;
        }
    }
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
    // The nodes on either side of the closest one (the whole horizon where there are no nodes).
    let last = node_times.len().saturating_sub(1);
    let (lo, hi) = match (
        node_times.get(best_node.saturating_sub(1)),
        node_times.get(best_node.saturating_add(1).min(last)),
    ) {
        (Some(&lo), Some(&hi)) => (lo, hi),
        _ => (0.0, horizon),
    };
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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::pseudospectral::guess::{solve_axis, AxisBoundary};

    /// Three axis tracks of one spacecraft from its boundary states (T = 10, Umax as given).
    fn tracks(p0: [f64; 3], v0: [f64; 3], p1: [f64; 3], umax: f64) -> [Track; 3] {
        core::array::from_fn(|axis| {
            let boundary = AxisBoundary {
                p0: p0[axis],
                v0: v0[axis],
                p1: p1[axis],
                v1: 0.0,
                horizon: 10.0,
                mass: 1.0,
                max_control: umax,
            };
            let law = solve_axis(boundary, 50).unwrap();
            if law.saturated {
                SATURATED.fetch_add(1, core::sync::atomic::Ordering::Relaxed);
            }
            law.track()
        })
    }

    /// Axis laws with a saturated arc built by `tracks` (the cases must include some).
    static SATURATED: core::sync::atomic::AtomicUsize = core::sync::atomic::AtomicUsize::new(0);

    #[test]
    fn newton_finds_the_closest_approach_of_dense_sampling() {
        // Crossings with and without saturated arcs, minima inside and at the ends.
        let mut cases = 0;
        for (k, umax) in [(0, 10.0), (1, 0.62), (2, 0.55)] {
            for offset in [-3.0, -0.7, 0.0, 0.4, 2.5] {
                let a = tracks(
                    [-6.0, offset, 0.1 * f64::from(k)],
                    [0.1, 0.0, 0.0],
                    [6.0, 1.0, 0.0],
                    umax,
                );
                let b = tracks([6.0, 0.0, 0.0], [0.0, -0.2, 0.0], [-6.0, offset, 0.5], umax);
                for (lo, hi) in [(0.0, 10.0), (2.0, 7.5), (0.0, 3.0)] {
                    let t = closest_approach(&a, &b, lo, hi, 80);
                    assert!((lo..=hi).contains(&t));
                    let at = |t: f64| norm2(&analytic_relative(&a, &b, t));
                    let sampled = (0..=20_000)
                        .map(|s| at(lo + (hi - lo) * f64::from(s) / 20_000.0))
                        .fold(f64::INFINITY, f64::min);
                    // Never above the sampled least value (beyond rounding), so never a
                    // different, higher local minimum than the samples see.
                    assert!(
                        at(t) <= sampled + 1e-12,
                        "umax {umax} offset {offset}: {} > {sampled}",
                        at(t)
                    );
                    cases += 1;
                }
            }
        }
        assert_eq!(cases, 45);
        assert!(SATURATED.load(core::sync::atomic::Ordering::Relaxed) >= 10);
    }

    #[test]
    fn newton_stops_where_the_slope_vanishes_to_rounding() {
        let a = tracks([-6.0, 0.5, 0.0], [0.0; 3], [6.0, 0.5, 0.0], 10.0);
        let b = tracks([6.0, 0.0, 0.0], [0.0; 3], [-6.0, 0.0, 0.0], 10.0);
        let t = closest_approach(&a, &b, 0.0, 10.0, 80);
        // Symmetric head-on pass: closest at mid-horizon.
        assert!((t - 5.0).abs() < 1e-12, "{t}");
        assert!(separation_slope(&a, &b, t).0.abs() < 1e-12);
    }
}
