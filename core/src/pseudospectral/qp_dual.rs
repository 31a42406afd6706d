//! The QP's capacity-free fallback: Hildreth's dual coordinate ascent for
//! `min 1/2 |y|^2  s.t.  a_k^T y >= b_k`.
//!
//! Why: the dual active-set method keeps a dense Cholesky factor of the working set's Gram
//! matrix, which fits `MAX_ACTIVE` rows. The real worst case is the number of variables,
//! `3 M (N - 3)` (504 at capacity: a 1 MB factor), far beyond the firmware's RAM. When a QP
//! needs more, it continues here from the active-set method's dual-feasible point. The dual
//! `max b^T l - 1/2 |A^T l|^2, l >= 0` is maximised one multiplier at a time, exactly (a
//! closed-form step per row), with `y = A^T l` kept up to date; every step raises the dual, the
//! method converges to the QP's optimum, and it needs one number per candidate row, which fits
//! in the same buffer as the factor (`DUAL_LEN <= STORE_LEN`).
//!
//! Each control bound pair `-Umax <= u <= Umax` at a node is one range row with one signed
//! multiplier (positive: lower bound active, negative: upper). Every row is tightened by
//! `TIGHTEN` (distance in `y`), and the result is returned only when every tightened row is met
//! to within half of it, so an `Optimal` or `Approximate` `y` meets every original row with a
//! margin. Where the sweeps run out first the point is `Unconverged`: the iteration takes it as
//! an inexact step, never as an answer (the answer's own checks decide its status).
//!
//! Cost: one sweep touches every candidate row once, `O(rows x 6 (N - 3))` flops; at most
//! `min(max_sweeps, MAX_SWEEPS)` sweeps (`max_sweeps` is the QP's iteration setting).

use super::kernel::{Coefficients, MAX_BLOCKS};
use super::qp_scan::for_each_elastic;
use super::qp_state::{
    control_id, dual_index, for_each_stored, keep_out_id, signed, Mode, QpOutcome, QpState,
    DUAL_LEN,
};
use super::transcription::{block_dot, row_axpy, row_dot, RowId, Transcription};
use super::work_units;
use crate::capacity::MAX_FREE_PER_AXIS;
use crate::indexed::IndexedExt as _;

/// Tightening of every row, as a distance in `y` (row normalised).
const TIGHTEN: f64 = 1e-9;

/// Most sweeps of one fallback solve, below the QP's iteration setting. Where the fallback is
/// needed early it rarely converges (the first subproblem of an antipodal cube, where the guess
/// sends every spacecraft through one point: 400 sweeps leave the rows 1e-4 to 1e-3 short), and
/// its point serves as an inexact step that fewer sweeps give almost as well. Where an optimum
/// itself holds more rows than the factor, the fallback must converge at the end: the
/// near-bang-bang case of `tests/tests/pseudospectral_capacity.rs` (240 rows) does in 100
/// sweeps, not in 20. Chosen on the tuning set (`reconfig sweep --set tuning --count 2000
/// [--work-budget 1000000000]`; `Solved` / usable at the default budget, then lifted): 400
/// sweeps (the setting) 1823 / 1955, 1948 / 1982; 100: 1825 / 1966, 1948 / 1982; 40: 1826 /
/// 1969, 1945 / 1979; 20: 1828 / 1970, 1946 / 1981.
pub(crate) const MAX_SWEEPS: u16 = 100;

/// One exact coordinate step on a control range row; returns the change of `y` along the row
/// (in units of the row vector) and the row's normalised violation of the original bounds.
fn control_step(control: f64, umax: f64, norm2: f64, multiplier: f64) -> f64 {
    let bound = umax - TIGHTEN * libm::sqrt(norm2);
    if control < -bound {
        (-bound - control) / norm2
    } else if control > bound {
        (bound - control) / norm2
    } else if multiplier > 0.0 {
        ((-bound - control) / norm2).max(-multiplier)
    } else if multiplier < 0.0 {
        ((bound - control) / norm2).min(-multiplier)
    } else {
        0.0
    }
}

