//! Per-leg option tables: what each leg can do, built once per sweep, before any time is
//! allocated. The drift method is kept as a continuous option (its admissible depth range);
//! the other methods are points `(duration, Δv)` that a longer leg reaches by waiting.

use super::drift::Drift;
use super::geo::Geo;
use super::hohmann::hohmann;
use super::lambert_phasing::{
    lambert_revs, well_minimum, well_skipped, wells_earliest_s, LambertBounds,
};
use super::maneuver::{Direction, Maneuver, Method};
use super::price_curve::PriceCurve;
use super::radial::{radial, radial_gauged};
use super::types::{MethodPolicy, PointKind, Settings, MAX_LAMBERT_REVOLUTIONS};
use super::work_units::{self, spend, Cut, Gauge};
use crate::work::Meter;

/// Most point options of a leg: Hohmann, radial, direct Lambert and one per Lambert well.
pub(crate) const MAX_POINTS: usize = 4 + MAX_LAMBERT_REVOLUTIONS as usize;

/// A point option.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Point {
    pub kind: PointKind,
    pub duration_s: f64,
    pub dv_mps: f64,
    /// Lambert wells: the time price this point minimises `dv + price t` for (0: the bottom).
    pub price: f64,
    /// The least Δv the point can take (a well's bottom, kept when the well is re-priced),
    /// m/s: a lower bound on an assignment's cost however its wells move.
    pub floor_dv_mps: f64,
}

/// The drift option of a leg: admissible depths `(0, x_max]`, fastest duration `t_min`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct DriftRange {
    pub model: Drift,
    pub x_max_km: f64,
    pub t_min_s: f64,
    /// The leg's marginal price of time on `(0, x_max_km]`, tabulated; added by [`finish`]
    /// (a sweep cut short by its bounds never needs it).
    pub curve: Option<PriceCurve>,
}

/// Everything one leg can do.
#[derive(Clone, Debug, PartialEq)]
pub(crate) struct LegTable {
    pub target_index: u8,
    pub from_lon_rad: f64,
    pub to_lon_rad: f64,
    pub phase_rad: f64,
    /// Sweep direction of the leg.
    pub east: bool,
    /// The per-burn cap the table was built for, m/s.
    pub cap_mps: f64,
    pub drift: Option<DriftRange>,
    pub points: heapless::Vec<Point, MAX_POINTS>,
    /// Fastest admissible duration (infinite when nothing is admissible), s.
    pub fastest_s: f64,
    /// Fastest duration ignoring the cap, s: the point options' only, until
    /// [`add_uncapped_drift`] adds the drift's (needed only to say why a request is
    /// infeasible).
    pub fastest_uncapped_s: f64,
    /// The policy allows the drift method on this leg.
    pub drift_allowed: bool,
}

impl LegTable {
    pub const fn empty() -> Self {
        Self {
            target_index: 0,
            from_lon_rad: 0.0,
            to_lon_rad: 0.0,
            phase_rad: 0.0,
            east: true,
            cap_mps: 0.0,
            drift: None,
            points: heapless::Vec::new(),
            fastest_s: f64::INFINITY,
            fastest_uncapped_s: f64::INFINITY,
            drift_allowed: false,
        }
    }
}

pub(crate) fn bounds(s: &Settings) -> LambertBounds {
    LambertBounds {
        max_iter: s.lambert_max_iter,
        tol: s.lambert_tol,
    }
}

/// The sweep direction a table was built for.
pub(crate) fn direction_of(t: &LegTable) -> Direction {
    if t.east {
        Direction::East
    } else {
        Direction::West
    }
}

/// The method the paper's rule gives a phase offset.
pub(crate) fn rule_method(phase_rad: f64, s: &Settings) -> Method {
    // A phase within `PHASE_TOL_RAD` of a threshold is at it: the same tour gets the same
    // methods whatever its base longitude (the offsets' rounding differs from one to another).
    let above = |threshold_rad: f64| phase_rad > threshold_rad + PHASE_TOL_RAD;
    if above(s.rule_drift_above_rad) {
        Method::Drift
    } else if above(s.rule_hohmann_above_rad) {
        Method::Hohmann
    } else if above(s.rule_radial_above_rad) {
        Method::Radial
    } else {
        Method::Lambert
    }
}

/// Phase offsets closer than this, rad, are the rounding of the input longitudes (degrees
/// converted, wrapped and subtracted), not a distance to fly: 4e-5 m along the GEO ring. A
/// client that close to the slot before it is co-located with it, and a phase that close to a
/// rule threshold is at the threshold.
pub(crate) const PHASE_TOL_RAD: f64 = 1e-12;

