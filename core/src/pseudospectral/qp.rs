//! The convex subproblem: `min 1/2 |y|^2  s.t.  a_k^T y >= b_k`, by the dual active-set method
//! of Goldfarb and Idnani (1983) specialised to an identity Hessian.
//!
//! Why this method: the Hessian is the identity in the cost-orthonormal coefficients, so the
//! unconstrained optimum is `y = 0` and the method needs only the Cholesky factor of the Gram
//! matrix of the *active* rows (at most `MAX_ACTIVE` squared numbers), never a matrix in the
//! number of variables or of candidate constraints. It is exact (no first-order tolerance
//! games), each step adds the most violated constraint or drops one, the dual objective rises
//! strictly, and the work per step is bounded by the capacities. Infeasibility is detected
//! exactly (a violated row dependent on the active rows with no multiplier to release).

use super::packed::{self, cholesky, set, solve_lower, solve_lower_transposed};
use super::transcription::{
    block_dot, row_axpy, row_dot, rows_dot, Coefficients, NodeDots, RowId, Transcription,
    MAX_BLOCKS,
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
    control_active: [[u8; MAX_NODES]; MAX_BLOCKS],
    keep_out_active: [[bool; MAX_CHECKS_PER_PAIR]; MAX_PAIRS],
}

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
            control_active: [[0; MAX_NODES]; MAX_BLOCKS],
            keep_out_active: [[false; MAX_CHECKS_PER_PAIR]; MAX_PAIRS],
        }
    }

    /// Whether a row is in the active set.
    fn is_active(&self, id: RowId) -> bool {
        match id {
            RowId::Control { block, node, upper } => {
                let bit = if upper { 1u8 } else { 2u8 };
                self.control_active
                    .get(usize::from(block))
                    .and_then(|row| row.get(usize::from(node)))
                    .is_some_and(|flags| flags & bit != 0)
            }
            // A row outside the table was never activated.
            RowId::KeepOut { pair, check } => self
                .keep_out_active
                .get(usize::from(pair))
                .and_then(|row| row.get(usize::from(check)))
                .is_some_and(|&active| active),
        }
    }

    /// Empty the active set, so the next QP starts without hints. Called at the start of every
    /// solve: a solve's result must depend on its input only, never on what the workspace
    /// solved before.
    pub fn reset(&mut self) {
        self.count = 0;
        self.peak = 0;
        self.mode = Mode::Factor;
        self.control_active = [[0; MAX_NODES]; MAX_BLOCKS];
        self.keep_out_active = [[false; MAX_CHECKS_PER_PAIR]; MAX_PAIRS];
    }

    pub(crate) fn mark(&mut self, id: RowId, on: bool) {
        match id {
            RowId::Control { block, node, upper } => {
                let bit = if upper { 1u8 } else { 2u8 };
                if let Some(slot) = self
                    .control_active
                    .get_mut(usize::from(block))
                    .and_then(|row| row.get_mut(usize::from(node)))
                {
                    *slot = if on { *slot | bit } else { *slot & !bit };
                }
            }
            RowId::KeepOut { pair, check } => {
                if let Some(slot) = self
                    .keep_out_active
                    .get_mut(usize::from(pair))
                    .and_then(|row| row.get_mut(usize::from(check)))
                {
                    *slot = on;
                }
            }
        }
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

/// The most violated inactive constraint at `y`, as (row, slack / |row|).
fn most_violated(tr: &Transcription, state: &QpState, y: &Coefficients) -> Option<(RowId, f64)> {
    let free = tr.basis.free;
    let mut best: Option<(RowId, f64)> = None;
    let mut consider = |id: RowId, value: f64| match best {
        Some((_, v)) if v <= value => {}
        _ => best = Some((id, value)),
    };
    // Blocks and nodes within the transcription's (validated) counts, walked with their flags.
    let nodes = tr.grid.nodes();
    for (block, flags) in state.control_active.iter().take(tr.blocks()).indexed() {
        let node_rows = tr.basis.accel_norm.iter().zip(tr.basis.accel.iter());
        for (node, ((&norm, row), &flag)) in node_rows.zip(flags.iter()).take(nodes).indexed() {
            if norm <= 0.0 {
                continue;
            }
            let control = super::transcription::node_value(&tr.base_control, block, node)
                + block_dot(row, y, block, free);
            let (b, h) = (block as u8, node as u8);
            if flag & 1 == 0 {
                let slack = (tr.max_control_fu - control) / norm;
                consider(
                    RowId::Control {
                        block: b,
                        node: h,
                        upper: true,
                    },
                    slack,
                );
            }
            if flag & 2 == 0 {
                let slack = (control + tr.max_control_fu) / norm;
                consider(
                    RowId::Control {
                        block: b,
                        node: h,
                        upper: false,
                    },
                    slack,
                );
            }
        }
    }
    let mut dots: NodeDots = [[0.0; MAX_NODES]; MAX_BLOCKS];
    tr.node_dots(y, &mut dots);
    // Pairs within the transcription's count, each with its checks and their active flags.
    let pair_rows = tr.check_count.iter().zip(tr.pairs.iter());
    let check_rows = tr.checks.iter().zip(state.keep_out_active.iter());
    for (pair, ((&count, &(i, j)), (checks, active_flags))) in
        pair_rows.zip(check_rows).take(tr.pair_count).indexed()
    {
        let (mi, mj) = (tr.mass_of(usize::from(i)), tr.mass_of(usize::from(j)));
        let mass_factor = libm::sqrt(1.0 / (mi * mi) + 1.0 / (mj * mj));
        for (c, (check, &active)) in checks.iter().zip(active_flags.iter()).take(count).indexed() {
            if check.pruned || active {
                continue;
            }
            let (_, row_norm) = tr.check_row(check.source);
            let norm = row_norm * mass_factor;
            if norm <= 0.0 {
                continue;
            }
            let relative = tr.relative_with(pair, check.source, y, &dots);
            let mut along = 0.0;
            for (n, r) in check.normal.iter().zip(relative.iter()) {
                along += n * r;
            }
            let slack = (along - tr.keep_out_for(pair)) / norm;
            consider(
                RowId::KeepOut {
                    pair: pair as u8,
                    check: c as u8,
                },
                slack,
            );
        }
    }
    best
}

/// The row belongs to the current transcription.
fn exists(tr: &Transcription, id: RowId) -> bool {
    match id {
        RowId::Control { block, node, .. } => {
            usize::from(block) < tr.blocks() && usize::from(node) < tr.grid.nodes()
        }
        RowId::KeepOut { pair, check } => {
            usize::from(pair) < tr.pair_count
                && tr
                    .check_count
                    .get(usize::from(pair))
                    .is_some_and(|&count| usize::from(check) < count)
        }
    }
}

/// The most violated inactive row among `hint` (the previous QP's active set), if any is
/// violated by more than `tol`.
fn most_violated_hint(
    tr: &Transcription,
    state: &QpState,
    y: &Coefficients,
    (hint, hint_count): (&[RowId; MAX_ACTIVE], usize),
    tol: f64,
) -> Option<(RowId, f64)> {
    let free = tr.basis.free;
    let mut best: Option<(RowId, f64)> = None;
    for &id in hint.iter().take(hint_count) {
        if state.is_active(id) || !exists(tr, id) {
            continue;
        }
        if let RowId::KeepOut { pair, check } = id {
            let pruned = tr
                .checks
                .get(usize::from(pair))
                .and_then(|row| row.get(usize::from(check)))
                .is_none_or(|c| c.pruned);
            if pruned {
                continue;
            }
        }
        let view = tr.view(id);
        if view.norm <= 0.0 {
            continue;
        }
        let slack = (row_dot(&view, y, free) - view.rhs) / view.norm;
        if slack < -tol && best.is_none_or(|(_, b)| slack < b) {
            best = Some((id, slack));
        }
    }
    best
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
pub(crate) fn solve(
    tr: &Transcription,
    state: &mut QpState,
    y: &mut Coefficients,
    max_iter: u16,
    tol: f64,
    iterations: &mut u32,
    work: &mut Meter,
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
        let hinted = most_violated_hint(tr, state, y, (&hint, hint_count), tol);
        let picked = match hinted {
            Some(row) => Some(row),
            None => {
                if !work.spend(work_units::qp_scan(tr)) {
                    return QpOutcome::IterationLimit;
                }
                most_violated(tr, state, y)
            }
        };
        let Some((p, violation)) = picked else {
            return QpOutcome::Optimal;
        };
        if violation >= -tol {
            return QpOutcome::Optimal;
        }
        let vp = tr.view(p);
        let norm2_p = vp.norm * vp.norm;
        let mut multiplier_p = 0.0;
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
                Some(-slack / z2)
            } else {
                None
            };
            let mut partial: Option<(usize, f64)> = None;
            for (j, (&rj, &multiplier_j)) in r.iter().zip(state.multiplier.iter()).take(k).indexed()
            {
                if rj > 0.0 {
                    let ratio = multiplier_j / rj;
                    if partial.is_none_or(|(_, best)| ratio < best) {
                        partial = Some((j, ratio));
                    }
                }
            }
            let step = match (full_step, partial) {
                (None, None) => return QpOutcome::Infeasible,
                (Some(f), None) => f,
                (None, Some((_, t))) => t,
                (Some(f), Some((_, t))) => f.min(t),
            };
            if full_step.is_some() {
                for (b, values) in y.iter_mut().indexed().take(blocks) {
                    if let Some(dir) = state.direction.get(b) {
                        for (slot, d) in values.iter_mut().zip(dir.iter()).take(free) {
                            *slot += step * d;
                        }
                    }
                }
            }
            for (m, rj) in state.multiplier.iter_mut().zip(r.iter()).take(k) {
                *m -= step * rj;
            }
            multiplier_p += step;
            let full = matches!(full_step, Some(f) if f <= step);
            if full {
                if k >= MAX_ACTIVE {
                    // The working set needs more rows than the factor holds (up to 3 M (N - 3)
                    // can be independent, 504 at capacity: far beyond any RAM budget). Continue
                    // without a factor, from this dual-feasible point.
                    return super::qp_dual::solve(
                        tr,
                        state,
                        y,
                        (p, multiplier_p),
                        max_iter,
                        tol,
                        iterations,
                        work,
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
            let Some((drop, _)) = partial else {
                return QpOutcome::Infeasible;
            };
            if !state.drop_row(tr, drop) {
                return QpOutcome::FactorFailure;
            }
        }
    }
}
