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

use super::anytime;
use super::certificate;
use super::kernel::{dot, u8_of, Coefficients, Live};
use super::linearise::{self, follow_minima, refine_moving_checks};
use super::newton;
use super::newton_cycle::RecentCosts;
use super::qp;
use super::qp_state::QpOutcome;
use super::settings::Settings;
use super::solution::Solution;
use super::solution::{Unmet, UnmetConstraint};
use super::status::{SolveStatus, Stage};
use super::swerve::turn_fallback;
use super::transcription::{row_dot, RowId, Transcription};
use super::work_units;
use super::workspace::Workspace;
use crate::indexed::IndexedExt as _;

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

impl SqpEnd {
    /// The QP state (active rows, multipliers) is the returned iterate's own: at a fixed point,
    /// or at the iteration limit on an accepted QP answer. Only then may the certificate, which
    /// measures the conditions with that state, certify the iterate or direct an escape.
    pub(super) fn at_own_qp_state(self) -> bool {
        matches!(
            self,
            Self::Converged | Self::MaxIterations { at_answer: true }
        )
    }
}

/// A converged iterate lies within this fraction of d of its linearisation point (so the QP's
/// rows are the constraint gradients there to about this relative accuracy).
pub(super) const FIXED_POINT_TOL_REL: f64 = 1e-4;

/// Newton points the line search may reject per round before the round falls back to
/// Anderson extrapolation.
pub(super) const MAX_NEWTON_REJECTIONS: u8 = 6;

/// Plain steps that may raise the cost in one run before the run ends at its last answer (as
/// at `sqp_max_iter`, certified there if it passes). A plain convex-concave step from a
/// feasible answer never raises the cost unless the moving checks moved under it: the answer
/// dips between its checks, the checks go to the dips, the next answer dips beside them, and
/// the iteration settles into a cycle of two answers ~1e-6 of J apart that no stopping test
/// meets (issue 28, measured on the tuning set: runs spent their 60 subproblems alternating
/// between two active sets). The verification round that follows checks the dips with fixed
/// points, which ends the cycle. Chosen on the tuning set (`reconfig sweep --set tuning`,
/// `Solved` at the default budget / lifted): no limit 1808 / 1916, 3: 1792 / 1862, 6: 1816 /
/// 1924, 9: 1812 / 1919, 12: 1812 / 1926.
pub(super) const MAX_COST_RISES: u8 = 6;

/// Plain steps that raised the cost in a run after which its moving checks freeze small
/// returns too (`linearise::FREEZE_JUMP_TAU_CYCLING`). One rise happens on the way (the
/// 8-spacecraft crossing has one early; freezing there cost it 3 subproblems, 16 -> 19); two
/// mark the cycle. Tuning set, `Solved` default / lifted: after one rise 1829 / 1924, after two
/// 1822 / 1925, after three 1817 / 1929.
const CYCLING_RISES: u8 = 2;

/// `|y|^2 / 2` over the live part: the cost above the base cubics' (the QP's objective).
fn half_norm2(y: &Coefficients, live: Live) -> f64 {
    0.5 * dot(y, y, live)
}

/// The SQP's steps, in the order one subproblem walks them; each step names the next
/// (`sqp` walks them).
#[derive(Clone, Copy, Debug)]
enum Step {
    /// Take one of the `sqp_max_iter` subproblems (and its work), move the moving checks to the
    /// iterate's separation minima, and linearise every check at the iterate.
    Linearise,
    /// Solve the QP linearised at the iterate: in its l1-elastic form where it is infeasible
    /// linearised at the last answer, and after a turn of the named pairs' swerve where that
    /// keeps a slack.
    SolveQp,
    /// Accept the QP's answer, or reject it where it raises the cost from an extrapolated
    /// point (`exact`: the QP reached its optimum).
    LineSearch { exact: bool },
    /// The fixed-point test on the accepted answer.
    CheckConvergence(Answer),
    /// The next linearisation point from the accepted answer of cost `cost`: the second-order
    /// (Newton) step, or Anderson extrapolation.
    Extrapolate { cost: f64 },
    /// The iteration ends.
    Done(SqpEnd),
}

