//! The planner-A result: node states and controls, cost, verified separation.

use super::certificate::{ActiveConstraint, Certificate};
use super::status::SolveInfo;
use crate::capacity::{MAX_NODES, MAX_PAIRS, MAX_SPACECRAFT, TEST_POINTS_PER_PAIR};
use crate::indexed::IndexedExt as _;
use serde::{Deserialize, Serialize};

/// A solved (or best) trajectory set, written by a solve into caller-owned memory.
///
/// Units: normalised (see the [module docs](super)). Only the first `spacecraft_count`
/// spacecraft and the first `degree + 1` nodes are meaningful; the rest are zero.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Solution {
    /// Polynomial degree N; `N + 1` nodes.
    pub degree: u16,
    /// Number of spacecraft M.
    pub spacecraft_count: u8,
    /// Horizon T in TU.
    pub horizon_tu: f64,
    /// Node times `t_h = T/2 (tau_h + 1)` in TU.
    pub node_times_tu: [f64; MAX_NODES],
    /// States `[x, y, z, vx, vy, vz]` (LU, LU/TU) per spacecraft per node.
    pub states: [[[f64; 6]; MAX_NODES]; MAX_SPACECRAFT],
    /// Control forces `[ux, uy, uz]` (FU) per spacecraft per node.
    pub controls_fu: [[[f64; 3]; MAX_NODES]; MAX_SPACECRAFT],
    /// Control energy `J = 1/2 sum_i int |U_i|^2 dt` (Huang 2012, eq. 18), in FU^2 TU.
    pub cost: f64,
    /// Least separation of any pair over the continuous interpolated trajectory, in LU; `None`
    /// when there is no pair (one spacecraft), and then `min_separation_pair` is `(0, 0)` and
    /// `min_separation_time_tu` 0.
    pub min_separation_lu: Option<f64>,
    /// The pair `(i, j)`, `i < j`, where the least separation occurs.
    pub min_separation_pair: (u8, u8),
    /// When the least separation occurs, in TU.
    pub min_separation_time_tu: f64,
    /// Largest position or velocity error when the true double integrator is propagated with
    /// the interpolated control and compared with the interpolated states (Huang 2012, eq. 29).
    pub max_dynamics_error: f64,
    /// Gaussian test-point times per pair (pairs in order (0,1), (0,2), ..., (1,2), ...), in TU;
    /// only meaningful when the problem asked for test points.
    pub test_point_times_tu: [[f64; TEST_POINTS_PER_PAIR]; MAX_PAIRS],
    /// Counters and status.
    pub info: SolveInfo,
    /// Optimality measures of the returned trajectory (`Solved` requires them met).
    pub certificate: Certificate,
    /// With `Infeasible`: the constraints the l1-elastic subproblem could not meet, the pairs
    /// that cannot be separated and when (empty with any other status).
    pub unmet: Unmet,
}

/// Most constraints an `Infeasible` answer names (the largest shortfalls).
pub const MAX_UNMET: usize = 8;

/// A constraint the l1-elastic subproblem could not meet.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct UnmetConstraint {
    /// Which: a pair's keep-out at a time, or a spacecraft's control bound at a node.
    pub constraint: ActiveConstraint,
    /// By how much the elastic answer misses it in the constraint's own units: LU inside the
    /// linearised keep-out (`d` less the separation along the check's normal), FU beyond
    /// Umax.
    pub shortfall: f64,
    /// `shortfall` relative to `d` (keep-out) or Umax (control): the order of the list.
    pub shortfall_rel: f64,
}

const NO_UNMET: UnmetConstraint = UnmetConstraint {
    constraint: ActiveConstraint::KeepOut {
        pair: (0, 0),
        time_tu: 0.0,
    },
    shortfall: 0.0,
    shortfall_rel: 0.0,
};

/// The constraints an `Infeasible` answer names: why no plan was found.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct Unmet {
    /// Constraints named, at most `MAX_UNMET`.
    pub count: u8,
    /// More constraints kept a positive slack than `constraints` holds (the smallest
    /// relative shortfalls were left out).
    pub truncated: bool,
    /// The constraints: keep-out checks first, then control bounds, each kind by relative
    /// shortfall, largest first.
    pub constraints: [UnmetConstraint; MAX_UNMET],
}

impl Default for Unmet {
    fn default() -> Self {
        Self::new()
    }
}

impl Unmet {
    /// None named.
    pub const fn new() -> Self {
        Self {
            count: 0,
            truncated: false,
            constraints: [NO_UNMET; MAX_UNMET],
        }
    }

    /// The named constraints.
    pub fn named(&self) -> &[UnmetConstraint] {
        self.constraints
            .get(..usize::from(self.count))
            .unwrap_or(&self.constraints)
    }

