//! The QP's state between and after solves: the working set with its packed Gram factor (the
//! dual active-set method, `qp.rs`) or the dual table of the capacity-free fallback
//! (`qp_dual.rs`), the rows' active and elastic flags, and how a solve ended. The solvers
//! change it; the second-order step (`newton.rs`), the curvature products (`curvature.rs`) and
//! the certificate read it, so it is its own file: none of them depends on a solver.

use super::kernel::{u8_of, Coefficients, MAX_BLOCKS};
use super::packed::{self, cholesky, solve_lower, solve_lower_transposed};
use super::qp_scan::ScanBounds;
use super::transcription::{rows_dot, RowId, Transcription};
use super::work_units::FinalChecks;
use crate::capacity::{MAX_ACTIVE, MAX_CHECKS_PER_PAIR, MAX_FREE_PER_AXIS, MAX_NODES, MAX_PAIRS};
use crate::indexed::IndexedExt as _;

/// How a QP ended.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum QpOutcome {
    Optimal,
    /// The capacity-free fallback ran out of sweeps with a feasible but not yet optimal point
    /// (every row met with the fallback's margin): usable as an iterate, not as a fixed point.
    Approximate,
    /// The capacity-free fallback ran out of sweeps before every row was met. Its point is the
    /// image `y = A^T l` of dual-feasible multipliers, short of some rows: the iteration takes
    /// it as an inexact step (the next subproblem is linearised there, where the spacecraft no
    /// longer meet in one point and the working set is smaller), never as a fixed point; the
    /// answer's own checks decide its status as for any other iterate.
    Unconverged,
    Infeasible,
    /// The l1-elastic QP (`solve` with a finite penalty) ended with a positive slack: no answer of this
    /// linearisation keeps every check and the control bound.
    Elastic,
    IterationLimit,
    FactorFailure,
}

/// Which representation the last QP's multipliers are in.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Mode {
    /// Goldfarb–Idnani: `active[..count]`, `multiplier`, and the packed Gram factor in `store`.
    Factor,
    /// The dual coordinate-ascent fallback: one multiplier per candidate row in `store`
    /// (see [`dual_index`]); no factor.
    Dual,
}

/// Numbers of the packed Gram factor at capacity.
const FACTOR_LEN: usize = packed::packed_len(MAX_ACTIVE);
/// The shared buffer: the Gram factor or the fallback's dual table, whichever is larger.
pub(crate) const STORE_LEN: usize = if FACTOR_LEN > DUAL_LEN {
    FACTOR_LEN
} else {
    DUAL_LEN
};

/// The active set and its factorisation.
#[derive(Clone, Debug)]
pub(crate) struct QpState {
    pub active: [RowId; MAX_ACTIVE],
    pub count: usize,
    /// Largest working set of the last solve: `count` in factor mode, or the rows with a
    /// positive multiplier in the fallback (which may exceed `MAX_ACTIVE`).
    pub peak: usize,
    pub multiplier: [f64; MAX_ACTIVE],
    pub mode: Mode,
    /// Packed lower Gram factor (factor mode) or dual table (fallback mode).
    pub store: [f64; STORE_LEN],
    /// The active-set method's primal direction (scratch of `qp::solve`).
    pub(super) direction: Coefficients,
    /// Per control node: `UPPER_ACTIVE`, `LOWER_ACTIVE`, `UPPER_ELASTIC`, `LOWER_ELASTIC` bits.
    pub(super) control_flags: [[u8; MAX_NODES]; MAX_BLOCKS],
    /// Per keep-out check: `ROW_ACTIVE`, `ROW_ELASTIC` bits.
    pub(super) keep_out_flags: [[u8; MAX_CHECKS_PER_PAIR]; MAX_PAIRS],
    /// Rows held elastic (multiplier at the penalty's bound, not in the active set).
    pub(super) elastic_count: usize,
    /// The final checks the solve's current stage keeps in reserve, which each QP step sets for
    /// its working set plus one row (the stage is set by `solver::run`, kept across `reset`).
    pub(crate) final_checks: FinalChecks,
    /// Lower bounds on each pair's candidate keep-out slacks, which let the scan skip the pairs
    /// that cannot hold a violated row (`qp_scan::ScanBounds`; forgotten by `reset`).
    pub(super) scan_bounds: ScanBounds,
}

/// A row in the active set (keep-out flags; `row_bits` maps a control row's side onto it).
pub(super) const ROW_ACTIVE: u8 = 1;
/// A row held elastic by the l1-elastic QP (`solve` with a finite penalty): its multiplier sits
/// at the penalty's bound and its violation is its slack.
pub(super) const ROW_ELASTIC: u8 = 2;
/// A control node's upper bound is active.
pub(super) const UPPER_ACTIVE: u8 = 1;
/// A control node's lower bound is active.
pub(super) const LOWER_ACTIVE: u8 = 2;
/// A control node's upper bound is elastic.
pub(super) const UPPER_ELASTIC: u8 = 4;
/// A control node's lower bound is elastic.
pub(super) const LOWER_ELASTIC: u8 = 8;

