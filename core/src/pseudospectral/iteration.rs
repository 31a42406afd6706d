//! The SQP iteration: one convex QP per linearisation, the next linearisation point from the
//! second-order (Newton) step on the QP's active set (`newton.rs`) or, where there is none,
//! Anderson extrapolation; globalised by a backtracking rule on the cost, and ended by the
//! fixed-point test.
//!
//! Globalisation: every QP answer meets every check whatever point it was linearised at (the
//! linearised keep-out is a tangent half-space inside the feasible set), so the iterates stay
//! feasible at the checks and the exact-penalty merit `J + nu sum max(0, -g_k)` equals the cost
//! `J` on them. The line search is over the linearisation point `y + alpha p`, `alpha` in
//! `{1, 0}`: an answer from an extrapolated point (`alpha = 1`) that raises the cost is
//! rejected and the QP is solved again linearised at the last accepted answer (`alpha = 0`, the
//! convex-concave step, which cannot raise the cost from a point feasible at its checks). One
//! backtrack per rejected step, each one QP of the `sqp_max_iter` budget.

use super::linearise::{follow_minima, linearise, refine_moving_checks};
use super::newton;
use super::qp::{self, QpOutcome};
use super::settings::Settings;
use super::solution::Solution;
use super::status::{SolveStatus, Stage};
use super::transcription::Coefficients;
use super::work_units;
use super::workspace::Workspace;

/// How the SQP loop ended.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum SqpEnd {
    Converged,
    /// `sqp_max_iter` subproblems (or the work budget) used before the fixed-point test held.
    /// `at_answer`: the returned iterate is the answer of the last QP solved (not a point the
    /// line search fell back to), so the QP state (active rows and multipliers) is that
    /// answer's and the certificate, which measures the conditions on the iterate itself with
    /// the constraint gradients there, may certify it like a converged one.
    MaxIterations {
        at_answer: bool,
    },
    Failed(SolveStatus),
}

/// A converged iterate lies within this fraction of d of its linearisation point (so the QP's
/// rows are the constraint gradients there to about this relative accuracy).
pub(super) const FIXED_POINT_TOL_REL: f64 = 1e-4;

/// Newton points the line search may reject per round before the round falls back to
/// Anderson extrapolation.
pub(super) const MAX_NEWTON_REJECTIONS: u8 = 6;

pub(super) fn half_norm2(y: &Coefficients, blocks: usize, free: usize) -> f64 {
    let mut sum = 0.0;
    for block in y.iter().take(blocks) {
        for v in block.iter().take(free) {
            sum += v * v;
        }
    }
    0.5 * sum
}

