//! The planner-A solve: set up the transcription, run the convex-concave sequence of QPs,
//! verify the separation on the continuous trajectory, refine, and write the solution.

use super::certificate;
use super::error::{PlanError, Quantity};
use super::guess::{self, AxisBoundary, AxisLaw, GuessError};
use super::iteration::{sqp, SqpEnd};
use super::kept::Kept;
use super::kernel::{per_axis, u8_of};
use super::linearise::{pair_bit, pair_minimum, unit_normals};
use super::output::{
    control_excess, state_scale, write_solution, CONTROL_TOL_REL, DYNAMICS_TOL_REL,
};
use super::problem::Problem;
use super::settings::Settings;
use super::setup::{initial_iterate, setup};
use super::solution::Solution;
use super::status::SolveStatus;
use super::validate;
use super::work_units::{self, FinalChecks};
use super::workspace::Workspace;
use crate::capacity::MAX_SPACECRAFT;
use crate::indexed::IndexedExt as _;
use crate::work::Meter;

/// Entry point behind `solve` and `solve_warm`.
pub(crate) fn solve(
    problem: &Problem,
    settings: &Settings,
    ws: &mut Workspace,
    warm: Option<&Solution>,
    lift: [f64; 3],
    out: &mut Solution,
) -> Result<(), PlanError> {
    validate::check(problem, settings)?;
    let m = problem.spacecraft.len();
    let n = usize::from(problem.degree);
    if let Some(previous) = warm {
        if usize::from(previous.degree) != n || usize::from(previous.spacecraft_count) != m {
            return Err(PlanError::WarmStartMismatch);
        }
        for sc in previous.controls_fu.iter().take(m) {
            for node in sc.iter().take(n.saturating_add(1)) {
                if let Some(&value) = node.iter().find(|v| !v.is_finite()) {
                    return Err(PlanError::NotFinite {
                        what: Quantity::WarmStart,
                        spacecraft: 0,
                        value,
                    });
                }
            }
        }
    }
    ws.setup.laws = guess_laws(problem, settings)?;
    out.reset();
    out.degree = problem.degree;
    out.spacecraft_count = u8_of(m);
    out.horizon_tu = problem.horizon_tu;
    let status = run(problem, settings, ws, warm, lift, out);
    out.info.status = status;
    if status != SolveStatus::Infeasible {
        // Named by an elastic subproblem of a run whose answer was not kept (a saddle escape's
        // or a flat probe's): the list belongs to `Infeasible` alone.
        out.unmet = super::solution::Unmet::new();
    }
    out.info.work_units = ws.work.used();
    Ok(())
}

/// The analytic guess per axis (eq. 24-26); an unreachable axis rejects the request.
pub(super) fn guess_laws(
    problem: &Problem,
    settings: &Settings,
) -> Result<[[AxisLaw; 3]; MAX_SPACECRAFT], PlanError> {
    let mut laws = [[AxisLaw::default(); 3]; MAX_SPACECRAFT];
    for (sc, (row, craft)) in laws.iter_mut().zip(problem.spacecraft.iter()).indexed() {
        let ends = per_axis(&craft.initial_state)
            .into_iter()
            .zip(per_axis(&craft.final_state));
        for (axis, (slot, ((p0, v0), (p1, v1)))) in row.iter_mut().zip(ends).indexed() {
            let boundary = AxisBoundary {
                p0,
                v0,
                p1,
                v1,
                horizon: problem.horizon_tu,
                mass: craft.mass_mu,
                max_control: problem.max_control_fu,
            };
            *slot = match guess::solve_axis(boundary, settings.newton_max_iter) {
                Ok(law) => law,
                Err(GuessError::Infeasible) => {
                    return Err(PlanError::ManoeuvreInfeasible {
                        spacecraft: u8_of(sc),
                        axis: u8_of(axis),
                    })
                }
                // Feasible but the saturated law did not converge: the cubic still serves as a
                // linearisation point; the QPs enforce the bound.
                Err(GuessError::NotConverged) => guess::unconstrained(boundary),
            };
        }
    }
    Ok(laws)
}

