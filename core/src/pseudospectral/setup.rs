//! Setting up a solve: the LGL grid, basis, base cubics, pairs, pruning windows and check
//! points (eq. 23, 27), and the first linearisation point (the analytic guess or a warm start).

use super::collision;
use super::guess::{self, tracks};
use super::kernel::{per_axis, u8_of, Coefficients, MAX_BLOCKS};
use super::problem::Problem;
use super::settings::Settings;
use super::solution::Solution;
use super::status::Stage;
use super::swerve;
use super::transcription::{node_value, Transcription};
use super::workspace::Workspace;
use crate::capacity::{
    MAX_FREE_PER_AXIS, MAX_NODES, MAX_PAIRS, MAX_SPACECRAFT, TEST_POINTS_PER_PAIR,
};
use crate::indexed::IndexedExt as _;

/// Build the grid, basis, base cubics, pairs, pruning windows and check points. The test-point
/// times per pair go straight into the solution's `test_times` (no workspace copy).
pub(super) fn setup(
    problem: &Problem,
    settings: &Settings,
    ws: &mut Workspace,
    test_times: &mut [[f64; TEST_POINTS_PER_PAIR]; MAX_PAIRS],
) -> Result<(), Stage> {
    let n = usize::from(problem.degree);
    let m = problem.spacecraft.len();
    let tr = &mut ws.setup.transcription;
    if !tr.grid.build(n, settings.newton_max_iter) {
        return Err(Stage::Transcription);
    }
    // The basis's square work array is the (idle) Anderson memory: no buffer of its own.
    let Some(scratch) = ws.iterates.anderson.setup_scratch() else {
        return Err(Stage::Basis);
    };
    if !tr.basis.build(&tr.grid, problem.horizon_tu, scratch) {
        return Err(Stage::Basis);
    }
    if !ws.setup.bernstein.build(&tr.grid) {
        return Err(Stage::Transcription);
    }
    tr.horizon_tu = problem.horizon_tu;
    tr.max_control_fu = problem.max_control_fu;
    tr.keep_out_lu = problem.keep_out_lu;
    tr.keep_out_active_lu = problem.keep_out_lu + settings.keep_out_margin_lu;
    tr.spacecraft = m;
    tr.mass = [1.0; MAX_SPACECRAFT];
    for (slot, craft) in tr.mass.iter_mut().zip(problem.spacecraft.iter()) {
        *slot = craft.mass_mu;
    }
    let nodes = tr.grid.nodes();
    tr.base_position = [[0.0; MAX_NODES]; MAX_BLOCKS];
    tr.base_control = [[0.0; MAX_NODES]; MAX_BLOCKS];
    for sc in 0..m {
        for axis in 0..3 {
            let Some(law) = ws.setup.laws.get(sc).and_then(|row| row.get(axis)) else {
                continue;
            };
            let cubic = guess::unconstrained(law.boundary);
            let block = sc.saturating_mul(3).saturating_add(axis);
            for h in 0..nodes {
                let t = tr.time_of(tr.grid.at(h));
                if let Some(slot) = tr.base_position.get_mut(block).and_then(|r| r.get_mut(h)) {
                    *slot = cubic.cubic_position(t);
                }
                if let Some(slot) = tr.base_control.get_mut(block).and_then(|r| r.get_mut(h)) {
                    *slot = cubic.cubic_control(t);
                }
            }
        }
    }
    // The exact ends: the cubic meets them to rounding; pin them so the boundary is exact.
    for (rows, craft) in tr
        .base_position
        .chunks_exact_mut(3)
        .zip(problem.spacecraft.iter())
    {
        let ends = per_axis(&craft.initial_state)
            .into_iter()
            .zip(per_axis(&craft.final_state));
        for (row, ((start, _), (end, _))) in rows.iter_mut().zip(ends) {
            if let Some(first) = row.first_mut() {
                *first = start;
            }
            if let Some(last) = row.get_mut(n) {
                *last = end;
            }
        }
    }
    let mut base_cost = 0.0;
    for block in 0..tr.blocks() {
        for h in 0..nodes {
            let u = node_value(&tr.base_control, block, h);
            base_cost +=
                0.25 * tr.horizon_tu * tr.grid.weight.get(h).copied().unwrap_or(0.0) * u * u;
        }
    }
    tr.base_cost = base_cost;
    for h in 0..nodes {
        let norm = match tr.basis.position.get(h) {
            Some(row) => super::transcription::norm(row, tr.basis.free),
            None => 0.0,
        };
        if let Some(slot) = tr.node_row_norm.get_mut(h) {
            *slot = norm;
        }
    }
    // Pairs, pruning windows (eq. 23) and checks at every node.
    tr.pair_count = 0;
    tr.point_count = 0;
    tr.moving_check = [None; MAX_PAIRS];
    tr.moving_from = [None; MAX_PAIRS];
    tr.margin = [0.0; MAX_PAIRS];
    ws.verification.verify_points = [0; MAX_PAIRS];
    tr.check_count = [0; MAX_PAIRS];
    for i in 0..m {
        for j in (i.saturating_add(1))..m {
            let pair = tr.pair_count;
            if pair >= MAX_PAIRS {
                return Err(Stage::Transcription);
            }
            if let Some(slot) = tr.pairs.get_mut(pair) {
                *slot = (u8_of(i), u8_of(j));
            }
            let (Some(a), Some(b)) = (problem.spacecraft.get(i), problem.spacecraft.get(j)) else {
                return Err(Stage::Transcription);
            };
            let accel =
                libm::sqrt(3.0) * problem.max_control_fu * (1.0 / a.mass_mu + 1.0 / b.mass_mu);
            // Relative position and velocity of a and b.
            let relative = |x: &[f64; 6], y: &[f64; 6]| {
                let (p, q) = (per_axis(x), per_axis(y));
                (
                    [p[0].0 - q[0].0, p[1].0 - q[1].0, p[2].0 - q[2].0],
                    [p[0].1 - q[0].1, p[1].1 - q[1].1, p[2].1 - q[2].1],
                )
            };
            let (r0, v0) = relative(&a.initial_state, &b.initial_state);
            let start = collision::earliest_contact(r0, v0, accel, problem.keep_out_lu);
            let (r1, v1) = relative(&a.final_state, &b.final_state);
            let before_end = collision::earliest_contact(r1, v1, accel, problem.keep_out_lu);
            if let Some(slot) = tr.window.get_mut(pair) {
                *slot = (start, problem.horizon_tu - before_end);
            }
            tr.pair_count = pair.saturating_add(1);
            for h in 0..nodes {
                let tau = tr.grid.at(h);
                if !tr.add_check(pair, tau) {
                    return Err(Stage::Transcription);
                }
            }
        }
    }
    // Gaussian test points (eq. 27) on the analytic trajectories.
    *test_times = [[0.0; TEST_POINTS_PER_PAIR]; MAX_PAIRS];
    if problem.test_points {
        let mut node_times = [0.0; MAX_NODES];
        for (h, slot) in node_times.iter_mut().indexed().take(nodes) {
            *slot = tr.time_of(tr.grid.at(h));
        }
        for pair in 0..tr.pair_count {
            let (i, j) = tr.pairs.get(pair).copied().unwrap_or((0, 0));
            let (Some(li), Some(lj)) = (
                ws.setup.laws.get(usize::from(i)),
                ws.setup.laws.get(usize::from(j)),
            ) else {
                continue;
            };
            let (times, count) = collision::test_points(
                &tracks(li),
                &tracks(lj),
                node_times.get(..nodes).unwrap_or(&[]),
                problem.horizon_tu,
                settings.refine_max_iter,
            );
            if let Some(slot) = test_times.get_mut(pair) {
                *slot = times;
            }
            for &t in times.iter().take(count) {
                let tau = tr.tau_of(t);
                if !tr.add_check(pair, tau) {
                    return Err(Stage::Transcription);
                }
            }
        }
    }
    Ok(())
}

