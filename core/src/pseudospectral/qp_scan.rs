//! The QP's row scans: which constraint enters the working set next (`qp.rs`).
//!
//! A row is a candidate when it is neither in the active set nor elastic (its multiplier held
//! at the l1 penalty's bound by the elastic QP); an elastic row is a candidate to leave that
//! bound when the answer meets it with room to spare (`most_met_elastic`).

use super::kernel::{Coefficients, MAX_BLOCKS};
use super::qp_state::{
    QpState, LOWER_ACTIVE, LOWER_ELASTIC, ROW_ELASTIC, UPPER_ACTIVE, UPPER_ELASTIC,
};
use super::transcription::{block_dot, row_dot, NodeDots, RowId, Transcription};
use crate::capacity::{MAX_ACTIVE, MAX_CHECKS_PER_PAIR, MAX_NODES, MAX_PAIRS};
use crate::indexed::IndexedExt as _;

/// Lower bounds on the normalised slacks of each pair's candidate keep-out rows within one QP
/// (its rows fixed), so that the scan can skip a pair that cannot hold a violated row.
///
/// Why it holds: a row's normalised slack `(a . y - b) / |a|` changes by at most `|dy|` when
/// `y` moves by `dy` (Cauchy-Schwarz; the scan's norm is the row's own Euclidean norm,
/// `the_scan_norm_is_the_rows_norm`). So after a pair's rows were all evaluated with least
/// slack `s` and `y` has moved a distance `D` since (the sum of the steps' lengths), every one
/// of them still has slack at least `s - D`. A pair whose bound is above `tol` holds no row
/// violated by more than `tol`, and only such rows can enter: skipping it changes no choice of
/// the scan (the most violated row is among the pairs evaluated whenever any row is violated),
/// so the QP's answers are the same bits, for less work. A row that becomes a candidate
/// again (dropped from the active set, released from an elastic bound) forgets its pair's
/// bound (`QpState::set_flag`); the bounds start unknown at every QP.
#[derive(Clone, Copy, Debug)]
pub(crate) struct ScanBounds {
    /// The distance `y` has moved in this QP so far (sum of the steps' lengths).
    moved: f64,
    /// Per pair: the least normalised slack of its candidate rows when last evaluated, plus
    /// `moved` at that time; read only where `known`.
    pairs: [f64; MAX_PAIRS],
    /// Per pair: whether `pairs` holds its bound. (A flag, not a `-inf` bound: all zeros is
    /// "nothing known", so the workspace holding this stays zero-initialised, in `.bss`.)
    known: [bool; MAX_PAIRS],
}

impl ScanBounds {
    /// Nothing known: every pair is evaluated.
    pub(crate) const fn unknown() -> Self {
        Self {
            moved: 0.0,
            pairs: [0.0; MAX_PAIRS],
            known: [false; MAX_PAIRS],
        }
    }

    /// `y` moved by a step of this length. A length that is not finite forgets every bound.
    pub(super) fn moved_by(&mut self, length: f64) {
        let moved = self.moved + libm::fabs(length);
        if moved.is_finite() {
            self.moved = moved;
        } else {
            *self = Self::unknown();
        }
    }

    /// Forget the bound of the row's pair (a control row has none).
    pub(super) fn forget_row(&mut self, id: RowId) {
        if let RowId::KeepOut { pair, .. } = id {
            if let Some(known) = self.known.get_mut(usize::from(pair)) {
                *known = false;
            }
        }
    }

    /// Whether pair `pair`'s candidate rows are all met with more than `tol` to spare.
    fn skips(&self, pair: usize, tol: f64) -> bool {
        self.pairs
            .get(pair)
            .zip(self.known.get(pair))
            .is_some_and(|(&bound, &known)| rules_out(bound, known, self.moved, tol))
    }

    /// Keep-out checks the next scan evaluates (of the pairs it does not skip): what it is
    /// charged for (`work_units::qp_scan`).
    pub(super) fn checks_to_scan(&self, tr: &Transcription, tol: f64) -> usize {
        tr.check_count
            .iter()
            .take(tr.pair_count)
            .indexed()
            .filter(|&(pair, _)| !self.skips(pair, tol))
            .fold(0usize, |total, (_, &count)| total.saturating_add(count))
    }
}

