//! Planner A's charged steps, one at a time, for the work-unit bound (issue 33 item 1; the
//! GEO tour's `geo_tour/kernels.rs` is the model). Not part of the planner's interface: the
//! kernel image (`firmware/src/ka_main.rs`) runs every case between its instruction markers
//! and divides each case's M7 instructions by the units the solve charges for it.
//!
//! Each case runs the solve's own code for one metered step, on a state [`prepare`] made
//! outside the measured span (the guess, the set-up, `warm` subproblems of the SQP, the
//! linearisation at the iterate), and returns the units the solve charges for what it ran:
//! the set-up, one SQP iteration's set-up (moving checks, linearisation, Anderson step), the
//! convergence test's separation search, a QP scan from an empty working set (no row active:
//! every row scanned), the previous working set's rows at `MAX_ACTIVE`, whole QPs cut after
//! `j` active-set steps, dual sweeps from zero, a verification round over every pair (none
//! taken as clean), the final checks (`solver::check_answer` and `solver::certify`, the two
//! parts of `solver::finish`), the second-order step, the elastic
//! QP's naming of the unmet constraints (every row named) and its two scans of the held rows
//! (every row held), the turn of every pair's swerve direction, a saddle escape's step, a row
//! dropped from a full working set (deleted from the Gram factor), and whole solves. The problems are 8 spacecraft crossing through the centre of a circle (every pair
//! meets, so no check is pruned), at the capacity N = 24 and at N = 10, and 2 spacecraft at the
//! least degree N = 4 (where the fixed-size clears weigh most).

use super::iteration::{name_unmet, newton_step_at_answer, sqp, turn_unmet_pairs, SqpEnd};
use super::linearise::{follow_minima, linearise};
use super::problem::{Problem, Spacecraft};
use super::qp_state::Mode;
use super::settings::Settings;
use super::setup::{initial_iterate, setup};
use super::solution::{Solution, Unmet};
use super::solver::{certify, check_answer, guess_laws, step_along, verification_round};
use super::transcription::{RowId, Transcription};
use super::workspace::Workspace;
use super::{newton, qp, qp_dual, qp_scan, work_units};
use crate::capacity::MAX_ACTIVE;
use crate::work::Meter;
use core::hint::black_box;

/// A problem of the cases: `spacecraft` on a circle of radius 6 crossing to the antipodes
/// (z +-0.5), degree `degree`, keep-out `keep_out_lu`, test points on.
#[derive(Clone, Copy, Debug)]
pub struct Shape {
    spacecraft: usize,
    degree: u16,
    keep_out_lu: f64,
}

/// 8 spacecraft at the capacity degree.
const CAP: Shape = Shape {
    spacecraft: 8,
    degree: 24,
    keep_out_lu: 2.0,
};
/// 8 spacecraft at N = 10 (the audit's size).
const N10: Shape = Shape {
    spacecraft: 8,
    degree: 10,
    keep_out_lu: 2.0,
};
/// `spacecraft` at degree `degree`, d = 2.
const fn shape(spacecraft: usize, degree: u16) -> Shape {
    Shape {
        spacecraft,
        degree,
        keep_out_lu: 2.0,
    }
}

/// 2 spacecraft at the least degree.
const SMALL: Shape = Shape {
    spacecraft: 2,
    degree: 4,
    keep_out_lu: 2.0,
};