/// An accepted QP answer, as the fixed-point test needs it.
#[derive(Clone, Copy, Debug)]
struct Answer {
    cost: f64,
    /// The QP reached its optimum: an answer that stopped short is no fixed point.
    exact: bool,
    /// The largest move of a coefficient from the last answer (LU: over the mass).
    step: f64,
    /// How far the answer is from the point it was linearised at (LU): a fixed point needs both
    /// equal, or the rows are not the constraint gradients at the answer and it is not a KKT
    /// point (two extrapolated points can give the same QP answer).
    off_linearisation: f64,
}

/// What the SQP's steps remember from one subproblem to the next.
struct Sqp {
    /// Subproblems linearised so far (at most `sqp_max_iter`).
    subproblems: u16,
    /// The cost of the last accepted answer.
    previous_cost: f64,
    /// Its decrease from the one before (the convergence test's rate).
    previous_decrease: f64,
    /// An answer has been accepted.
    have_solution: bool,
    /// The iterate is an extrapolated point (Newton or Anderson), not the last answer.
    extrapolated: bool,
    /// The last extrapolated point was a Newton point.
    newton_used: bool,
    /// Newton points rejected by the line search this round; past `MAX_NEWTON_REJECTIONS` the
    /// round continues with Anderson extrapolation (the active set is not settled enough for the
    /// second-order model: measured on the dense lattice, where the Newton point's QP kept
    /// changing the active set and cost more than the plain step, every other subproblem).
    rejections: u8,
    /// The last step restarted the iteration from the last answer (a backtrack, a cost that
    /// rose, a converged cost linearised elsewhere): a small change right after it is no
    /// convergence.
    restarted: bool,
    /// The last QP solved was accepted: its answer is `ws.iterates.accepted` (see
    /// `SqpEnd::MaxIterations`).
    at_answer: bool,
    /// Turns of the unseparated pairs' fallback directions tried (elastic mode).
    turns: u8,
    /// Plain steps that raised the cost this run (the moving checks moved under the answer).
    rises: u8,
    /// The last accepted costs: a Newton answer that repeats one is a loop (`newton_cycle`).
    recent: RecentCosts,
}

/// The convex-concave sequence of QPs from the current iterate, accelerated by the Newton step
/// or Anderson extrapolation. On return `ws.iterates.iterate` holds the last QP solution
/// (feasible at every check).
pub(super) fn sqp(ws: &mut Workspace, settings: &Settings, out: &mut Solution) -> SqpEnd {
    ws.iterates.anderson.reset();
    ws.iterates.accepted = ws.iterates.iterate;
    ws.verification.searched_clean = 0;
    let mut sqp = Sqp {
        subproblems: 0,
        previous_cost: f64::INFINITY,
        previous_decrease: f64::INFINITY,
        have_solution: false,
        extrapolated: false,
        newton_used: false,
        rejections: 0,
        restarted: false,
        at_answer: false,
        turns: 0,
        rises: 0,
        recent: RecentCosts::new(),
    };
    // Bounded by `sqp_max_iter`: every step leads on to `Linearise` or `Done`, never back to an
    // earlier step of the same subproblem, and each `Linearise` takes one subproblem.
    let mut step = Step::Linearise;
    loop {
        step = match step {
            Step::Linearise => sqp.linearise(ws, settings),
            Step::SolveQp => sqp.solve_qp(ws, settings, out),
            Step::LineSearch { exact } => sqp.line_search(ws, settings, exact),
            Step::CheckConvergence(answer) => sqp.check_convergence(ws, settings, answer),
            Step::Extrapolate { cost } => sqp.extrapolate(ws, settings, cost),
            Step::Done(end) => return end,
        };
    }
}

