//! The geometry of the iterate: relative node positions and states of a pair, each pair's
//! continuous separation minimum (and the moving check that follows it), and the
//! linearisation of every keep-out check (the unit separation, or a swerved normal where the
//! iterate violates the check).

use super::kernel::{Coefficients, MAX_BLOCKS};
use super::settings::Settings;
use super::swerve::perpendicular_direction;
use super::transcription::{
    block_dot, spacecraft_blocks, NodeDots, Pair, Transcription, MAX_POINTS,
};
use super::verify::{Minimum, MAX_PRODUCT};
use super::work_units;
use super::workspace::Workspace;
use crate::capacity::{MAX_CHECKS_PER_PAIR, MAX_FREE_PER_AXIS, MAX_NODES, MAX_PAIRS};
use crate::indexed::IndexedExt as _;
use crate::vec3;

/// Node values of `r_i - r_j` on one axis for the coefficients `y` (`None` for an axis or a
/// spacecraft the arrays do not hold).
pub(super) fn relative_nodes(
    tr: &Transcription,
    y: &Coefficients,
    pair: &Pair,
    axis: usize,
) -> Option<[f64; MAX_NODES]> {
    let (i, j) = pair.spacecraft;
    let (mi, mj) = pair.masses;
    let mut pi = [0.0; MAX_NODES];
    let mut pj = [0.0; MAX_NODES];
    block_positions(
        tr,
        spacecraft_blocks(y, i)?.get(axis)?,
        spacecraft_blocks(&tr.base_position, i)?.get(axis)?,
        mi,
        &mut pi,
    );
    block_positions(
        tr,
        spacecraft_blocks(y, j)?.get(axis)?,
        spacecraft_blocks(&tr.base_position, j)?.get(axis)?,
        mj,
        &mut pj,
    );
    let mut relative = [0.0; MAX_NODES];
    for ((slot, a), b) in relative.iter_mut().zip(pi.iter()).zip(pj.iter()) {
        *slot = a - b;
    }
    Some(relative)
}

/// Relative position and velocity of a pair at `tau` on the current iterate.
pub(super) fn relative_state(
    ws: &Workspace,
    pair: &Pair,
    tau: f64,
) -> Option<([f64; 3], [f64; 3])> {
    let tr = &ws.setup.transcription;
    let mut position = [0.0; 3];
    let mut velocity = [0.0; 3];
    let mut lagrange = [0.0; MAX_NODES];
    tr.grid.lagrange_row(tau, &mut lagrange);
    for (axis, (p, v)) in position.iter_mut().zip(velocity.iter_mut()).indexed() {
        let relative = relative_nodes(tr, &ws.iterates.iterate, pair, axis)?;
        let mut derivative = [0.0; MAX_NODES];
        tr.grid.differentiate(&relative, &mut derivative);
        *p = tr.grid.interpolate_with(&lagrange, &relative);
        *v = 2.0 / tr.horizon_tu * tr.grid.interpolate_with(&lagrange, &derivative);
    }
    Some((position, velocity))
}

/// Relative depth below the keep-out that counts as violated when linearising.
pub(super) const LINEARISE_TOL_REL: f64 = 1e-9;

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
pub(super) fn linearise(ws: &mut Workspace) {
    let mut dots: NodeDots = [[0.0; MAX_NODES]; MAX_BLOCKS];
    ws.setup
        .transcription
        .node_dots(&ws.iterates.iterate, &mut dots);
    let pair_count = ws.setup.transcription.pair_count;
    let fallbacks = ws.iterates.fallback_normal.iter().take(pair_count);
    for (pair, &fallback) in fallbacks.indexed() {
        let tr = &ws.setup.transcription;
        // Every index below `pair_count` is a pair, every check of it has a relative position.
        let (Some(geometry), Some(&count)) = (tr.pair(pair), tr.check_count.get(pair)) else {
            continue;
        };
        let keep_out = geometry.keep_out;
        // A check the QP met to its tolerance is feasible, not violated: swerving its normal
        // there would make a fixed point of the iteration that is not a KKT point (the normal
        // must be the unit separation, the constraint's gradient, at a converged iterate).
        let violated_below = keep_out * (1.0 - LINEARISE_TOL_REL);
        let mut closest: Option<(f64, f64)> = None;
        for (_, check) in tr.checks_of(pair) {
            let Some(relative) =
                tr.relative_with(&geometry, check.source, &ws.iterates.iterate, &dots)
            else {
                continue;
            };
            let length = vec3::norm(&relative);
            if length < violated_below && closest.is_none_or(|(_, best)| length < best) {
                closest = Some((check.tau, length));
            }
        }
        // The swerve's side from the relative state at the closest check (none where that
        // state cannot be had: the checks keep their unit separations).
        let swerve = closest.and_then(|(tau, _)| {
            let (relative, velocity) = relative_state(ws, &geometry, tau)?;
            let direction = perpendicular_direction(&relative, &velocity, Some(fallback));
            let speed = vec3::norm(&velocity);
            let width = if speed > 0.0 {
                keep_out / speed
            } else {
                f64::INFINITY
            };
            Some((ws.setup.transcription.time_of(tau), direction, width))
        });
        let tr = &mut ws.setup.transcription;
        for c in 0..count {
            let Some(check) = tr.check(pair, c) else {
                continue;
            };
            let Some(mut relative) =
                tr.relative_with(&geometry, check.source, &ws.iterates.iterate, &dots)
            else {
                continue;
            };
            let length = vec3::norm(&relative);
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
            let length = vec3::norm(&relative);
            let normal = if length > 0.0 {
                [
                    relative[0] / length,
                    relative[1] / length,
                    relative[2] / length,
                ]
            } else {
                fallback
            };
            if let Some(slot) = tr.checks.get_mut(pair).and_then(|row| row.get_mut(c)) {
                slot.normal = normal;
            }
        }
    }
}