/// What a case runs; `warm` is the number of SQP subproblems solved in [`prepare`].
#[derive(Clone, Copy, Debug)]
enum Kind {
    /// The analytic guess (`solver::guess_laws`): not charged.
    Guess,
    /// `setup` and `initial_iterate`.
    Setup,
    /// One SQP iteration's set-up: moving checks, linearisation, Anderson step.
    SqpIteration(u16),
    /// The convergence test's separation search (`follow_minima` without moving the checks).
    ConvergenceSearch(u16),
    /// `qp_scan::most_violated` with no row active.
    QpScan(u16),
    /// `qp_scan::most_violated_hint` over `MAX_ACTIVE` keep-out rows, none active.
    QpHint(u16),
    /// `qp::solve` with at most this many active-set steps (0: the settings').
    Qp(u16, u16),
    /// `qp_dual::solve` from zero with at most this many sweeps.
    Dual(u16, u16),
    /// A verification round over every pair.
    Verify(u16),
    /// `solver::check_answer` (every pair's continuous minimum, the answer's node values).
    AnswerChecks(u16),
    /// `solver::certify` (the certificate with the last QP's state).
    Certificate(u16),
    /// The second-order step (set-up and CG iterations).
    Newton(u16),
    /// `iteration::name_unmet` naming every row (its dearest path: every row described and
    /// offered to the sorted list).
    NameUnmet(u16),
    /// The elastic QP's two scans of its held rows (`qp_scan::most_met_elastic` and
    /// `qp_scan::elastic_slack_left`) with every row held elastic.
    ElasticScans(u16),
    /// `iteration::turn_unmet_pairs` with no keep-out named (every pair turned).
    TurnSwerves(u16),
    /// `solver::step_along` (a saddle escape's or a flat probe's step).
    StepAlong(u16),
    /// The first row dropped from a working set of `MAX_ACTIVE` rows (`QpState::drop_row`: the
    /// row deleted from the Gram factor, every row below it moved and updated).
    DropRow(u16),
    /// A whole solve with this budget (0: the default).
    Solve(u64),
}

/// A kernel case: its name (the record's key), its problem and what it runs.
#[derive(Clone, Copy, Debug)]
pub struct Case {
    /// Name in the firmware's output.
    pub name: &'static str,
    shape: Shape,
    kind: Kind,
}

impl Case {
    /// Whether the solve charges what the case runs: every case but the analytic guess (which
    /// the `setup-*` cases run inside their span, so the set-up's charge covers it).
    pub const fn charged(&self) -> bool {
        !matches!(self.kind, Kind::Guess)
    }
}

const fn case(name: &'static str, shape: Shape, kind: Kind) -> Case {
    Case { name, shape, kind }
}