impl Sqp {
    /// `Step::Linearise`.
    fn linearise(&mut self, ws: &mut Workspace, settings: &Settings) -> Step {
        if self.subproblems >= settings.sqp_max_iter
            || (self.at_answer && self.rises >= MAX_COST_RISES)
            || !ws
                .work
                .spend(work_units::sqp_iteration(&ws.setup.transcription))
        {
            ws.iterates.iterate = ws.iterates.accepted;
            return Step::Done(SqpEnd::MaxIterations {
                at_answer: self.at_answer,
            });
        }
        self.subproblems = self.subproblems.saturating_add(1);
        if settings.continuous_verification {
            let _ = follow_minima(ws, settings, true, self.rises >= CYCLING_RISES);
        }
        linearise::linearise(ws);
        self.at_answer = false;
        Step::SolveQp
    }

    /// `Step::SolveQp`.
    fn solve_qp(&mut self, ws: &mut Workspace, settings: &Settings, out: &mut Solution) -> Step {
        // An infeasible subproblem linearised at the last answer (not at an extrapolated point,
        // which the plain step below replaces) is solved again in its l1-elastic form: an
        // answer there is taken like any other; a positive slack names the constraints and
        // ends the solve `Infeasible` (elastic mode, issue 9 item 3). One call site for both
        // (the QP's arrays sit once in this frame: 5 KB of M7 stack with two).
        let mut penalty = f64::INFINITY;
        let outcome = loop {
            let outcome = qp::solve(
                &ws.setup.transcription,
                &mut ws.iterates.qp,
                &mut ws.iterates.trial,
                settings.qp_max_iter,
                settings.qp_tol_feas,
                &mut out.info.qp_iterations,
                &mut ws.work,
                penalty,
            );
            if outcome == QpOutcome::Infeasible && !self.extrapolated && penalty.is_infinite() {
                penalty = elastic_penalty(ws);
                out.info.elastic_subproblems = out.info.elastic_subproblems.saturating_add(1);
                continue;
            }
            break outcome;
        };
        if outcome == QpOutcome::Elastic {
            // Charged as it runs, at its dearest path (every row named); the next step's
            // `spend` is bounded by it.
            ws.work
                .charge(work_units::name_unmet(&ws.setup.transcription));
            name_unmet(
                &ws.setup.transcription,
                &ws.iterates.trial,
                settings.qp_tol_feas,
                &mut out.unmet,
            );
        }
        out.info.sqp_iterations = out.info.sqp_iterations.saturating_add(1);
        let active = u16::try_from(ws.iterates.qp.peak).unwrap_or(u16::MAX);
        out.info.max_active = out.info.max_active.max(active);
        // A pair that cannot be separated may only be swerving the wrong way: turn the
        // fallback direction of every named pair by 45 degrees and linearise again, at most
        // `MAX_SWERVE_TURNS` times per run, before the answer is `Infeasible`.
        if outcome == QpOutcome::Elastic && self.turns < MAX_SWERVE_TURNS {
            // Charged as it runs, at its dearest path (every pair turned); the next step's
            // `spend` is bounded by it.
            ws.work
                .charge(work_units::turn_swerves(&ws.setup.transcription));
            if turn_unmet_pairs(ws, &out.unmet, self.turns.saturating_add(1)) {
                self.turns = self.turns.saturating_add(1);
                out.unmet = Unmet::new();
                return Step::Linearise;
            }
        }
        let failure = match outcome {
            // An unconverged fallback's point is taken as an inexact step: stopping there
            // (`QpLimit`) ended 30 of the tuning set's solves with no plan at the default budget
            // (46 lifted), all in their first subproblem; stepping on took the set's lifted
            // `Solved` from 1925 to 1948 (docs/planner-a.md, the fallback step).
            QpOutcome::Optimal | QpOutcome::Approximate | QpOutcome::Unconverged => None,
            QpOutcome::Infeasible | QpOutcome::Elastic => Some(SolveStatus::Infeasible),
            QpOutcome::IterationLimit => Some(SolveStatus::QpLimit),
            QpOutcome::FactorFailure => Some(SolveStatus::NumericalFailure(Stage::QpFactor)),
        };
        if let Some(status) = failure {
            if self.extrapolated {
                // The extrapolated point was a poor linearisation: fall back to plain iteration
                // from the last solution.
                ws.iterates.anderson.reset();
                self.extrapolated = false;
                ws.iterates.iterate = ws.iterates.accepted;
                return Step::Linearise;
            }
            ws.iterates.iterate = ws.iterates.accepted;
            return Step::Done(SqpEnd::Failed(status));
        }
        Step::LineSearch {
            exact: outcome == QpOutcome::Optimal,
        }
    }