const NO_ROW: RowId = RowId::Control {
    block: 0,
    node: 0,
    upper: false,
};

impl QpState {
    pub const fn new() -> Self {
        Self {
            active: [NO_ROW; MAX_ACTIVE],
            count: 0,
            peak: 0,
            multiplier: [0.0; MAX_ACTIVE],
            mode: Mode::Factor,
            store: [0.0; STORE_LEN],
            direction: [[0.0; MAX_FREE_PER_AXIS]; MAX_BLOCKS],
            control_flags: [[0; MAX_NODES]; MAX_BLOCKS],
            keep_out_flags: [[0; MAX_CHECKS_PER_PAIR]; MAX_PAIRS],
            elastic_count: 0,
            final_checks: FinalChecks::FirstRun,
            scan_bounds: ScanBounds::unknown(),
        }
    }

    /// A row's `ROW_ACTIVE` / `ROW_ELASTIC` bits (`None` for a row outside the tables).
    fn flags(&self, id: RowId) -> Option<u8> {
        match id {
            RowId::Control { block, node, upper } => {
                let flags = *self
                    .control_flags
                    .get(usize::from(block))?
                    .get(usize::from(node))?;
                let (active, elastic) = if upper {
                    (UPPER_ACTIVE, UPPER_ELASTIC)
                } else {
                    (LOWER_ACTIVE, LOWER_ELASTIC)
                };
                Some(
                    (if flags & active != 0 { ROW_ACTIVE } else { 0 })
                        | (if flags & elastic != 0 { ROW_ELASTIC } else { 0 }),
                )
            }
            RowId::KeepOut { pair, check } => self
                .keep_out_flags
                .get(usize::from(pair))?
                .get(usize::from(check))
                .copied(),
        }
    }

    /// Set or clear one of a row's bits (`ROW_ACTIVE` or `ROW_ELASTIC`).
    fn set_flag(&mut self, id: RowId, bit: u8, on: bool) {
        let (slot, bit) = match id {
            RowId::Control { block, node, upper } => {
                let bit = match (bit, upper) {
                    (ROW_ACTIVE, true) => UPPER_ACTIVE,
                    (ROW_ACTIVE, false) => LOWER_ACTIVE,
                    (_, true) => UPPER_ELASTIC,
                    (_, false) => LOWER_ELASTIC,
                };
                let slot = self
                    .control_flags
                    .get_mut(usize::from(block))
                    .and_then(|row| row.get_mut(usize::from(node)));
                (slot, bit)
            }
            RowId::KeepOut { pair, check } => {
                let slot = self
                    .keep_out_flags
                    .get_mut(usize::from(pair))
                    .and_then(|row| row.get_mut(usize::from(check)));
                (slot, bit)
            }
        };
        if let Some(slot) = slot {
            *slot = if on { *slot | bit } else { *slot & !bit };
        }
        // A row that leaves the active set or an elastic bound is a candidate again: its
        // pair's bound, taken without it, no longer covers the pair.
        if !on {
            self.scan_bounds.forget_row(id);
        }
    }

    /// Whether a row is in the active set (a row outside the flag tables never enters it).
    pub(super) fn is_active(&self, id: RowId) -> bool {
        self.flags(id).is_some_and(|flags| flags & ROW_ACTIVE != 0)
    }

    /// Whether a row is held elastic (a row outside the flag tables never is).
    pub(super) fn is_elastic(&self, id: RowId) -> bool {
        self.flags(id).is_some_and(|flags| flags & ROW_ELASTIC != 0)
    }

    /// Release every row held elastic (their multipliers moved to the fallback's table).
    pub(super) fn clear_elastic(&mut self) {
        for flags in self.control_flags.iter_mut().flatten() {
            *flags &= !(UPPER_ELASTIC | LOWER_ELASTIC);
        }
        for flags in self.keep_out_flags.iter_mut().flatten() {
            *flags &= !ROW_ELASTIC;
        }
        self.elastic_count = 0;
        self.scan_bounds = ScanBounds::unknown();
    }

    /// Hold a row elastic or release it, keeping `elastic_count`.
    pub(super) fn mark_elastic(&mut self, id: RowId, on: bool) {
        if self.is_elastic(id) != on {
            self.set_flag(id, ROW_ELASTIC, on);
            self.elastic_count = if on {
                self.elastic_count.saturating_add(1)
            } else {
                self.elastic_count.saturating_sub(1)
            };
        }
    }

