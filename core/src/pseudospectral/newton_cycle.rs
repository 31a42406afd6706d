//! Seeing the Newton points cycle: the costs of the last accepted answers of one SQP run, and
//! whether a new Newton answer's cost repeats one of them.
//!
//! Near a fixed point whose active set is not settled, the Newton points can walk a closed
//! loop: one check enters the active set and leaves it again, and the accepted answers repeat
//! the same costs to the last digits with a period of a few subproblems (traced on the tuning
//! set's #33, a collinear reversal: period 7, active sets of 8 and 9 rows, the costs 2e-8 apart
//! relative, just above `sqp_tol_cost`). Each loop pays one rejected Newton point, so the run
//! spends `MAX_NEWTON_REJECTIONS` loops (about 40 subproblems there) before it falls back to
//! plain steps. A repeated cost is that loop seen at its first return: the run takes plain
//! steps from then on.

/// Accepted costs remembered: a loop longer than this is not seen. The traced loop had
/// period 7. Chosen on the tuning set with `REPEAT_TOL_REL` (`reconfig sweep --set tuning`,
/// `Solved` at the default budget / lifted to 1e9 units): no detection 1825 / 1948; 4 costs
/// 1829 / 1950; 8: 1831 / 1950; 16: 1831 / 1950.
pub(super) const REMEMBERED_COSTS: usize = 8;

/// Two costs closer than this, relative to `1 + |J|`, are the same point of a loop: far below
/// `sqp_tol_cost` (1e-8), so answers still descending (a decrease the convergence test counts)
/// are never taken for a loop. Not every loop returns to the same bits (equal costs alone
/// caught fewer). Tuning set (as above, 8 costs): equal costs only 1826 / 1948; 1e-14:
/// 1828 / 1950; 1e-13: 1831 / 1950; 1e-12 and 1e-11: 1829 / 1949.
pub(super) const REPEAT_TOL_REL: f64 = 1e-13;

/// The last `REMEMBERED_COSTS` accepted costs of one SQP run (a ring; empty slots are NaN,
/// which repeats nothing).
#[derive(Clone, Copy, Debug)]
pub(super) struct RecentCosts {
    costs: [f64; REMEMBERED_COSTS],
    /// The slot the next cost overwrites (always `< REMEMBERED_COSTS`).
    next: usize,
}

impl RecentCosts {
    pub(super) const fn new() -> Self {
        Self {
            costs: [f64::NAN; REMEMBERED_COSTS],
            next: 0,
        }
    }

    /// Remember `cost_fu` (an accepted answer's cost); returns whether it repeats one of the
    /// costs remembered before it.
    pub(super) fn record(&mut self, cost_fu: f64) -> bool {
        let tolerance = REPEAT_TOL_REL * (1.0 + libm::fabs(cost_fu));
        let repeated = self
            .costs
            .iter()
            .any(|&c| libm::fabs(c - cost_fu) <= tolerance);
        if let Some(slot) = self.costs.get_mut(self.next) {
            *slot = cost_fu;
        }
        let following = self.next.saturating_add(1);
        self.next = if following >= REMEMBERED_COSTS {
            0
        } else {
            following
        };
        repeated
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_loop_of_seven_is_seen_at_its_first_return_and_not_before() {
        let mut recent = RecentCosts::new();
        let loop_costs = [
            14.602_080_234,
            14.602_080_301,
            14.602_080_529,
            14.602_080_412,
            14.602_080_377,
            14.602_080_266,
            14.602_080_488,
        ];
        // A descent first: no repeat.
        for k in 0..20 {
            assert!(!recent.record(20.0 - f64::from(k) * 0.25));
        }
        for &c in &loop_costs {
            assert!(!recent.record(c), "{c} is new");
        }
        // The loop's first return.
        assert!(recent.record(loop_costs[0]));
        // A cost 1e-12 relative away is no repeat; one within 1e-13 is.
        assert!(!recent.record(14.602_080_234 * (1.0 + 1e-12)));
        assert!(recent.record(14.602_080_234 * (1.0 + 5e-15)));
    }

    #[test]
    fn a_loop_longer_than_the_memory_is_not_seen() {
        let mut recent = RecentCosts::new();
        let period = REMEMBERED_COSTS + 1;
        for round in 0..3 {
            for k in 0..period {
                let cost = 1.0 + 1e-6 * f64::from(u32::try_from(k).unwrap());
                assert!(!recent.record(cost), "round {round}, point {k}");
            }
        }
    }

    #[test]
    fn nothing_repeats_an_empty_memory_and_nan_repeats_nothing() {
        let mut recent = RecentCosts::new();
        assert!(!recent.record(0.0));
        assert!(!recent.record(f64::NAN));
        assert!(!recent.record(f64::NAN));
        assert!(recent.record(0.0));
    }
}