/// Every case, in the order the kernel image runs them.
pub const CASES: &[Case] = &[
    case("guess-cap", CAP, Kind::Guess),
    case("setup-cap", CAP, Kind::Setup),
    case("setup-n10", N10, Kind::Setup),
    case("setup-small", SMALL, Kind::Setup),
    case("setup-m8-n16", shape(8, 16), Kind::Setup),
    case("setup-m8-n20", shape(8, 20), Kind::Setup),
    case("setup-m4-n24", shape(4, 24), Kind::Setup),
    case("setup-m2-n24", shape(2, 24), Kind::Setup),
    case("sqp-iteration-cap-w0", CAP, Kind::SqpIteration(0)),
    case("sqp-iteration-cap-w3", CAP, Kind::SqpIteration(3)),
    case("sqp-iteration-n10-w3", N10, Kind::SqpIteration(3)),
    case("sqp-iteration-small-w1", SMALL, Kind::SqpIteration(1)),
    case("convergence-search-cap-w3", CAP, Kind::ConvergenceSearch(3)),
    case("convergence-search-n10-w3", N10, Kind::ConvergenceSearch(3)),
    case("qp-scan-cap-w0", CAP, Kind::QpScan(0)),
    case("qp-scan-cap-w3", CAP, Kind::QpScan(3)),
    case("qp-scan-n10-w3", N10, Kind::QpScan(3)),
    case("qp-scan-small-w1", SMALL, Kind::QpScan(1)),
    case("qp-hint-cap-w3", CAP, Kind::QpHint(3)),
    case("qp-hint-n10-w3", N10, Kind::QpHint(3)),
    case("qp-1-cap-w0", CAP, Kind::Qp(0, 1)),
    case("qp-2-cap-w0", CAP, Kind::Qp(0, 2)),
    case("qp-8-cap-w0", CAP, Kind::Qp(0, 8)),
    case("qp-16-cap-w0", CAP, Kind::Qp(0, 16)),
    case("qp-32-cap-w0", CAP, Kind::Qp(0, 32)),
    case("qp-full-cap-w0", CAP, Kind::Qp(0, 0)),
    case("qp-1-n10-w0", N10, Kind::Qp(0, 1)),
    case("qp-2-n10-w0", N10, Kind::Qp(0, 2)),
    case("qp-8-n10-w0", N10, Kind::Qp(0, 8)),
    case("qp-16-n10-w0", N10, Kind::Qp(0, 16)),
    case("qp-1-small-w0", SMALL, Kind::Qp(0, 1)),
    case("qp-2-small-w0", SMALL, Kind::Qp(0, 2)),
    case("qp-full-cap-w3", CAP, Kind::Qp(3, 0)),
    case("qp-full-n10-w0", N10, Kind::Qp(0, 0)),
    case("qp-full-n10-w3", N10, Kind::Qp(3, 0)),
    case("qp-full-small-w1", SMALL, Kind::Qp(1, 0)),
    case("dual-1-cap-w3", CAP, Kind::Dual(3, 1)),
    case("dual-4-cap-w3", CAP, Kind::Dual(3, 4)),
    case("dual-4-n10-w3", N10, Kind::Dual(3, 4)),
    case("verify-cap-w3", CAP, Kind::Verify(3)),
    case("verify-n10-w3", N10, Kind::Verify(3)),
    case("verify-small-w1", SMALL, Kind::Verify(1)),
    case("answer-checks-cap-w3", CAP, Kind::AnswerChecks(3)),
    case("answer-checks-n10-w3", N10, Kind::AnswerChecks(3)),
    case("answer-checks-small-w1", SMALL, Kind::AnswerChecks(1)),
    case("certificate-cap-w3", CAP, Kind::Certificate(3)),
    case("certificate-cap-w8", CAP, Kind::Certificate(8)),
    case("certificate-n10-w3", N10, Kind::Certificate(3)),
    case("certificate-small-w1", SMALL, Kind::Certificate(1)),
    case("newton-cap-w3", CAP, Kind::Newton(3)),
    case("newton-cap-w8", CAP, Kind::Newton(8)),
    case("newton-n10-w3", N10, Kind::Newton(3)),
    case("name-unmet-cap-w3", CAP, Kind::NameUnmet(3)),
    case("name-unmet-n10-w3", N10, Kind::NameUnmet(3)),
    case("name-unmet-small-w1", SMALL, Kind::NameUnmet(1)),
    case("elastic-scans-cap-w3", CAP, Kind::ElasticScans(3)),
    case("elastic-scans-n10-w3", N10, Kind::ElasticScans(3)),
    case("elastic-scans-small-w1", SMALL, Kind::ElasticScans(1)),
    case("turn-swerves-cap-w3", CAP, Kind::TurnSwerves(3)),
    case("turn-swerves-n10-w3", N10, Kind::TurnSwerves(3)),
    case("turn-swerves-small-w1", SMALL, Kind::TurnSwerves(1)),
    case("step-along-cap-w3", CAP, Kind::StepAlong(3)),
    case("step-along-small-w1", SMALL, Kind::StepAlong(1)),
    case("drop-row-cap-w3", CAP, Kind::DropRow(3)),
    case("drop-row-n10-w3", N10, Kind::DropRow(3)),
    case("drop-row-small-w1", SMALL, Kind::DropRow(1)),
    case("solve-cap-1m", CAP, Kind::Solve(1_000_000)),
    case("solve-n10-default", N10, Kind::Solve(0)),
    case("solve-small-default", SMALL, Kind::Solve(0)),
    // The worst planner-A request within the built-in limits, whole, at the default budget:
    // `fixtures/worst-case/crossing-8-sats-n24.toml`'s problem (a test holds them equal).
    case("solve-cap-default", CAP, Kind::Solve(0)),
];

/// The crossing problem of `shape`.
fn problem(shape: Shape) -> Problem {
    let mut spacecraft = heapless::Vec::new();
    let m = shape.spacecraft.max(1);
    for i in 0..m {
        let angle = core::f64::consts::TAU * (i as f64) / (m as f64);
        let (s, c) = (libm::sin(angle), libm::cos(angle));
        let z = if i % 2 == 0 { 0.5 } else { -0.5 };
        let _ = spacecraft.push(Spacecraft {
            mass_mu: 1.0,
            initial_state: [6.0 * c, 6.0 * s, z, 0.0, 0.0, 0.0],
            final_state: [-6.0 * c, -6.0 * s, -z, 0.0, 0.0, 0.0],
        });
    }
    Problem {
        horizon_tu: 10.0,
        max_control_fu: 1.0,
        keep_out_lu: shape.keep_out_lu,
        degree: shape.degree,
        test_points: true,
        spacecraft,
    }
}

