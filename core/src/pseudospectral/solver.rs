//! The planner-A solve: set up the transcription, run the convex-concave sequence of QPs,
//! verify the separation on the continuous trajectory, refine, and write the solution.

use super::certificate;
use super::collision;
use super::error::{PlanError, Quantity};
use super::guess::{self, AxisBoundary, AxisLaw, GuessError};
use super::problem::Problem;
use super::qp::{self, QpOutcome};
use super::settings::Settings;
use super::solution::Solution;
use super::status::{SolveStatus, Stage};
use super::transcription::{block_dot, node_value, Coefficients, Transcription, MAX_BLOCKS};
use super::validate;
use super::verify::{Minimum, MAX_PRODUCT};
use super::workspace::Workspace;
use crate::capacity::{
    MAX_FREE_PER_AXIS, MAX_NODES, MAX_PAIRS, MAX_SPACECRAFT, TEST_POINTS_PER_PAIR,
};

/// How the SQP loop ended.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum SqpEnd {
    Converged,
    MaxIterations,
    Failed(SolveStatus),
}

fn u8_of(value: usize) -> u8 {
    u8::try_from(value).unwrap_or(u8::MAX)
}

fn norm3(v: &[f64; 3]) -> f64 {
    libm::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2])
}

/// Entry point behind `solve` and `solve_warm`.
pub(crate) fn solve(
    problem: &Problem,
    settings: &Settings,
    ws: &mut Workspace,
    warm: Option<&Solution>,
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
                if node.iter().any(|v| !v.is_finite()) {
                    return Err(PlanError::NotFinite {
                        what: Quantity::WarmStart,
                        spacecraft: 0,
                    });
                }
            }
        }
    }
    // The analytic guess per axis (eq. 24-26); an unreachable axis rejects the request.
    let mut laws = [[AxisLaw::default(); 3]; MAX_SPACECRAFT];
    for (sc, craft) in problem.spacecraft.iter().enumerate() {
        for axis in 0..3 {
            let boundary = AxisBoundary {
                p0: craft.initial_state.get(axis).copied().unwrap_or(0.0),
                v0: craft
                    .initial_state
                    .get(axis.saturating_add(3))
                    .copied()
                    .unwrap_or(0.0),
                p1: craft.final_state.get(axis).copied().unwrap_or(0.0),
                v1: craft
                    .final_state
                    .get(axis.saturating_add(3))
                    .copied()
                    .unwrap_or(0.0),
                horizon: problem.horizon_tu,
                mass: craft.mass_mu,
                max_control: problem.max_control_fu,
            };
            let law = match guess::solve_axis(boundary, settings.newton_max_iter) {
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
            if let Some(slot) = laws.get_mut(sc).and_then(|row| row.get_mut(axis)) {
                *slot = law;
            }
        }
    }
    ws.laws = laws;
    out.reset();
    out.degree = problem.degree;
    out.spacecraft_count = u8_of(m);
    out.horizon_tu = problem.horizon_tu;
    let status = run(problem, settings, ws, warm, out);
    out.info.status = status;
    Ok(())
}

/// Set up and iterate; returns the final status. `out` receives the solution in every case.
fn run(
    problem: &Problem,
    settings: &Settings,
    ws: &mut Workspace,
    warm: Option<&Solution>,
    out: &mut Solution,
) -> SolveStatus {
    ws.qp.reset();
    if let Err(stage) = setup(problem, settings, ws) {
        return SolveStatus::NumericalFailure(stage);
    }
    initial_iterate(ws, warm, out);
    let mut end = iterate_and_verify(ws, settings, out);
    let mut direction = [[0.0; MAX_FREE_PER_AXIS]; MAX_BLOCKS];
    let mut status = finish(ws, settings, out, end, &mut direction);
    // Saddle escape: a feasible first-order point with negative reduced curvature is left
    // along the curvature direction (deterministic: a fixed power-method start and sign), and
    // the iteration resumes; the better verified answer is kept.
    let mut escapes = 0u8;
    while escapes < MAX_SADDLE_ESCAPES && is_saddle(status, end, out) {
        escapes = escapes.saturating_add(1);
        out.info.saddle_escapes = escapes;
        let saddle_cost = out.cost;
        ws.saved = ws.iterate;
        step_along(ws, &direction);
        end = iterate_and_verify(ws, settings, out);
        status = finish(ws, settings, out, end, &mut direction);
        if !status.is_usable() || out.cost >= saddle_cost {
            // No better: return to the saddle's answer (a fixed point: it re-converges at once).
            ws.iterate = ws.saved;
            end = iterate_and_verify(ws, settings, out);
            status = finish(ws, settings, out, end, &mut direction);
            break;
        }
    }
    status
}

/// Most saddle escapes per solve (each one more run of the iteration and verification rounds).
pub(crate) const MAX_SADDLE_ESCAPES: u8 = 2;

/// A feasible, stationary point whose reduced Hessian has a negative eigenvalue.
fn is_saddle(status: SolveStatus, end: SqpEnd, out: &Solution) -> bool {
    let c = &out.certificate;
    status == SolveStatus::Feasible
        && end == SqpEnd::Converged
        && c.second_order_evaluated
        && c.stationarity <= certificate::STATIONARITY_TOL
        && c.min_reduced_eigenvalue < -certificate::CURVATURE_TOL
}

