//! Setting up a solve: the LGL grid, basis, base cubics, pairs, pruning windows and check
//! points (eq. 23, 27), and the first linearisation point (the analytic guess or a warm start).

use super::collision;
use super::guess::{self, tracks};
use super::kernel::{per_axis, u8_of, MAX_BLOCKS};
use super::problem::Problem;
use super::settings::Settings;
use super::solution::Solution;
use super::status::Stage;
use super::swerve;
use super::transcription::Transcription;
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
    // Each spacecraft's three axis laws beside its three blocks of base positions and controls.
    let horizon = tr.horizon_tu;
    let blocks = tr
        .base_position
        .chunks_exact_mut(3)
        .zip(tr.base_control.chunks_exact_mut(3));
    for (laws, (positions, controls)) in ws.setup.laws.iter().zip(blocks).take(m) {
        for (law, (position_row, control_row)) in laws
            .iter()
            .zip(positions.iter_mut().zip(controls.iter_mut()))
        {
            let cubic = guess::unconstrained(law.boundary);
            let nodal = position_row.iter_mut().zip(control_row.iter_mut());
            for ((position, control), tau) in nodal.zip(tr.grid.taus()) {
                // `Transcription::time_of` (the transcription's rows are borrowed here).
                let t = 0.5 * horizon * (tau + 1.0);
                *position = cubic.cubic_position(t);
                *control = cubic.cubic_control(t);
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
    for control_row in tr.base_control.iter().take(tr.blocks()) {
        for (&u, (_, w)) in control_row.iter().zip(tr.grid.nodes_and_weights()) {
            base_cost += 0.25 * tr.horizon_tu * w * u * u;
        }
    }
    tr.base_cost = base_cost;
    let rows = tr.node_row_norm.iter_mut().zip(tr.basis.position.iter());
    for (slot, row) in rows.take(nodes) {
        *slot = super::transcription::norm(row, tr.basis.free);
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
                let Some(&tau) = tr.grid.tau.get(h) else {
                    return Err(Stage::Transcription);
                };
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
        for (slot, tau) in node_times.iter_mut().zip(tr.grid.taus()) {
            *slot = tr.time_of(tau);
        }
        let Some(node_times) = node_times.get(..nodes) else {
            return Err(Stage::Transcription);
        };
        for pair in 0..tr.pair_count {
            let Some(&(i, j)) = tr.pairs.get(pair) else {
                return Err(Stage::Transcription);
            };
            let (Some(li), Some(lj)) = (
                ws.setup.laws.get(usize::from(i)),
                ws.setup.laws.get(usize::from(j)),
            ) else {
                return Err(Stage::Transcription);
            };
            let (times, count) = collision::test_points(
                &tracks(li),
                &tracks(lj),
                node_times,
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

/// Project a control profile (node values, FU) onto one block's coefficients `target`:
/// `y_b = T/2 sum_h w_h G_h (U_h - U_cubic,h)`, `base_controls` the block's `U_cubic`, the
/// cost-metric projection (exact for a polynomial of degree N that meets the boundary
/// conditions).
pub(super) fn project_controls(
    tr: &Transcription,
    base_controls: &[f64; MAX_NODES],
    controls: &[f64; MAX_NODES],
    target: &mut [f64; MAX_FREE_PER_AXIS],
) {
    let free = tr.basis.free;
    *target = [0.0; MAX_FREE_PER_AXIS];
    let nodal = tr
        .grid
        .nodes_and_weights()
        .zip(controls.iter().zip(base_controls.iter()))
        .zip(tr.basis.accel.iter());
    for (((_, w), (&u, &base)), row) in nodal {
        let du = u - base;
        let scale = 0.5 * tr.horizon_tu * w * du;
        for (slot, g) in target.iter_mut().zip(row.iter()).take(free) {
            *slot += scale * g;
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
    // Each spacecraft's three blocks with their base controls, its axis laws and its mass.
    let spacecraft = ws
        .iterates
        .iterate
        .chunks_exact_mut(3)
        .zip(tr.base_control.chunks_exact(3))
        .zip(ws.setup.laws.iter())
        .zip(tr.mass.iter())
        .take(tr.spacecraft);
    for (sc, (((targets, base_controls), laws), &mass)) in spacecraft.indexed() {
        let warm_nodes = warm.and_then(|previous| previous.controls_fu.get(sc));
        let axes = targets
            .iter_mut()
            .zip(base_controls.iter())
            .zip(laws.iter());
        for (axis, (((target, base), law), &amplitude)) in axes.zip(lift.iter()).indexed() {
            let mut controls = [0.0; MAX_NODES];
            for (h, (slot, tau)) in controls
                .iter_mut()
                .zip(tr.grid.taus())
                .take(nodes)
                .indexed()
            {
                // The warm start's control (the solve checked its size), else the guess's.
                let warm_control = warm_nodes
                    .and_then(|nodes| nodes.get(h))
                    .and_then(|u| u.get(axis));
                *slot = match warm_control {
                    Some(&u) => u,
                    None => law.control(tr.time_of(tau)),
                };
                if amplitude != 0.0 {
                    let side = if sc % 2 == 0 { amplitude } else { -amplitude };
                    *slot += mass * rate * rate * tr.keep_out_lu * side * (12.0 * tau * tau - 4.0);
                }
            }
            project_controls(tr, base, &controls, target);
        }
    }
    out.info.warm_start_used = warm.is_some();
    swerve::choose_fallback_directions(ws);
}
