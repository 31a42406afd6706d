//! The last leg of an arc under J2: Lambert's two-body orbit as the first guess, corrected by
//! moving the aim point.
//!
//! Aim-point iteration: solve Lambert to `aim`, fly the departure velocity in the J2 model,
//! and move `aim` against the arrival miss. The plain move (`aim -= miss`) contracts the miss
//! only by a factor of about 1.5-3 per iteration on the paper's 12-revolution legs (measured:
//! the J2 flight's arrival moves with the aim point by far more than the aim point itself, so
//! the map from aim to miss is not close to the identity), so the step is the quasi-Newton one,
//! `aim -= H miss`, with `H` the inverse Jacobian of miss over aim kept by Broyden's update
//! ([`Secant`]): the map is smooth and nearly linear, and `H` carried from one shooting to the
//! next of the same search converges in 2-4 iterations. At most `shoot_max_iter` iterations.
//! The converged aim offset (and the velocity the J2 flight adds at arrival) is the [`Offset`]
//! that the search keeps frozen between re-shootings: the "J2-corrected Lambert".

use super::flight::Flight;
use super::j2::{join, pos, vel, State};
use super::types::Settings;
use super::work_units;
use crate::lambert::{self, Branch};
use crate::vec3::{add, cross, dot, norm, scale, sub, Vec3};
use crate::work::Meter;

/// A Lambert family: whole revolutions and branch.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Family {
    /// Whole revolutions.
    pub revs: u16,
    /// Branch (ignored for 0 revolutions).
    pub branch: Branch,
}

/// The J2 correction of a two-body Lambert leg: aim at `target + dr_km`, and add `dv_km_s` to
/// the two-body arrival velocity.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Offset {
    /// Aim-point offset, km.
    pub dr_km: Vec3,
    /// Arrival velocity the J2 flight adds, km/s.
    pub dv_km_s: Vec3,
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
    corrected_lambert_from(settings, from, target_r, tof_s, fam, off, None, meter)
        .map(|(v1, v2, _)| (v1, v2))
}

/// [`corrected_lambert`] started from `guess` (Izzo's x of a nearby solve of the same family;
/// see [`lambert::solve_from`]): (departure velocity, arrival velocity, the solution's x).
#[allow(clippy::too_many_arguments)]
pub fn corrected_lambert_from(
    settings: &Settings,
    from: &State,
    target_r: &Vec3,
    tof_s: f64,
    fam: Family,
    off: &Offset,
    guess: Option<f64>,
    meter: &mut Meter,
) -> Option<(Vec3, Vec3, f64)> {
    let r1 = pos(from);
    let normal = cross(&r1, &vel(from));
    let aim = add(target_r, &off.dr_km);
    let sol = metered_lambert(settings, (&r1, &aim, tof_s), fam, &normal, guess, meter)?;
    Some((sol.v1_km_s, add(&sol.v2_km_s, &off.dv_km_s), sol.x))
}

/// A Lambert solve from `r1` to `r2` in `tof_s` (`guess` as in [`lambert::solve_from`])
/// charged to `meter`: its set-up, then each step as it starts (a refused step ends the solve
/// with no answer).
pub(crate) fn metered_lambert(
    settings: &Settings,
    (r1, r2, tof_s): (&Vec3, &Vec3, f64),
    fam: Family,
    normal: &Vec3,
    guess: Option<f64>,
    meter: &mut Meter,
) -> Option<lambert::LambertSolution> {
    if !meter.spend(work_units::LAMBERT_SOLVE) {
        return None;
    }
    let step_units = lambert::step_units(fam.revs);
    lambert::solve_from_stepped(
        settings.mu_km3_s2,
        r1,
        r2,
        tof_s,
        fam.revs,
        fam.branch,
        normal,
        (settings.lambert_max_iter, settings.lambert_tol),
        guess,
        &mut || meter.spend(step_units),
    )
    .ok()
}

/// Broyden's estimate of the inverse Jacobian of the arrival miss over the aim offset: the
/// quasi-Newton step of the aim-point iteration is `-H miss`. Starts as the identity (the plain
/// aim-point iteration); carried from one shooting to the next within a search.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Secant {
    /// Rows of `H`.
    pub inv_jac: [Vec3; 3],
}

impl Default for Secant {
    fn default() -> Self {
        Self {
            inv_jac: [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]],
        }
    }
}

impl Secant {
    /// `H v`.
    pub fn apply(&self, v: &Vec3) -> Vec3 {
        let [r0, r1, r2] = &self.inv_jac;
        [dot(r0, v), dot(r1, v), dot(r2, v)]
    }

    /// Broyden's ("second") update on the inverse: after a step `s` of the aim offset that
    /// changed the miss by `y`, `H += (s - H y) y^T / (y^T y)`, so that `H y = s`. A zero or
    /// non-finite `y` leaves `H` as it is.
    pub fn update(&mut self, s: &Vec3, y: &Vec3) {
        let yy = dot(y, y);
        if !(yy > 0.0 && yy.is_finite()) {
            return;
        }
        let r = sub(s, &self.apply(y));
        let mut next = self.inv_jac;
        for (row, rk) in next.iter_mut().zip(r.iter()) {
            *row = add(row, &scale(y, rk / yy));
        }
        if next.iter().flatten().all(|v| v.is_finite()) {
            self.inv_jac = next;
        }
    }
}

/// Result of a J2 shooting.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Shot {
    /// The offset for the next solve: the one flown, moved against the miss.
    pub offset: Offset,
    /// Departure velocity, km/s.
    pub v_dep_km_s: Vec3,
    /// State at arrival (before the matching burn), flown in the J2 model.
    pub arrival: State,
    /// Arrival position miss, km.
    pub miss_km: f64,
}

