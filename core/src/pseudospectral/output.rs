//! Writing the returned trajectory and checking it: states, controls, cost, the verified
//! continuous separation, the largest violations and the dynamics check (eq. 29).

use super::kernel::per_axis;
use super::linearise::{block_positions, pair_minimum};
use super::settings::Settings;
use super::solution::Solution;
use super::transcription::{block_dot, Transcription};
use super::workspace::Workspace;
use crate::capacity::{MAX_NODES, MAX_SPACECRAFT};
use crate::indexed::IndexedExt as _;
use crate::vec3;

/// A node control may exceed Umax by this fraction of Umax and still count as within the bound
/// (the QP's own tolerance is 1e-12 of a row norm).
pub(crate) const CONTROL_TOL_REL: f64 = 1e-9;

/// The dynamics check (eq. 29) must be below this times (1 + the largest state magnitude).
pub(crate) const DYNAMICS_TOL_REL: f64 = 1e-8;

/// Largest excess of a node control over Umax (negative when all are inside).
pub(super) fn control_excess(out: &Solution, max_control_fu: f64) -> f64 {
    let mut worst = f64::NEG_INFINITY;
    let m = usize::from(out.spacecraft_count);
    let nodes = usize::from(out.degree).saturating_add(1);
    for sc in out.controls_fu.iter().take(m) {
        for node in sc.iter().take(nodes) {
            for u in node {
                worst = worst.max(libm::fabs(*u) - max_control_fu);
            }
        }
    }
    worst
}

/// Largest magnitude of any returned state component.
pub(super) fn state_scale(out: &Solution) -> f64 {
    let m = usize::from(out.spacecraft_count);
    let nodes = usize::from(out.degree).saturating_add(1);
    let mut largest = 0.0f64;
    for sc in out.states.iter().take(m) {
        for node in sc.iter().take(nodes) {
            for v in node {
                largest = largest.max(libm::fabs(*v));
            }
        }
    }
    largest
}

/// Write states, controls, cost, verified separation and the dynamics check into `out`.
/// Returns whether every pair's continuous separation is at least `d - verify_tol`.
pub(super) fn write_solution(ws: &mut Workspace, settings: &Settings, out: &mut Solution) -> bool {
    let mut verified = true;
    let mut least = f64::INFINITY;
    let pairs = ws.setup.transcription.pairs;
    for (pair, &pair_ids) in pairs
        .iter()
        .take(ws.setup.transcription.pair_count)
        .indexed()
    {
        // A pair whose minimum cannot be searched (never: the index is a pair's) is unverified.
        let Some(minimum) = pair_minimum(ws, pair, settings) else {
            verified = false;
            continue;
        };
        let separation = libm::sqrt(minimum.value_squared.max(0.0));
        if !minimum.certified
            || separation < ws.setup.transcription.keep_out_lu - settings.verify_tol_lu
        {
            verified = false;
        }
        if separation < least {
            least = separation;
            out.min_separation_lu = Some(separation);
            out.min_separation_pair = pair_ids;
            out.min_separation_time_tu = minimum.at_s * ws.setup.transcription.horizon_tu;
        }
    }
    // No pair (one spacecraft): no separation, absent (not infinite: issue 29, finite answers).
    if ws.setup.transcription.pair_count == 0 {
        out.min_separation_lu = None;
        out.min_separation_pair = (0, 0);
        out.min_separation_time_tu = 0.0;
    }
    let tr = &ws.setup.transcription;
    let nodes = tr.grid.nodes();
    let scale = 2.0 / tr.horizon_tu;
    for (slot, tau) in out.node_times_tu.iter_mut().zip(tr.grid.taus()) {
        *slot = tr.time_of(tau);
    }
    let mut cost = 0.0;
    // Each spacecraft's three blocks (coefficients, base positions and controls) and its mass.
    let spacecraft = ws
        .iterates
        .iterate
        .chunks_exact(3)
        .zip(tr.base_position.chunks_exact(3))
        .zip(tr.base_control.chunks_exact(3))
        .zip(tr.mass.iter())
        .take(tr.spacecraft);
    for (sc, (((y3, base3), control3), &mass)) in spacecraft.indexed() {
        let axes = y3.iter().zip(base3.iter()).zip(control3.iter());
        for (axis, ((values, base), base_controls)) in axes.indexed() {
            let mut positions = [0.0; MAX_NODES];
            block_positions(tr, values, base, mass, &mut positions);
            let mut velocities = [0.0; MAX_NODES];
            tr.grid.differentiate(&positions, &mut velocities);
            // Every node's row, weight, base control, position and velocity together (`nodes`
            // <= MAX_NODES).
            let node_values = tr.basis.accel.iter().zip(tr.grid.weight.iter());
            let node_states = positions.iter().zip(velocities.iter());
            for (h, (((row, &w), &base_control), (&position, &velocity))) in node_values
                .zip(base_controls.iter())
                .zip(node_states)
                .take(nodes)
                .indexed()
            {
                let control = base_control + block_dot(row, values, tr.basis.free);
                cost += 0.25 * tr.horizon_tu * w * control * control;
                if let Some(state) = out.states.get_mut(sc).and_then(|row| row.get_mut(h)) {
                    if let Some(p) = state.get_mut(axis) {
                        *p = position;
                    }
                    if let Some(v) = state.get_mut(axis.saturating_add(3)) {
                        *v = scale * velocity;
                    }
                }
                if let Some(u) = out
                    .controls_fu
                    .get_mut(sc)
                    .and_then(|row| row.get_mut(h))
                    .and_then(|node| node.get_mut(axis))
                {
                    *u = control;
                }
            }
        }
    }
    out.cost = cost;
    // Largest violation of a checked constraint.
    let mut violation = 0.0f64;
    let pair_checks = tr
        .checks
        .iter()
        .zip(tr.check_count.iter())
        .take(tr.pair_count);
    for (pair, (checks, &count)) in pair_checks.clone().indexed() {
        let Some(geometry) = tr.pair(pair) else {
            continue;
        };
        for check in checks.iter().take(count) {
            if check.pruned {
                continue;
            }
            if let Some(relative) = tr.relative(&geometry, check.source, &ws.iterates.iterate) {
                violation = violation.max(tr.keep_out_lu - vec3::norm(&relative));
            }
        }
    }
    for sc in out.controls_fu.iter().take(tr.spacecraft) {
        for node in sc.iter().take(nodes) {
            for u in node {
                violation = violation.max(libm::fabs(*u) - tr.max_control_fu);
            }
        }
    }
    out.info.max_violation = violation;
    out.info.keep_out_checks = 0;
    for (checks, &count) in pair_checks {
        for check in checks.iter().take(count) {
            if !check.pruned {
                out.info.keep_out_checks = out.info.keep_out_checks.saturating_add(1);
            }
        }
    }
    out.max_dynamics_error = dynamics_error(tr, out);
    verified
}