/// Rebuild the manoeuvre of a point option (deterministic: the same numbers as when the
/// table was built). Not metered: the returned plan's legs are paid from the reserve, at
/// their bound (`work_units::leg_assembly`).
pub(crate) fn point_maneuver(
    g: &Geo,
    dir: Direction,
    phase_rad: f64,
    p: &Point,
    p_cap: f64,
    s: &Settings,
) -> Option<Maneuver> {
    match p.kind {
        PointKind::Stay => Some(Maneuver::none()),
        PointKind::Hohmann => hohmann(g, dir, phase_rad, s.min_radius_km),
        PointKind::Radial => radial(g, dir, phase_rad, s.min_radius_km, s.root_max_iter),
        PointKind::Direct => lambert_revs(
            g,
            dir,
            phase_rad,
            p.duration_s,
            0,
            p_cap,
            bounds(s),
            &mut Gauge::paid(),
        ),
        PointKind::Well(m) => lambert_revs(
            g,
            dir,
            phase_rad,
            p.duration_s,
            m.saturating_sub(1),
            p_cap,
            bounds(s),
            &mut Gauge::paid(),
        ),
    }
}

fn push(t: &mut LegTable, kind: PointKind, m: Option<Maneuver>, cap: f64) {
    if let Some(m) = m {
        t.fastest_uncapped_s = t.fastest_uncapped_s.min(m.transfer_s);
        if m.max_burn_mps <= cap {
            t.fastest_s = t.fastest_s.min(m.transfer_s);
            // MAX_POINTS holds every kind once and each well once.
            let _ = t.points.push(Point {
                kind,
                duration_s: m.transfer_s,
                dv_mps: m.dv_mps,
                price: 0.0,
                floor_dv_mps: m.dv_mps,
            });
        }
    }
}

/// Build the table of one leg, its roots' evaluations and its direct Lambert arc metered by
/// `gauge` (its set-up is charged by the caller, `work_units::leg_table`). When a step is
/// refused the table is incomplete: the caller sees `gauge.stopped()`.
#[allow(clippy::too_many_arguments)]
pub(crate) fn build(
    g: &Geo,
    dir: Direction,
    target_index: u8,
    from_lon_rad: f64,
    to_lon_rad: f64,
    phase_rad: f64,
    cap_mps: f64,
    policy: MethodPolicy,
    s: &Settings,
    gauge: &mut Gauge<'_>,
) -> LegTable {
    let mut t = LegTable::empty();
    t.target_index = target_index;
    t.from_lon_rad = from_lon_rad;
    t.to_lon_rad = to_lon_rad;
    t.phase_rad = phase_rad;
    t.east = dir == Direction::East;
    t.cap_mps = cap_mps;
    if phase_rad <= 0.0 {
        push(&mut t, PointKind::Stay, Some(Maneuver::none()), cap_mps);
        return t;
    }
    let allowed = |m: Method| match policy {
        MethodPolicy::ByCost => true,
        MethodPolicy::PaperRule | MethodPolicy::PaperRuleFreeLambert => {
            rule_method(phase_rad, s) == m
        }
    };
    if allowed(Method::Drift) {
        t.drift_allowed = true;
        let model = Drift {
            g: *g,
            dir,
            phase_rad,
        };
        if let Some(x) = model.max_depth_km(cap_mps, s.min_radius_km, s.root_max_iter, gauge) {
            let t_min = model.at(x).duration_s;
            t.fastest_s = t.fastest_s.min(t_min);
            t.drift = Some(DriftRange {
                model,
                x_max_km: x,
                t_min_s: t_min,
                curve: None,
            });
        }
    }
    if allowed(Method::Hohmann) {
        push(
            &mut t,
            PointKind::Hohmann,
            hohmann(g, dir, phase_rad, s.min_radius_km),
            cap_mps,
        );
    }
    if allowed(Method::Radial) {
        push(
            &mut t,
            PointKind::Radial,
            radial_gauged(g, dir, phase_rad, s.min_radius_km, s.root_max_iter, gauge),
            cap_mps,
        );
    }
    if allowed(Method::Lambert) {
        let direct = lambert_revs(
            g,
            dir,
            phase_rad,
            s.lambert_direct_time_s,
            0,
            f64::INFINITY,
            bounds(s),
            gauge,
        );
        push(&mut t, PointKind::Direct, direct, cap_mps);
    }
    t
}

/// Add the drift's fastest duration ignoring the cap to `t.fastest_uncapped_s` (a second
/// search for the deepest drift orbit, left out of [`build`] because only an infeasible
/// request needs it). Not metered: paid from the reserve, at its bound.
pub(crate) fn add_uncapped_drift(g: &Geo, t: &mut LegTable, s: &Settings) {
    if !t.drift_allowed {
        return;
    }
    let model = Drift {
        g: *g,
        dir: direction_of(t),
        phase_rad: t.phase_rad,
    };
    if let Some(x) = model.max_depth_km(
        f64::INFINITY,
        s.min_radius_km,
        s.root_max_iter,
        &mut Gauge::paid(),
    ) {
        t.fastest_uncapped_s = t.fastest_uncapped_s.min(model.at(x).duration_s);
    }
}