    /// Keep `entry` if it is among the first `MAX_UNMET` offered so far in the list's order:
    /// keep-out checks before control bounds (the pairs that cannot be separated are what an
    /// `Infeasible` answer is about), each kind by relative shortfall, largest first.
    pub(crate) fn offer(&mut self, entry: UnmetConstraint) {
        let count = usize::from(self.count).min(MAX_UNMET);
        // The list is kept sorted: the entry goes before the first it comes before.
        let mut place = count;
        for (k, named) in self.constraints.iter().take(count).indexed() {
            if before(&entry, named) {
                place = k;
                break;
            }
        }
        if place >= MAX_UNMET {
            self.truncated = true;
            return;
        }
        if count == MAX_UNMET {
            self.truncated = true;
        } else {
            self.count = self.count.saturating_add(1);
        }
        // Shift the tail down one place (the last falls off when full), then insert. (No
        // library sort: its order-violation check is a panic path.)
        let live = usize::from(self.count).min(MAX_UNMET);
        if let Some(tail) = self.constraints.get_mut(place..live) {
            if !tail.is_empty() {
                tail.rotate_right(1);
            }
            if let Some(first) = tail.first_mut() {
                *first = entry;
            }
        }
    }
}

/// `a` comes before `b` in the list's order (see `Unmet::offer`).
fn before(a: &UnmetConstraint, b: &UnmetConstraint) -> bool {
    let keep_out = |u: &UnmetConstraint| matches!(u.constraint, ActiveConstraint::KeepOut { .. });
    match (keep_out(a), keep_out(b)) {
        (true, false) => true,
        (false, true) => false,
        _ => a.shortfall_rel > b.shortfall_rel,
    }
}

impl Solution {
    /// An empty solution (status `Unsolved`), for use as an output buffer.
    pub const fn new() -> Self {
        Self {
            degree: 0,
            spacecraft_count: 0,
            horizon_tu: 0.0,
            node_times_tu: [0.0; MAX_NODES],
            states: [[[0.0; 6]; MAX_NODES]; MAX_SPACECRAFT],
            controls_fu: [[[0.0; 3]; MAX_NODES]; MAX_SPACECRAFT],
            cost: 0.0,
            min_separation_lu: None,
            min_separation_pair: (0, 0),
            min_separation_time_tu: 0.0,
            max_dynamics_error: 0.0,
            test_point_times_tu: [[0.0; TEST_POINTS_PER_PAIR]; MAX_PAIRS],
            info: SolveInfo {
                status: super::status::SolveStatus::Unsolved,
                sqp_iterations: 0,
                qp_iterations: 0,
                verify_rounds: 0,
                verify_points_added: 0,
                keep_out_checks: 0,
                max_active: 0,
                warm_start_used: false,
                work_units: 0,
                max_violation: 0.0,
                saddle_escapes: 0,
                elastic_subproblems: 0,
            },
            certificate: Certificate::new(),
            unmet: Unmet::new(),
        }
    }
}

impl Solution {
    /// Reset to the empty state in place (no large temporary on the stack).
    pub fn reset(&mut self) {
        self.degree = 0;
        self.spacecraft_count = 0;
        self.horizon_tu = 0.0;
        self.node_times_tu.fill(0.0);
        for sc in self.states.iter_mut() {
            sc.fill([0.0; 6]);
        }
        for sc in self.controls_fu.iter_mut() {
            sc.fill([0.0; 3]);
        }
        self.cost = 0.0;
        self.min_separation_lu = None;
        self.min_separation_pair = (0, 0);
        self.min_separation_time_tu = 0.0;
        self.max_dynamics_error = 0.0;
        for pair in self.test_point_times_tu.iter_mut() {
            pair.fill(0.0);
        }
        self.info = SolveInfo::default();
        self.certificate = Certificate::new();
        self.unmet = Unmet::new();
    }
}

impl Default for Solution {
    fn default() -> Self {
        Self::new()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn keep_out(shortfall_rel: f64) -> UnmetConstraint {
        UnmetConstraint {
            constraint: ActiveConstraint::KeepOut {
                pair: (0, 1),
                time_tu: shortfall_rel,
            },
            shortfall: 2.0 * shortfall_rel,
            shortfall_rel,
        }
    }

    #[test]
    fn unmet_keeps_the_largest_relative_shortfalls_in_order() {
        let mut unmet = Unmet::new();
        assert!(unmet.named().is_empty());
        // Twelve offers in a scrambled order: the eight largest stay, largest first.
        for k in [3, 11, 0, 7, 5, 9, 1, 10, 2, 8, 6, 4] {
            unmet.offer(keep_out(f64::from(k)));
        }
        let kept: heapless::Vec<f64, MAX_UNMET> =
            unmet.named().iter().map(|u| u.shortfall_rel).collect();
        assert_eq!(kept.as_slice(), &[11.0, 10.0, 9.0, 8.0, 7.0, 6.0, 5.0, 4.0]);
        assert!(unmet.truncated);
        // A control bound, however large its shortfall, comes after the keep-out checks.
        unmet.offer(UnmetConstraint {
            constraint: ActiveConstraint::Control {
                spacecraft: 0,
                axis: 0,
                node: 0,
                upper: true,
            },
            shortfall: 100.0,
            shortfall_rel: 100.0,
        });
        assert_eq!(unmet.named()[0].shortfall_rel, 11.0);
        let mut few = Unmet::new();
        few.offer(keep_out(1.0));
        few.offer(keep_out(3.0));
        assert_eq!(few.named().len(), 2);
        assert_eq!(few.named()[0].shortfall_rel, 3.0);
        assert!(!few.truncated);
    }
}