    /// Empty the active set, so the next QP starts without hints. Called at the start of every
    /// solve: a solve's result must depend on its input only, never on what the workspace
    /// solved before.
    pub fn reset(&mut self) {
        self.count = 0;
        self.peak = 0;
        self.mode = Mode::Factor;
        self.control_flags = [[0; MAX_NODES]; MAX_BLOCKS];
        self.keep_out_flags = [[0; MAX_CHECKS_PER_PAIR]; MAX_PAIRS];
        self.elastic_count = 0;
        self.scan_bounds = ScanBounds::unknown();
    }

    pub(crate) fn mark(&mut self, id: RowId, on: bool) {
        self.set_flag(id, ROW_ACTIVE, on);
    }

    /// Refactor the Gram matrix of the active rows (as the transcription now linearises
    /// them). Returns false on a non-positive pivot, in fallback mode (no active set), or for an
    /// active row the transcription does not hold.
    pub(crate) fn refactor(&mut self, tr: &Transcription) -> bool {
        if self.mode != Mode::Factor {
            return false;
        }
        let free = tr.basis.free;
        for (a, &ida) in self.active.iter().indexed().take(self.count) {
            let Some(va) = tr.view(ida) else {
                return false;
            };
            for (b, &idb) in self.active.iter().indexed().take(a.saturating_add(1)) {
                let Some(vb) = tr.view(idb) else {
                    return false;
                };
                packed::set(&mut self.store, a, b, rows_dot(&va, &vb, free));
            }
        }
        cholesky(&mut self.store, self.count).is_none()
    }

    /// Merge active keep-out checks of one pair closer than `CLOSE_CHECKS_TAU` into the first
    /// of them (its multiplier takes the other's), then refactor. Why: the moving check can
    /// sit a few 1e-5 off a node check at the same minimum (measured on the square swap: t = 5
    /// and t = 5 - 8e-5, both active); their rows are then parallel to 1e-5, the Gram matrix
    /// is near singular, and the null-space projector of the second-order step and of the
    /// certificate loses the reduced Hessian. As one constraint they are what they describe:
    /// the keep-out at that minimum. Returns false when the refactorisation fails (or in
    /// fallback mode).
    pub(crate) fn merge_close_checks(&mut self, tr: &Transcription) -> bool {
        if self.mode != Mode::Factor {
            return false;
        }
        let tau_of = |id: RowId| match id {
            RowId::KeepOut { pair, check } => tr
                .check(usize::from(pair), usize::from(check))
                .map(|c| (pair, c.tau)),
            RowId::Control { .. } => None,
        };
        let mut k = 0usize;
        while k < self.count {
            let current = self.active.get(k).copied().and_then(tau_of);
            let mut merged_into = None;
            if let Some((pair, tau)) = current {
                for (e, &earlier) in self.active.iter().indexed().take(k) {
                    if let Some((other_pair, other_tau)) = tau_of(earlier) {
                        if other_pair == pair
                            && libm::fabs(other_tau - tau) < super::transcription::CLOSE_CHECKS_TAU
                        {
                            merged_into = Some(e);
                            break;
                        }
                    }
                }
            }
            match merged_into {
                Some(e) => {
                    // `k` and `e < k` are live rows (`k < count`), so both multipliers exist.
                    if let (Some(&value), true) = (self.multiplier.get(k), e < k) {
                        if let Some(slot) = self.multiplier.get_mut(e) {
                            *slot += value;
                        }
                    }
                    self.remove_active(k);
                }
                None => k = k.saturating_add(1),
            }
        }
        self.refactor(tr)
    }

    /// Every multiplier of the last QP as (row, value >= 0): the working set's in factor mode,
    /// the dual table's nonzero ones in table order in the fallback's.
    pub(super) fn for_each_multiplier(&self, tr: &Transcription, mut f: impl FnMut(RowId, f64)) {
        match self.mode {
            Mode::Factor => {
                for (&id, &value) in self
                    .active
                    .iter()
                    .zip(self.multiplier.iter())
                    .take(self.count)
                {
                    f(id, value);
                }
            }
            Mode::Dual => for_each_dual_multiplier(self, tr, f),
        }
    }

    /// Solve `G x = b` with the current Gram factor (factor mode). Returns false when the store
    /// does not hold the factor of the working set (never: it holds `MAX_ACTIVE` rows' and the
    /// set has at most that many).
    #[must_use]
    pub(crate) fn gram_solve(&self, b: &mut [f64; MAX_ACTIVE]) -> bool {
        solve_lower(&self.store, self.count, b)
            && solve_lower_transposed(&self.store, self.count, b)
    }

