//! GEO servicing tour: one servicer on the geostationary ring visits clients in other slots in
//! one sweep within a mission time, least total Δv, every burn under a cap (the GEO servicing
//! paper digested in SPEC-servicing.md, seed 003).
//!
//! * Per leg, four phasing methods on the circular ring (two-body, coplanar): one-revolution
//!   Hohmann-type ([`hohmann`]), drift ([`drift_for_duration`]; drift orbit from the duration
//!   by a bounded 1-D root), radial-impulse ([`radial`]) and Lambert ([`lambert_phasing`],
//!   every revolution count and branch up to `Settings::lambert_max_revolutions`).
//! * Time allocation by a Lagrange time price (exact for the convex drift legs), the duality
//!   gap at the critical price closed by enumerating the switching legs, and a local
//!   refinement of the Lambert wells (module `allocate`).
//! * Both sweeps (east and west), the cheaper kept unless the request fixes one; the paper's
//!   threshold rule as `MethodPolicy::PaperRule`.
//!
//! ## Frame and units
//! Longitudes in rad (Earth-fixed, east positive), times in s from the mission epoch, burns in
//! m/s in the servicer's local radial / along-track / normal frame. A leg's time beyond its
//! transfer is spent waiting co-located with the client, after the arrival.
//!
//! ## Bounds
//! Every loop is bounded by a `Settings` field or a capacity ([`MAX_TARGETS`] clients,
//! [`MAX_LAMBERT_REVOLUTIONS`]); the worst case is in the [`Settings`] docs.

mod allocate;
mod drift;
mod drift_time;
mod error;
mod exchange;
mod exchange_pairs;
mod geo;
mod hohmann;
#[doc(hidden)]
pub mod kernels;
mod lambert_phasing;
mod maneuver;
mod pick;
mod price_curve;
mod radial;
mod reallocate;
mod root;
mod solution;
mod table;
mod types;
mod validate;
mod well_price;
mod work_units;
mod workspace;

pub use drift::{drift_at_depth, drift_for_duration};
pub use error::{Field, PlanError};
pub use geo::{inertial_to_rtn, rtn_to_inertial, Geo};
pub use hohmann::hohmann;
pub use lambert_phasing::lambert_phasing;
pub use maneuver::{Burn, Direction, Maneuver, Method, MAX_BURNS};
pub use radial::radial;
pub use solution::{Leg, Solution, SolveInfo, SolveStatus};
pub use types::{
    MethodPolicy, Problem, SettingId, Settings, SweepChoice, DEFAULT_WORK_BUDGET, MAX_GAP_LEGS,
    MAX_INSTRUCTIONS_PER_UNIT, MAX_LAMBERT_REVOLUTIONS, MAX_TARGETS,
};
pub use validate::{MAX_BURN_CAP_MPS, MAX_MISSION_TIME_S};
pub use workspace::Workspace;

use crate::astro::{wrap_two_pi, TWO_PI};
use crate::indexed::IndexedExt as _;
use crate::work::Meter;
use allocate::{allocate, NoAllocation};
use pick::Choice;
use table::{build, point_maneuver};
use work_units::{spend, Cut, Gauge};

/// The method the paper's threshold rule gives a phase offset (rad) under `settings`.
pub fn rule_method(phase_rad: f64, settings: &Settings) -> Method {
    table::rule_method(phase_rad, settings)
}

/// The GEO tour in the planners' contract ([`crate::contract::Planner`]): [`solve`].
#[derive(Clone, Copy, Debug)]
pub struct GeoTour;

crate::impl_planner!(
    GeoTour: Problem, Settings, Workspace, Solution, PlanError, SolveStatus,
    GeoTour, solve, reset |out| *out = Solution::new()
);

