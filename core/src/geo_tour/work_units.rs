//! The GEO tour's work units: every loop of a solve is charged to the work meter
//! ([`crate::work::Meter`]) before each step runs, by the most that step can cost: a Lambert
//! solver step at its dearest branch, a drift or radial evaluation, a Lambert arc's set-up, a
//! leg's share of a price step, and so on. A unit is about 100 Cortex-M7 instructions: each
//! constant below is the measured M7 instruction count of its kernel on its dearest path
//! (`kernels.rs` runs them), divided by 90 and rounded up. So a solve's units bound its
//! instructions: instructions <= units x the largest instructions per unit over the kernels,
//! at most [`MAX_INSTRUCTIONS_PER_UNIT`](super::MAX_INSTRUCTIONS_PER_UNIT). The GEO image measures every kernel case on the M7
//! under QEMU in CI and fails above that bound (`tests/tests/qemu_firmware/geo_image.rs`; the
//! figures and the argument: docs/geo-tour.md, "Work budget").
//!
//! An iteration is charged as it starts, not by its loop's bound up front: a Lambert solve
//! runs 2-4 of its up to `3 lambert_max_iter` steps and a root 4-20 of its up to
//! `2 root_max_iter + 4` evaluations, so charging the bounds would cost the published 60-day
//! case 5.6 M units (about 560 M instructions' worth) for 6.3 M instructions of work. Only
//! the end of a sweep (the returned plan's legs rebuilt and checked, or why a request is
//! infeasible) is charged at its bound, from the reserve kept for it.

use super::types::{MethodPolicy, PointKind, Settings};
use crate::work::Meter;

/// The Lambert solver's steps (shared with the LEO tour, whose unit is the same).
pub(crate) use crate::lambert::{
    step_units as lambert_step, STEP_UNITS as LAMBERT_STEP,
    STEP_UNITS_DIRECT as LAMBERT_STEP_DIRECT,
};
/// One Lambert arc outside its steps: the two slot states, the solver's set-up, guess and
/// velocities, the burns in the local frame, and the golden-section step or the table entry
/// around it.
pub(crate) const LAMBERT_ARC: u64 = 64;
/// One drift evaluation (`Drift::at`, `price_and_point`: dual numbers) with the root step or
/// the price-curve node around it.
pub(crate) const DRIFT_EVAL: u64 = 15;
/// One radial-phasing evaluation (the arc of an eccentricity) with the root step around it.
pub(crate) const RADIAL_EVAL: u64 = 12;
/// The Hohmann-type manoeuvre.
pub(crate) const HOHMANN: u64 = 18;
/// A leg table's set-up: the table written, the methods allowed, the options pushed, the
/// roots' set-up.
pub(crate) const LEG_TABLE: u64 = 60;
/// A Lambert well outside its arcs: the skip test, the window, the branch choice.
pub(crate) const WELL: u64 = 17;
/// One leg's part of a price step outside the drift's root: its points scanned, the price
/// curve's lower bound and bracket.
pub(crate) const PICK_LEG: u64 = 12;
/// One price step (or drift re-allocation step) outside its legs: the totals, the bracket.
pub(crate) const PRICE_STEP: u64 = 10;
/// One assignment tried by the gap enumeration or the exchange search outside its
/// re-allocation: the picks copied, the totals compared.
pub(crate) const ASSIGNMENT: u64 = 20;
/// One leg's part of the west sweep's bounds outside its wells' tests and its duration root:
/// the points scanned, the sums.
pub(crate) const BOUNDS_LEG: u64 = 20;
/// One well's skip test (the tangential phasing orbit's burn) and search window.
pub(crate) const WELL_TEST: u64 = 8;
/// One leg of the returned plan outside its manoeuvre: the leg written and checked.
pub(crate) const LEG_ASSEMBLY: u64 = 20;
/// One sweep's set-up: the solution cleared, the clients ordered.
pub(crate) const SWEEP: u64 = 100;
/// One solve's fixed part: the request validated, the sweeps' plans compared and swapped, the
/// answer's numbers checked.
pub(crate) const SOLVE: u64 = 200;