/// The problem a whole-solve case solves (`None` for the other cases).
pub fn case_problem(index: usize) -> Option<Problem> {
    let c = CASES.get(index)?;
    match c.kind {
        Kind::Solve(_) => Some(problem(c.shape)),
        _ => None,
    }
}

/// Every row of the transcription: control rows (both sides), then unpruned keep-out rows.
fn for_each_row(tr: &Transcription, mut f: impl FnMut(RowId)) {
    for block in 0..tr.blocks() {
        for node in 0..tr.grid.nodes() {
            for upper in [true, false] {
                f(RowId::Control {
                    block: u8::try_from(block).unwrap_or(u8::MAX),
                    node: u8::try_from(node).unwrap_or(u8::MAX),
                    upper,
                });
            }
        }
    }
    for_each_keep_out(tr, f);
}

/// Every unpruned keep-out row, then the control rows' upper sides.
fn for_each_row_keep_out_first(tr: &Transcription, mut f: impl FnMut(RowId)) {
    for_each_keep_out(tr, &mut f);
    for block in 0..tr.blocks() {
        for node in 0..tr.grid.nodes() {
            f(RowId::Control {
                block: u8::try_from(block).unwrap_or(u8::MAX),
                node: u8::try_from(node).unwrap_or(u8::MAX),
                upper: true,
            });
        }
    }
}

/// Every unpruned keep-out row.
fn for_each_keep_out(tr: &Transcription, mut f: impl FnMut(RowId)) {
    for pair in 0..tr.pair_count {
        for (check, c) in tr.checks_of(pair) {
            if !c.pruned {
                f(RowId::KeepOut {
                    pair: u8::try_from(pair).unwrap_or(u8::MAX),
                    check: u8::try_from(check).unwrap_or(u8::MAX),
                });
            }
        }
    }
}

/// What [`prepare`] made for [`run`]: nothing past the workspace's state.
#[derive(Clone, Copy, Debug, Default)]
pub struct Prepared {
    /// The set-up failed (the case then runs nothing).
    failed: bool,
}

fn warm_of(kind: Kind) -> Option<u16> {
    match kind {
        Kind::Guess | Kind::Setup | Kind::Solve(_) => None,
        Kind::SqpIteration(w)
        | Kind::ConvergenceSearch(w)
        | Kind::QpScan(w)
        | Kind::QpHint(w)
        | Kind::Qp(w, _)
        | Kind::Dual(w, _)
        | Kind::Verify(w)
        | Kind::AnswerChecks(w)
        | Kind::Certificate(w)
        | Kind::Newton(w)
        | Kind::NameUnmet(w)
        | Kind::ElasticScans(w)
        | Kind::TurnSwerves(w)
        | Kind::StepAlong(w)
        | Kind::DropRow(w) => Some(w),
    }
}

/// The set-up of case `index`, outside the measured span: the guess, the transcription, the
/// first iterate, `warm` subproblems (unmetered), and for the QP cases the linearisation at
/// the iterate.
pub fn prepare(index: usize, ws: &mut Workspace, out: &mut Solution) -> Prepared {
    let Some(c) = CASES.get(index) else {
        return Prepared::default();
    };
    let Some(warm) = warm_of(c.kind) else {
        return Prepared::default();
    };
    let p = problem(c.shape);
    let settings = Settings::default();
    let failed = Prepared { failed: true };
    let Ok(laws) = guess_laws(&p, &settings) else {
        return failed;
    };
    ws.setup.laws = laws;
    out.reset();
    ws.iterates.qp.reset();
    ws.work = Meter::new(u64::MAX);
    if setup(&p, &settings, ws, &mut out.test_point_times_tu).is_err() {
        return failed;
    }
    initial_iterate(ws, None, [0.0; 3], out);
    if warm > 0 {
        let s = Settings {
            sqp_max_iter: warm,
            ..settings
        };
        let _ = sqp(ws, &s, out);
    }
    ws.iterates.trial = ws.iterates.iterate;
    if matches!(
        c.kind,
        Kind::QpScan(_)
            | Kind::QpHint(_)
            | Kind::Qp(..)
            | Kind::Dual(..)
            | Kind::NameUnmet(_)
            | Kind::ElasticScans(_)
            | Kind::DropRow(_)
    ) {
        let _ = follow_minima(ws, &settings, true, false);
        linearise(ws);
    }
    match c.kind {
        Kind::ElasticScans(_) => {
            ws.iterates.qp.reset();
            let tr = &ws.setup.transcription;
            let qp = &mut ws.iterates.qp;
            for_each_row(tr, |id| qp.mark_elastic(id, true));
        }
        Kind::DropRow(_) => {
            // Up to `MAX_ACTIVE` independent working rows, keep-out rows first (six blocks
            // each), in factor mode: a row whose factor fails is left out.
            let tr = &ws.setup.transcription;
            let qp = &mut ws.iterates.qp;
            qp.reset();
            for_each_row_keep_out_first(tr, |id| {
                let count = qp.count;
                if let Some(slot) = qp.active.get_mut(count) {
                    *slot = id;
                    qp.count = count.saturating_add(1);
                    if !qp.refactor(tr) {
                        qp.count = count;
                    }
                }
            });
            if !qp.refactor(tr) {
                return failed;
            }
        }
        _ => {}
    }
    Prepared::default()
}