    /// `Step::LineSearch`.
    fn line_search(&mut self, ws: &mut Workspace, settings: &Settings, exact: bool) -> Step {
        let tr = &ws.setup.transcription;
        let (blocks, free) = (tr.blocks(), tr.basis.free);
        let cost = tr.base_cost + half_norm2(&ws.iterates.trial, (blocks, free));
        if self.extrapolated
            && self.have_solution
            && cost > self.previous_cost + settings.sqp_tol_cost * (1.0 + cost)
        {
            // Backtrack (alpha = 0): the extrapolated point gave a costlier answer; reject it
            // and linearise at the last accepted answer.
            ws.iterates.anderson.reset();
            self.extrapolated = false;
            ws.iterates.iterate = ws.iterates.accepted;
            self.restarted = true;
            if self.newton_used {
                self.rejections = self.rejections.saturating_add(1);
            }
            return Step::Linearise;
        }
        let mut step = 0.0f64;
        let mut off_linearisation = 0.0f64;
        // Each spacecraft's three blocks with its mass.
        let iterates = &ws.iterates;
        let spacecraft_blocks = iterates.trial.chunks_exact(3).zip(
            iterates
                .accepted
                .chunks_exact(3)
                .zip(iterates.iterate.chunks_exact(3)),
        );
        for ((new3, (old3, at3)), &mass) in
            spacecraft_blocks.zip(tr.mass.iter()).take(tr.spacecraft)
        {
            for (new, (old, at)) in new3.iter().zip(old3.iter().zip(at3.iter())) {
                for ((x, y), z) in new.iter().zip(old.iter()).zip(at.iter()).take(free) {
                    step = step.max(libm::fabs(x - y) / mass);
                    off_linearisation = off_linearisation.max(libm::fabs(x - z) / mass);
                }
            }
        }
        ws.iterates.accepted = ws.iterates.trial;
        self.at_answer = true;
        // A Newton answer that repeats an earlier cost closes a loop of Newton points: plain
        // steps from here (as after `MAX_NEWTON_REJECTIONS` rejections, without paying them).
        if self.recent.record(cost) && self.newton_used {
            self.rejections = MAX_NEWTON_REJECTIONS;
        }
        anytime::offer(ws, settings, cost);
        Step::CheckConvergence(Answer {
            cost,
            exact,
            step,
            off_linearisation,
        })
    }

    /// `Step::CheckConvergence`.
    fn check_convergence(
        &mut self,
        ws: &mut Workspace,
        settings: &Settings,
        answer: Answer,
    ) -> Step {
        let Answer {
            cost,
            exact,
            step,
            off_linearisation,
        } = answer;
        // Convergence: the cost decrease and the remaining gap it predicts are both small. The
        // convex-concave tail is linear; with rate rho = dJ_k / dJ_(k-1) the remaining gap is
        // about dJ_k rho / (1 - rho), which stays large while the iterate slides slowly along
        // the keep-out surface even though each step changes little.
        let decrease = self.previous_cost - cost;
        let tolerance = settings.sqp_tol_cost * (1.0 + cost);
        let rate = if self.previous_decrease > 0.0 && decrease >= 0.0 {
            (decrease / self.previous_decrease).min(0.999)
        } else {
            0.999
        };
        let gap = decrease.max(0.0) * rate / (1.0 - rate);
        // A rise within the tolerance counts as no change: near a fixed point the Newton
        // points' answers differ in the last digits both ways (measured: a three-cycle of
        // +-3e-11 in J with steps of 5e-6 LU that never met a sign-sensitive test).
        let small_change = libm::fabs(decrease) <= tolerance
            && (decrease <= 0.0 || gap <= tolerance)
            && !self.restarted;
        self.previous_decrease = decrease;
        if !(self.have_solution && exact && (small_change || step <= settings.sqp_tol_step_lu)) {
            return Step::Extrapolate { cost };
        }
        if off_linearisation <= FIXED_POINT_TOL_REL * ws.setup.transcription.keep_out_lu {
            ws.iterates.iterate = ws.iterates.accepted;
            // The moving checks sit at the linearisation point's minima, which the answer has
            // moved off (by up to the tolerance above). Search the answer's own minima without
            // moving the checks (a returned answer's certificate must see the rows its QP had):
            // a dip beyond the verification's tolerance means the answer is not yet the
            // continuous problem's fixed point, so iterate on; the next subproblem's
            // `follow_minima` moves the checks there.
            if !settings.continuous_verification {
                return Step::Done(SqpEnd::Converged);
            }
            ws.work
                .charge(work_units::convergence_search(&ws.setup.transcription));
            let (deepest, clean) = follow_minima(ws, settings, false, false);
            if deepest <= 0.0 {
                ws.verification.searched_clean = clean;
                return Step::Done(SqpEnd::Converged);
            }
            ws.iterates.anderson.reset();
            self.previous_cost = cost;
            self.restarted = true;
            return Step::Linearise;
        }
        // Converged in cost but linearised elsewhere: take plain steps from the answer.
        ws.iterates.anderson.reset();
        ws.iterates.iterate = ws.iterates.accepted;
        self.previous_cost = cost;
        self.restarted = true;
        Step::Linearise
    }