/// Where a metered kernel's units go: spent from the meter's loops' share, each before the
/// step it pays for (refused once the share runs out: the kernel then stops and returns what
/// it has, and every later step is refused too), or nowhere (`paid`: a caller outside the
/// solve, or a part the solve has already charged at its bound, such as the returned plan's
/// legs paid from the reserve).
pub(crate) struct Gauge<'a> {
    meter: Option<&'a mut Meter>,
}

impl<'a> Gauge<'a> {
    /// Spend from `meter`.
    pub(crate) fn metered(meter: &'a mut Meter) -> Self {
        Self { meter: Some(meter) }
    }

    /// Meter nothing.
    pub(crate) const fn paid() -> Self {
        Self { meter: None }
    }

    /// Take `units` for the step about to run; `false` (the caller stops) when refused.
    pub(crate) fn take(&mut self, units: u64) -> bool {
        self.meter.as_deref_mut().is_none_or(|m| m.spend(units))
    }

    /// A step was refused: what the kernel returned is incomplete.
    pub(crate) fn stopped(&self) -> bool {
        self.meter.as_deref().is_some_and(Meter::exhausted)
    }
}

/// The work budget ran out: the loop that asked stops, and so does every later one.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) struct Cut;

/// Charge `units` for the step about to run, or [`Cut`] when they do not fit in the loops'
/// share of the budget (nothing charged; every later step is refused too).
pub(crate) fn spend(meter: &mut Meter, units: u64) -> Result<(), Cut> {
    if meter.spend(units) {
        Ok(())
    } else {
        Err(Cut)
    }
}

fn times(a: u64, b: u64) -> u64 {
    a.saturating_mul(b)
}

fn plus(a: u64, b: u64) -> u64 {
    a.saturating_add(b)
}

/// A Lambert arc of `revs` revolutions at its bound (for the reserve): `lambert_max_iter`
/// steps per stage (the least-time search of a multi-revolution family, the solve from
/// Izzo's guess; no warm start in the returned plan's legs).
pub(crate) fn lambert_arc_bound(s: &Settings, revs: u16) -> u64 {
    let stages = plus(1, u64::from(revs > 0));
    plus(
        LAMBERT_ARC,
        times(
            times(stages, u64::from(s.lambert_max_iter)),
            lambert_step(revs),
        ),
    )
}

/// The deepest drift orbit at its bound (for the reserve): `2 root_max_iter + 4`
/// evaluations.
pub(crate) fn drift_max_depth_bound(s: &Settings) -> u64 {
    times(plus(times(2, u64::from(s.root_max_iter)), 4), DRIFT_EVAL)
}

/// The radial manoeuvre at its bound (for the reserve): `2 root_max_iter + 4` evaluations.
pub(crate) fn radial_bound(s: &Settings) -> u64 {
    times(plus(times(2, u64::from(s.root_max_iter)), 4), RADIAL_EVAL)
}

/// A leg table's set-up and its Hohmann option (the roots and the direct Lambert arc are
/// charged as they run).
pub(crate) fn leg_table(allowed: [bool; 4]) -> u64 {
    let [_, hohmann, _, _] = allowed;
    if hohmann {
        plus(LEG_TABLE, HOHMANN)
    } else {
        LEG_TABLE
    }
}

/// One price step over `legs` legs of which `drift_legs` may pick their drift (`pick_all`,
/// or the drift legs' re-allocation step `drift_time`), outside the drift roots' evaluations
/// (charged as they run): each leg's points and price-curve scans, each drift's point at its
/// root.
pub(crate) fn price_step(legs: usize, drift_legs: usize) -> u64 {
    plus(
        PRICE_STEP,
        plus(
            times(legs as u64, PICK_LEG),
            times(drift_legs as u64, DRIFT_EVAL),
        ),
    )
}

/// The west sweep's bounds over `legs` legs outside their duration roots' evaluations: per
/// leg its fastest duration bound twice and its Δv bound once (each up to a skip test per
/// well), the points, the drift's point.
pub(crate) fn bounds(s: &Settings, legs: usize) -> u64 {
    let wells = u64::from(s.lambert_max_revolutions).saturating_add(1);
    times(
        legs as u64,
        plus(
            plus(BOUNDS_LEG, times(times(3, wells), WELL_TEST)),
            DRIFT_EVAL,
        ),
    )
}

/// One leg's alternatives in the exchange search outside their wells' refinement and the
/// drift root's evaluations: the points scanned, the drift's point.
pub(crate) const fn alternatives_leg() -> u64 {
    PICK_LEG.saturating_add(DRIFT_EVAL)
}

