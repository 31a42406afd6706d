//! The convex subproblem: `min 1/2 |y|^2  s.t.  a_k^T y >= b_k`, by the dual active-set method
//! of Goldfarb and Idnani (1983) specialised to an identity Hessian.
//!
//! Why this method: the Hessian is the identity in the cost-orthonormal coefficients, so the
//! unconstrained optimum is `y = 0` and the method needs only the Cholesky factor of the Gram
//! matrix of the *active* rows (at most `MAX_ACTIVE` squared numbers), never a matrix in the
//! number of variables or of candidate constraints. It is exact (no first-order tolerance
//! games), each step adds the most violated constraint or drops one, the dual objective rises
//! strictly, and the work per step is bounded by the capacities. Infeasibility is detected
//! exactly (a violated row dependent on the active rows with no multiplier to release); the
//! same method with bounded multipliers solves the l1-elastic form of an infeasible QP
//! (`solve`'s `penalty`; issue 9 item 3). Which row enters next: `qp_scan.rs`.

use super::packed::{self, cholesky, set, solve_lower, solve_lower_transposed};
use super::qp_scan;
use super::transcription::{
    row_axpy, row_dot, rows_dot, Coefficients, RowId, Transcription, MAX_BLOCKS,
};
use super::work_units;
use crate::capacity::{MAX_ACTIVE, MAX_CHECKS_PER_PAIR, MAX_FREE_PER_AXIS, MAX_NODES, MAX_PAIRS};
use crate::indexed::IndexedExt as _;
use crate::work::Meter;

/// How a QP ended.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum QpOutcome {
    Optimal,
    /// The capacity-free fallback ran out of sweeps with a feasible but not yet optimal point
    /// (every row met with the fallback's margin): usable as an iterate, not as a fixed point.
    Approximate,
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
    /// (see [`super::qp_dual::dual_index`]); no factor.
    Dual,
}