/// Plan the tour of `problem` into `out`.
///
/// Time is bounded by `settings` and the capacities alone (see [`Settings`]), and every loop
/// is charged to a work meter that stops the solve at `settings.work_budget` units: the best
/// plan found by then is returned, checked, with `BudgetExhausted { verified }`. No heap, no
/// panics, bit-identical on every run. The status in `out.info` says whether the plan is
/// usable ([`SolveStatus::is_usable`]) or which leg makes the request infeasible.
///
/// # Errors
/// [`PlanError`] naming the field, the value and the limit when an input or a setting is out
/// of range; `out` is then untouched.
pub fn solve(
    problem: &Problem,
    settings: &Settings,
    workspace: &mut Workspace,
    out: &mut Solution,
) -> Result<(), PlanError> {
    settings.validate().map_err(PlanError::InvalidSetting)?;
    validate::problem(problem)?;
    let g = Geo::standard();
    let n = problem.targets_lon_rad.len().min(MAX_TARGETS);
    let mut meter = Meter::new(settings.work_budget);
    meter.charge(work_units::SOLVE);
    // Each sweep's end (its plan's legs rebuilt and checked, or why it is infeasible) is paid
    // from this reserve, so a usable plan is never lost to the check that shows it usable.
    meter.reserve(work_units::reserve(settings, n));
    // The sweep asked for, or east first when the cheaper one is wanted.
    let first = match problem.sweep {
        SweepChoice::West => Direction::West,
        SweepChoice::East | SweepChoice::Cheaper => Direction::East,
    };
    solve_sweep(
        &g, first, problem, settings, workspace, out, None, &mut meter,
    );
    if problem.sweep == SweepChoice::Cheaper {
        let mut other = core::mem::take(&mut workspace.other);
        // The west plan replaces the east one only when it is usable and strictly
        // cheaper (or the east one is not usable), so a west sweep that provably is
        // neither is cut short.
        let beat = if out.info.status.is_usable() {
            out.total_dv_mps
        } else {
            f64::INFINITY
        };
        solve_sweep(
            &g,
            Direction::West,
            problem,
            settings,
            workspace,
            &mut other,
            Some(beat),
            &mut meter,
        );
        let usable = |s: &Solution| s.info.status.is_usable();
        let iterations = out.info.price_iterations;
        let take_west = (usable(&other) && !usable(out))
            || (usable(&other) && usable(out) && other.total_dv_mps < out.total_dv_mps);
        if take_west {
            core::mem::swap(out, &mut other);
        }
        out.info.price_iterations = out.info.price_iterations.saturating_add(iterations);
        workspace.other = other;
    }
    // A budget stop anywhere (in either sweep) makes the answer a budget stop: the plan
    // returned is the best usable one found, verified by its own checks.
    if meter.exhausted() {
        out.info.status = SolveStatus::BudgetExhausted {
            verified: out.info.status.is_usable(),
        };
    }
    solution::make_finite(out);
    out.info.work_units = meter.used();
    Ok(())
}