/// Run case `index` (after [`prepare`]) and return the units the solve charges for what it
/// ran (0 for an index past the cases, or a step the solve does not charge).
pub fn run(index: usize, ws: &mut Workspace, out: &mut Solution, prepared: &Prepared) -> u64 {
    let Some(c) = CASES.get(index) else {
        return 0;
    };
    if prepared.failed {
        return 0;
    }
    let d = Settings::default();
    let before = ws.work.used();
    match black_box(c.kind) {
        Kind::Guess => {
            let p = problem(c.shape);
            black_box(guess_laws(black_box(&p), &d).is_ok());
            0
        }
        Kind::Setup => {
            let p = problem(c.shape);
            let Ok(laws) = guess_laws(&p, &d) else {
                return 0;
            };
            ws.setup.laws = laws;
            // Outside the measured step in the solve too: the guess (uncharged) is measured
            // alone above; here it is counted with the set-up (a safe over-count).
            ws.iterates.qp.reset();
            let _ = setup(black_box(&p), &d, ws, &mut out.test_point_times_tu);
            initial_iterate(ws, None, [0.0; 3], out);
            work_units::setup(&ws.setup.transcription)
        }
        Kind::SqpIteration(_) => {
            let _ = ws
                .work
                .spend(work_units::sqp_iteration(&ws.setup.transcription));
            let _ = follow_minima(ws, &d, true, false);
            linearise(ws);
            let tr = &ws.setup.transcription;
            ws.iterates.anderson.step(
                &mut ws.iterates.iterate,
                &ws.iterates.trial,
                usize::from(d.acceleration_memory),
                tr.blocks(),
                tr.basis.free,
            );
            ws.work.used().saturating_sub(before)
        }
        Kind::ConvergenceSearch(_) => {
            ws.work
                .charge(work_units::convergence_search(&ws.setup.transcription));
            black_box(follow_minima(ws, &d, false, false));
            ws.work.used().saturating_sub(before)
        }
        Kind::QpScan(_) => {
            // At the start of a QP: no pair's bound known, every pair evaluated.
            ws.iterates.qp.reset();
            let checks = ws
                .iterates
                .qp
                .scan_bounds
                .checks_to_scan(&ws.setup.transcription, d.qp_tol_feas);
            let _ = ws
                .work
                .spend(work_units::qp_scan(&ws.setup.transcription, checks));
            black_box(qp_scan::most_violated(
                &ws.setup.transcription,
                &mut ws.iterates.qp,
                &ws.iterates.iterate,
                d.qp_tol_feas,
            ));
            ws.work.used().saturating_sub(before)
        }
        Kind::QpHint(_) => {
            let tr = &ws.setup.transcription;
            let mut hint = [RowId::Control {
                block: 0,
                node: 0,
                upper: true,
            }; MAX_ACTIVE];
            let mut count = 0usize;
            for pair in 0..tr.pair_count {
                for (check, c) in tr.checks_of(pair) {
                    if c.pruned || count >= MAX_ACTIVE {
                        continue;
                    }
                    if let Some(slot) = hint.get_mut(count) {
                        *slot = RowId::KeepOut {
                            pair: pair as u8,
                            check: check as u8,
                        };
                        count = count.saturating_add(1);
                    }
                }
            }
            let _ = ws.work.spend(work_units::qp_hint(tr, count));
            ws.iterates.qp.reset();
            black_box(qp_scan::most_violated_hint(
                tr,
                &ws.iterates.qp,
                &ws.iterates.iterate,
                (&hint, count),
                -1.0,
            ));
            ws.work.used().saturating_sub(before)
        }
        Kind::Qp(_, steps) => {
            let mut iterations = 0u32;
            let max_iter = if steps == 0 { d.qp_max_iter } else { steps };
            black_box(qp::solve(
                &ws.setup.transcription,
                &mut ws.iterates.qp,
                &mut ws.iterates.trial,
                max_iter,
                d.qp_tol_feas,
                &mut iterations,
                &mut ws.work,
                f64::INFINITY,
            ));
            ws.work.used().saturating_sub(before)
        }
        Kind::Dual(_, sweeps) => {
            let mut iterations = 0u32;
            ws.iterates.qp.reset();
            black_box(qp_dual::solve(
                &ws.setup.transcription,
                &mut ws.iterates.qp,
                &mut ws.iterates.trial,
                None,
                sweeps,
                d.qp_tol_feas,
                &mut iterations,
                &mut ws.work,
                f64::INFINITY,
            ));
            ws.work.used().saturating_sub(before)
        }
        Kind::Verify(_) => {
            let _ = ws
                .work
                .spend(work_units::verify_round(&ws.setup.transcription));
            let end = SqpEnd::MaxIterations { at_answer: true };
            black_box(verification_round(ws, &d, out, end, 0));
            ws.work.used().saturating_sub(before)
        }
        Kind::AnswerChecks(_) => {
            black_box(check_answer(ws, &d, out));
            ws.work.used().saturating_sub(before)
        }
        Kind::Certificate(_) => {
            certify(ws, out);
            black_box(&out.certificate);
            ws.work.used().saturating_sub(before)
        }
        Kind::Newton(_) => {
            if ws.iterates.qp.mode != Mode::Factor || !newton::applies(&ws.iterates.qp) {
                return 0;
            }
            black_box(newton_step_at_answer(ws, true));
            ws.work.used().saturating_sub(before)
        }
        Kind::NameUnmet(_) => {
            let tr = &ws.setup.transcription;
            name_unmet(tr, &ws.iterates.iterate, f64::NEG_INFINITY, &mut out.unmet);
            black_box(&out.unmet);
            work_units::name_unmet(tr)
        }
        Kind::ElasticScans(_) => {
            let tr = &ws.setup.transcription;
            let (qp, y) = (&ws.iterates.qp, &ws.iterates.iterate);
            black_box(qp_scan::most_met_elastic(tr, qp, y, f64::NEG_INFINITY));
            black_box(qp_scan::elastic_slack_left(tr, qp, y, f64::NEG_INFINITY));
            work_units::elastic_scans(tr, qp.elastic_count)
        }
        Kind::TurnSwerves(_) => {
            black_box(turn_unmet_pairs(ws, &Unmet::new(), 1));
            work_units::turn_swerves(&ws.setup.transcription)
        }
        Kind::StepAlong(_) => {
            step_along(ws, 1.0);
            black_box(&ws.iterates.iterate);
            work_units::step_along()
        }
        Kind::DropRow(_) => {
            let k = ws.iterates.qp.count;
            let mut scratch = [0.0; MAX_ACTIVE];
            black_box(ws.iterates.qp.drop_row(0, &mut scratch));
            work_units::drop_row(k)
        }
        Kind::Solve(budget) => {
            let p = problem(c.shape);
            let s = Settings {
                work_budget: if budget == 0 { d.work_budget } else { budget },
                ..d
            };
            let _ = super::solve(black_box(&p), black_box(&s), ws, out);
            black_box(&*out);
            out.info.work_units
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    extern crate std;

    #[test]
    fn every_case_runs() {
        let mut ws = std::boxed::Box::new(Workspace::new());
        let mut out = std::boxed::Box::new(Solution::new());
        for (i, c) in CASES.iter().enumerate() {
            let p = prepare(i, &mut ws, &mut out);
            assert!(!p.failed, "{}", c.name);
            let units = run(i, &mut ws, &mut out, &p);
            std::println!("{} {units} active {}", c.name, ws.iterates.qp.count);
        }
    }
}