/// `y <- y + alpha v` with `v` the unit negative-curvature direction, signed so that its
/// largest component is positive (deterministic), and `alpha` a quarter of `|y|` (at least
/// 0.1): large enough to leave the saddle's neighbourhood, small enough to stay in its basin.
fn step_along(ws: &mut Workspace, direction: &Coefficients) {
    let mut largest = 0.0f64;
    let mut norm2 = 0.0;
    for (row, values) in direction.iter().zip(ws.iterate.iter()) {
        for (d, y) in row.iter().zip(values.iter()) {
            if libm::fabs(*d) > libm::fabs(largest) {
                largest = *d;
            }
            norm2 += y * y;
        }
    }
    let sign = if largest < 0.0 { -1.0 } else { 1.0 };
    let alpha = sign * (0.25 * libm::sqrt(norm2)).max(0.1);
    for (row, values) in direction.iter().zip(ws.iterate.iter_mut()) {
        for (d, y) in row.iter().zip(values.iter_mut()) {
            *y += alpha * d;
        }
    }
}

/// The convex-concave iteration from `ws.iterate`, with the continuous verification rounds.
fn iterate_and_verify(ws: &mut Workspace, settings: &Settings, out: &mut Solution) -> SqpEnd {
    let tr = &ws.transcription;
    let d = tr.keep_out_lu;
    let mut end;
    let mut rounds: u8 = 0;
    loop {
        end = sqp(ws, settings, out);
        if let SqpEnd::Failed(_) = end {
            break;
        }
        if rounds >= settings.verify_max_rounds || !settings.continuous_verification {
            break;
        }
        // Continuous verification: add a check where a pair dips below d, then re-solve.
        // Changes this round: points added, and margins raised.
        let mut added = 0u16;
        let mut points = 0u16;
        for pair in 0..ws.transcription.pair_count {
            let minimum = pair_minimum(ws, pair, settings);
            let separation = libm::sqrt(minimum.value_squared.max(0.0));
            if separation < d - settings.verify_tol_lu {
                // A dip the moving check did not catch (a second local minimum): check it too.
                // Where the pair already had one and still dips, the dip sits between closely
                // spaced checks: raise the pair's keep-out by its depth, which lifts the
                // continuous minimum by about as much (the dips are then ~1e-4 d or less, so the
                // cost moves by parts per million).
                let tau = 2.0 * minimum.at_s - 1.0;
                let tr = &mut ws.transcription;
                let refined_before = tr.verify_points.get(pair).copied().unwrap_or(0) > 0;
                if refined_before {
                    if let Some(margin) = tr.margin.get_mut(pair) {
                        *margin += d - separation;
                    }
                    added = added.saturating_add(1);
                }
                if tr.add_check(pair, tau) {
                    if let Some(count) = tr.verify_points.get_mut(pair) {
                        *count = count.saturating_add(1);
                    }
                    added = added.saturating_add(1);
                    points = points.saturating_add(1);
                }
            }
        }
        if added == 0 {
            break;
        }
        rounds = rounds.saturating_add(1);
        out.info.verify_rounds = rounds;
        out.info.verify_points_added = out.info.verify_points_added.saturating_add(points);
    }
    end
}

/// Write the solution, check its feasibility, evaluate its certificate, and return its status.
/// `direction` receives the certificate's negative-curvature direction.
fn finish(
    ws: &mut Workspace,
    settings: &Settings,
    out: &mut Solution,
    end: SqpEnd,
    direction: &mut Coefficients,
) -> SolveStatus {
    let verified = write_solution(ws, settings, out);
    // Feasibility is checked on the returned trajectory itself, whatever the iteration says.
    let control_excess = control_excess(out, ws.transcription.max_control_fu);
    let separation_deficit = ws.transcription.keep_out_lu - out.min_separation_lu;
    out.certificate.max_violation = control_excess.max(separation_deficit).max(0.0);
    let feasible = verified
        && control_excess <= CONTROL_TOL_REL * ws.transcription.max_control_fu
        && out.max_dynamics_error <= DYNAMICS_TOL_REL * (1.0 + state_scale(out));
    out.certificate.first_order_evaluated = false;
    out.certificate.second_order_evaluated = false;
    if !matches!(end, SqpEnd::Failed(_)) {
        unit_normals(ws);
        certificate::evaluate(
            &ws.transcription,
            &mut ws.qp,
            &ws.iterate,
            out.cost,
            direction,
            &mut out.certificate,
        );
    }
    let certified = end == SqpEnd::Converged && out.certificate.certifies_local_optimum();
    match end {
        _ if feasible && certified => SolveStatus::Solved,
        _ if feasible => SolveStatus::Feasible,
        SqpEnd::Failed(status) => status,
        SqpEnd::MaxIterations => SolveStatus::MaxIterations,
        SqpEnd::Converged => SolveStatus::SeparationNotVerified,
    }
}

/// A node control may exceed Umax by this fraction of Umax and still count as within the bound
/// (the QP's own tolerance is 1e-12 of a row norm).
pub(crate) const CONTROL_TOL_REL: f64 = 1e-9;
/// The dynamics check (eq. 29) must be below this times (1 + the largest state magnitude).
pub(crate) const DYNAMICS_TOL_REL: f64 = 1e-8;