/// Set up and iterate; returns the final status. `out` receives the solution in every case.
fn run(
    problem: &Problem,
    settings: &Settings,
    ws: &mut Workspace,
    warm: Option<&Solution>,
    lift: [f64; 3],
    out: &mut Solution,
) -> SolveStatus {
    ws.iterates.qp.reset();
    ws.work = Meter::new(settings.work_budget);
    let setup_result = setup(problem, settings, ws, &mut out.test_point_times_tu);
    ws.work.charge(work_units::setup(&ws.setup.transcription));
    if let Err(stage) = setup_result {
        return SolveStatus::NumericalFailure(stage);
    }
    ws.iterates.qp.final_checks = FinalChecks::FirstRun;
    ws.work.reserve(work_units::reserve(
        &ws.setup.transcription,
        0,
        FinalChecks::FirstRun,
    ));
    initial_iterate(ws, warm, lift, out);
    ws.iterates.kept = Kept::START;
    let first = iterate_and_check(ws, settings, out);
    let mut answer = answer_or_kept(ws, settings, out, first);
    // Bounded: the saddle escapes by `MAX_SADDLE_ESCAPES` (`escapes` rises at each), the flat
    // probes by their two sides; every other step leads on, never back.
    let mut step = Step::LookForSaddle { escapes: 0 };
    loop {
        step = match step {
            Step::LookForSaddle { escapes } => {
                if escapes < MAX_SADDLE_ESCAPES
                    && answer.is_saddle(out)
                    && start_escape_or_probe(ws)
                {
                    Step::EscapeSaddle { escapes }
                } else {
                    Step::LookForFlat
                }
            }
            Step::EscapeSaddle { escapes } => {
                let escapes = escapes.saturating_add(1);
                out.info.saddle_escapes = escapes;
                let saddle_cost = out.cost;
                ws.iterates.saved = ws.iterates.iterate;
                step_along(ws, 1.0);
                answer = iterate_and_check(ws, settings, out);
                if !answer.status.is_usable() || out.cost >= saddle_cost {
                    Step::ReturnToSaddle
                } else {
                    Step::LookForSaddle { escapes }
                }
            }
            Step::ReturnToSaddle => {
                // No better: return to the saddle's answer (a fixed point: it re-converges at
                // once).
                ws.iterates.iterate = ws.iterates.saved;
                answer = iterate_and_check(ws, settings, out);
                Step::LookForFlat
            }
            Step::LookForFlat => {
                if answer.is_flat(out) {
                    Step::ProbeFlat {
                        side: 1.0,
                        flat_cost: out.cost,
                    }
                } else {
                    Step::Done
                }
            }
            Step::ProbeFlat { side, flat_cost } => {
                if start_escape_or_probe(ws) {
                    ws.iterates.saved = ws.iterates.iterate;
                    step_along(ws, side);
                    answer = iterate_and_check(ws, settings, out);
                    let tolerance = certificate::FLAT_PROBE_TOL_REL * (1.0 + flat_cost);
                    if answer.status.is_usable() && out.cost < flat_cost - tolerance {
                        // Not flat after all: the lower answer is kept (with its own status).
                        Step::Done
                    } else {
                        Step::ReturnToFlat {
                            side,
                            flat_cost,
                            probe_usable: answer.status.is_usable(),
                        }
                    }
                } else {
                    Step::Done
                }
            }
            Step::ReturnToFlat {
                side,
                flat_cost,
                probe_usable,
            } => {
                // Back to the flat point (a fixed point: it re-converges at once, and the
                // certificate's direction is again the flat one for the other side).
                ws.iterates.iterate = ws.iterates.saved;
                answer = iterate_and_check(ws, settings, out);
                if !probe_usable || !answer.is_flat(out) {
                    Step::Done
                } else if side > 0.0 {
                    Step::ProbeFlat {
                        side: -1.0,
                        flat_cost,
                    }
                } else {
                    Step::CertifyFlat
                }
            }
            Step::CertifyFlat => {
                out.certificate.flat_direction_probed = true;
                if out.certificate.certifies_local_optimum() {
                    answer.status = SolveStatus::Solved;
                }
                Step::Done
            }
            Step::Done => break,
        };
    }
    // Stopped by the budget: the status says so, and whether the answer passed the checks.
    if ws.work.exhausted() {
        return SolveStatus::BudgetExhausted {
            verified: answer.status.is_usable(),
        };
    }
    answer.status
}

/// Start a saddle escape or a flat probe, if the loops' share has room for its step along the
/// direction with the reserve raised to the stage's final checks (its answer's and the
/// return's, `FinalChecks::EscapeAndReturn`). `false` (the meter then exhausted) when it has
/// not: a point whose own checks overran the loops' share starts nothing.
fn start_escape_or_probe(ws: &mut Workspace) -> bool {
    let checks = FinalChecks::EscapeAndReturn;
    ws.iterates.qp.final_checks = checks;
    ws.work.raise_reserve(work_units::reserve(
        &ws.setup.transcription,
        ws.iterates.qp.count,
        checks,
    ));
    ws.work.spend(work_units::step_along())
}

