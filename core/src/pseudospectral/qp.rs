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

use super::kernel::{self, Coefficients, MAX_BLOCKS};
use super::packed::{set, solve_lower, solve_lower_transposed};
use super::qp_scan;
use super::qp_state::{QpOutcome, QpState};
use super::transcription::{row_axpy, row_dot, rows_dot, Transcription};
use super::work_units;
use crate::capacity::{MAX_ACTIVE, MAX_FREE_PER_AXIS};
use crate::indexed::IndexedExt as _;
use crate::work::Meter;

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
                // With rows held elastic, no violated row found is followed by the two scans
                // of the held rows (`most_met_elastic`, then `elastic_slack_left` at the end):
                // charged with the scan, at their dearest (both run).
                let elastic = if state.elastic_count > 0 {
                    work_units::elastic_scans(tr, state.elastic_count)
                } else {
                    0
                };
                // Charged for the pairs it evaluates (`qp_scan::ScanBounds`).
                let checks = state.scan_bounds.checks_to_scan(tr, tol);
                if !work.spend(work_units::qp_scan(tr, checks).saturating_add(elastic)) {
                    return QpOutcome::IterationLimit;
                }
                qp_scan::most_violated(tr, state, y, tol)
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
        // A row the transcription does not hold (never: rows come from its own scans) cannot
        // enter: the factor fails.
        let Some(vp) = tr.view(p) else {
            return QpOutcome::FactorFailure;
        };
        let norm2_p = vp.norm * vp.norm;
        let cap_p = if penalty.is_finite() {
            penalty / vp.norm
        } else {
            f64::INFINITY
        };
        let mut multiplier_p = if sign > 0.0 { 0.0 } else { cap_p };
        loop {
            // The step may add a row: keep the final checks of a working set one row larger
            // than this one. Set, not raised: the checks run on the last QP's working set, so
            // rows dropped since give their reserve back to the loops.
            work.reserve(work_units::reserve(
                tr,
                state.count.saturating_add(1),
                state.final_checks,
            ));
            if steps >= max_iter || !work.spend(work_units::qp_step(tr, state.count)) {
                return QpOutcome::IterationLimit;
            }
            steps = steps.saturating_add(1);
            *iterations = iterations.saturating_add(1);
            let k = state.count;
            for (slot, &row) in g.iter_mut().zip(state.active.iter()).take(k) {
                let Some(vj) = tr.view(row) else {
                    return QpOutcome::FactorFailure;
                };
                *slot = rows_dot(&vj, &vp, free);
            }
            // r = G^{-1} g; keep l = L^{-1} g for appending p to the factor.
            let mut l = g;
            if !solve_lower(&state.store, k, &mut l) {
                return QpOutcome::FactorFailure;
            }
            r.copy_from_slice(&l);
            if !solve_lower_transposed(&state.store, k, &mut r) {
                return QpOutcome::FactorFailure;
            }
            // Primal direction z = a_p - A^T r: the part of a_p orthogonal to the active rows.
            state.direction = [[0.0; MAX_FREE_PER_AXIS]; MAX_BLOCKS];
            row_axpy(&vp, 1.0, &mut state.direction, free);
            for (rj, &row) in r.iter().zip(state.active.iter()).take(k) {
                let Some(vj) = tr.view(row) else {
                    return QpOutcome::FactorFailure;
                };
                row_axpy(&vj, -rj, &mut state.direction, free);
            }
            let z2 = kernel::dot(&state.direction, &state.direction, (blocks, free));
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
                    let Some(view) = tr.view(row) else {
                        return QpOutcome::FactorFailure;
                    };
                    let cap_j = penalty / view.norm;
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
                kernel::axpy(y, signed_step, &state.direction, (blocks, free));
                state.scan_bounds.moved_by(signed_step * libm::sqrt(z2));
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
            // The drop deletes the row from the Gram factor: charged as it runs (the next
            // step's `spend` is bounded by it). `r` is free until the next step computes it.
            work.charge(work_units::drop_row(k));
            if !state.drop_row(leaving, &mut r) {
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