/// Continue a QP without a factor. `entering` is the row the active-set method was adding and
/// its multiplier so far (none for a start from zero). On return `state.mode` is `Dual` and
/// `state.store` holds every multiplier.
///
/// `penalty` (`rho`; `f64::INFINITY`: none) bounds every row's multiplier by `rho / |a_k|`
/// (a control range row's in size), which makes this the dual of the l1-elastic QP
/// `min 1/2 |y|^2 + rho sum_k s_k`, `a_k^T y / |a_k| + s_k >= b_k / |a_k|`, `s_k >= 0` (`s_k`
/// a distance in `y`): a row whose multiplier reaches the bound stops pulling and keeps its
/// violation as its slack. `QpOutcome::Elastic` says the converged answer keeps a positive
/// slack somewhere.
// The active-set method's arguments, carried on unchanged, plus its entering row.
#[allow(clippy::too_many_arguments)]
pub(crate) fn solve(
    tr: &Transcription,
    state: &mut QpState,
    y: &mut Coefficients,
    entering: Option<(RowId, f64)>,
    max_sweeps: u16,
    tol: f64,
    iterations: &mut u32,
    work: &mut crate::work::Meter,
    penalty: f64,
) -> QpOutcome {
    let free = tr.basis.free;
    // Load the active-set method's multipliers (it is dual feasible: `y = A^T l`).
    state.store.fill(0.0);
    let count = state.count;
    for k in 0..count {
        let (Some(&id), Some(&value)) = (state.active.get(k), state.multiplier.get(k)) else {
            continue;
        };
        if let Some(slot) = dual_index(id).and_then(|i| state.store.get_mut(i)) {
            *slot += signed(id, value);
        }
        state.mark(id, false);
    }
    if let Some((id, value)) = entering {
        if let Some(slot) = dual_index(id).and_then(|i| state.store.get_mut(i)) {
            *slot += signed(id, value);
        }
    }
    // Rows the elastic QP held at the bound keep their multiplier `penalty / |a_k|` here; from
    // here the bound is the table's.
    if state.elastic_count > 0 {
        let store = &mut state.store;
        for_each_elastic(tr, &state.control_flags, &state.keep_out_flags, |id| {
            // Held rows are the transcription's (they entered from its scans).
            let (Some(view), Some(slot)) =
                (tr.view(id), dual_index(id).and_then(|i| store.get_mut(i)))
            else {
                return;
            };
            let bound = penalty / view.norm;
            *slot += signed(id, bound);
        });
        state.clear_elastic();
    }
    state.count = 0;
    state.mode = Mode::Dual;
    // Rebuild y = A^T l from the table so the two agree to rounding.
    *y = [[0.0; MAX_FREE_PER_AXIS]; MAX_BLOCKS];
    for_each_stored(state, tr, |id, value| {
        if let Some(view) = tr.view(id) {
            row_axpy(&view, value, y, free);
        }
    });
    let mut sweeps: u16 = 0;
    loop {
        if !work.spend(work_units::dual_sweep(tr)) {
            return QpOutcome::IterationLimit;
        }
        let mut worst = 0.0f64;
        // The largest violation of a row at its bound (the elastic slack).
        let mut elastic = 0.0f64;
        let mut largest_move = 0.0f64;
        let control_blocks = y.iter_mut().zip(tr.base_control.iter());
        for (block, (values, base)) in control_blocks.take(tr.blocks()).indexed() {
            let node_rows = tr.basis.accel_norm.iter().zip(tr.basis.accel.iter());
            for (node, ((&norm, row), &base_control)) in
                node_rows.zip(base.iter()).take(tr.grid.nodes()).indexed()
            {
                // Every control row has its slot in the table (`dual_index`, `DUAL_LEN`).
                let Some((index, &multiplier)) = dual_index(control_id(block, node))
                    .and_then(|index| Some((index, state.store.get(index)?)))
                else {
                    continue;
                };
                if norm <= 0.0 {
                    continue;
                }
                let control = base_control + block_dot(row, values, free);
                let violation = (libm::fabs(control) - tr.max_control_fu) / norm + TIGHTEN;
                let mut delta = control_step(control, tr.max_control_fu, norm * norm, multiplier);
                let cap = penalty / norm;
                if multiplier + delta > cap {
                    delta = cap - multiplier;
                } else if multiplier + delta < -cap {
                    delta = -cap - multiplier;
                }
                if libm::fabs(multiplier + delta) >= cap {
                    elastic = elastic.max(violation);
                } else {
                    worst = worst.max(violation);
                }
                if delta != 0.0 {
                    if let Some(slot) = state.store.get_mut(index) {
                        *slot = multiplier + delta;
                    }
                    for (slot, g) in values.iter_mut().zip(row.iter()).take(free) {
                        *slot += delta * g;
                    }
                    largest_move = largest_move.max(libm::fabs(delta) * norm);
                }
            }
        }
        let pair_checks = tr.checks.iter().zip(tr.check_count.iter());
        for (pair, (checks, &count)) in pair_checks.take(tr.pair_count).indexed() {
            for (check, c) in checks.iter().take(count).indexed() {
                let id = keep_out_id(pair, check);
                // Every check has its slot in the table (`dual_index`, `DUAL_LEN`) and its row.
                let Some((index, &multiplier)) =
                    dual_index(id).and_then(|index| Some((index, state.store.get(index)?)))
                else {
                    continue;
                };
                if c.pruned {
                    continue;
                }
                let Some(view) = tr.view(id) else {
                    continue;
                };
                if view.norm <= 0.0 {
                    continue;
                }
                let norm2 = view.norm * view.norm;
                let slack = row_dot(&view, y, free) - view.rhs - TIGHTEN * view.norm;
                let cap = penalty / view.norm;
                let delta = (-slack / norm2).max(-multiplier).min(cap - multiplier);
                if multiplier + delta >= cap {
                    elastic = elastic.max(-slack / view.norm);
                } else {
                    worst = worst.max(-slack / view.norm);
                }
                if delta != 0.0 {
                    if let Some(slot) = state.store.get_mut(index) {
                        *slot = multiplier + delta;
                    }
                    row_axpy(&view, delta, y, free);
                    largest_move = largest_move.max(libm::fabs(delta) * view.norm);
                }
            }
        }
        sweeps = sweeps.saturating_add(1);
        *iterations = iterations.saturating_add(1);
        // Converged: every tightened row met within half the tightening (so every original row
        // holds with margin), and the last sweep moved y by no more than the QP's tolerance.
        // An elastic row (at the bound) counts among the met rows: its violation is its slack.
        let feasible = worst <= 0.5 * TIGHTEN;
        let slack_left = elastic > TIGHTEN;
        if feasible && largest_move <= tol.max(1e-3 * TIGHTEN) {
            state.peak = state.peak.max(positive_multipliers(state));
            return if slack_left {
                QpOutcome::Elastic
            } else {
                QpOutcome::Optimal
            };
        }
        if sweeps >= max_sweeps.min(MAX_SWEEPS) {
            state.peak = state.peak.max(positive_multipliers(state));
            return if !feasible {
                QpOutcome::Unconverged
            } else if slack_left {
                QpOutcome::Elastic
            } else {
                QpOutcome::Approximate
            };
        }
    }
}

fn positive_multipliers(state: &QpState) -> usize {
    state
        .store
        .iter()
        .take(DUAL_LEN)
        .filter(|v| **v != 0.0)
        // Counted with `fold`, not `count()`, whose overflow check is a panic path.
        .fold(0_usize, |n, _| n.wrapping_add(1))
}