/// What the solve does after the first answer (`run` walks these; each step names the next).
///
/// Saddle escape: a feasible first-order point with negative reduced curvature is left along
/// the curvature direction (deterministic: a fixed power-method start and sign), and the
/// iteration resumes; the better verified answer is kept.
///
/// Flat direction: a feasible first-order point whose reduced Hessian is singular within the
/// tolerance (measured on the symmetric family: eigenvalue ~1e-9 where two or three spacecraft
/// swap through the centre, whose passing side is a continuous symmetry) is neither a certified
/// minimum nor a saddle. Probe it: step along the flat direction both ways (as the saddle escape
/// does) and iterate again; a lower answer is kept, and when neither side is lower the point is
/// certified on the second-order necessary condition (`Certificate::flat_direction_probed`). At
/// most 2 probes and 2 returns, each one run of the iteration, charged by it.
#[derive(Clone, Copy, Debug)]
enum Step {
    /// Is the answer a saddle to escape from (`escapes` tried so far)?
    LookForSaddle { escapes: u8 },
    /// Step along the negative curvature and iterate again (escape number `escapes + 1`).
    EscapeSaddle { escapes: u8 },
    /// The escape found nothing better: back to the saddle's answer.
    ReturnToSaddle,
    /// Is the answer flat (a singular reduced Hessian) and so to be probed?
    LookForFlat,
    /// Step along the flat direction to `side` and iterate again; `flat_cost` is the flat
    /// answer's cost.
    ProbeFlat { side: f64, flat_cost: f64 },
    /// Back to the flat point from the probe to `side` (`probe_usable`: its answer was usable).
    ReturnToFlat {
        side: f64,
        flat_cost: f64,
        probe_usable: bool,
    },
    /// Neither side is lower and the point is flat again: certify it on the second-order
    /// necessary condition.
    CertifyFlat,
    /// The answer in `out` is final.
    Done,
}

/// How one run of the iteration ended and what its answer is.
#[derive(Clone, Copy, Debug)]
struct Answer {
    end: SqpEnd,
    status: SolveStatus,
}

impl Answer {
    /// A feasible, stationary point whose reduced Hessian has a negative eigenvalue.
    fn is_saddle(&self, out: &Solution) -> bool {
        let c = &out.certificate;
        self.status == SolveStatus::Feasible
            && self.measured_at_answer()
            && c.second_order_evaluated
            && c.stationarity <= certificate::STATIONARITY_TOL
            && c.min_reduced_eigenvalue < -certificate::CURVATURE_TOL
    }

    /// A feasible, converged point whose reduced Hessian is singular within the tolerance.
    fn is_flat(&self, out: &Solution) -> bool {
        self.status == SolveStatus::Feasible
            && self.measured_at_answer()
            && out.certificate.is_flat()
    }

    /// The certificate was measured with the point's own QP state: at a fixed point, or at the
    /// iteration limit on an accepted QP answer (as `finish` certifies). Issue 28: a head-on
    /// pair's flat direction (the side it passes on) lets the iteration slide along it until
    /// `sqp_max_iter`; such a point was neither probed nor escaped from, and ended `Feasible`.
    fn measured_at_answer(&self) -> bool {
        self.end.at_own_qp_state()
    }
}

/// The iteration and its verification rounds from `ws.iterates.iterate`, then the answer's
/// checks (`finish`).
fn iterate_and_check(ws: &mut Workspace, settings: &Settings, out: &mut Solution) -> Answer {
    let end = iterate_and_verify(ws, settings, out);
    let status = finish(ws, settings, out, end);
    Answer { end, status }
}

/// The first run's answer, or where it is not usable the best verified answer the run passed
/// (`kept.rs`), checked again by `finish` on its own trajectory. Its QP state is not the last
/// QP's, so it is not certified (`MaxIterations { at_answer: false }`): at best `Feasible`, and
/// no saddle escape or flat probe starts from it. Ends the keeping (`saved` is the escape's).
fn answer_or_kept(
    ws: &mut Workspace,
    settings: &Settings,
    out: &mut Solution,
    first: Answer,
) -> Answer {
    let kept = core::mem::replace(&mut ws.iterates.kept, Kept::OFF);
    if first.status.is_usable() || kept.cost().is_none() {
        return first;
    }
    ws.iterates.iterate = ws.iterates.saved;
    let end = SqpEnd::MaxIterations { at_answer: false };
    let status = finish(ws, settings, out, end);
    Answer { end, status }
}

