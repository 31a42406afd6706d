//! A deterministic work meter: the planners count the work they do in integer units and stop
//! at a budget given in their settings (`work_budget`).
//!
//! Why a count and not a clock: the same request must give the same answer on the host and on
//! the flight computer, whatever the load, so the stopping point cannot depend on time. The
//! units are charged at the loop heads of the planners, in proportion to the cost of the step
//! about to run (its rows times its variables, its propagations, its pairs times its
//! intervals...), so that `budget x instructions per unit` bounds a solve's instructions.
//! Every planner's weights are set so that each charged step, measured alone on its dearest
//! path on the Cortex-M7 under QEMU, costs at most its planner's `MAX_INSTRUCTIONS_PER_UNIT`
//! instructions per unit (`pseudospectral/kernels.rs`, `impulsive/kernels.rs`,
//! `geo_tour/kernels.rs`, `leo_tour/kernels/`, checked by the QEMU tests).
//!
//! Every count saturates (no overflow, no float): the meter is plain integer arithmetic.

/// The work meter of one solve.
///
/// Loops call [`Meter::spend`] before a step; it refuses (and the loop stops) once the step
/// would pass the loops' share of the budget. That share is the budget minus a reserve
/// ([`Meter::reserve`]) kept for the final checks of the returned answer, which are charged
/// unconditionally ([`Meter::charge`]): a usable answer is never lost to the check that shows it
/// usable. Once a step has been refused, every later `spend` is refused too, so a solve stops
/// at one well-defined point.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Meter {
    /// Units charged so far.
    used: u64,
    /// The budget.
    budget: u64,
    /// The loops' share: `budget - reserve`.
    limit: u64,
    /// A step of the current stage was refused.
    refusing: bool,
    /// A step of any stage was refused.
    exhausted: bool,
}

impl Meter {
    /// A meter with `budget` units and no reserve.
    pub const fn new(budget: u64) -> Self {
        Self {
            used: 0,
            budget,
            limit: budget,
            refusing: false,
            exhausted: false,
        }
    }

    /// Start a solve's next stage (planner B's final solve after its search) with a new
    /// reserve: its loops may spend again, up to `budget - units`. A stage cut short stays
    /// reported by [`Meter::exhausted`].
    pub fn next_stage(&mut self, units: u64) {
        self.reserve(units);
        self.refusing = false;
    }

    /// Keep `units` of the budget for the final checks: the loops stop that far short of it.
    pub fn reserve(&mut self, units: u64) {
        self.limit = self.budget.saturating_sub(units);
    }

    /// Keep at least `units` for the final checks: the loops' share only shrinks (for a stage
    /// whose final checks cost more than the ones already kept, such as planner A's saddle
    /// escape, which keeps its answer's checks and those of the return).
    pub fn raise_reserve(&mut self, units: u64) {
        self.limit = self.limit.min(self.budget.saturating_sub(units));
    }

    /// Charge `units` for a step about to run, if it fits in the loops' share. `false` (nothing
    /// charged) when it does not, or when an earlier step was refused: the caller stops.
    pub fn spend(&mut self, units: u64) -> bool {
        let after = self.used.saturating_add(units);
        if self.refusing || after > self.limit {
            self.refusing = true;
            self.exhausted = true;
            return false;
        }
        self.used = after;
        true
    }

    /// Charge `units` whatever the budget: the reserved final checks, or work whose size was
    /// known only once done (it then bounds the next `spend`).
    pub fn charge(&mut self, units: u64) {
        self.used = self.used.saturating_add(units);
    }

    /// Units the loops may still spend (their share minus what is charged): the budget to
    /// give a nested solve whose units are charged here once it returns.
    pub const fn remaining(&self) -> u64 {
        self.limit.saturating_sub(self.used)
    }

    /// Units charged so far.
    pub const fn used(&self) -> u64 {
        self.used
    }

    /// A step of the current stage was refused: that stage's loops stop. A later stage
    /// ([`Meter::next_stage`]) may spend again, so the loops of a stage test this, not
    /// [`Meter::exhausted`], which stays set once any stage was cut.
    pub const fn stage_refused(&self) -> bool {
        self.refusing
    }

    /// A step was refused (in any stage): the solve stopped short of its own end.
    pub const fn exhausted(&self) -> bool {
        self.exhausted
    }
}

/// Product of small sizes as work units (saturating; sizes are capacities, far below overflow).
pub(crate) fn units(factors: &[usize]) -> u64 {
    factors.iter().fold(1u64, |acc, &f| {
        acc.saturating_mul(u64::try_from(f).unwrap_or(u64::MAX))
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn spends_up_to_the_loops_share_then_refuses_for_good() {
        let mut m = Meter::new(100);
        m.reserve(30);
        assert!(m.spend(50));
        assert!(m.spend(20));
        assert!(!m.spend(1));
        assert!(m.exhausted());
        // Refused for good, even a step that would fit.
        assert!(!m.spend(0));
        assert_eq!(m.used(), 70);
        // The reserve pays the final checks.
        m.charge(25);
        assert_eq!(m.used(), 95);
        // A next stage may spend its share again; the cut stays reported.
        assert!(m.stage_refused());
        m.next_stage(0);
        assert!(!m.stage_refused());
        assert!(m.exhausted());
        assert!(m.spend(5));
        assert!(!m.spend(1));
        assert!(m.stage_refused() && m.exhausted());
    }

    #[test]
    fn saturates_instead_of_overflowing() {
        let mut m = Meter::new(u64::MAX - 1);
        m.charge(u64::MAX);
        m.charge(5);
        assert_eq!(m.used(), u64::MAX);
        assert!(!m.spend(0));
        let mut r = Meter::new(10);
        r.reserve(20);
        assert!(!r.spend(1));
        assert_eq!(units(&[3, 4, 5]), 60);
        assert_eq!(units(&[usize::MAX, usize::MAX]), u64::MAX);
    }
}
