//! The QP's l1-elastic form (`qp::solve` with a finite penalty) against the QP itself, on the
//! first linearisation of two problems: the paper's case (feasible) and two spacecraft that
//! must swap places keeping 20 LU apart (infeasible, see `iteration.rs`' tests).
#![allow(clippy::indexing_slicing, clippy::unwrap_used, clippy::expect_used)]

use super::kernel::{Coefficients, MAX_BLOCKS};
use super::qp;
use super::qp_state::QpOutcome;
use super::test_problems::first_subproblem;
use super::transcription::{row_dot, RowId, Transcription};
use super::{Problem, Workspace};
use crate::capacity::MAX_FREE_PER_AXIS;
use crate::work::Meter;

fn rest_to_rest(moves: &[([f64; 3], [f64; 3])], keep_out: f64, degree: u16) -> Problem {
    super::test_problems::rest_to_rest(moves, keep_out, degree, true)
}

fn solve(ws: &mut Workspace, penalty: f64) -> (QpOutcome, Coefficients) {
    let mut y = [[0.0; MAX_FREE_PER_AXIS]; MAX_BLOCKS];
    let mut iterations = 0u32;
    let mut meter = Meter::new(u64::MAX);
    ws.iterates.qp.reset();
    let outcome = qp::solve(
        &ws.setup.transcription,
        &mut ws.iterates.qp,
        &mut y,
        400,
        1e-12,
        &mut iterations,
        &mut meter,
        penalty,
    );
    (outcome, y)
}

/// Every row (control bounds, unpruned keep-out checks) with its normalised slack at `y`.
fn slacks(tr: &Transcription, y: &Coefficients, mut f: impl FnMut(RowId, f64)) {
    let free = tr.basis.free;
    let mut visit = |id: RowId| {
        let view = tr.view(id).unwrap();
        if view.norm > 0.0 {
            f(id, (row_dot(&view, y, free) - view.rhs) / view.norm);
        }
    };
    for block in 0..tr.blocks() {
        for node in 0..tr.grid.nodes() {
            for upper in [true, false] {
                visit(RowId::Control {
                    block: block as u8,
                    node: node as u8,
                    upper,
                });
            }
        }
    }
    for pair in 0..tr.pair_count {
        for check in 0..tr.check_count[pair] {
            if !tr.checks[pair][check].pruned {
                visit(RowId::KeepOut {
                    pair: pair as u8,
                    check: check as u8,
                });
            }
        }
    }
}

/// The elastic objective `1/2 |y|^2 + rho sum max(0, -slack)`.
fn elastic_objective(tr: &Transcription, y: &Coefficients, rho: f64) -> f64 {
    let mut sum = 0.0;
    for row in y.iter() {
        for v in row.iter() {
            sum += 0.5 * v * v;
        }
    }
    slacks(tr, y, |_, s| sum += rho * (-s).max(0.0));
    sum
}

#[test]
fn a_large_penalty_changes_nothing_on_a_feasible_subproblem() {
    let problem = rest_to_rest(
        &[
            ([0.0, 0.0, 0.0], [12.0, 12.0, 12.0]),
            ([8.0, 0.0, 0.0], [0.0, 12.0, 12.0]),
            ([8.0, 0.0, 8.0], [0.0, 12.0, 0.0]),
        ],
        2.0,
        10,
    );
    let mut ws = Workspace::new();
    first_subproblem(&problem, &mut ws);
    let (exact, y_exact) = solve(&mut ws, f64::INFINITY);
    assert_eq!(exact, QpOutcome::Optimal);
    let size: f64 = y_exact.iter().flatten().map(|v| v * v).sum();
    assert!(size > 1e-6, "the guess itself is the answer: {size}");
    // Far above every multiplier: the same answer, nothing held elastic.
    let (elastic, y_elastic) = solve(&mut ws, 1e6);
    assert_eq!(elastic, QpOutcome::Optimal);
    for (a, b) in y_exact.iter().flatten().zip(y_elastic.iter().flatten()) {
        assert!((a - b).abs() <= 1e-10 * (1.0 + a.abs()), "{a} vs {b}");
    }
    // A small penalty trades the rows against the cost: never above the exact answer's
    // objective (which meets every row), and some row then keeps a slack.
    let rho = 1e-3;
    let (small, y_small) = solve(&mut ws, rho);
    assert_eq!(small, QpOutcome::Elastic);
    let tr = &ws.setup.transcription;
    assert!(elastic_objective(tr, &y_small, rho) <= elastic_objective(tr, &y_exact, rho) + 1e-12);
}

#[test]
fn the_elastic_answer_of_an_infeasible_subproblem_is_a_minimum_of_its_objective() {
    let problem = rest_to_rest(
        &[
            ([11.0, 0.0, 0.0], [-11.0, 0.0, 0.0]),
            ([-11.0, 0.0, 0.0], [11.0, 0.0, 0.0]),
        ],
        20.0,
        12,
    );
    let mut ws = Workspace::new();
    first_subproblem(&problem, &mut ws);
    let (exact, _) = solve(&mut ws, f64::INFINITY);
    assert_eq!(exact, QpOutcome::Infeasible);
    let rho = 10.0;
    let (outcome, y) = solve(&mut ws, rho);
    assert_eq!(outcome, QpOutcome::Elastic);
    let tr = &ws.setup.transcription;
    let mut violated = 0;
    slacks(tr, &y, |_, s| {
        if s < -1e-6 {
            violated += 1;
        }
    });
    assert!(violated > 0);
    // A minimum of the convex elastic objective: no coordinate step of either sign and a
    // range of sizes lowers it (a wrong bound or a missed limit moves the answer off it).
    let f0 = elastic_objective(tr, &y, rho);
    for block in 0..tr.blocks() {
        for k in 0..tr.basis.free {
            for step in [1e-3, -1e-3, 1e-5, -1e-5] {
                let mut trial = y;
                trial[block][k] += step;
                let f = elastic_objective(tr, &trial, rho);
                assert!(
                    f >= f0 - 1e-9 * (1.0 + f0),
                    "block {block} k {k} step {step}: {f} < {f0}"
                );
            }
        }
    }
}