    /// `Step::Extrapolate`.
    fn extrapolate(&mut self, ws: &mut Workspace, settings: &Settings, cost: f64) -> Step {
        // Safeguard: an extrapolation that raised the cost restarts the memory, so the next
        // step is a plain convex-concave step (which never raises the cost from a feasible
        // point).
        self.restarted = false;
        if self.have_solution && cost > self.previous_cost + settings.sqp_tol_cost * (1.0 + cost) {
            ws.iterates.anderson.reset();
            if !self.extrapolated {
                self.rises = self.rises.saturating_add(1);
            }
            ws.iterates.iterate = ws.iterates.accepted;
            self.restarted = true;
        }
        self.have_solution = true;
        self.previous_cost = cost;
        self.newton_used =
            self.rejections < MAX_NEWTON_REJECTIONS && newton::applies(&ws.iterates.qp);
        if self.newton_used {
            // The Newton step is taken at the answer, with the gradients there: the moving
            // checks go to the answer's local separation minima first (the envelope theorem
            // makes that the semi-infinite constraint's gradient).
            if !newton_step_at_answer(ws, settings.continuous_verification) {
                ws.iterates.iterate = ws.iterates.accepted;
            }
            self.extrapolated = true;
        } else {
            let memory = usize::from(settings.acceleration_memory);
            let tr = &ws.setup.transcription;
            ws.iterates.anderson.step(
                &mut ws.iterates.iterate,
                &ws.iterates.trial,
                memory,
                tr.blocks(),
                tr.basis.free,
            );
            self.extrapolated = memory > 0;
        }
        Step::Linearise
    }
}

/// The l1 penalty of the elastic subproblem per unit of slack (a distance in the
/// cost-orthonormal coefficients), relative to `1 + |y|` at the last answer. An exact penalty
/// needs it above every multiplier of the answer it should find; a normalised row's multiplier
/// is at most about |y| (stationarity: `y = sum mu_k a_k / |a_k|`), so 100 times that leaves a
/// slack only where no answer meets the rows.
const ELASTIC_PENALTY_REL: f64 = 100.0;

/// The elastic QP's penalty `rho` (see `qp::solve`) at the last answer.
/// The Newton step from the accepted answer, charged first; with `refine` the moving checks go
/// to the answer's local separation minima before it. False when the step failed (the iterate
/// is then partly written: the caller restores it).
pub(super) fn newton_step_at_answer(ws: &mut Workspace, refine: bool) -> bool {
    ws.iterates.iterate = ws.iterates.accepted;
    ws.work.charge(work_units::newton_step(
        &ws.setup.transcription,
        ws.iterates.qp.count,
    ));
    if refine {
        refine_moving_checks(ws);
    }
    newton::step(
        &mut ws.setup.transcription,
        &mut ws.iterates.qp,
        &ws.iterates.accepted,
        &mut ws.iterates.iterate,
        newton::Scratch::from_buffers(ws.iterates.anderson.lend()),
        &mut ws.work,
    )
}