/// Most saddle escapes per solve (each one more run of the iteration and verification rounds).
pub(crate) const MAX_SADDLE_ESCAPES: u8 = 2;

/// `y <- y + alpha v` with `v` the unit negative-curvature direction, signed so that its
/// largest component has the sign of `side` (deterministic), and `alpha` a quarter of `|y|` (at
/// least 0.1): large enough to leave the saddle's neighbourhood, small enough to stay in its
/// basin.
pub(super) fn step_along(ws: &mut Workspace, side: f64) {
    let direction = &ws.iterates.trial;
    let mut largest = 0.0f64;
    let mut norm2 = 0.0;
    for (row, values) in direction.iter().zip(ws.iterates.iterate.iter()) {
        for (d, y) in row.iter().zip(values.iter()) {
            if libm::fabs(*d) > libm::fabs(largest) {
                largest = *d;
            }
            norm2 += y * y;
        }
    }
    let sign = if largest < 0.0 { -side } else { side };
    let alpha = sign * (0.25 * libm::sqrt(norm2)).max(0.1);
    for (row, values) in direction.iter().zip(ws.iterates.iterate.iter_mut()) {
        for (d, y) in row.iter().zip(values.iter_mut()) {
            *y += alpha * d;
        }
    }
}

/// The convex-concave iteration from `ws.iterates.iterate`, with the continuous verification
/// rounds: after each run of the iteration a round checks every pair's continuous separation,
/// and where it added a check or a margin the iteration runs again (at most
/// `verify_max_rounds` rounds, each charged to the work budget).
fn iterate_and_verify(ws: &mut Workspace, settings: &Settings, out: &mut Solution) -> SqpEnd {
    let mut rounds: u8 = 0;
    loop {
        let end = sqp(ws, settings, out);
        let verify = !matches!(end, SqpEnd::Failed(_))
            && rounds < settings.verify_max_rounds
            && settings.continuous_verification
            && ws
                .work
                .spend(work_units::verify_round(&ws.setup.transcription));
        if !verify || !verification_round(ws, settings, out, end, rounds) {
            return end;
        }
        rounds = rounds.saturating_add(1);
        out.info.verify_rounds = rounds;
    }
}

/// One continuous-verification round after a run of the iteration that ended with `end`, the
/// `rounds + 1`-th: add a check where a pair dips below d, or raise its margin. Returns whether
/// it changed the transcription (then the iteration runs again).
pub(super) fn verification_round(
    ws: &mut Workspace,
    settings: &Settings,
    out: &mut Solution,
    end: SqpEnd,
    rounds: u8,
) -> bool {
    let d = ws.setup.transcription.keep_out_lu;
    // Changes this round: points added, and margins raised.
    let mut added = 0u16;
    let mut points = 0u16;
    // Pairs the convergence test searched at this iterate and found clean: the same search
    // again would find the same.
    let clean = if end == SqpEnd::Converged {
        ws.verification.searched_clean
    } else {
        0
    };
    for pair in 0..ws.setup.transcription.pair_count {
        if pair_bit(pair).is_some_and(|bit| clean & bit != 0) {
            continue;
        }
        // A pair whose minimum cannot be searched (never: the index is a pair's) gets no check
        // here; the answer's own search (`output::write_solution`) leaves it unverified.
        let Some(minimum) = pair_minimum(ws, pair, settings) else {
            continue;
        };
        let separation = libm::sqrt(minimum.value_squared.max(0.0));
        if separation < d - settings.verify_tol_lu {
            // A dip the moving check did not catch (a second local minimum): check it too.
            // Where the pair already had one and still dips, the dip sits between closely
            // spaced checks: raise the pair's keep-out by its depth, which lifts the
            // continuous minimum by about as much (the dips are then ~1e-4 d or less, so the
            // cost moves by parts per million).
            let tau = 2.0 * minimum.at_s - 1.0;
            let tr = &mut ws.setup.transcription;
            let verify_points = &mut ws.verification.verify_points;
            let Some(&points_before) = verify_points.get(pair) else {
                continue;
            };
            let refined_before = points_before > 0;
            let checked = tr.add_check(pair, tau);
            if checked {
                if let Some(count) = verify_points.get_mut(pair) {
                    *count = count.saturating_add(1);
                }
                added = added.saturating_add(1);
                points = points.saturating_add(1);
            }
            // The margin also goes at once to a pair out of check slots (moving checks
            // frozen at other minima hold them), and in the last round to every dipping
            // pair: that round's re-solve is not verified again.
            let last_round = rounds.saturating_add(1) >= settings.verify_max_rounds;
            if refined_before || !checked || last_round {
                if let Some(margin) = tr.margin.get_mut(pair) {
                    *margin += d - separation;
                }
                added = added.saturating_add(1);
            }
        }
    }
    if added == 0 {
        return false;
    }
    out.info.verify_points_added = out.info.verify_points_added.saturating_add(points);
    true
}