/// Plan one sweep (inputs already validated), every loop charged to `meter`. With `beat`
/// given, a sweep that provably cannot fit the mission time, or provably costs at least `beat`
/// m/s, stops before its Lambert wells and price curves are built, with the status `Unsolved`
/// (the caller only uses a usable plan cheaper than `beat`): its fastest tour is bounded below
/// by the legs' fastest options other than wells and the start of their wells' search windows,
/// and its cost by each leg's cheapest option within the time the other legs leave it at their
/// fastest (0 for a leg with wells). When the budget runs out the sweep ends with
/// `BudgetExhausted`: the best feasible assignment the allocation had, assembled and checked
/// (`verified`), or no plan when the allocation had none.
#[allow(clippy::too_many_arguments)]
fn solve_sweep(
    g: &Geo,
    dir: Direction,
    problem: &Problem,
    s: &Settings,
    ws: &mut Workspace,
    out: &mut Solution,
    beat: Option<f64>,
    meter: &mut Meter,
) {
    *out = Solution::new();
    out.info.direction = Some(dir);
    let cut = SolveStatus::BudgetExhausted { verified: false };
    if spend(meter, work_units::SWEEP).is_err() {
        out.info.status = cut;
        return;
    }
    let n = match build_tables(g, dir, problem, s, ws, meter) {
        Ok(n) => n,
        Err(Cut) => {
            out.info.status = cut;
            return;
        }
    };
    let Some(tables) = ws.tables.get_mut(..n) else {
        out.info.status = SolveStatus::CheckFailed { leg: 0 };
        return;
    };
    if let Some(beat) = beat {
        if spend(meter, work_units::bounds(s, n)).is_err() {
            out.info.status = cut;
            return;
        }
        let fastest_lb =
            |t: &table::LegTable| table::fastest_lower_bound_s(g, t, problem.policy, s);
        let bound: f64 = tables.iter().map(fastest_lb).sum();
        let mut gauge = Gauge::metered(meter);
        let dominated = bound > problem.mission_time_s || {
            let mut dv_lb = 0.0;
            for t in tables.iter() {
                let avail_s = problem.mission_time_s - (bound - fastest_lb(t));
                dv_lb += table::dv_lower_bound_mps(g, t, problem.policy, s, avail_s, &mut gauge);
                if gauge.stopped() {
                    break;
                }
            }
            dv_lb >= beat
        };
        if gauge.stopped() {
            out.info.status = cut;
            return;
        }
        if dominated {
            out.info.status = SolveStatus::Unsolved;
            return;
        }
    }
    let Ok(fastest) = finish_tables(g, tables, problem.policy, s, meter) else {
        out.info.status = cut;
        return;
    };
    out.info.fastest_tour_s = fastest.is_finite().then_some(fastest);
    if fastest.is_nan() || fastest > problem.mission_time_s {
        out.info.status = infeasible(g, tables, problem, s, meter);
        return;
    }
    let alloc = match allocate(
        tables,
        problem.mission_time_s,
        s,
        (&mut ws.picks, &mut ws.lo_picks, &mut ws.trial),
        meter,
    ) {
        Ok(alloc) => alloc,
        Err(NoAllocation::Failed) => {
            out.info.status = SolveStatus::CheckFailed { leg: 0 };
            return;
        }
        Err(NoAllocation::Cut) => {
            out.info.status = cut;
            return;
        }
    };
    out.info.price_mps_per_s = alloc.price;
    out.info.price_iterations = alloc.iterations;
    out.info.gap_assignments = alloc.gap_assignments;
    out.info.refined_legs = alloc.refined;
    // Assemble the legs from the picks, paid from the reserve.
    let mut clock = 0.0;
    let mut failed: Option<u8> = None;
    for (j, (t, p)) in tables.iter().zip(ws.picks.iter()).indexed() {
        let jj = u8::try_from(j).unwrap_or(u8::MAX);
        let kind = match p.choice {
            Choice::Drift => None,
            Choice::Point(i) => Some(
                t.points
                    .get(usize::from(i))
                    .map_or(types::PointKind::Stay, |pt| pt.kind),
            ),
        };
        meter.charge(work_units::leg_assembly(s, kind));
        let mv = match p.choice {
            Choice::Drift => t.drift.as_ref().map(|d| d.model.maneuver(p.x_km)),
            Choice::Point(i) => t.points.get(usize::from(i)).and_then(|pt| {
                // The pick's time (a Lambert well may have been re-priced since).
                let at = table::Point {
                    duration_s: p.duration_s,
                    ..*pt
                };
                point_maneuver(g, dir, t.phase_rad, &at, t.cap_mps, s)
            }),
        };
        let Some(mv) = mv else {
            failed = failed.or(Some(jj));
            continue;
        };
        let duration = p.duration_s.max(mv.transfer_s);
        let leg = Leg {
            target_index: t.target_index,
            from_lon_rad: t.from_lon_rad,
            to_lon_rad: t.to_lon_rad,
            phase_rad: t.phase_rad,
            method: mv.method,
            start_s: clock,
            duration_s: duration,
            transfer_s: mv.transfer_s,
            wait_s: duration - mv.transfer_s,
            dv_mps: mv.dv_mps,
            max_burn_mps: mv.max_burn_mps,
            orbit_sma_km: mv.orbit_sma_km,
            revolutions: mv.revolutions,
            burns: mv.burns.clone(),
        };
        clock += duration;
        out.total_dv_mps += leg.dv_mps;
        out.max_burn_mps = out.max_burn_mps.max(leg.max_burn_mps);
        let ok_leg = leg.max_burn_mps <= problem.max_burn_mps * (1.0 + 1e-12)
            && leg.dv_mps.is_finite()
            && leg.duration_s.is_finite()
            && solution::leg_is_finite(&leg);
        if !ok_leg {
            failed = failed.or(Some(jj));
        }
        // n <= MAX_TARGETS legs.
        let _ = out.legs.push(leg);
    }
    out.mission_time_s = clock;
    if clock > problem.mission_time_s * (1.0 + 1e-12) {
        failed = failed.or(Some(u8::try_from(n.saturating_sub(1)).unwrap_or(u8::MAX)));
    }
    out.info.status = match (failed, alloc.cut) {
        (Some(leg), false) => SolveStatus::CheckFailed { leg },
        (None, false) => SolveStatus::Solved,
        (failed, true) => SolveStatus::BudgetExhausted {
            verified: failed.is_none(),
        },
    };
}