/// Numbers of the packed Gram factor at capacity.
const FACTOR_LEN: usize = packed::packed_len(MAX_ACTIVE);
/// The shared buffer: the Gram factor or the fallback's dual table, whichever is larger.
pub(crate) const STORE_LEN: usize = if FACTOR_LEN > super::qp_dual::DUAL_LEN {
    FACTOR_LEN
} else {
    super::qp_dual::DUAL_LEN
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
    direction: Coefficients,
    /// Per control node: `UPPER_ACTIVE`, `LOWER_ACTIVE`, `UPPER_ELASTIC`, `LOWER_ELASTIC` bits.
    pub(super) control_flags: [[u8; MAX_NODES]; MAX_BLOCKS],
    /// Per keep-out check: `ROW_ACTIVE`, `ROW_ELASTIC` bits.
    pub(super) keep_out_flags: [[u8; MAX_CHECKS_PER_PAIR]; MAX_PAIRS],
    /// Rows held elastic (multiplier at the penalty's bound, not in the active set).
    pub(super) elastic_count: usize,
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
        }
    }

    /// A row's `ROW_ACTIVE` / `ROW_ELASTIC` bits (a row outside the tables has none).
    fn flags(&self, id: RowId) -> u8 {
        match id {
            RowId::Control { block, node, upper } => {
                let flags = self
                    .control_flags
                    .get(usize::from(block))
                    .and_then(|row| row.get(usize::from(node)))
                    .copied()
                    .unwrap_or(0);
                let (active, elastic) = if upper {
                    (UPPER_ACTIVE, UPPER_ELASTIC)
                } else {
                    (LOWER_ACTIVE, LOWER_ELASTIC)
                };
                (if flags & active != 0 { ROW_ACTIVE } else { 0 })
                    | (if flags & elastic != 0 { ROW_ELASTIC } else { 0 })
            }
            RowId::KeepOut { pair, check } => self
                .keep_out_flags
                .get(usize::from(pair))
                .and_then(|row| row.get(usize::from(check)))
                .copied()
                .unwrap_or(0),
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
    }

    /// Whether a row is in the active set.
    pub(super) fn is_active(&self, id: RowId) -> bool {
        self.flags(id) & ROW_ACTIVE != 0
    }

    /// Whether a row is held elastic.
    pub(super) fn is_elastic(&self, id: RowId) -> bool {
        self.flags(id) & ROW_ELASTIC != 0
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
    }

    /// Hold a row elastic or release it, keeping `elastic_count`.
    fn mark_elastic(&mut self, id: RowId, on: bool) {
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
    }

    pub(crate) fn mark(&mut self, id: RowId, on: bool) {
        self.set_flag(id, ROW_ACTIVE, on);
    }

    /// Refactor the Gram matrix of the active rows (as the transcription now linearises
    /// them). Returns false on a non-positive pivot, or in fallback mode (no active set).
    pub(crate) fn refactor(&mut self, tr: &Transcription) -> bool {
        if self.mode != Mode::Factor {
            return false;
        }
        let free = tr.basis.free;
        for (a, &ida) in self.active.iter().indexed().take(self.count) {
            let va = tr.view(ida);
            for (b, &idb) in self.active.iter().indexed().take(a.saturating_add(1)) {
                let vb = tr.view(idb);
                set(&mut self.store, a, b, rows_dot(&va, &vb, free));
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
                .checks
                .get(usize::from(pair))
                .and_then(|row| row.get(usize::from(check)))
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

    /// Solve `G x = b` with the current Gram factor (factor mode).
    pub(crate) fn gram_solve(&self, b: &mut [f64; MAX_ACTIVE]) {
        solve_lower(&self.store, self.count, b);
        solve_lower_transposed(&self.store, self.count, b);
    }

    /// Remove active row `index`, keeping the others' order and multipliers.
    fn drop_row(&mut self, tr: &Transcription, index: usize) -> bool {
        if index >= self.count {
            return true;
        }
        self.remove_active(index);
        self.refactor(tr)
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

fn dense_norm2(v: &Coefficients, blocks: usize, free: usize) -> f64 {
    let mut sum = 0.0;
    for block in v.iter().take(blocks) {
        for x in block.iter().take(free) {
            sum += x * x;
        }
    }
    sum
}

/// Solve the QP from `y = 0`. `y` holds the optimum (or the last iterate) on return;
/// `iterations` counts active-set changes.
///
/// `penalty` (`rho`; `f64::INFINITY` for the QP itself) bounds every row's multiplier by
/// `rho / |a_k|`: the dual of the l1-elastic QP `min 1/2 |y|^2 + rho sum_k s_k`,
/// `a_k^T y / |a_k| + s_k >= b_k / |a_k|`, `s_k >= 0` (issue 9, item 3). The dual active-set
/// method extends to it with three more limits on a step: the entering row's multiplier
/// reaching the bound (the row is then held *elastic*: its multiplier stays there, out of the
/// factor, and its violation is its slack), an active row's reaching it (the row leaves the
/// factor, elastic), and an elastic row the answer meets with room to spare entering back
/// with its multiplier falling from the bound. The dual objective still rises at every step.
/// With a finite penalty the QP is never infeasible; `Elastic` says a held row keeps a slack.
// The active-set method's arguments, and the elastic penalty.
#[allow(clippy::too_many_arguments)]
pub(crate) fn solve(
    tr: &Transcription,
    state: &mut QpState,
    y: &mut Coefficients,
    max_iter: u16,
    tol: f64,
    iterations: &mut u32,
    work: &mut Meter,
    penalty: f64,
) -> QpOutcome {
    let free = tr.basis.free;
    let blocks = tr.blocks();
    *y = [[0.0; MAX_FREE_PER_AXIS]; MAX_BLOCKS];
    // Warm start: the previous QP's active set (the convex subproblems change little from one
    // to the next) is tried first as the entering rows; any violated row is a valid choice for
    // the dual method, and the full scan still certifies optimality at the end.
    let hint = state.active;
    let hint_count = state.count.min(MAX_ACTIVE);
    state.reset();
    let mut steps: u16 = 0;
    let mut g = [0.0; MAX_ACTIVE];
    let mut r = [0.0; MAX_ACTIVE];
    loop {
        // The hint rows first (each a keep-out row's six blocks at most); the scan of every
        // candidate row only when none of them is violated, and charged only then.
        if !work.spend(work_units::qp_hint(tr, hint_count)) {
            return QpOutcome::IterationLimit;
        }
        let hinted = qp_scan::most_violated_hint(tr, state, y, (&hint, hint_count), tol);
        let picked = match hinted {
            Some(row) => Some(row),
            None => {
                if !work.spend(work_units::qp_scan(tr)) {
                    return QpOutcome::IterationLimit;
                }
                qp_scan::most_violated(tr, state, y)
            }
        };
        // The entering row and the sign of its multiplier's change: +1 a violated row from
        // zero, -1 an elastic row met with room to spare, from the bound.
        let (p, sign) = match picked {
            Some((p, violation)) if violation < -tol => (p, 1.0),
            _ => {
                let met = if state.elastic_count > 0 {
                    qp_scan::most_met_elastic(tr, state, y, tol)
                } else {
                    None
                };
                match met {
                    Some((p, _)) => (p, -1.0),
                    None => return elastic_end(tr, state, y, tol),
                }
            }
        };
        let vp = tr.view(p);
        let norm2_p = vp.norm * vp.norm;
        let cap_p = if penalty.is_finite() {
            penalty / vp.norm
        } else {
            f64::INFINITY
        };
        let mut multiplier_p = if sign > 0.0 { 0.0 } else { cap_p };
        loop {
            // The step may add a row: keep the final checks of the larger working set.
            work.raise_reserve(work_units::reserve(tr, state.count.saturating_add(1)));
            if steps >= max_iter || !work.spend(work_units::qp_step(tr, state.count)) {
                return QpOutcome::IterationLimit;
            }
            steps = steps.saturating_add(1);
            *iterations = iterations.saturating_add(1);
            let k = state.count;
            for (slot, &row) in g.iter_mut().zip(state.active.iter()).take(k) {
                let vj = tr.view(row);
                *slot = rows_dot(&vj, &vp, free);
            }
            // r = G^{-1} g; keep l = L^{-1} g for appending p to the factor.
            let mut l = g;
            solve_lower(&state.store, k, &mut l);
            r.copy_from_slice(&l);
            solve_lower_transposed(&state.store, k, &mut r);
            // Primal direction z = a_p - A^T r: the part of a_p orthogonal to the active rows.
            state.direction = [[0.0; MAX_FREE_PER_AXIS]; MAX_BLOCKS];
            row_axpy(&vp, 1.0, &mut state.direction, free);
            for (rj, &row) in r.iter().zip(state.active.iter()).take(k) {
                let vj = tr.view(row);
                row_axpy(&vj, -rj, &mut state.direction, free);
            }
            let z2 = dense_norm2(&state.direction, blocks, free);
            let slack = row_dot(&vp, y, free) - vp.rhs;
            // A row whose part orthogonal to the active rows is below 1e-7 of its norm counts as
            // dependent: adding it would make the Gram factor ill-conditioned.
            let full_step = if z2 > 1e-14 * norm2_p {
                Some(-sign * slack / z2)
            } else {
                None
            };
            // An active row's multiplier changes by -sign r_j per unit step: the first to reach
            // zero leaves the set, the first to reach its bound is held elastic.
            let mut partial: Option<(usize, f64, bool)> = None;
            for (j, ((&rj, &multiplier_j), &row)) in r
                .iter()
                .zip(state.multiplier.iter())
                .zip(state.active.iter())
                .take(k)
                .indexed()
            {
                let rate = sign * rj;
                let limit = if rate > 0.0 {
                    Some((multiplier_j / rate, false))
                } else if rate < 0.0 && penalty.is_finite() {
                    // Elastic form only: the row's bound, `penalty / |a_j|`.
                    let cap_j = penalty / tr.view(row).norm;
                    Some(((cap_j - multiplier_j) / -rate, true))
                } else {
                    None
                };
                if let Some((ratio, to_bound)) = limit {
                    if partial.is_none_or(|(_, best, _)| ratio < best) {
                        partial = Some((j, ratio, to_bound));
                    }
                }
            }
            // The entering row's own multiplier: up to the bound, or down to zero.
            let own = if sign > 0.0 {
                cap_p - multiplier_p
            } else {
                multiplier_p
            };
            let step = match (full_step, partial) {
                (None, None) if own.is_finite() => own,
                (None, None) => return QpOutcome::Infeasible,
                (Some(f), None) => f.min(own),
                (None, Some((_, t, _))) => t.min(own),
                (Some(f), Some((_, t, _))) => f.min(t).min(own),
            };
            let signed_step = sign * step;
            if full_step.is_some() {
                for (b, values) in y.iter_mut().indexed().take(blocks) {
                    if let Some(dir) = state.direction.get(b) {
                        for (slot, d) in values.iter_mut().zip(dir.iter()).take(free) {
                            *slot += signed_step * d;
                        }
                    }
                }
            }
            for (m, rj) in state.multiplier.iter_mut().zip(r.iter()).take(k) {
                *m -= signed_step * rj;
            }
            multiplier_p += signed_step;
            let full = matches!(full_step, Some(f) if f <= step);
            if full {
                state.mark_elastic(p, false);
                if k >= MAX_ACTIVE {
                    // The working set needs more rows than the factor holds (up to 3 M (N - 3)
                    // can be independent, 504 at capacity: far beyond any RAM budget). Continue
                    // without a factor, from this dual-feasible point.
                    return super::qp_dual::solve(
                        tr,
                        state,
                        y,
                        Some((p, multiplier_p)),
                        max_iter,
                        tol,
                        iterations,
                        work,
                        penalty,
                    );
                }
                for (c, value) in l.iter().indexed().take(k) {
                    set(&mut state.store, k, c, *value);
                }
                set(&mut state.store, k, k, libm::sqrt(z2));
                if let Some(slot) = state.active.get_mut(k) {
                    *slot = p;
                }
                if let Some(slot) = state.multiplier.get_mut(k) {
                    *slot = multiplier_p;
                }
                state.count = k.saturating_add(1);
                state.peak = state.peak.max(state.count);
                state.mark(p, true);
                break;
            }
            if own <= step {
                // The entering row's multiplier reached its bound (held elastic) or zero (an
                // elastic row released): done with this row.
                state.mark_elastic(p, sign > 0.0);
                break;
            }
            let Some((leaving, _, to_bound)) = partial else {
                return QpOutcome::Infeasible;
            };
            let leaving_id = state.active.get(leaving).copied();
            if !state.drop_row(tr, leaving) {
                return QpOutcome::FactorFailure;
            }
            if let (true, Some(id)) = (to_bound, leaving_id) {
                state.mark_elastic(id, true);
            }
        }
    }
}

/// The end of a solve with no candidate row left: `Optimal` unless rows are held elastic, then
/// `Elastic` when one of them keeps a slack beyond `tol` and `Approximate` when none does (the
/// rows are met, but the held multipliers are not in the active set the rest of the solver
/// reads, so the answer is no fixed point).
fn elastic_end(tr: &Transcription, state: &QpState, y: &Coefficients, tol: f64) -> QpOutcome {
    if state.elastic_count == 0 {
        return QpOutcome::Optimal;
    }
    if qp_scan::elastic_slack_left(tr, state, y, tol) {
        QpOutcome::Elastic
    } else {
        QpOutcome::Approximate
    }
}
