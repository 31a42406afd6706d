//! Which side a pair passes on where the iterate violates a keep-out check: the miss direction
//! perpendicular to the pair's relative velocity, or, where they meet head on, each pair's
//! fallback direction chosen from the analytic guess at set-up (the right-hand rule), turned by
//! 45 degrees when an elastic subproblem names the pair (`iteration.rs`). Any unit normal gives a
//! valid inner approximation of the keep-out, so these choose a side, never feasibility.

use super::collision;
use super::guess::tracks;
use super::workspace::Workspace;
use crate::indexed::IndexedExt as _;
use crate::vec3;

/// A unit vector perpendicular to `velocity`, along the miss vector `relative` when it is not
/// negligible, else a fixed choice (the coordinate axis least aligned with the velocity, made
/// perpendicular), deterministic per pair.
pub(super) fn perpendicular_direction(
    relative: &[f64; 3],
    velocity: &[f64; 3],
    fallback: Option<[f64; 3]>,
) -> [f64; 3] {
    let speed = vec3::norm(velocity);
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
    let miss_norm = vec3::norm(&miss);
    if miss_norm > 1e-9 * (1.0 + vec3::norm(relative)) {
        return [
            miss[0] / miss_norm,
            miss[1] / miss_norm,
            miss[2] / miss_norm,
        ];
    }
    if let Some(direction) = fallback {
        let candidate = reject(direction);
        let c_norm = vec3::norm(&candidate);
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
    for (k, component) in unit_v.iter().indexed() {
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
    let r_norm = vec3::norm(&right);
    if r_norm > 0.0 {
        [right[0] / r_norm, right[1] / r_norm, right[2] / r_norm]
    } else {
        [1.0, 0.0, 0.0]
    }
}

/// Each pair's fallback direction: perpendicular to the analytic relative velocity at the
/// closest approach, toward the existing miss vector when there is one.
pub(super) fn choose_fallback_directions(ws: &mut Workspace) {
    for pair in 0..ws.setup.transcription.pair_count {
        if let Some((direction, _)) = fallback_frame(ws, pair) {
            if let Some(slot) = ws.iterates.fallback_normal.get_mut(pair) {
                *slot = direction;
            }
        }
    }
}

/// A pair's fallback direction and the analytic relative velocity at the analytic
/// trajectories' closest approach (the direction is perpendicular to it).
fn fallback_frame(ws: &Workspace, pair: usize) -> Option<([f64; 3], [f64; 3])> {
    let tr = &ws.setup.transcription;
    let (i, j) = tr.pairs.get(pair).copied()?;
    let (li, lj) = (
        ws.setup.laws.get(usize::from(i))?,
        ws.setup.laws.get(usize::from(j))?,
    );
    let (ti, tj) = (tracks(li), tracks(lj));
    let t = collision::closest_approach(&ti, &tj, 0.0, tr.horizon_tu, 60);
    let (relative, velocity) = collision::analytic_relative_motion(&ti, &tj, t);
    Some((
        perpendicular_direction(&relative, &velocity, None),
        velocity,
    ))
}

/// Turn a pair's fallback direction by `eighths` of a turn (45 degrees each) about the analytic
/// relative velocity, from where `setup` put it. Why: a pair that meets head on swerves along
/// one fixed perpendicular in the first subproblems, and with the bound on each axis of the
/// control a swerve along one axis reaches `1/sqrt(2)` of one along a diagonal (measured: two
/// spacecraft swapping places with d = 14 LU, T = 10, Umax = 1 reach 12.5 LU along z alone
/// and 17.7 along the diagonal, so the subproblem was infeasible and the problem is not).
/// Returns false when the pair has no such direction.
pub(super) fn turn_fallback(ws: &mut Workspace, pair: usize, eighths: u8) -> bool {
    let Some((normal, velocity)) = fallback_frame(ws, pair) else {
        return false;
    };
    let speed = vec3::norm(&velocity);
    if speed.partial_cmp(&0.0) != Some(core::cmp::Ordering::Greater) {
        return false;
    }
    let v = velocity.map(|c| c / speed);
    // v x n: the normal's quarter turn about v (n is perpendicular to v, so both are unit).
    let side = vec3::cross(&v, &normal);
    let angle = core::f64::consts::FRAC_PI_4 * f64::from(eighths);
    let (sin, cos) = (libm::sin(angle), libm::cos(angle));
    let turned = vec3::add(&vec3::scale(&normal, cos), &vec3::scale(&side, sin));
    match ws.iterates.fallback_normal.get_mut(pair) {
        Some(slot) => {
            *slot = turned;
            true
        }
        None => false,
    }
}