    /// Remove active row `index`, keeping the others' order and multipliers, and delete it from
    /// the Gram factor (`packed::delete_row`, with `scratch` for its column: O(k^2) where
    /// forming and factoring the Gram matrix of the rest again was O(k^2 free + k^3), 11.7 % of
    /// the on-board work of the solves that ran out of budget, measured 29 Nov). False in the
    /// fallback (no factor) or when the factor cannot be updated.
    pub(super) fn drop_row(&mut self, index: usize, scratch: &mut [f64; MAX_ACTIVE]) -> bool {
        if index >= self.count {
            return true;
        }
        let order = self.count;
        self.remove_active(index);
        self.mode == Mode::Factor && packed::delete_row(&mut self.store, order, index, scratch)
    }

    /// Remove live row `index` from the active set: its flag goes off, the rows after it (and
    /// their multipliers) move down one place in order. Nothing for an index not live.
    fn remove_active(&mut self, index: usize) {
        let live = self.count.min(MAX_ACTIVE);
        let Some(&id) = self.active.get(..live).and_then(|rows| rows.get(index)) else {
            return;
        };
        self.mark(id, false);
        // Non-empty: `index < live`. The last live slot keeps its old value (outside the set).
        if let Some(rows) = self.active.get_mut(index..live) {
            if !rows.is_empty() {
                rows.copy_within(1.., 0);
            }
        }
        if let Some(multipliers) = self.multiplier.get_mut(index..live) {
            if !multipliers.is_empty() {
                multipliers.copy_within(1.., 0);
            }
        }
        self.count = self.count.saturating_sub(1);
    }
}

/// Multipliers of the control range rows in the dual table, one per block per node.
const CONTROL_DUALS: usize = MAX_BLOCKS * MAX_NODES;
/// The dual table: control range rows, then keep-out checks per pair.
pub(crate) const DUAL_LEN: usize = CONTROL_DUALS + MAX_PAIRS * MAX_CHECKS_PER_PAIR;

/// Where a row's multiplier lives in the dual table. A control row's two bounds share one slot.
pub(crate) fn dual_index(id: RowId) -> Option<usize> {
    let index = match id {
        RowId::Control { block, node, .. } => usize::from(block)
            .checked_mul(MAX_NODES)?
            .checked_add(usize::from(node))?,
        RowId::KeepOut { pair, check } => usize::from(pair)
            .checked_mul(MAX_CHECKS_PER_PAIR)?
            .checked_add(usize::from(check))?
            .checked_add(CONTROL_DUALS)?,
    };
    (index < DUAL_LEN).then_some(index)
}

/// The signed dual-table value of a row's multiplier (control: lower positive, upper negative).
pub(super) fn signed(id: RowId, multiplier: f64) -> f64 {
    match id {
        RowId::Control { upper: true, .. } => -multiplier,
        _ => multiplier,
    }
}

/// The control range row of `block` at `node` (its lower side: the table's slot for both).
pub(super) fn control_id(block: usize, node: usize) -> RowId {
    RowId::Control {
        block: u8_of(block),
        node: u8_of(node),
        upper: false,
    }
}

/// The keep-out row of `pair`'s check `check`.
pub(super) fn keep_out_id(pair: usize, check: usize) -> RowId {
    RowId::KeepOut {
        pair: u8_of(pair),
        check: u8_of(check),
    }
}

/// Every nonzero value of the dual table with its row, in table order (control rows, then
/// keep-out checks per pair): control values are signed (lower bound positive, upper negative).
/// A row without a slot in the table has no multiplier: it is not visited.
pub(super) fn for_each_stored(state: &QpState, tr: &Transcription, mut f: impl FnMut(RowId, f64)) {
    let mut visit = |id: RowId| {
        if let Some(&value) = dual_index(id).and_then(|i| state.store.get(i)) {
            if value != 0.0 {
                f(id, value);
            }
        }
    };
    for block in 0..tr.blocks() {
        for node in 0..tr.grid.nodes() {
            visit(control_id(block, node));
        }
    }
    for (pair, &count) in tr.check_count.iter().take(tr.pair_count).indexed() {
        for check in 0..count {
            visit(keep_out_id(pair, check));
        }
    }
}

/// Every nonzero multiplier of the fallback's table as (row, multiplier >= 0), in table order.
fn for_each_dual_multiplier(state: &QpState, tr: &Transcription, mut f: impl FnMut(RowId, f64)) {
    for_each_stored(state, tr, |id, value| match id {
        RowId::Control { block, node, .. } if value < 0.0 => f(
            RowId::Control {
                block,
                node,
                upper: true,
            },
            -value,
        ),
        _ if value > 0.0 => f(id, value),
        _ => {}
    });
}
