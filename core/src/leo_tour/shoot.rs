//! The last leg of an arc under J2: Lambert's two-body orbit as the first guess, corrected by
//! moving the aim point.
//!
//! Aim-point iteration: solve Lambert to `aim`, fly the departure velocity in the J2 model,
//! and move `aim` against the arrival miss. The J2 map differs from the two-body map by O(J2)
//! so each iteration shrinks the miss by a factor of order J2 times the revolutions (measured:
//! about 10-100 per iteration over a 15-revolution LEO leg); at most `shoot_max_iter`
//! iterations. The converged aim offset (and the velocity the J2 flight adds at arrival) is the
//! [`Offset`] that the search keeps frozen between re-shootings: the "J2-corrected Lambert".

use super::j2::{join, pos, propagate_steps, step_count, vel, Gravity, State};
use super::types::Settings;
use crate::lambert::{self, Branch};
use crate::vec3::{add, cross, norm, sub, Vec3};
use crate::work::Meter;

/// Work units charged for one Lambert solve.
pub const LAMBERT_UNITS: u64 = 8;

/// A Lambert family: whole revolutions and branch.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Family {
    /// Whole revolutions.
    pub revs: u16,
    /// Branch (ignored for 0 revolutions).
    pub branch: Branch,
}

/// The J2 correction of a two-body Lambert leg: aim at `target + dr_km`, and add `dv_kmps` to
/// the two-body arrival velocity.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Offset {
    /// Aim-point offset, km.
    pub dr_km: Vec3,
    /// Arrival velocity the J2 flight adds, km/s.
    pub dv_kmps: Vec3,
}

/// A two-body Lambert leg with the offset applied: (departure velocity, arrival velocity).
pub fn corrected_lambert(
    settings: &Settings,
    from: &State,
    target_r: &Vec3,
    tof_s: f64,
    fam: Family,
    off: &Offset,
    meter: &mut Meter,
) -> Option<(Vec3, Vec3)> {
    if !meter.spend(LAMBERT_UNITS) {
        return None;
    }
    let r1 = pos(from);
    let normal = cross(&r1, &vel(from));
    let aim = add(target_r, &off.dr_km);
    let sol = lambert::solve(
        settings.mu_km3_s2,
        &r1,
        &aim,
        tof_s,
        fam.revs,
        fam.branch,
        &normal,
        settings.lambert_max_iter,
        settings.lambert_tol,
    )
    .ok()?;
    Some((sol.v1_kmps, add(&sol.v2_kmps, &off.dv_kmps)))
}

/// Result of a J2 shooting.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Shot {
    /// The offset for the next solve: the one flown, moved against the miss.
    pub offset: Offset,
    /// Departure velocity, km/s.
    pub v_dep_kmps: Vec3,
    /// State at arrival (before the matching burn), flown in the J2 model.
    pub arrival: State,
    /// Arrival position miss, km.
    pub miss_km: f64,
}

/// Shoot from `from` to `target_r` in `tof_s` under J2, from the offset `start`; the best shot
/// (smallest miss) within `shoot_max_iter` iterations, or `None` if no Lambert solve of the
/// family converged or the budget refused.
#[allow(clippy::too_many_arguments)]
pub fn shoot(
    g: &Gravity,
    settings: &Settings,
    from: &State,
    target_r: &Vec3,
    tof_s: f64,
    fam: Family,
    start: &Offset,
    meter: &mut Meter,
) -> Option<Shot> {
    let n = step_count(tof_s, settings.step_s, settings.max_steps)?;
    let mut off = *start;
    let mut best: Option<Shot> = None;
    for _ in 0..settings.shoot_max_iter {
        // A Lambert solve that fails on a moved aim point ends the iteration with the best
        // shot so far (the caller checks its miss).
        let Some((v_dep, v_arr_2b)) = corrected_lambert(
            settings,
            from,
            target_r,
            tof_s,
            fam,
            &Offset {
                dr_km: off.dr_km,
                dv_kmps: [0.0; 3],
            },
            meter,
        ) else {
            break;
        };
        if !meter.spend(u64::from(n)) {
            break;
        }
        let Some(end) = propagate_steps(g, &join(&pos(from), &v_dep), tof_s, n) else {
            break;
        };
        let miss = sub(&pos(&end), target_r);
        let miss_km = norm(&miss);
        let shot = Shot {
            // The next estimate of the aim offset (equal to the one flown once converged).
            offset: Offset {
                dr_km: sub(&off.dr_km, &miss),
                dv_kmps: sub(&vel(&end), &v_arr_2b),
            },
            v_dep_kmps: v_dep,
            arrival: end,
            miss_km,
        };
        if best.is_none_or(|b| miss_km < b.miss_km) {
            best = Some(shot);
        }
        if miss_km <= settings.arrival_tol_km {
            break;
        }
        off.dr_km = sub(&off.dr_km, &miss);
    }
    best
}
