//! The scan's pair bounds (`qp_scan::ScanBounds`): the norm it divides by is each row's own,
//! and a pair it skips holds no row the QP could take.
#![allow(clippy::indexing_slicing, clippy::unwrap_used, clippy::expect_used)]

use crate::capacity::MAX_FREE_PER_AXIS;
use crate::pseudospectral::kernel::{dot, Coefficients, MAX_BLOCKS};
use crate::pseudospectral::qp;
use crate::pseudospectral::qp_state::QpOutcome;
use crate::pseudospectral::test_problems::first_subproblem;
use crate::pseudospectral::transcription::{row_axpy, row_dot, RowId};
use crate::pseudospectral::{Problem, Settings, Workspace};
use crate::work::Meter;

/// Two spacecraft crossing at the centre and two far away on parallel lanes (the far pairs
/// keep a wide margin, so their bounds let the scan skip them), masses unequal.
fn crossing_and_lanes() -> Problem {
    let mut problem = crate::pseudospectral::test_problems::rest_to_rest(
        &[
            ([-6.0, 0.0, 0.0], [6.0, 0.0, 0.0]),
            ([6.0, 0.5, 0.0], [-6.0, 0.5, 0.0]),
            ([-6.0, 30.0, 0.0], [6.0, 30.0, 0.0]),
            ([-6.0, -30.0, 5.0], [6.0, -30.0, 5.0]),
        ],
        2.0,
        12,
        true,
    );
    for (spacecraft, mass) in problem.spacecraft.iter_mut().zip([1.0, 1.2, 0.8, 1.1]) {
        spacecraft.mass_mu = mass;
    }
    problem
}

#[test]
fn the_scan_norm_is_the_rows_norm() {
    // The bound `slack >= s - |dy|` needs the scan's normalisation to be each row's Euclidean
    // norm: checked against the row written out, for every unpruned check of unequal masses.
    let mut ws = Workspace::new();
    first_subproblem(&crossing_and_lanes(), &mut ws);
    let tr = &ws.setup.transcription;
    let size = (tr.blocks(), tr.basis.free);
    let mut checked = 0;
    for pair in 0..tr.pair_count {
        let geometry = tr.pair(pair).unwrap();
        let (mi, mj) = geometry.masses;
        let mass_factor = libm::sqrt(1.0 / (mi * mi) + 1.0 / (mj * mj));
        for check in 0..tr.check_count[pair] {
            let c = tr.checks[pair][check];
            if c.pruned {
                continue;
            }
            let (_, row_norm) = tr.check_row(c.source).unwrap();
            let scan_norm = row_norm * mass_factor;
            let view = tr
                .view(RowId::KeepOut {
                    pair: pair as u8,
                    check: check as u8,
                })
                .unwrap();
            let mut row: Coefficients = [[0.0; MAX_FREE_PER_AXIS]; MAX_BLOCKS];
            row_axpy(&view, 1.0, &mut row, tr.basis.free);
            let euclid = libm::sqrt(dot(&row, &row, size));
            assert!(
                (scan_norm - euclid).abs() <= 1e-12 * euclid,
                "pair {pair} check {check}: scan {scan_norm}, row {euclid}"
            );
            checked += 1;
        }
    }
    assert!(checked > 20, "{checked} checks");
}

#[test]
fn a_skipped_pair_holds_no_violated_row() {
    // After the QP, every pair with a known bound has each candidate row's slack at the
    // answer at least its bound less the distance moved since; and the far pairs are skipped.
    let mut ws = Workspace::new();
    first_subproblem(&crossing_and_lanes(), &mut ws);
    let mut y = [[0.0; MAX_FREE_PER_AXIS]; MAX_BLOCKS];
    let (mut iterations, mut meter) = (0u32, Meter::new(u64::MAX));
    ws.iterates.qp.reset();
    let tol = Settings::default().qp_tol_feas;
    let outcome = qp::solve(
        &ws.setup.transcription,
        &mut ws.iterates.qp,
        &mut y,
        400,
        tol,
        &mut iterations,
        &mut meter,
        f64::INFINITY,
    );
    assert_eq!(outcome, QpOutcome::Optimal);
    let (tr, state) = (&ws.setup.transcription, &ws.iterates.qp);
    let bounds = &state.scan_bounds;
    assert!(bounds.moved > 0.0, "the QP moved y: {}", bounds.moved);
    let mut skipped = 0;
    for pair in 0..tr.pair_count {
        if !bounds.known[pair] {
            continue;
        }
        let bound = bounds.pairs[pair] - bounds.moved;
        if bound > tol {
            skipped += 1;
        }
        for check in 0..tr.check_count[pair] {
            let id = RowId::KeepOut {
                pair: pair as u8,
                check: check as u8,
            };
            if tr.checks[pair][check].pruned || state.is_active(id) || state.is_elastic(id) {
                continue;
            }
            let view = tr.view(id).unwrap();
            let slack = (row_dot(&view, &y, tr.basis.free) - view.rhs) / view.norm;
            assert!(
                slack >= bound - 1e-12 * (1.0 + bound.abs()),
                "pair {pair} check {check}: slack {slack} below its bound {bound}"
            );
        }
    }
    // The four lanes' far pairs (all but the crossing pair and its near neighbours).
    assert!(skipped >= 3, "{skipped} pairs skipped");
    // Forgetting a row's pair makes the next scan evaluate it again.
    let mut forgetting = *bounds;
    forgetting.forget_row(RowId::KeepOut { pair: 5, check: 0 });
    assert!(!forgetting.known[5]);
    assert!(
        forgetting.checks_to_scan(tr, tol) >= bounds.checks_to_scan(tr, tol),
        "forgetting never scans less"
    );
}