fn elastic_penalty(ws: &Workspace) -> f64 {
    let tr = &ws.setup.transcription;
    let size = half_norm2(&ws.iterates.accepted, (tr.blocks(), tr.basis.free));
    ELASTIC_PENALTY_REL * (1.0 + libm::sqrt(2.0 * size))
}

/// Turns of a pair's head-on swerve direction (45 degrees each) before `Infeasible`.
pub(super) const MAX_SWERVE_TURNS: u8 = 2;

/// Turn the fallback direction of every pair `unmet` names a keep-out of, or of every pair when
/// it names only control bounds (the elastic answer may trade a swerve's bound for the
/// keep-out), to `eighths` of a turn from its first (`swerve::turn_fallback`). A fallback
/// direction only acts where a violated check meets head on, so turning one elsewhere changes
/// nothing. Returns whether any pair was turned.
pub(super) fn turn_unmet_pairs(ws: &mut Workspace, unmet: &Unmet, eighths: u8) -> bool {
    let keep_out_named = unmet
        .named()
        .iter()
        .any(|u| matches!(u.constraint, certificate::ActiveConstraint::KeepOut { .. }));
    let mut turned = false;
    for pair in 0..ws.setup.transcription.pair_count {
        let Some(spacecraft) = ws.setup.transcription.pair(pair).map(|p| p.spacecraft) else {
            continue;
        };
        let named = unmet.named().iter().any(|u| {
            matches!(u.constraint, certificate::ActiveConstraint::KeepOut { pair, .. } if pair == spacecraft)
        });
        if (named || !keep_out_named) && turn_fallback(ws, pair, eighths) {
            turned = true;
        }
    }
    turned
}