/// Order the clients in the sweep's direction and build every leg's table into `ws.tables`,
/// each charged to `meter` first; the number of legs.
///
/// # Errors
/// [`Cut`] when the work budget runs out.
pub(crate) fn build_tables(
    g: &Geo,
    dir: Direction,
    problem: &Problem,
    s: &Settings,
    ws: &mut Workspace,
    meter: &mut Meter,
) -> Result<usize, Cut> {
    let sign = dir.sign();
    let start = wrap_two_pi(problem.start_lon_rad);
    // Visiting order: by offset from the start in the sweep's direction (ties by index).
    let n = problem.targets_lon_rad.len().min(MAX_TARGETS);
    let mut order = [0usize; MAX_TARGETS];
    let mut offsets = [0.0f64; MAX_TARGETS];
    for (i, (&lon, off)) in problem
        .targets_lon_rad
        .iter()
        .zip(offsets.iter_mut())
        .indexed()
    {
        // A client within the rounding of the start slot (a longitude given as its
        // equivalent, -312 deg for 48 deg) is in it, not a full revolution away.
        let wrapped = wrap_two_pi(sign * (wrap_two_pi(lon) - start));
        *off = if wrapped <= table::PHASE_TOL_RAD || TWO_PI - wrapped <= table::PHASE_TOL_RAD {
            0.0
        } else {
            wrapped
        };
        if let Some(o) = order.get_mut(i) {
            *o = i;
        }
    }
    let key = |i: usize| offsets.get(i).copied().unwrap_or(f64::INFINITY);
    // Insertion sort, n <= 16.
    for i in 1..n {
        let mut j = i;
        while j > 0 {
            let (Some(&a), Some(&b)) = (order.get(j.wrapping_sub(1)), order.get(j)) else {
                break;
            };
            if key(a) > key(b) {
                order.swap(j.wrapping_sub(1), j);
                j = j.wrapping_sub(1);
            } else {
                break;
            }
        }
    }
    let mut prev_off = 0.0;
    let mut prev_lon = start;
    for (leg, &i) in order.iter().take(n).indexed() {
        let off = key(i);
        let to = problem
            .targets_lon_rad
            .get(i)
            .map_or(0.0, |&l| wrap_two_pi(l));
        // Two clients within the rounding of each other are co-located (no leg to fly).
        let phase = (off - prev_off).max(0.0);
        let phase = if phase <= table::PHASE_TOL_RAD {
            0.0
        } else {
            phase
        };
        let allowed = if phase > 0.0 {
            work_units::allowed_methods(problem.policy, table::rule_method(phase, s))
        } else {
            [false; 4]
        };
        spend(meter, work_units::leg_table(allowed))?;
        let mut gauge = Gauge::metered(meter);
        if let Some(t) = ws.tables.get_mut(leg) {
            *t = build(
                g,
                dir,
                u8::try_from(i).unwrap_or(u8::MAX),
                prev_lon,
                to,
                phase,
                problem.max_burn_mps,
                problem.policy,
                s,
                &mut gauge,
            );
        }
        if gauge.stopped() {
            return Err(Cut);
        }
        prev_off = off;
        prev_lon = to;
    }
    Ok(n)
}

/// Complete every table (price curves, Lambert wells), each charged to `meter` first; the
/// fastest tour's duration (infinite when a leg has no admissible option).
///
/// # Errors
/// [`Cut`] when the work budget runs out.
pub(crate) fn finish_tables(
    g: &Geo,
    tables: &mut [table::LegTable],
    policy: MethodPolicy,
    s: &Settings,
    meter: &mut Meter,
) -> Result<f64, Cut> {
    let mut fastest = 0.0;
    for t in tables.iter_mut() {
        table::finish(g, t, policy, s, meter)?;
        fastest += t.fastest_s;
    }
    Ok(fastest)
}

/// Which leg makes the request infeasible, and why (its searches paid from the reserve).
fn infeasible(
    g: &Geo,
    tables: &mut [table::LegTable],
    problem: &Problem,
    s: &Settings,
    meter: &mut Meter,
) -> SolveStatus {
    let mut fastest_uncapped = 0.0;
    for t in tables.iter_mut() {
        meter.charge(if t.drift_allowed {
            work_units::infeasible_leg(s)
        } else {
            work_units::LEG_ASSEMBLY
        });
        table::add_uncapped_drift(g, t, s);
        fastest_uncapped += t.fastest_uncapped_s;
    }
    let idx = |j: usize| u8::try_from(j).unwrap_or(u8::MAX);
    if fastest_uncapped <= problem.mission_time_s {
        // The cap is what fails: name the leg it slows most (infinite: nothing admissible).
        let mut worst = (0usize, f64::NEG_INFINITY);
        for (j, t) in tables.iter().indexed() {
            let slowed = t.fastest_s - t.fastest_uncapped_s;
            if slowed > worst.1 || (t.fastest_s.is_infinite() && worst.1.is_finite()) {
                worst = (j, slowed);
            }
        }
        SolveStatus::CapTooLow { leg: idx(worst.0) }
    } else if let Some(j) = tables
        .iter()
        .index_of(|t| t.fastest_s.is_infinite())
        .filter(|_| problem.policy.follows_rule())
    {
        SolveStatus::RuleMethodInadmissible { leg: idx(j) }
    } else {
        let mut worst = (0usize, f64::NEG_INFINITY);
        for (j, t) in tables.iter().indexed() {
            if t.fastest_s > worst.1 {
                worst = (j, t.fastest_s);
            }
        }
        SolveStatus::MissionTooShort { leg: idx(worst.0) }
    }
}

#[cfg(test)]
mod tests;