/// Largest excess of a node control over Umax (negative when all are inside).
fn control_excess(out: &Solution, max_control_fu: f64) -> f64 {
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
fn state_scale(out: &Solution) -> f64 {
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

/// Build the grid, basis, base cubics, pairs, pruning windows and check points.
fn setup(problem: &Problem, settings: &Settings, ws: &mut Workspace) -> Result<(), Stage> {
    let n = usize::from(problem.degree);
    let m = problem.spacecraft.len();
    let tr = &mut ws.transcription;
    if !tr.grid.build(n, settings.newton_max_iter) {
        return Err(Stage::Transcription);
    }
    if !tr
        .basis
        .build(&tr.grid, problem.horizon_tu, &mut ws.basis_scratch)
    {
        return Err(Stage::Basis);
    }
    if !ws.bernstein.build(&tr.grid) {
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
            let Some(law) = ws.laws.get(sc).and_then(|row| row.get(axis)) else {
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
    for (sc, craft) in problem.spacecraft.iter().enumerate() {
        for axis in 0..3 {
            let block = sc.saturating_mul(3).saturating_add(axis);
            if let Some(row) = tr.base_position.get_mut(block) {
                if let Some(first) = row.first_mut() {
                    *first = craft.initial_state.get(axis).copied().unwrap_or(0.0);
                }
                if let Some(last) = row.get_mut(n) {
                    *last = craft.final_state.get(axis).copied().unwrap_or(0.0);
                }
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
    tr.margin = [0.0; MAX_PAIRS];
    tr.verify_points = [0; MAX_PAIRS];
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
            let part = |s: &[f64; 6], k: usize| s.get(k).copied().unwrap_or(0.0);
            let relative = |x: &[f64; 6], y: &[f64; 6], offset: usize| {
                [
                    part(x, offset) - part(y, offset),
                    part(x, offset.saturating_add(1)) - part(y, offset.saturating_add(1)),
                    part(x, offset.saturating_add(2)) - part(y, offset.saturating_add(2)),
                ]
            };
            let start = collision::earliest_contact(
                relative(&a.initial_state, &b.initial_state, 0),
                relative(&a.initial_state, &b.initial_state, 3),
                accel,
                problem.keep_out_lu,
            );
            let before_end = collision::earliest_contact(
                relative(&a.final_state, &b.final_state, 0),
                relative(&a.final_state, &b.final_state, 3),
                accel,
                problem.keep_out_lu,
            );
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
    ws.test_times = [[0.0; TEST_POINTS_PER_PAIR]; MAX_PAIRS];
    if problem.test_points {
        let mut node_times = [0.0; MAX_NODES];
        for (h, slot) in node_times.iter_mut().enumerate().take(nodes) {
            *slot = tr.time_of(tr.grid.at(h));
        }
        for pair in 0..tr.pair_count {
            let (i, j) = tr.pairs.get(pair).copied().unwrap_or((0, 0));
            let (Some(li), Some(lj)) = (ws.laws.get(usize::from(i)), ws.laws.get(usize::from(j)))
            else {
                continue;
            };
            let (times, count) = collision::test_points(
                li,
                lj,
                node_times.get(..nodes).unwrap_or(&[]),
                problem.horizon_tu,
                settings.refine_max_iter,
            );
            if let Some(slot) = ws.test_times.get_mut(pair) {
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
fn project_controls(
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

/// The first linearisation point: the warm start, or the analytic Pontryagin trajectories.
/// Also chooses each pair's fallback direction for the linearisation where the analytic
/// trajectories pass through each other (the normal is undefined there).
fn initial_iterate(ws: &mut Workspace, warm: Option<&Solution>, out: &mut Solution) {
    let tr = &ws.transcription;
    let nodes = tr.grid.nodes();
    ws.iterate = [[0.0; MAX_FREE_PER_AXIS]; MAX_BLOCKS];
    for sc in 0..tr.spacecraft {
        for axis in 0..3 {
            let block = sc.saturating_mul(3).saturating_add(axis);
            let mut controls = [0.0; MAX_NODES];
            for (h, slot) in controls.iter_mut().enumerate().take(nodes) {
                *slot = match warm {
                    Some(previous) => previous
                        .controls_fu
                        .get(sc)
                        .and_then(|row| row.get(h))
                        .and_then(|u| u.get(axis))
                        .copied()
                        .unwrap_or(0.0),
                    None => match ws.laws.get(sc).and_then(|row| row.get(axis)) {
                        Some(law) => law.control(tr.time_of(tr.grid.at(h))),
                        None => 0.0,
                    },
                };
            }
            project_controls(tr, block, &controls, &mut ws.iterate);
        }
    }
    out.info.warm_start_used = warm.is_some();
    // Fallback directions: perpendicular to the analytic relative velocity at the closest
    // approach, toward the existing miss vector when there is one.
    for pair in 0..tr.pair_count {
        let (i, j) = tr.pairs.get(pair).copied().unwrap_or((0, 0));
        let (Some(li), Some(lj)) = (ws.laws.get(usize::from(i)), ws.laws.get(usize::from(j)))
        else {
            continue;
        };
        let t = collision::closest_approach(li, lj, 0.0, tr.horizon_tu, 60);
        let relative = collision::analytic_relative(li, lj, t);
        let mut velocity = [0.0; 3];
        for (axis, slot) in velocity.iter_mut().enumerate() {
            let (Some(a), Some(b)) = (li.get(axis), lj.get(axis)) else {
                continue;
            };
            *slot = a.state(t).1 - b.state(t).1;
        }
        let direction = perpendicular_direction(&relative, &velocity, None);
        if let Some(slot) = ws.fallback_normal.get_mut(pair) {
            *slot = direction;
        }
    }
}

/// A unit vector perpendicular to `velocity`, along the miss vector `relative` when it is not
/// negligible, else a fixed choice (the coordinate axis least aligned with the velocity, made
/// perpendicular), deterministic per pair.
fn perpendicular_direction(
    relative: &[f64; 3],
    velocity: &[f64; 3],
    fallback: Option<[f64; 3]>,
) -> [f64; 3] {
    let speed = norm3(velocity);
    let unit_v = if speed > 0.0 {
        [
            velocity[0] / speed,
            velocity[1] / speed,
            velocity[2] / speed,
        ]
    } else {
        [0.0, 0.0, 0.0]
    };
    let reject = |v: [f64; 3]| {
        let along = v[0] * unit_v[0] + v[1] * unit_v[1] + v[2] * unit_v[2];
        [
            v[0] - along * unit_v[0],
            v[1] - along * unit_v[1],
            v[2] - along * unit_v[2],
        ]
    };
    let miss = reject(*relative);
    let miss_norm = norm3(&miss);
    if miss_norm > 1e-9 * (1.0 + norm3(relative)) {
        return [
            miss[0] / miss_norm,
            miss[1] / miss_norm,
            miss[2] / miss_norm,
        ];
    }
    if let Some(direction) = fallback {
        let candidate = reject(direction);
        let c_norm = norm3(&candidate);
        if c_norm > 0.5 {
            return [
                candidate[0] / c_norm,
                candidate[1] / c_norm,
                candidate[2] / c_norm,
            ];
        }
    }
    // Head on: pass to the right of the relative velocity, `v x e` with `e` the coordinate axis
    // least aligned with it. For crossings in a plane this is a consistent roundabout: every
    // pair turns the same way, so no pair's choice fights another's.
    let mut axis = 0usize;
    let mut least = f64::INFINITY;
    for (k, component) in unit_v.iter().enumerate() {
        if libm::fabs(*component) < least {
            least = libm::fabs(*component);
            axis = k;
        }
    }
    let mut e = [0.0; 3];
    if let Some(slot) = e.get_mut(axis) {
        *slot = 1.0;
    }
    let right = [
        unit_v[1] * e[2] - unit_v[2] * e[1],
        unit_v[2] * e[0] - unit_v[0] * e[2],
        unit_v[0] * e[1] - unit_v[1] * e[0],
    ];
    let r_norm = norm3(&right);
    if r_norm > 0.0 {
        [right[0] / r_norm, right[1] / r_norm, right[2] / r_norm]
    } else {
        [1.0, 0.0, 0.0]
    }
}

/// Node values of `r_i - r_j` on one axis for the coefficients `y`.
fn relative_nodes(
    tr: &Transcription,
    y: &Coefficients,
    (i, j): (u8, u8),
    axis: usize,
) -> [f64; MAX_NODES] {
    let mut pi = [0.0; MAX_NODES];
    let mut pj = [0.0; MAX_NODES];
    block_positions(
        tr,
        y,
        usize::from(i).saturating_mul(3).saturating_add(axis),
        &mut pi,
    );
    block_positions(
        tr,
        y,
        usize::from(j).saturating_mul(3).saturating_add(axis),
        &mut pj,
    );
    let mut relative = [0.0; MAX_NODES];
    for ((slot, a), b) in relative.iter_mut().zip(pi.iter()).zip(pj.iter()) {
        *slot = a - b;
    }
    relative
}

/// Relative position and velocity of a pair at `tau` on the current iterate.
fn relative_state(ws: &Workspace, pair: usize, tau: f64) -> ([f64; 3], [f64; 3]) {
    let tr = &ws.transcription;
    let (i, j) = tr.pairs.get(pair).copied().unwrap_or((0, 0));
    let mut position = [0.0; 3];
    let mut velocity = [0.0; 3];
    for axis in 0..3 {
        let relative = relative_nodes(tr, &ws.iterate, (i, j), axis);
        let mut derivative = [0.0; MAX_NODES];
        tr.grid.differentiate(&relative, &mut derivative);
        if let Some(slot) = position.get_mut(axis) {
            *slot = tr.grid.interpolate(&relative, tau);
        }
        if let Some(slot) = velocity.get_mut(axis) {
            *slot = 2.0 / tr.horizon_tu * tr.grid.interpolate(&derivative, tau);
        }
    }
    (position, velocity)
}

/// A converged iterate lies within this fraction of d of its linearisation point (so the QP's
/// rows are the constraint gradients there to about this relative accuracy).
const FIXED_POINT_TOL_REL: f64 = 1e-4;

/// Relative depth below the keep-out that counts as violated when linearising.
const LINEARISE_TOL_REL: f64 = 1e-9;

/// Set every check's normal from the current iterate.
///
/// Where a check is feasible at the iterate, the normal is the unit separation:
/// `n . (r_i - r_j) >= d` is then the tangent half-space of the keep-out ball, inside the feasible set, and the
/// iterate satisfies it (the convex-concave procedure: feasible and never more costly).
///
/// Where a check is violated (the first iterate, or a dip found by verification), the unit
/// separation can flip sign along a pass-through, which would demand an along-track jump of 2d
/// between neighbouring checks. There the linearisation is taken about a swerved relative
/// trajectory `dr + d p phi(t)`: `p` the miss direction perpendicular to the relative velocity
/// at the pair's closest approach (a fixed perpendicular when they meet head on), `phi` a bump of
/// the width the pair needs to cover d at its relative speed. Any unit normal gives a valid
/// inner approximation, so this only chooses which side the pair passes on.
fn linearise(ws: &mut Workspace) {
    for pair in 0..ws.transcription.pair_count {
        let tr = &ws.transcription;
        let keep_out = tr.keep_out_for(pair);
        // A check the QP met to its tolerance is feasible, not violated: swerving its normal
        // there would make a fixed point of the iteration that is not a KKT point (the normal
        // must be the unit separation, the constraint's gradient, at a converged iterate).
        let violated_below = keep_out * (1.0 - LINEARISE_TOL_REL);
        let count = tr.check_count.get(pair).copied().unwrap_or(0);
        let mut closest: Option<(f64, f64)> = None;
        for c in 0..count {
            let Some(check) = tr.checks.get(pair).and_then(|row| row.get(c)).copied() else {
                continue;
            };
            let length = norm3(&tr.relative(pair, check.source, &ws.iterate));
            if length < violated_below && closest.is_none_or(|(_, best)| length < best) {
                closest = Some((check.tau, length));
            }
        }
        let swerve = closest.map(|(tau, _)| {
            let (relative, velocity) = relative_state(ws, pair, tau);
            let fallback = ws
                .fallback_normal
                .get(pair)
                .copied()
                .unwrap_or([1.0, 0.0, 0.0]);
            let direction = perpendicular_direction(&relative, &velocity, Some(fallback));
            let speed = norm3(&velocity);
            let width = if speed > 0.0 {
                keep_out / speed
            } else {
                f64::INFINITY
            };
            (ws.transcription.time_of(tau), direction, width)
        });
        let tr = &mut ws.transcription;
        for c in 0..count {
            let Some(check) = tr.checks.get(pair).and_then(|row| row.get(c)).copied() else {
                continue;
            };
            let mut relative = tr.relative(pair, check.source, &ws.iterate);
            let length = norm3(&relative);
            if length < violated_below {
                if let Some((t_star, direction, width)) = swerve {
                    let x = (tr.time_of(check.tau) - t_star) / width;
                    let bump = if width.is_finite() {
                        libm::exp(-x * x)
                    } else {
                        1.0
                    };
                    for (r, p) in relative.iter_mut().zip(direction.iter()) {
                        *r += keep_out * bump * p;
                    }
                }
            }
            let length = norm3(&relative);
            let normal = if length > 0.0 {
                [
                    relative[0] / length,
                    relative[1] / length,
                    relative[2] / length,
                ]
            } else {
                ws.fallback_normal
                    .get(pair)
                    .copied()
                    .unwrap_or([1.0, 0.0, 0.0])
            };
            if let Some(slot) = tr.checks.get_mut(pair).and_then(|row| row.get_mut(c)) {
                slot.normal = normal;
            }
        }
    }
}

/// Set every check's normal to the unit separation at the iterate: the constraint gradients
/// the certificate needs (`linearise` swerves where a check is violated, even by rounding).
fn unit_normals(ws: &mut Workspace) {
    let tr = &mut ws.transcription;
    for pair in 0..tr.pair_count {
        for c in 0..tr.check_count.get(pair).copied().unwrap_or(0) {
            let Some(check) = tr.checks.get(pair).and_then(|row| row.get(c)).copied() else {
                continue;
            };
            let relative = tr.relative(pair, check.source, &ws.iterate);
            let length = norm3(&relative);
            if length > 0.0 {
                if let Some(slot) = tr.checks.get_mut(pair).and_then(|row| row.get_mut(c)) {
                    slot.normal = [
                        relative[0] / length,
                        relative[1] / length,
                        relative[2] / length,
                    ];
                }
            }
        }
    }
}

fn half_norm2(y: &Coefficients, blocks: usize, free: usize) -> f64 {
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
fn sqp(ws: &mut Workspace, settings: &Settings, out: &mut Solution) -> SqpEnd {
    let blocks = ws.transcription.blocks();
    let free = ws.transcription.basis.free;
    let memory = usize::from(settings.acceleration_memory);
    let mut previous_cost = f64::INFINITY;
    ws.anderson.reset();
    ws.accepted = ws.iterate;
    let mut have_solution = false;
    let mut accelerated = false;
    let mut restarted = false;
    let mut previous_decrease = f64::INFINITY;
    for _ in 0..settings.sqp_max_iter {
        if settings.continuous_verification {
            follow_minima(ws, settings);
        }
        linearise(ws);
        let outcome = qp::solve(
            &ws.transcription,
            &mut ws.qp,
            &mut ws.trial,
            settings.qp_max_iter,
            settings.qp_tol_feas,
            &mut out.info.qp_iterations,
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
            if accelerated {
                // The extrapolated point was a poor linearisation: fall back to plain iteration
                // from the last solution.
                ws.anderson.reset();
                accelerated = false;
                ws.iterate = ws.accepted;
                continue;
            }
            ws.iterate = ws.accepted;
            return SqpEnd::Failed(status);
        }
        let cost = ws.transcription.base_cost + half_norm2(&ws.trial, blocks, free);
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
        let small_change = decrease >= 0.0
            && decrease <= tolerance
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
        let mut next = [[0.0; MAX_FREE_PER_AXIS]; MAX_BLOCKS];
        ws.anderson
            .step(&ws.iterate, &ws.trial, &mut next, memory, blocks, free);
        accelerated = memory > 0;
        ws.iterate = next;
    }
    ws.iterate = ws.accepted;
    SqpEnd::MaxIterations
}

/// Node positions of a block at the current iterate.
fn block_positions(tr: &Transcription, y: &Coefficients, block: usize, out: &mut [f64; MAX_NODES]) {
    let mass = tr.mass_of(block / 3);
    *out = [0.0; MAX_NODES];
    for (h, slot) in out.iter_mut().enumerate().take(tr.grid.nodes()) {
        let row = tr.basis.position.get(h);
        let offset = match row {
            Some(row) => block_dot(row, y, block, tr.basis.free) / mass,
            None => 0.0,
        };
        *slot = node_value(&tr.base_position, block, h) + offset;
    }
}

/// Move each near-contact pair's moving check to the pair's current continuous separation
/// minimum (a local-reduction step for the semi-infinite keep-out constraint): the convex
/// subproblems then converge to the continuous optimum, not only to the checked points'.
fn follow_minima(ws: &mut Workspace, settings: &Settings) {
    for pair in 0..ws.transcription.pair_count {
        let keep_out = ws.transcription.keep_out_for(pair);
        // Only pairs near contact: the least separation over the fixed checks within 10 % of d.
        let tr = &ws.transcription;
        let mut least = f64::INFINITY;
        for c in 0..tr.check_count.get(pair).copied().unwrap_or(0) {
            if let Some(check) = tr.checks.get(pair).and_then(|row| row.get(c)) {
                least = least.min(norm3(&tr.relative(pair, check.source, &ws.iterate)));
            }
        }
        if least > 1.1 * keep_out && tr.moving_check.get(pair).copied().flatten().is_none() {
            continue;
        }
        let minimum = pair_minimum(ws, pair, settings);
        let tau = 2.0 * minimum.at_s - 1.0;
        if tau > -1.0 && tau < 1.0 {
            let _ = ws.transcription.place_moving_check(pair, tau);
        }
    }
}

/// The global minimum of the squared separation of one pair over the whole horizon.
fn pair_minimum(ws: &mut Workspace, pair: usize, settings: &Settings) -> Minimum {
    let tr = &ws.transcription;
    let (i, j) = tr.pairs.get(pair).copied().unwrap_or((0, 0));
    let mut axes = [[0.0; MAX_NODES]; 3];
    for (axis, coeffs) in axes.iter_mut().enumerate() {
        let relative = relative_nodes(tr, &ws.iterate, (i, j), axis);
        ws.bernstein.coefficients(&relative, coeffs);
    }
    let mut product = [0.0; MAX_PRODUCT];
    ws.bernstein.squared_norm(&axes, &mut product);
    // Tolerance on the squared separation equivalent to verify_tol / 100 on the separation.
    let tol = 0.02 * tr.keep_out_lu * settings.verify_tol_lu;
    ws.bernstein.minimum(
        &product,
        tol,
        u32::from(settings.refine_max_iter).saturating_mul(50),
    )
}

/// Write states, controls, cost, verified separation and the dynamics check into `out`.
/// Returns whether every pair's continuous separation is at least `d - verify_tol`.
fn write_solution(ws: &mut Workspace, settings: &Settings, out: &mut Solution) -> bool {
    let mut verified = true;
    let mut least = f64::INFINITY;
    for pair in 0..ws.transcription.pair_count {
        let minimum = pair_minimum(ws, pair, settings);
        let separation = libm::sqrt(minimum.value_squared.max(0.0));
        if !minimum.certified || separation < ws.transcription.keep_out_lu - settings.verify_tol_lu
        {
            verified = false;
        }
        if separation < least {
            least = separation;
            out.min_separation_lu = separation;
            out.min_separation_pair = ws.transcription.pairs.get(pair).copied().unwrap_or((0, 0));
            out.min_separation_time_tu = minimum.at_s * ws.transcription.horizon_tu;
        }
    }
    if ws.transcription.pair_count == 0 {
        out.min_separation_lu = f64::INFINITY;
    }
    let tr = &ws.transcription;
    let nodes = tr.grid.nodes();
    let scale = 2.0 / tr.horizon_tu;
    for (h, slot) in out.node_times_tu.iter_mut().enumerate().take(nodes) {
        *slot = tr.time_of(tr.grid.at(h));
    }
    let mut cost = 0.0;
    for sc in 0..tr.spacecraft {
        for axis in 0..3 {
            let block = sc.saturating_mul(3).saturating_add(axis);
            let mut positions = [0.0; MAX_NODES];
            block_positions(tr, &ws.iterate, block, &mut positions);
            let mut velocities = [0.0; MAX_NODES];
            tr.grid.differentiate(&positions, &mut velocities);
            for h in 0..nodes {
                let control = node_value(&tr.base_control, block, h)
                    + match tr.basis.accel.get(h) {
                        Some(row) => block_dot(row, &ws.iterate, block, tr.basis.free),
                        None => 0.0,
                    };
                let w = tr.grid.weight.get(h).copied().unwrap_or(0.0);
                cost += 0.25 * tr.horizon_tu * w * control * control;
                if let Some(state) = out.states.get_mut(sc).and_then(|row| row.get_mut(h)) {
                    if let Some(p) = state.get_mut(axis) {
                        *p = positions.get(h).copied().unwrap_or(0.0);
                    }
                    if let Some(v) = state.get_mut(axis.saturating_add(3)) {
                        *v = scale * velocities.get(h).copied().unwrap_or(0.0);
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
    out.test_point_times_tu = ws.test_times;
    // Largest violation of a checked constraint.
    let mut violation = 0.0f64;
    for pair in 0..tr.pair_count {
        for c in 0..tr.check_count.get(pair).copied().unwrap_or(0) {
            if let Some(check) = tr.checks.get(pair).and_then(|row| row.get(c)) {
                if check.pruned {
                    continue;
                }
                let relative = tr.relative(pair, check.source, &ws.iterate);
                violation = violation.max(tr.keep_out_lu - norm3(&relative));
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
    for pair in 0..tr.pair_count {
        for c in 0..tr.check_count.get(pair).copied().unwrap_or(0) {
            if tr
                .checks
                .get(pair)
                .and_then(|row| row.get(c))
                .is_some_and(|k| !k.pruned)
            {
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
fn dynamics_error(tr: &Transcription, out: &Solution) -> f64 {
    let grid = &tr.grid;
    let nodes = grid.nodes();
    let mut worst = 0.0f64;
    for sc in 0..tr.spacecraft {
        let mass = tr.mass_of(sc);
        let (Some(states), Some(controls)) = (out.states.get(sc), out.controls_fu.get(sc)) else {
            continue;
        };
        for axis in 0..3 {
            let mut position = [0.0; MAX_NODES];
            let mut velocity = [0.0; MAX_NODES];
            let mut control = [0.0; MAX_NODES];
            for h in 0..nodes {
                let state = states.get(h).copied().unwrap_or([0.0; 6]);
                if let Some(slot) = position.get_mut(h) {
                    *slot = state.get(axis).copied().unwrap_or(0.0);
                }
                if let Some(slot) = velocity.get_mut(h) {
                    *slot = state.get(axis.saturating_add(3)).copied().unwrap_or(0.0);
                }
                if let Some(slot) = control.get_mut(h) {
                    *slot = controls
                        .get(h)
                        .and_then(|u| u.get(axis))
                        .copied()
                        .unwrap_or(0.0);
                }
            }
            let x0 = position[0];
            let v0 = velocity[0];
            let samples = nodes.saturating_mul(2).saturating_sub(1);
            for k in 0..samples {
                let tau = if k % 2 == 0 {
                    grid.at(k / 2)
                } else {
                    0.5 * (grid.at(k / 2) + grid.at((k / 2).saturating_add(1)))
                };
                let t = tr.time_of(tau);
                // int_0^t u(s) ds and int_0^t (t - s) u(s) ds by LGL quadrature on [0, t].
                let mut first = 0.0;
                let mut second = 0.0;
                for q in 0..nodes {
                    let s = 0.5 * t * (grid.at(q) + 1.0);
                    let w = 0.5 * t * grid.weight.get(q).copied().unwrap_or(0.0);
                    let u = grid.interpolate(&control, tr.tau_of(s));
                    first += w * u;
                    second += w * (t - s) * u;
                }
                let propagated_v = v0 + first / mass;
                let propagated_x = x0 + v0 * t + second / mass;
                let interpolated_x = grid.interpolate(&position, tau);
                let interpolated_v = grid.interpolate(&velocity, tau);
                worst = worst
                    .max(libm::fabs(propagated_x - interpolated_x))
                    .max(libm::fabs(propagated_v - interpolated_v));
            }
        }
    }
    worst
}

#[cfg(test)]
#[allow(clippy::unwrap_used, clippy::indexing_slicing)]
mod tests {
    use super::*;
    use crate::pseudospectral::Spacecraft;

    fn paper_case(degree: u16, test_points: bool) -> Problem {
        let craft = |a: [f64; 3], b: [f64; 3]| Spacecraft {
            mass_mu: 1.0,
            initial_state: [a[0], a[1], a[2], 0.0, 0.0, 0.0],
            final_state: [b[0], b[1], b[2], 0.0, 0.0, 0.0],
        };
        let mut spacecraft = heapless::Vec::new();
        spacecraft
            .push(craft([0.0, 0.0, 0.0], [12.0, 12.0, 12.0]))
            .unwrap();
        spacecraft
            .push(craft([8.0, 0.0, 0.0], [0.0, 12.0, 12.0]))
            .unwrap();
        spacecraft
            .push(craft([8.0, 0.0, 8.0], [0.0, 12.0, 0.0]))
            .unwrap();
        Problem {
            horizon_tu: 10.0,
            max_control_fu: 1.0,
            keep_out_lu: 2.0,
            degree,
            test_points,
            spacecraft,
        }
    }

    fn run(problem: &Problem, settings: &Settings) -> Solution {
        let mut ws = Workspace::new();
        let mut out = Solution::new();
        solve(problem, settings, &mut ws, None, &mut out).unwrap();
        out
    }

    #[test]
    fn paper_case_reaches_the_independent_optimum_with_verified_separation() {
        let out = run(&paper_case(10, true), &Settings::default());
        let c = &out.certificate;
        extern crate std;
        std::println!(
            "{:?} {} {} {} {} {} {}",
            out.info.status,
            c.stationarity,
            c.complementarity,
            c.min_reduced_eigenvalue,
            c.max_violation,
            c.multipliers.len(),
            c.second_order_evaluated
        );
        std::println!("{:?}", c.multipliers);
        assert_eq!(out.info.status, SolveStatus::Solved);
        assert!((out.cost - 6.743183).abs() < 1e-5, "J = {}", out.cost);
        assert!(out.min_separation_lu >= 2.0 - 1e-6);
        assert!(out.max_dynamics_error < 1e-9);
    }

    #[test]
    fn nodes_only_lets_spacecraft_pass_through_each_other() {
        let settings = Settings {
            continuous_verification: false,
            ..Settings::default()
        };
        let out = run(&paper_case(10, false), &settings);
        assert!(out.min_separation_lu < 1.0, "{}", out.min_separation_lu);
        // Every node check is still met: the violation is between nodes.
        assert!(out.info.max_violation <= 1e-9, "{}", out.info.max_violation);
    }

    #[test]
    fn warm_start_from_the_solution_is_used_and_converges_at_once() {
        let problem = paper_case(10, true);
        let cold = run(&problem, &Settings::default());
        let mut ws = Workspace::new();
        let mut warm = Solution::new();
        crate::pseudospectral::solve_warm(
            &problem,
            &Settings::default(),
            &mut ws,
            &cold,
            &mut warm,
        )
        .unwrap();
        assert!(warm.info.warm_start_used);
        assert!(
            warm.info.sqp_iterations <= 4,
            "warm: {} subproblems",
            warm.info.sqp_iterations
        );
        assert_eq!(warm.info.status, SolveStatus::Solved);
        assert!(
            warm.info.sqp_iterations < cold.info.sqp_iterations,
            "{} vs {}",
            warm.info.sqp_iterations,
            cold.info.sqp_iterations
        );
        // Nearby fixed points of the convex-concave map differ by parts per million.
        assert!(
            (warm.cost - cold.cost).abs() < 2e-5 * cold.cost,
            "{} vs {}",
            warm.cost,
            cold.cost
        );
    }

    #[test]
    fn square_swap_leaves_the_plane_by_the_saddle_escape() {
        let craft = |a: [f64; 3], b: [f64; 3]| Spacecraft {
            mass_mu: 1.0,
            initial_state: [a[0], a[1], a[2], 0.0, 0.0, 0.0],
            final_state: [b[0], b[1], b[2], 0.0, 0.0, 0.0],
        };
        let mut spacecraft = heapless::Vec::new();
        for (x, y) in [(6.0, 6.0), (-6.0, 6.0), (-6.0, -6.0), (6.0, -6.0)] {
            spacecraft.push(craft([x, y, 0.0], [-x, -y, 0.0])).unwrap();
        }
        let p = Problem {
            horizon_tu: 10.0,
            max_control_fu: 1.0,
            keep_out_lu: 2.0,
            degree: 16,
            test_points: true,
            spacecraft,
        };
        let out = run(&p, &Settings::default());
        // In the plane the iteration stops on a saddle (J = 7.6805, reduced-Hessian eigenvalue
        // -0.29); one escape along the negative curvature leaves the plane.
        assert_eq!(
            out.info.status,
            SolveStatus::Solved,
            "{:?}",
            out.certificate
        );
        assert_eq!(out.info.saddle_escapes, 1);
        assert!(out.cost <= 7.50, "J = {}", out.cost);
        assert!(out.certificate.min_reduced_eigenvalue > 0.1);
        let out_of_plane = out.states[..4]
            .iter()
            .flat_map(|sc| sc[..17].iter())
            .map(|s| s[2].abs())
            .fold(0.0f64, f64::max);
        assert!(out_of_plane > 0.1, "{out_of_plane}");
    }

    #[test]
    fn perpendicular_direction_passes_to_the_right_when_head_on() {
        let d = perpendicular_direction(&[0.0; 3], &[1.0, 0.0, 0.0], None);
        assert!((d[0]).abs() < 1e-15 && (d[2] - 1.0).abs() < 1e-15, "{d:?}");
        let miss = perpendicular_direction(&[0.5, 0.2, 0.0], &[1.0, 0.0, 0.0], None);
        assert!((miss[1] - 1.0).abs() < 1e-12, "{miss:?}");
    }
}