/// Every constraint `y` misses by more than `tol` (normalised, the QP's feasibility tolerance:
/// the test by which the elastic QP said a slack is left, so the list is never empty then), in
/// the list's order. Not inlined: its frame is on the stack only while it runs.
#[inline(never)]
pub(super) fn name_unmet(tr: &Transcription, y: &Coefficients, tol: f64, unmet: &mut Unmet) {
    *unmet = Unmet::new();
    let free = tr.basis.free;
    let mut offer = |id: RowId, scale: f64| {
        // Every row offered is one of the transcription's (walked from its counts below).
        let Some(view) = tr.view(id) else {
            return;
        };
        let shortfall = view.rhs - row_dot(&view, y, free);
        let shortfall_rel = shortfall / scale;
        if view.norm > 0.0 && shortfall / view.norm > tol {
            if let Some(constraint) = certificate::describe(tr, id) {
                unmet.offer(UnmetConstraint {
                    constraint,
                    shortfall,
                    shortfall_rel,
                });
            }
        }
    };
    for block in 0..tr.blocks() {
        for node in 0..tr.grid.nodes() {
            let (block, node) = (u8_of(block), u8_of(node));
            for upper in [true, false] {
                offer(RowId::Control { block, node, upper }, tr.max_control_fu);
            }
        }
    }
    for (pair, (&count, checks)) in tr
        .check_count
        .iter()
        .zip(tr.checks.iter())
        .take(tr.pair_count)
        .indexed()
    {
        for (c, check) in checks.iter().take(count).indexed() {
            if !check.pruned {
                let id = RowId::KeepOut {
                    pair: u8_of(pair),
                    check: u8_of(c),
                };
                offer(id, tr.keep_out_lu);
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::super::certificate::ActiveConstraint;
    use super::super::{self as pseudospectral, Problem, SolveStatus};
    use super::*;

    /// Two spacecraft at rest swap places along x (from +-x0 to -+x0) in T = 10 with
    /// Umax = 1, m = 1, keeping `keep_out` apart.
    fn swap(x0: f64, keep_out: f64) -> Problem {
        super::super::test_problems::rest_to_rest(
            &[
                ([x0, 0.0, 0.0], [-x0, 0.0, 0.0]),
                ([-x0, 0.0, 0.0], [x0, 0.0, 0.0]),
            ],
            keep_out,
            12,
            true,
        )
    }

    fn solve(problem: &Problem) -> Solution {
        let mut ws = Workspace::new();
        let mut out = Solution::new();
        pseudospectral::solve(problem, &Settings::default(), &mut ws, &mut out).unwrap();
        out
    }

    #[test]
    fn an_unseparable_swap_is_infeasible_and_names_the_pair_and_the_bounds() {
        // Each spacecraft must return to y = z = 0 at rest, so with |u| <= 1 per axis it can
        // be at most Umax (T/4)^2 = 6.25 LU off the x axis on each of y and z: the pair at most
        // 2 sqrt(2) 6.25 = 17.7 LU apart when their x coincide. d = 20 cannot be kept (the
        // start, 22 LU apart, can).
        let reach = 2.0 * libm::sqrt(2.0) * 1.0 * (10.0f64 / 4.0).powi(2);
        assert!(reach < 20.0);
        let out = solve(&swap(11.0, 20.0));
        assert_eq!(out.info.status, SolveStatus::Infeasible);
        // The first subproblem, then one per turn of the pair's swerve direction.
        assert_eq!(out.info.elastic_subproblems, 1 + MAX_SWERVE_TURNS);
        let named = out.unmet.named();
        assert!(!named.is_empty());
        assert!(named
            .iter()
            .all(|u| u.shortfall > 0.0 && u.shortfall_rel > 0.0));
        // Keep-out checks first, then control bounds, each kind largest first.
        let keep_out =
            |u: &UnmetConstraint| matches!(u.constraint, ActiveConstraint::KeepOut { .. });
        assert!(named.windows(2).all(|w| {
            (keep_out(&w[0]) && !keep_out(&w[1]))
                || (keep_out(&w[0]) == keep_out(&w[1]) && w[0].shortfall_rel >= w[1].shortfall_rel)
        }));
        // The keep-out of the pair, around the crossing, and the bounds a swerve would exceed.
        assert!(named.iter().any(|u| matches!(
            u.constraint,
            ActiveConstraint::KeepOut { pair: (0, 1), time_tu } if time_tu > 2.0 && time_tu < 8.0
        )));
        assert!(named
            .iter()
            .any(|u| matches!(u.constraint, ActiveConstraint::Control { axis: 1 | 2, .. })));
        assert!(!out.info.status.is_usable());
    }

    #[test]
    fn a_swap_that_needs_a_diagonal_swerve_is_solved_after_a_turn() {
        // d = 14: along one axis off x the pair gets at most 2 x 6.25 = 12.5 LU apart, along
        // the diagonal of y and z 17.7. The head-on swerve starts along one axis, so the first
        // subproblem is infeasible; turned by 45 degrees it is not.
        assert!(2.0 * (10.0f64 / 4.0).powi(2) < 14.0);
        let out = solve(&swap(11.0, 14.0));
        assert_eq!(out.info.status, SolveStatus::Solved);
        assert!(out.info.elastic_subproblems >= 1);
        assert_eq!(out.unmet.count, 0);
        assert!(out.min_separation_lu.unwrap() >= 14.0 - 1e-6);
        // The pair passes off both lateral axes at the crossing.
        let mid = usize::from(out.degree) / 2;
        let (a, b) = (out.states[0][mid], out.states[1][mid]);
        assert!((a[1] - b[1]).abs() > 1.0 && (a[2] - b[2]).abs() > 1.0);
    }

    #[test]
    fn a_separable_swap_names_nothing() {
        // d = 6 < 17.7: the pair can pass; nothing is named, whatever path the solve took.
        let out = solve(&swap(11.0, 6.0));
        assert!(out.info.status.is_usable(), "{:?}", out.info.status);
        assert_eq!(out.unmet.count, 0);
        assert!(out.min_separation_lu.unwrap() >= 6.0 - 1e-6);
    }
}