/// Whether the leg of table `t` has Lambert wells under `policy`: a positive phase, by cost,
/// or by the rule with free Lambert time where the rule says Lambert (the table's settings
/// are those the rule was applied with).
fn has_wells(t: &LegTable, policy: MethodPolicy, s: &Settings) -> bool {
    t.phase_rad > 0.0
        && match policy {
            MethodPolicy::ByCost => true,
            MethodPolicy::PaperRule => false,
            MethodPolicy::PaperRuleFreeLambert => rule_method(t.phase_rad, s) == Method::Lambert,
        }
}

/// Complete a table from [`build`] with its dear parts, once the sweep is known to be needed:
/// the drift's price curve and the Lambert wells (a golden section of Lambert solves per well),
/// each charged to `meter` first.
///
/// # Errors
/// [`Cut`] when the work budget runs out (the table is then incomplete).
pub(crate) fn finish(
    g: &Geo,
    t: &mut LegTable,
    policy: MethodPolicy,
    s: &Settings,
    meter: &mut Meter,
) -> Result<(), Cut> {
    if let Some(d) = t.drift.as_mut() {
        spend(meter, PriceCurve::work_units())?;
        d.curve = Some(PriceCurve::new(&d.model, d.x_max_km));
    }
    if !has_wells(t, policy, s) {
        return Ok(());
    }
    let (dir, phase_rad, cap_mps) = (direction_of(t), t.phase_rad, t.cap_mps);
    for m in 1..=s.lambert_max_revolutions.saturating_add(1) {
        spend(meter, work_units::WELL)?;
        if well_skipped(g, dir, phase_rad, m, cap_mps) {
            continue;
        }
        let mut gauge = Gauge::metered(meter);
        let w = well_minimum(
            g,
            dir,
            phase_rad,
            m,
            0.0,
            cap_mps,
            s.well_iterations,
            bounds(s),
            &mut gauge,
        );
        if gauge.stopped() {
            return Err(Cut);
        }
        push(t, PointKind::Well(m), w, cap_mps);
    }
    Ok(())
}

/// A lower bound on the leg's fastest admissible duration once its wells are added: every
/// well is searched no earlier than its window's start, and a well skipped outright under the
/// cap adds nothing, so the wells cannot make the leg faster than `wells_earliest_s`.
pub(crate) fn fastest_lower_bound_s(
    g: &Geo,
    t: &LegTable,
    policy: MethodPolicy,
    s: &Settings,
) -> f64 {
    if has_wells(t, policy, s) {
        let last_well = s.lambert_max_revolutions.saturating_add(1);
        t.fastest_s.min(wells_earliest_s(
            g,
            direction_of(t),
            t.phase_rad,
            last_well,
            t.cap_mps,
        ))
    } else {
        t.fastest_s
    }
}

/// A lower bound on the Δv of the leg of table `t` (wells not yet added) when it may take at
/// most `avail_s`: 0 when any of its wells may exist (a well is not priced before it is
/// built), else the cheapest option that fits: a point of duration <= `avail_s` (a longer leg
/// waits), or the drift at `avail_s` (its cost falls with its duration). Infinite when nothing
/// fits. The drift's root is metered by `gauge` (when a step is refused the bound is not one:
/// the caller sees `gauge.stopped()`).
pub(crate) fn dv_lower_bound_mps(
    g: &Geo,
    t: &LegTable,
    policy: MethodPolicy,
    s: &Settings,
    avail_s: f64,
    gauge: &mut Gauge<'_>,
) -> f64 {
    if has_wells(t, policy, s) {
        let dir = direction_of(t);
        let any = (1..=s.lambert_max_revolutions.saturating_add(1))
            .any(|m| !well_skipped(g, dir, t.phase_rad, m, t.cap_mps));
        if any {
            return 0.0;
        }
    }
    let mut best = f64::INFINITY;
    for p in &t.points {
        if p.duration_s <= avail_s {
            best = best.min(p.dv_mps);
        }
    }
    if let Some(d) = t.drift.as_ref() {
        if avail_s >= d.t_min_s {
            let x = d
                .model
                .depth_for_duration(avail_s, d.x_max_km, s.root_max_iter, gauge);
            // The root is bracketed to rounding; the margin keeps the bound below D(avail_s).
            best = best.min(d.model.at(x).dv_mps * (1.0 - 1e-9));
        }
    }
    best
}