/// One leg's alternatives scored by the exchange's pair stage (`points` table points and the
/// drift): each effect.
pub(crate) fn pair_leg(points: usize) -> u64 {
    let p = u64::try_from(points).unwrap_or(u64::MAX).saturating_add(1);
    PAIR_SCAN.saturating_add(p.saturating_mul(PAIR_ALTERNATIVE))
}

/// One pair of legs scanned by the pair stage: the second leg's alternatives scored
/// ([`pair_leg`]), and per pair of the two legs' alternatives the effects summed and the
/// best-scored list's test (an insertion into its 8 entries at most).
pub(crate) fn pair_scan(points_a: usize, points_b: usize) -> u64 {
    let a = u64::try_from(points_a)
        .unwrap_or(u64::MAX)
        .saturating_add(1);
    let b = u64::try_from(points_b)
        .unwrap_or(u64::MAX)
        .saturating_add(1);
    pair_leg(points_b).saturating_add(a.saturating_mul(b).saturating_mul(PAIR_COMBO))
}

/// A leg's or a pair of legs' set-up in the pair scan.
pub(crate) const PAIR_SCAN: u64 = 4;
/// One alternative scored in the pair scan.
pub(crate) const PAIR_ALTERNATIVE: u64 = 2;
/// One pair of alternatives in the pair scan.
pub(crate) const PAIR_COMBO: u64 = 1;
/// One pair of legs' test against the pair scan's cut-off (their least effects summed).
pub(crate) const PAIR_TEST: u64 = 1;

/// One leg of the returned plan at its bound (paid from the reserve): its manoeuvre rebuilt
/// (a point of `kind`, or the drift) and the leg checked.
pub(crate) fn leg_assembly(s: &Settings, kind: Option<PointKind>) -> u64 {
    let manoeuvre = match kind {
        None => DRIFT_EVAL,
        Some(PointKind::Stay) => 0,
        Some(PointKind::Hohmann) => HOHMANN,
        Some(PointKind::Radial) => radial_bound(s),
        Some(PointKind::Direct) => lambert_arc_bound(s, 0),
        Some(PointKind::Well(m)) => {
            let revs = m.saturating_sub(1);
            let branches = if revs == 0 { 1 } else { 2 };
            times(branches, lambert_arc_bound(s, revs))
        }
    };
    plus(LEG_ASSEMBLY, manoeuvre)
}

/// One leg of an infeasible request's diagnosis at its bound (paid from the reserve): the
/// uncapped drift's deepest orbit, the leg's times compared.
pub(crate) fn infeasible_leg(s: &Settings) -> u64 {
    plus(LEG_ASSEMBLY, drift_max_depth_bound(s))
}

/// What a sweep's end may charge outside the loops' share, per leg: the dearest leg of the
/// returned plan, or the uncapped drift search that says why a request is infeasible.
fn end_of_sweep_leg(s: &Settings) -> u64 {
    let last_well = s.lambert_max_revolutions.saturating_add(1);
    let mut dearest = leg_assembly(s, None).max(infeasible_leg(s));
    for kind in [PointKind::Hohmann, PointKind::Radial, PointKind::Direct] {
        dearest = dearest.max(leg_assembly(s, Some(kind)));
    }
    for m in 1..=last_well {
        dearest = dearest.max(leg_assembly(s, Some(PointKind::Well(m))));
    }
    dearest
}

/// The reserve kept out of the loops' share for the end of a sweep (the returned plan's legs
/// rebuilt and checked, or the infeasible request's diagnosis) of `legs` legs.
pub(crate) fn reserve(s: &Settings, legs: usize) -> u64 {
    times(legs as u64, end_of_sweep_leg(s))
}

/// Which methods `table::build` tries for a leg (drift, Hohmann, radial, direct Lambert).
pub(crate) fn allowed_methods(policy: MethodPolicy, rule: super::Method) -> [bool; 4] {
    use super::Method;
    match policy {
        MethodPolicy::ByCost => [true; 4],
        MethodPolicy::PaperRule | MethodPolicy::PaperRuleFreeLambert => [
            rule == Method::Drift,
            rule == Method::Hohmann,
            rule == Method::Radial,
            rule == Method::Lambert,
        ],
    }
}