/// Set every check's normal to the unit separation at the iterate: the constraint gradients
/// the certificate needs (`linearise` swerves where a check is violated, even by rounding).
pub(super) fn unit_normals(ws: &mut Workspace) {
    unit_normals_at(&mut ws.setup.transcription, &ws.iterates.iterate);
}

/// Set every check's normal to the unit separation at `y`.
pub(super) fn unit_normals_at(tr: &mut Transcription, y: &Coefficients) {
    for pair in 0..tr.pair_count {
        let (Some(geometry), Some(&count)) = (tr.pair(pair), tr.check_count.get(pair)) else {
            continue;
        };
        for c in 0..count {
            let Some(relative) = tr
                .check(pair, c)
                .and_then(|check| tr.relative(&geometry, check.source, y))
            else {
                continue;
            };
            let length = vec3::norm(&relative);
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

/// Node positions of one block (a spacecraft's axis): its base cubic's node values `base`
/// plus the basis rows' offset by its coefficients `values` over its `mass`.
pub(super) fn block_positions(
    tr: &Transcription,
    values: &[f64; MAX_FREE_PER_AXIS],
    base: &[f64; MAX_NODES],
    mass: f64,
    out: &mut [f64; MAX_NODES],
) {
    *out = [0.0; MAX_NODES];
    let rows = tr.basis.position.iter().zip(base.iter());
    for (slot, (row, &base_position)) in out.iter_mut().zip(rows).take(tr.grid.nodes()) {
        *slot = base_position + block_dot(row, values, tr.basis.free) / mass;
    }
}

/// Move each near-contact pair's moving check to the pair's current continuous separation
/// minimum (a local-reduction step for the semi-infinite keep-out constraint): the convex
/// subproblems then converge to the continuous optimum, not only to the checked points'.
/// With `place` false, only searches. Returns the deepest dip below `d - verify_tol` among the
/// pairs it searched (0 if none), and the searched pairs without one (bit `pair`): a converged
/// iterate with a dip there has its checks lagging its minima (`iteration::sqp`), and the
/// clean pairs need no verification search at the same iterate (`solver`). Inlined into the
/// SQP's two call sites: its node table (4.8 KB at capacity) then shares the SQP frame's
/// slots, idle while it runs; called, it put 5 KB more on the M7's stack.
#[inline(always)]
pub(super) fn follow_minima(
    ws: &mut Workspace,
    settings: &Settings,
    place: bool,
    cycling: bool,
) -> (f64, u32) {
    let mut deepest = 0.0f64;
    let mut clean = 0u32;
    let mut dots: NodeDots = [[0.0; MAX_NODES]; MAX_BLOCKS];
    ws.setup
        .transcription
        .node_dots(&ws.iterates.iterate, &mut dots);
    for pair in 0..ws.setup.transcription.pair_count {
        let tr = &ws.setup.transcription;
        let Some(geometry) = tr.pair(pair) else {
            continue;
        };
        // Only pairs near contact: the least separation over the fixed checks within 10 % of d.
        let mut least = f64::INFINITY;
        for (_, check) in tr.checks_of(pair) {
            if let Some(relative) =
                tr.relative_with(&geometry, check.source, &ws.iterates.iterate, &dots)
            {
                least = least.min(vec3::norm(&relative));
            }
        }
        if least > 1.1 * geometry.keep_out && tr.moving_check.get(pair).copied().flatten().is_none()
        {
            continue;
        }
        // A pair whose minimum cannot be searched is not clean (and the returned answer's own
        // search, `output::write_solution`, leaves it unverified).
        // Charged as it runs (each pair searched at its dearest cost); it then bounds the
        // next step the meter allows.
        ws.work
            .charge(work_units::pair_search(&ws.setup.transcription));
        let Some(minimum) = pair_minimum(ws, pair, settings) else {
            continue;
        };
        let separation = libm::sqrt(minimum.value_squared.max(0.0));
        let allowed = ws.setup.transcription.keep_out_lu - settings.verify_tol_lu;
        deepest = deepest.max(allowed - separation);
        if separation >= allowed {
            if let Some(bit) = pair_bit(pair) {
                clean |= bit;
            }
        }
        let tau = 2.0 * minimum.at_s - 1.0;
        if place && tau > -1.0 && tau < 1.0 {
            freeze_if_cycling(
                &mut ws.setup.transcription,
                pair,
                tau,
                if cycling {
                    FREEZE_JUMP_TAU_CYCLING
                } else {
                    FREEZE_JUMP_TAU
                },
                &ws.iterates.iterate,
                &dots,
            );
            let _ = ws.setup.transcription.place_moving_check(pair, tau);
        }
    }
    (deepest, clean)
}

/// A pair's bit in a `u32` set of pairs (`MAX_PAIRS` <= 32, so every pair has one; `None` past
/// that: such a pair is never in a set).
pub(super) fn pair_bit(pair: usize) -> Option<u32> {
    1u32.checked_shl(u32::try_from(pair).ok()?)
}

const _: () = assert!(MAX_PAIRS <= 32);

/// A moving check whose pair's minimum moved by more than this (normalised time) jumped to
/// another local minimum.
const FREEZE_JUMP_TAU: f64 = 0.01;
/// The same once the run's plain steps have raised the cost (`iteration::CYCLING_RISES`: the
/// moving checks chase the answer's dips in a cycle of two answers, where the minima move by
/// 2e-3 to 8e-3 in tau, below `FREEZE_JUMP_TAU`). Chosen on the tuning set (issue 28;
/// `reconfig sweep --set tuning`, `Solved` at the default budget / lifted) with the threshold
/// used throughout, not only once cycling: 0.01 1755 / 1920, 3e-3 1771 / 1919, 1e-3 1785 /
/// 1916, 3e-4 1808 / 1916, 1e-4 1806 / 1916, 1e-5 1798 / 1914. Used throughout it also froze
/// a small return on the paper's case (one more active row, stationarity 1.2e-4 instead of
/// 3e-5 at the same J): kept to cycling runs, the published cases' paths are unchanged.
const FREEZE_JUMP_TAU_CYCLING: f64 = 0.0003;
/// The check left behind still binds when the iterate's separation there is within this
/// fraction of the keep-out.
const FREEZE_BINDING_REL: f64 = 1e-3;

/// Before a pair's moving check jumps back toward where it came from, keep it where it is as a
/// fixed check when the iterate still touches the keep-out there (an exchange step for the
/// semi-infinite constraint: keep the binding point, add the new one). With a single check
/// that jumps, two binding minima take turns: the answer dips below d at the one the check
/// just left, the check goes back, and the cost cycles without end (measured on the dense
/// lattice, #168: two minima at tau = +-0.124 taking turns for 300 subproblems, J cycling by
/// 1e-4). Only a return is frozen, not every jump: a check that moves on as the trajectory
/// reshapes (a saddle escape, the first subproblems) would leave checks where nothing binds
/// any more and cost subproblems (measured: the symmetric family's escapes ran out of the
/// default budget when every binding jump was frozen). Keeps one check slot of the pair free
/// for continuous verification.
fn freeze_if_cycling(
    tr: &mut Transcription,
    pair: usize,
    tau: f64,
    jump_tau: f64,
    y: &Coefficients,
    dots: &NodeDots,
) {
    let Some(check) = tr.moving_check_of(pair) else {
        return;
    };
    let jump = libm::fabs(check.tau - tau);
    if jump <= jump_tau {
        return;
    }
    let from = tr.moving_from.get(pair).copied().flatten();
    if let Some(slot) = tr.moving_from.get_mut(pair) {
        *slot = Some(check.tau);
    }
    // A return: the new minimum is nearer where the check came from than where it is.
    let returning = from.is_some_and(|from| libm::fabs(tau - from) < jump);
    if !returning || check.pruned {
        return;
    }
    let (Some(&count), Some(geometry)) = (tr.check_count.get(pair), tr.pair(pair)) else {
        return;
    };
    if count.saturating_add(2) > MAX_CHECKS_PER_PAIR
        || tr.point_count.saturating_add(2) > MAX_POINTS
    {
        return;
    }
    let Some(relative) = tr.relative_with(&geometry, check.source, y, dots) else {
        return;
    };
    let separation = vec3::norm(&relative);
    if separation <= geometry.keep_out * (1.0 + FREEZE_BINDING_REL) {
        if let Some(slot) = tr.moving_check.get_mut(pair) {
            *slot = None;
        }
        if let Some(slot) = tr.moving_from.get_mut(pair) {
            *slot = None;
        }
    }
}

/// Most normalised time (tau) one refinement step may move a moving check.
const REFINE_MAX_STEP_TAU: f64 = 0.05;

/// Move each moving check by one Newton step in time on `|r(t)|^2` at the iterate, toward the
/// local minimum of the separation near it. The second-order step needs the constraint
/// gradients at the QP's answer, which the envelope theorem gives at the pair's minimum in
/// time; the answer is near the point the checks were placed for, so a local step replaces the
/// global branch and bound (`follow_minima`), which cost about one subproblem's worth of work
/// again (measured on the M7: the paper's case at N = 20 from 39.4 M to 42.1 M instructions
/// with the global search). A check whose separation is not convex in time there stays put.
pub(super) fn refine_moving_checks(ws: &mut Workspace) {
    'pairs: for pair in 0..ws.setup.transcription.pair_count {
        let tr = &ws.setup.transcription;
        let Some(check) = tr.moving_check_of(pair) else {
            continue;
        };
        if check.pruned {
            continue;
        }
        let Some(geometry) = tr.pair(pair) else {
            continue;
        };
        let (mut along, mut curvature) = (0.0, 0.0);
        let mut lagrange = [0.0; MAX_NODES];
        tr.grid.lagrange_row(check.tau, &mut lagrange);
        for axis in 0..3 {
            // A pair whose relative nodes cannot be had keeps its check where it is.
            let Some(values) = relative_nodes(tr, &ws.iterates.iterate, &geometry, axis) else {
                continue 'pairs;
            };
            let mut first = [0.0; MAX_NODES];
            let mut second = [0.0; MAX_NODES];
            tr.grid.differentiate(&values, &mut first);
            tr.grid.differentiate(&first, &mut second);
            let r = tr.grid.interpolate_with(&lagrange, &values);
            let rd = tr.grid.interpolate_with(&lagrange, &first);
            let rdd = tr.grid.interpolate_with(&lagrange, &second);
            // d/dtau |r|^2 / 2 and d^2/dtau^2 |r|^2 / 2.
            along += r * rd;
            curvature += rd * rd + r * rdd;
        }
        if curvature <= 0.0 {
            continue;
        }
        let step = (-along / curvature).clamp(-REFINE_MAX_STEP_TAU, REFINE_MAX_STEP_TAU);
        let tau = check.tau + step;
        if tau > -1.0 && tau < 1.0 {
            let _ = ws.setup.transcription.place_moving_check(pair, tau);
        }
    }
}

/// The global minimum of the squared separation of one pair over the whole horizon (`None`
/// for an index that names no pair, or whose relative nodes cannot be had: nothing searched).
pub(super) fn pair_minimum(
    ws: &mut Workspace,
    pair: usize,
    settings: &Settings,
) -> Option<Minimum> {
    pair_minimum_of(ws, Iterate::Current, pair, settings)
}

/// Which of the iteration's coefficient vectors a separation search reads.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum Iterate {
    /// `ws.iterates.iterate`: the linearisation point (and the answer being written).
    Current,
    /// `ws.iterates.accepted`: the last accepted QP answer.
    Accepted,
}

/// [`pair_minimum`] for the coefficients `which` names.
pub(super) fn pair_minimum_of(
    ws: &mut Workspace,
    which: Iterate,
    pair: usize,
    settings: &Settings,
) -> Option<Minimum> {
    let tr = &ws.setup.transcription;
    let y = match which {
        Iterate::Current => &ws.iterates.iterate,
        Iterate::Accepted => &ws.iterates.accepted,
    };
    let geometry = tr.pair(pair)?;
    let mut axes = [[0.0; MAX_NODES]; 3];
    for (axis, coeffs) in axes.iter_mut().indexed() {
        let relative = relative_nodes(tr, y, &geometry, axis)?;
        ws.setup.bernstein.coefficients(&relative, coeffs);
    }
    let mut product = [0.0; MAX_PRODUCT];
    ws.setup.bernstein.squared_norm(&axes, &mut product);
    // Tolerance on the squared separation equivalent to verify_tol / 100 on the separation.
    let tol = 0.02 * tr.keep_out_lu * settings.verify_tol_lu;
    Some(ws.setup.bernstein.minimum(
        &mut ws.verification.search,
        &product,
        tol,
        u32::from(settings.refine_max_iter).saturating_mul(50),
    ))
}