/// Project a control profile (node values, FU) onto the coefficients: `y_b = T/2 sum_h w_h
/// G_h (U_h - U_cubic,h)`, the cost-metric projection (exact for a polynomial of degree N that
/// meets the boundary conditions).
pub(super) fn project_controls(
    tr: &Transcription,
    block: usize,
    controls: &[f64; MAX_NODES],
    y: &mut Coefficients,
) {
    let free = tr.basis.free;
    let Some(target) = y.get_mut(block) else {
        return;
    };
    *target = [0.0; MAX_FREE_PER_AXIS];
    for h in 0..tr.grid.nodes() {
        let w = tr.grid.weight.get(h).copied().unwrap_or(0.0);
        let du = controls.get(h).copied().unwrap_or(0.0) - node_value(&tr.base_control, block, h);
        let scale = 0.5 * tr.horizon_tu * w * du;
        if let Some(row) = tr.basis.accel.get(h) {
            for (slot, g) in target.iter_mut().zip(row.iter()).take(free) {
                *slot += scale * g;
            }
        }
    }
}

/// The first linearisation point: the warm start, or the analytic Pontryagin trajectories,
/// with every spacecraft's path lifted by `lift[axis] d (1 - tau^2)^2` on each axis, the sign
/// alternating from one spacecraft to the next (`lift` = 0: no lift; an alternative start, see
/// `solve_with_alternative_starts`). The bump keeps the boundary positions and velocities, and
/// its control `m (2/T)^2 d (12 tau^2 - 4)` is a polynomial the basis spans, so the projection
/// is exact. Also chooses each pair's fallback direction for the linearisation where the
/// analytic trajectories pass through each other (the normal is undefined there).
pub(super) fn initial_iterate(
    ws: &mut Workspace,
    warm: Option<&Solution>,
    lift: [f64; 3],
    out: &mut Solution,
) {
    let tr = &ws.setup.transcription;
    let rate = 2.0 / tr.horizon_tu;
    let nodes = tr.grid.nodes();
    ws.iterates.iterate = [[0.0; MAX_FREE_PER_AXIS]; MAX_BLOCKS];
    for sc in 0..tr.spacecraft {
        for (axis, &amplitude) in lift.iter().indexed() {
            let block = sc.saturating_mul(3).saturating_add(axis);
            let mut controls = [0.0; MAX_NODES];
            for (h, slot) in controls.iter_mut().indexed().take(nodes) {
                *slot = match warm {
                    Some(previous) => previous
                        .controls_fu
                        .get(sc)
                        .and_then(|row| row.get(h))
                        .and_then(|u| u.get(axis))
                        .copied()
                        .unwrap_or(0.0),
                    None => match ws.setup.laws.get(sc).and_then(|row| row.get(axis)) {
                        Some(law) => law.control(tr.time_of(tr.grid.at(h))),
                        None => 0.0,
                    },
                };
                if amplitude != 0.0 {
                    let tau = tr.grid.at(h);
                    let side = if sc % 2 == 0 { amplitude } else { -amplitude };
                    *slot += tr.mass_of(sc)
                        * rate
                        * rate
                        * tr.keep_out_lu
                        * side
                        * (12.0 * tau * tau - 4.0);
                }
            }
            project_controls(tr, block, &controls, &mut ws.iterates.iterate);
        }
    }
    out.info.warm_start_used = warm.is_some();
    swerve::choose_fallback_directions(ws);
}