/// Shoot from `from` to `target_r` in `tof_s` under J2, from the offset `start` with the
/// quasi-Newton matrix `secant` (updated in place); the best shot (smallest miss) within
/// `shoot_max_iter` iterations, or `None` if no Lambert solve of the family converged or the
/// budget refused. A step that does not lower the miss resets `secant` to the identity and
/// restarts from the best shot, so the iteration is never worse than the plain one for long.
#[allow(clippy::too_many_arguments)]
pub fn shoot(
    flight: &Flight,
    settings: &Settings,
    from: &State,
    target_r: &Vec3,
    tof_s: f64,
    fam: Family,
    start: &Offset,
    secant: &mut Secant,
    meter: &mut Meter,
) -> Option<Shot> {
    let mut off = *start;
    let mut best: Option<Shot> = None;
    // The best shot's flown offset and miss: the secant update and every step start there.
    let mut anchor: Option<(Vec3, Vec3)> = None;
    let mut failures_in_a_row = 0_u8;
    for _ in 0..settings.shoot_max_iter {
        if !meter.spend(work_units::SHOOT_ITERATION) {
            break;
        }
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
                dv_km_s: [0.0; 3],
            },
            meter,
        ) else {
            break;
        };
        let Some(end) = flight.fly(&join(&pos(from), &v_dep), tof_s, meter) else {
            break;
        };
        let miss = sub(&pos(&end), target_r);
        let miss_km = norm(&miss);
        let improved = best.is_none_or(|b| miss_km < b.miss_km);
        if let Some((dr_a, miss_a)) = anchor {
            secant.update(&sub(&off.dr_km, &dr_a), &sub(&miss, &miss_a));
        }
        if improved {
            failures_in_a_row = 0;
        } else {
            // The step made the miss worse: its secant information is kept, but a second
            // failure in a row falls back to the plain iteration.
            failures_in_a_row = failures_in_a_row.saturating_add(1);
            if failures_in_a_row >= 2 {
                *secant = Secant::default();
            }
        }
        if improved {
            anchor = Some((off.dr_km, miss));
            best = Some(Shot {
                offset: Offset {
                    dr_km: off.dr_km,
                    dv_km_s: sub(&vel(&end), &v_arr_2b),
                },
                v_dep_km_s: v_dep,
                arrival: end,
                miss_km,
            });
        }
        if miss_km <= settings.arrival_tol_km {
            break;
        }
        // The next aim: the quasi-Newton step from the best shot.
        let Some((dr_a, miss_a)) = anchor else { break };
        off.dr_km = sub(&dr_a, &secant.apply(&miss_a));
    }
    // The offset returned is the next estimate (equal to the one flown once converged).
    best.map(|b| Shot {
        offset: Offset {
            dr_km: anchor.map_or(b.offset.dr_km, |(dr_a, miss_a)| {
                sub(&dr_a, &secant.apply(&miss_a))
            }),
            ..b.offset
        },
        ..b
    })
}

/// [`shoot`] from `start`, and where that does not reach `accept_km`, again with continuation
/// in J2 from the two-body Lambert leg: J2 scaled up in steps of `1/stages`, each shooting
/// started from the previous step's offset scaled by the ratio of the J2 values (the offset is
/// nearly linear in J2) and its quasi-Newton matrix; a step whose shooting fails (its first
/// Lambert solve has no solution in the family) or does not reach `accept_km` is halved, at
/// most `3 stages` shootings in all. On long legs (20-30 revolutions: thousands of km of J2
/// drift) a start far from the answer can leave the family's Lambert solutions before the
/// aim-point iteration settles; each step starts within a fraction of its own offset. The
/// better of the direct and the continued full-J2 shots, or `None` (a continuation that does
/// not reach full J2 gives no shot).
#[allow(clippy::too_many_arguments)]
pub fn shoot_continued(
    flight: &Flight,
    settings: &Settings,
    from: &State,
    target_r: &Vec3,
    tof_s: f64,
    fam: Family,
    start: &Offset,
    (stages, accept_km): (u8, f64),
    secant: &mut Secant,
    meter: &mut Meter,
) -> Option<Shot> {
    let direct = shoot(
        flight, settings, from, target_r, tof_s, fam, start, secant, meter,
    );
    if direct.is_some_and(|s| s.miss_km <= accept_km) || stages == 0 {
        return direct;
    }
    *secant = Secant::default();
    let mut off = Offset::default();
    let mut reached = 0.0_f64;
    let mut increment = 1.0 / f64::from(stages);
    let mut continued: Option<Shot> = None;
    for _ in 0..u16::from(stages).saturating_mul(3) {
        let fraction = (reached + increment).min(1.0);
        let scaled = flight.with_j2_fraction(fraction);
        let trial_start = Offset {
            dr_km: if reached > 0.0 {
                scale(&off.dr_km, fraction / reached)
            } else {
                off.dr_km
            },
            dv_km_s: off.dv_km_s,
        };
        let mut trial_secant = *secant;
        let shot = shoot(
            &scaled,
            settings,
            from,
            target_r,
            tof_s,
            fam,
            &trial_start,
            &mut trial_secant,
            meter,
        )
        .filter(|s| s.miss_km <= accept_km);
        match shot {
            Some(s) => {
                off = s.offset;
                *secant = trial_secant;
                reached = fraction;
                if reached >= 1.0 {
                    continued = Some(s);
                    break;
                }
            }
            None => increment *= 0.5,
        }
        if meter.stage_refused() {
            break;
        }
    }
    match (direct, continued) {
        (Some(d), Some(c)) if d.miss_km < c.miss_km => Some(d),
        (d, None) => d,
        (_, c) => c,
    }
}