/// The convex-concave sequence of QPs from the current iterate, Anderson-accelerated.
/// On return `ws.iterate` holds the last QP solution (feasible at every check).
pub(super) fn sqp(ws: &mut Workspace, settings: &Settings, out: &mut Solution) -> SqpEnd {
    let blocks = ws.transcription.blocks();
    let free = ws.transcription.basis.free;
    let memory = usize::from(settings.acceleration_memory);
    let mut previous_cost = f64::INFINITY;
    ws.anderson.reset();
    ws.accepted = ws.iterate;
    let mut have_solution = false;
    let mut extrapolated = false;
    // Newton points rejected by the line search this round; past `MAX_NEWTON_REJECTIONS` the
    // round continues with Anderson extrapolation (the active set is not settled enough for the
    // second-order model: measured on the dense lattice, where the Newton point's QP kept
    // changing the active set and cost more than the plain step, every other subproblem).
    let mut rejections = 0u8;
    let mut newton_used = false;
    let mut restarted = false;
    let mut previous_decrease = f64::INFINITY;
    // The last QP solved was accepted: its answer is `ws.accepted` (see `SqpEnd::MaxIterations`).
    let mut at_answer = false;
    for _ in 0..settings.sqp_max_iter {
        if !ws.work.spend(work_units::sqp_iteration(&ws.transcription)) {
            break;
        }
        if settings.continuous_verification {
            follow_minima(ws, settings);
        }
        linearise(ws);
        at_answer = false;
        let outcome = qp::solve(
            &ws.transcription,
            &mut ws.qp,
            &mut ws.trial,
            settings.qp_max_iter,
            settings.qp_tol_feas,
            &mut out.info.qp_iterations,
            &mut ws.work,
        );
        out.info.sqp_iterations = out.info.sqp_iterations.saturating_add(1);
        let active = u16::try_from(ws.qp.peak).unwrap_or(u16::MAX);
        out.info.max_active = out.info.max_active.max(active);
        let failure = match outcome {
            QpOutcome::Optimal | QpOutcome::Approximate => None,
            QpOutcome::Infeasible => Some(SolveStatus::Infeasible),
            QpOutcome::IterationLimit => Some(SolveStatus::QpLimit),
            QpOutcome::FactorFailure => Some(SolveStatus::NumericalFailure(Stage::QpFactor)),
        };
        if let Some(status) = failure {
            if extrapolated {
                // The extrapolated point was a poor linearisation: fall back to plain iteration
                // from the last solution.
                ws.anderson.reset();
                extrapolated = false;
                ws.iterate = ws.accepted;
                continue;
            }
            ws.iterate = ws.accepted;
            return SqpEnd::Failed(status);
        }
        let cost = ws.transcription.base_cost + half_norm2(&ws.trial, blocks, free);
        if extrapolated
            && have_solution
            && cost > previous_cost + settings.sqp_tol_cost * (1.0 + cost)
        {
            // Backtrack (alpha = 0): the extrapolated point gave a costlier answer; reject it
            // and linearise at the last accepted answer.
            ws.anderson.reset();
            extrapolated = false;
            ws.iterate = ws.accepted;
            restarted = true;
            if newton_used {
                rejections = rejections.saturating_add(1);
            }
            continue;
        }
        let mut step = 0.0f64;
        // How far the QP's answer is from the point it was linearised at (the Anderson
        // extrapolation): a fixed point needs both equal, or the rows are not the constraint
        // gradients at the answer and it is not a KKT point (two extrapolated points can give the
        // same QP answer).
        let mut off_linearisation = 0.0f64;
        for b in 0..blocks {
            let mass = ws.transcription.mass_of(b / 3);
            if let (Some(new), Some(old), Some(at)) =
                (ws.trial.get(b), ws.accepted.get(b), ws.iterate.get(b))
            {
                for ((x, y), z) in new.iter().zip(old.iter()).zip(at.iter()).take(free) {
                    step = step.max(libm::fabs(x - y) / mass);
                    off_linearisation = off_linearisation.max(libm::fabs(x - z) / mass);
                }
            }
        }
        ws.accepted = ws.trial;
        at_answer = true;
        // Convergence: the cost decrease and the remaining gap it predicts are both small. The
        // convex-concave tail is linear; with rate rho = dJ_k / dJ_(k-1) the remaining gap is
        // about dJ_k rho / (1 - rho), which stays large while the iterate slides slowly along
        // the keep-out surface even though each step changes little.
        let decrease = previous_cost - cost;
        let tolerance = settings.sqp_tol_cost * (1.0 + cost);
        let rate = if previous_decrease > 0.0 && decrease >= 0.0 {
            (decrease / previous_decrease).min(0.999)
        } else {
            0.999
        };
        let gap = decrease.max(0.0) * rate / (1.0 - rate);
        // A rise within the tolerance counts as no change: near a fixed point the Newton
        // points' answers differ in the last digits both ways (measured: a three-cycle of
        // +-3e-11 in J with steps of 5e-6 LU that never met a sign-sensitive test).
        let small_change = libm::fabs(decrease) <= tolerance
            && (decrease <= 0.0 || gap <= tolerance)
            && !restarted;
        previous_decrease = decrease;
        // A QP that stopped short of its optimum is no fixed point, however small the step.
        let exact = outcome == QpOutcome::Optimal;
        if have_solution && exact && (small_change || step <= settings.sqp_tol_step_lu) {
            if off_linearisation <= FIXED_POINT_TOL_REL * ws.transcription.keep_out_lu {
                ws.iterate = ws.accepted;
                return SqpEnd::Converged;
            }
            // Converged in cost but linearised elsewhere: take plain steps from the answer.
            ws.anderson.reset();
            ws.iterate = ws.accepted;
            previous_cost = cost;
            restarted = true;
            continue;
        }
        // Safeguard: an extrapolation that raised the cost restarts the memory, so the next
        // step is a plain convex-concave step (which never raises the cost from a feasible
        // point).
        restarted = false;
        if have_solution && cost > previous_cost + settings.sqp_tol_cost * (1.0 + cost) {
            ws.anderson.reset();
            ws.iterate = ws.accepted;
            restarted = true;
        }
        have_solution = true;
        previous_cost = cost;
        newton_used = rejections < MAX_NEWTON_REJECTIONS && newton::applies(&ws.qp);
        if newton_used {
            // The Newton step is taken at the answer, with the gradients there: the moving
            // checks go to the answer's local separation minima first (the envelope theorem
            // makes that the semi-infinite constraint's gradient).
            ws.iterate = ws.accepted;
            ws.work
                .charge(work_units::newton_step(&ws.transcription, ws.qp.count));
            if settings.continuous_verification {
                refine_moving_checks(ws);
            }
            if !newton::step(
                &mut ws.transcription,
                &mut ws.qp,
                &ws.accepted,
                &mut ws.iterate,
                ws.anderson.scratch(),
                &mut ws.work,
            ) {
                ws.iterate = ws.accepted;
            }
            extrapolated = true;
        } else {
            ws.anderson
                .step(&mut ws.iterate, &ws.trial, memory, blocks, free);
            extrapolated = memory > 0;
        }
    }
    ws.iterate = ws.accepted;
    SqpEnd::MaxIterations { at_answer }
}