/// A pair's bound shows every candidate row met with more than `tol` to spare.
fn rules_out(bound: f64, known: bool, moved: f64, tol: f64) -> bool {
    known && bound - moved > tol
}

/// The most violated constraint at `y` neither active nor elastic, as (row, slack / |row|),
/// skipping the pairs `state.scan_bounds` shows met with more than `tol` to spare (and
/// recording the bounds of the pairs it evaluates). The row it returns is the same as with no
/// pair skipped whenever one is violated by more than `tol` (`ScanBounds`).
pub(super) fn most_violated(
    tr: &Transcription,
    state: &mut QpState,
    y: &Coefficients,
    tol: f64,
) -> Option<(RowId, f64)> {
    let free = tr.basis.free;
    let mut best: Option<(RowId, f64)> = None;
    let mut consider = |id: RowId, value: f64| match best {
        Some((_, v)) if v <= value => {}
        _ => best = Some((id, value)),
    };
    // Blocks and nodes within the transcription's (validated) counts, walked with their flags.
    let nodes = tr.grid.nodes();
    let control_blocks = state
        .control_flags
        .iter()
        .zip(y.iter())
        .zip(tr.base_control.iter());
    for (block, ((flags, values), base)) in control_blocks.take(tr.blocks()).indexed() {
        let node_rows = tr.basis.accel_norm.iter().zip(tr.basis.accel.iter());
        let nodal = node_rows.zip(base.iter()).zip(flags.iter());
        for (node, (((&norm, row), &base_control), &flag)) in nodal.take(nodes).indexed() {
            if norm <= 0.0 {
                continue;
            }
            let control = base_control + block_dot(row, values, free);
            let (b, h) = (block as u8, node as u8);
            if flag & (UPPER_ACTIVE | UPPER_ELASTIC) == 0 {
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
            if flag & (LOWER_ACTIVE | LOWER_ELASTIC) == 0 {
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
    // Pairs within the transcription's count, each with its checks and their active flags (a
    // check without a row or a relative position is no candidate: never, both are built with
    // the check).
    let moved = state.scan_bounds.moved;
    let bounds = state
        .scan_bounds
        .pairs
        .iter_mut()
        .zip(state.scan_bounds.known.iter_mut());
    let check_rows = tr
        .checks
        .iter()
        .zip(state.keep_out_flags.iter())
        .zip(bounds);
    for (pair, ((checks, active_flags), (bound, known))) in check_rows.take(tr.pair_count).indexed()
    {
        if rules_out(*bound, *known, moved, tol) {
            continue;
        }
        // Unknown until every candidate row of the pair is evaluated below.
        *known = false;
        let (Some(geometry), Some(&count)) = (tr.pair(pair), tr.check_count.get(pair)) else {
            continue;
        };
        let mut least = f64::INFINITY;
        let mut complete = true;
        let (mi, mj) = geometry.masses;
        let mass_factor = libm::sqrt(1.0 / (mi * mi) + 1.0 / (mj * mj));
        for (c, (check, &flags)) in checks.iter().zip(active_flags.iter()).take(count).indexed() {
            if check.pruned || flags != 0 {
                continue;
            }
            let Some((_, row_norm)) = tr.check_row(check.source) else {
                complete = false;
                continue;
            };
            let norm = row_norm * mass_factor;
            if norm <= 0.0 {
                complete = false;
                continue;
            }
            let Some(relative) = tr.relative_with(&geometry, check.source, y, &dots) else {
                complete = false;
                continue;
            };
            let mut along = 0.0;
            for (n, r) in check.normal.iter().zip(relative.iter()) {
                along += n * r;
            }
            let slack = (along - geometry.keep_out) / norm;
            if !slack.is_finite() {
                complete = false;
            } else if slack < least {
                least = slack;
            }
            consider(
                RowId::KeepOut {
                    pair: pair as u8,
                    check: c as u8,
                },
                slack,
            );
        }
        if complete {
            *bound = least + moved;
            *known = true;
        }
    }
    best
}

/// The row belongs to the current transcription.
pub(super) fn exists(tr: &Transcription, id: RowId) -> bool {
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

/// The most violated row neither active nor elastic among `hint` (the previous QP's active
/// set), if any is violated by more than `tol`.
pub(super) fn most_violated_hint(
    tr: &Transcription,
    state: &QpState,
    y: &Coefficients,
    (hint, hint_count): (&[RowId; MAX_ACTIVE], usize),
    tol: f64,
) -> Option<(RowId, f64)> {
    let free = tr.basis.free;
    let mut best: Option<(RowId, f64)> = None;
    for &id in hint.iter().take(hint_count) {
        if state.is_active(id) || state.is_elastic(id) || !exists(tr, id) {
            continue;
        }
        if let RowId::KeepOut { pair, check } = id {
            let pruned = tr
                .check(usize::from(pair), usize::from(check))
                .is_none_or(|c| c.pruned);
            if pruned {
                continue;
            }
        }
        let Some(view) = tr.view(id) else {
            continue;
        };
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

/// The elastic row the answer `y` meets by the most (more than `tol`, normalised), if any: its
/// multiplier, held at the penalty's bound, should fall (a row with slack has none).
pub(super) fn most_met_elastic(
    tr: &Transcription,
    state: &QpState,
    y: &Coefficients,
    tol: f64,
) -> Option<(RowId, f64)> {
    let free = tr.basis.free;
    let mut best: Option<(RowId, f64)> = None;
    for_each_elastic(tr, &state.control_flags, &state.keep_out_flags, |id| {
        let Some(view) = tr.view(id) else {
            return;
        };
        if view.norm > 0.0 {
            let slack = (row_dot(&view, y, free) - view.rhs) / view.norm;
            if slack > tol && best.is_none_or(|(_, b)| slack > b) {
                best = Some((id, slack));
            }
        }
    });
    best
}

/// Whether an elastic row keeps a violation beyond `tol` (normalised) at `y`: the elastic QP's
/// answer has a positive slack.
pub(super) fn elastic_slack_left(
    tr: &Transcription,
    state: &QpState,
    y: &Coefficients,
    tol: f64,
) -> bool {
    let free = tr.basis.free;
    let mut left = false;
    for_each_elastic(tr, &state.control_flags, &state.keep_out_flags, |id| {
        let left_here = tr.view(id).is_some_and(|view| {
            view.norm > 0.0 && (view.rhs - row_dot(&view, y, free)) / view.norm > tol
        });
        if left_here {
            left = true;
        }
    });
    left
}

/// Every row held elastic, control rows first, from the QP state's flag tables (passed apart
/// so the caller may write the state's other fields meanwhile).
pub(super) fn for_each_elastic(
    tr: &Transcription,
    control_flags: &[[u8; MAX_NODES]; MAX_BLOCKS],
    keep_out_flags: &[[u8; MAX_CHECKS_PER_PAIR]; MAX_PAIRS],
    mut f: impl FnMut(RowId),
) {
    let nodes = tr.grid.nodes();
    for (block, flags) in control_flags.iter().take(tr.blocks()).indexed() {
        for (node, &flag) in flags.iter().take(nodes).indexed() {
            let (block, node) = (block as u8, node as u8);
            if flag & UPPER_ELASTIC != 0 {
                f(RowId::Control {
                    block,
                    node,
                    upper: true,
                });
            }
            if flag & LOWER_ELASTIC != 0 {
                f(RowId::Control {
                    block,
                    node,
                    upper: false,
                });
            }
        }
    }
    for (pair, (flags, &count)) in keep_out_flags
        .iter()
        .zip(tr.check_count.iter())
        .take(tr.pair_count)
        .indexed()
    {
        for (check, &flag) in flags.iter().take(count.min(MAX_CHECKS_PER_PAIR)).indexed() {
            if flag & ROW_ELASTIC != 0 {
                f(RowId::KeepOut {
                    pair: pair as u8,
                    check: check as u8,
                });
            }
        }
    }
}

#[cfg(test)]
#[path = "qp_scan_tests.rs"]
mod tests;