/// Eq. 29: propagate the true double integrator from the initial state with the interpolated
/// control and compare with the interpolated states, at every node and every midpoint between
/// nodes. The quadrature (LGL on [0, t]) is exact for the polynomial integrands.
///
/// The interpolation rows depend only on the grid and the sample, not on the spacecraft or the
/// axis: each is built once per sample and quadrature node and applied to all 3 M components
/// (the same sums in the same order as interpolating each component on its own, so the figure
/// is bit-identical; the check was about 10 % of the paper case's solve, M = 3, N = 10).
pub(super) fn dynamics_error(tr: &Transcription, out: &Solution) -> f64 {
    let grid = &tr.grid;
    let nodes = grid.nodes();
    let spacecraft = tr.spacecraft.min(MAX_SPACECRAFT);
    let mut worst = 0.0f64;
    let mut row = [0.0; MAX_NODES];
    // Every node and every midpoint between neighbours, in time order.
    let taus = grid.taus();
    let midpoints = taus
        .clone()
        .zip(taus.clone().skip(1))
        .map(|(a, b)| 0.5 * (a + b));
    let samples = taus
        .zip(midpoints.map(Some).chain(core::iter::once(None)))
        .flat_map(|(node, midpoint)| core::iter::once(node).chain(midpoint));
    for tau in samples {
        let t = tr.time_of(tau);
        // int_0^t u(s) ds and int_0^t (t - s) u(s) ds by LGL quadrature on [0, t], per
        // spacecraft and axis.
        let mut first = [[0.0; 3]; MAX_SPACECRAFT];
        let mut second = [[0.0; 3]; MAX_SPACECRAFT];
        for (tau_q, weight_q) in grid.nodes_and_weights() {
            let s = 0.5 * t * (tau_q + 1.0);
            let w = 0.5 * t * weight_q;
            grid.lagrange_row(tr.tau_of(s), &mut row);
            for ((f, g), controls) in first
                .iter_mut()
                .zip(second.iter_mut())
                .zip(out.controls_fu.iter())
                .take(spacecraft)
            {
                // The interpolated control on each axis: `sum_h row[h] u_h`.
                let mut u = [0.0; 3];
                for (l, node) in row.iter().zip(controls.iter()).take(nodes) {
                    for (ua, c) in u.iter_mut().zip(node.iter()) {
                        *ua += l * c;
                    }
                }
                for ((fa, ga), ua) in f.iter_mut().zip(g.iter_mut()).zip(u) {
                    *fa += w * ua;
                    *ga += w * (t - s) * ua;
                }
            }
        }
        grid.lagrange_row(tau, &mut row);
        for (((f, g), states), &mass) in first
            .iter()
            .zip(second.iter())
            .zip(out.states.iter())
            .zip(tr.mass.iter())
            .take(spacecraft)
        {
            // The interpolated state: `sum_h row[h] state_h`, every component.
            let mut interpolated = [0.0; 6];
            for (l, state) in row.iter().zip(states.iter()).take(nodes) {
                for (sum, v) in interpolated.iter_mut().zip(state.iter()) {
                    *sum += l * v;
                }
            }
            let [start, ..] = states;
            let axes = per_axis(start).into_iter().zip(per_axis(&interpolated));
            for ((fa, ga), ((x0, v0), (interpolated_x, interpolated_v))) in
                f.iter().zip(g.iter()).zip(axes)
            {
                let propagated_v = v0 + fa / mass;
                let propagated_x = x0 + v0 * t + ga / mass;
                worst = worst
                    .max(libm::fabs(propagated_x - interpolated_x))
                    .max(libm::fabs(propagated_v - interpolated_v));
            }
        }
    }
    worst
}