/// Write the solution, check its feasibility, evaluate its certificate where it can matter, and
/// return its status. The certificate is taken only for a feasible answer at its own QP state
/// (`SqpEnd::at_own_qp_state`): only such an answer can be certified, escaped from or probed
/// (`Answer::is_saddle`, `Answer::is_flat`). Elsewhere it says it was not evaluated, and its
/// power method (most of a finish's work) is not paid: the first run's reserve holds one
/// certificate, not two (`work_units::FinalChecks`).
pub(super) fn finish(
    ws: &mut Workspace,
    settings: &Settings,
    out: &mut Solution,
    end: SqpEnd,
) -> SolveStatus {
    let feasible = check_answer(ws, settings, out);
    let certified = if feasible && end.at_own_qp_state() {
        certify(ws, out);
        out.certificate.certifies_local_optimum()
    } else {
        out.certificate.not_evaluated();
        false
    };
    match end {
        _ if feasible && certified => SolveStatus::Solved,
        _ if feasible => SolveStatus::Feasible,
        SqpEnd::Failed(status) => status,
        SqpEnd::MaxIterations { .. } => SolveStatus::MaxIterations,
        SqpEnd::Converged => SolveStatus::SeparationNotVerified,
    }
}

/// Write the solution and check its feasibility on the returned trajectory itself, whatever
/// the iteration says: every pair's continuous separation, the control bound, the dynamics.
/// Sets the certificate's `max_violation`; returns whether the answer is feasible.
pub(super) fn check_answer(ws: &mut Workspace, settings: &Settings, out: &mut Solution) -> bool {
    ws.work
        .charge(work_units::answer_checks(&ws.setup.transcription));
    let verified = write_solution(ws, settings, out);
    let control_excess = control_excess(out, ws.setup.transcription.max_control_fu);
    // No pair, no keep-out to miss.
    let separation_deficit = out
        .min_separation_lu
        .map_or(0.0, |s| ws.setup.transcription.keep_out_lu - s);
    out.certificate.max_violation = control_excess.max(separation_deficit).max(0.0);
    verified
        && control_excess <= CONTROL_TOL_REL * ws.setup.transcription.max_control_fu
        && out.max_dynamics_error <= DYNAMICS_TOL_REL * (1.0 + state_scale(out))
}

/// Evaluate the certificate of the returned iterate with the constraint gradients there and the
/// QP state of the last QP (the caller has checked it is the iterate's own). Measured on the
/// dense lattice (issue 9): 10 `Feasible` answers met every tolerance of the certificate but
/// had used their `sqp_max_iter` sliding along the keep-out by parts per million of J per step,
/// so the state must be the answer's own, not merely near it.
/// `ws.iterates.trial` receives the negative-curvature direction (`ws.iterates.accepted` is its
/// scratch): workspace buffers idle at this point, so the certificate adds nothing to the
/// stack. Never inlined: its frame (the envelope corrections, 6.4 KB at capacity) must not sit
/// under the iteration's, which `iterate_and_check` calls beside it (inlined there, it added
/// 8.2 KB to the M7's stack high-water).
#[inline(never)]
pub(super) fn certify(ws: &mut Workspace, out: &mut Solution) {
    ws.work.charge(work_units::certificate(
        &ws.setup.transcription,
        ws.iterates.qp.count,
    ));
    unit_normals(ws);
    let extra = certificate::evaluate(
        &ws.setup.transcription,
        &mut ws.iterates.qp,
        &ws.iterates.iterate,
        out.cost,
        &mut ws.iterates.trial,
        &mut ws.iterates.accepted,
        &mut out.certificate,
    );
    ws.work.charge(work_units::extra_products(
        &ws.setup.transcription,
        ws.iterates.qp.count,
        extra,
    ));
}

#[cfg(test)]
#[path = "solver_tests.rs"]
mod tests;
