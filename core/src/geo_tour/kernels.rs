//! The charged kernels, one at a time, for the work-unit bound (docs/geo-tour.md, "Work
//! budget"). Not part of the planner's interface: the GEO image (`cargo firmware-geo`) runs
//! every case between its instruction markers after its fixtures, and the QEMU test
//! (`tests/tests/qemu_firmware/geo_image.rs`) records each case's M7 instructions and units in
//! `fixtures/golden/m7-figures.toml` and fails when one takes more than its units x
//! [`MAX_INSTRUCTIONS_PER_UNIT`](super::MAX_INSTRUCTIONS_PER_UNIT).
//!
//! Each case runs the solve's own code for one metered kernel and returns the units the solve
//! charges for what it ran:
//!
//! * a Householder or Halley step of Lambert's solver on each branch of the time-of-flight
//!   function (the hypergeometric series near x = 1 at its longest), one drift evaluation,
//!   one radial evaluation, the Hohmann manoeuvre: the constants of `work_units.rs`, each
//!   measured alone on its dearest path;
//! * with a real meter, whose units the case returns: Lambert arcs that run to their bound
//!   (`lambert_max_iter` 1 and 4, no tolerance: every step of every stage is made, with the
//!   loop's bookkeeping and the meter's checks), arcs and wells on their success paths, cold
//!   and warm, the drift and radial roots, leg tables, a price curve, a price step over 16
//!   legs, the west sweep's bounds, the whole allocation, and whole solves cut at several
//!   budgets (the stops' wind-down included).
//!
//! The set-up a case needs (a warm start's guess, the tables of a 16-client tour) is made by
//! [`prepare`], outside the measured span; [`run`] is the measured part.

use super::allocate::allocate;
use super::drift::Drift;
use super::geo::Geo;
use super::hohmann::hohmann;
use super::lambert_phasing::{arc, well_minimum, well_skipped, LambertBounds};
use super::maneuver::Direction;
use super::pick::pick_all;
use super::price_curve::PriceCurve;
use super::radial::{arc as radial_arc, radial_gauged};
use super::table::{self, bounds};
use super::types::{MethodPolicy, Problem, Settings, SweepChoice};
use super::work_units::{self as wu, Gauge};
use super::{build_tables, finish_tables, solve, Solution, Workspace};
use crate::lambert::{self, Branch};
use crate::work::Meter;
use core::hint::black_box;

/// One degree, rad.
const DEG: f64 = core::f64::consts::PI / 180.0;
/// One hour, s.
const HOUR: f64 = 3600.0;

/// What a case runs.
#[derive(Clone, Copy, Debug)]
enum Kind {
    /// `lambert::householder_step(x, lambda, revs, t_nd)`.
    HouseholderStep(f64, f64, f64, f64),
    /// `lambert::halley_step(x, lambda, revs)`.
    HalleyStep(f64, f64, f64),
    /// One arc of the GEO tour (phase deg, time h, revs, branch), warm started from the
    /// arc 0.1 % later when asked, metered.
    Arc(f64, f64, u16, Branch, bool),
    /// One arc that runs to its bound: `lambert_max_iter` = the last field, no tolerance,
    /// warm started at x = 0.999 (phase deg, time h, revs, branch, max_iter), metered.
    ArcBound(f64, f64, u16, Branch, u16),
    /// One Lambert well's golden section (phase deg, cap m/s, well m), metered.
    Well(f64, f64, u16),
    /// `Drift::at` (phase deg, depth km).
    DriftAt(f64, f64),
    /// `Drift::price_and_point` (phase deg, depth km).
    DriftPrice(f64, f64),
    /// The radial arc of eccentricity e.
    RadialEval(f64),
    /// `Drift::max_depth_km` (phase deg, cap m/s, root_max_iter), metered.
    DriftMaxDepth(f64, f64, u16),
    /// `radial` (phase deg, root_max_iter), metered.
    Radial(f64, u16),
    /// `hohmann` (phase deg).
    Hohmann(f64),
    /// `table::build` (phase deg, policy, root_max_iter), metered.
    LegTable(f64, MethodPolicy, u16),
    /// `PriceCurve::new` (phase deg), metered.
    PriceCurve(f64),
    /// One price step over the prepared 16 legs at the allocation's price (root_max_iter),
    /// metered.
    PriceStep(u16),
    /// The west sweep's bounds over the prepared 16 legs (root_max_iter), metered.
    Bounds(u16),
    /// The whole allocation over the prepared 16 legs (root_max_iter), metered.
    Allocate(u16),
    /// A whole solve of the 16-client tour with this work budget (0: the default).
    Solve(u64),
    /// The 16-client tour swept west (clients in reverse order: the ordering's worst case)
    /// with a budget that stops it at its first leg table.
    SolveWestOrderingOnly,
}

/// A kernel case: its name (the record's key) and what it runs.
#[derive(Clone, Copy, Debug)]
pub struct Case {
    /// Name in the firmware's output and the record.
    pub name: &'static str,
    kind: Kind,
}

const fn case(name: &'static str, kind: Kind) -> Case {
    Case { name, kind }
}

/// Every case, in the order the GEO image runs them.
pub const CASES: &[Case] = &[
    case(
        "householder-direct-acos",
        Kind::HouseholderStep(0.3, 0.6, 0.0, 1.5),
    ),
    case(
        "householder-direct-acos-neg",
        Kind::HouseholderStep(-0.6, 0.9, 0.0, 3.0),
    ),
    case(
        "householder-direct-series-low",
        Kind::HouseholderStep(0.7746, -1.0, 0.0, 1.2),
    ),
    case(
        "householder-direct-series-mid",
        Kind::HouseholderStep(0.9, -0.7, 0.0, 1.0),
    ),
    case(
        "householder-direct-series-high",
        Kind::HouseholderStep(1.18321, -1.0, 0.0, 0.6),
    ),
    case(
        "householder-direct-asinh",
        Kind::HouseholderStep(2.0, 0.5, 0.0, 0.3),
    ),
    case(
        "householder-direct-asinh-far",
        Kind::HouseholderStep(30.0, -0.2, 0.0, 0.01),
    ),
    case(
        "householder-multirev-acos",
        Kind::HouseholderStep(0.5, 0.3, 3.0, 12.0),
    ),
    case(
        "householder-multirev-acos-neg",
        Kind::HouseholderStep(-0.7, -0.6, 1.0, 8.0),
    ),
    case(
        "householder-multirev-asinh",
        Kind::HouseholderStep(1.5, 0.3, 3.0, 12.0),
    ),
    case("halley-multirev", Kind::HalleyStep(0.1, 0.5, 3.0)),
    case("halley-multirev-neg", Kind::HalleyStep(-0.5, -0.8, 1.0)),
    case(
        "arc-bound-1-rev0",
        Kind::ArcBound(0.7, 9.0, 0, Branch::Left, 1),
    ),
    case(
        "arc-bound-4-rev0",
        Kind::ArcBound(0.7, 9.0, 0, Branch::Left, 4),
    ),
    case(
        "arc-bound-1-rev3",
        Kind::ArcBound(0.7, 90.0, 3, Branch::Right, 1),
    ),
    case(
        "arc-bound-4-rev3",
        Kind::ArcBound(0.7, 90.0, 3, Branch::Right, 4),
    ),
    case(
        "arc-direct-9h",
        Kind::Arc(0.12, 9.0, 0, Branch::Left, false),
    ),
    case(
        "arc-direct-1min",
        Kind::Arc(1.0, 1.0 / 60.0, 0, Branch::Left, false),
    ),
    case(
        "arc-direct-240h",
        Kind::Arc(30.0, 240.0, 0, Branch::Left, false),
    ),
    case(
        "arc-rev1-left-cold",
        Kind::Arc(0.7, 44.0, 1, Branch::Left, false),
    ),
    case(
        "arc-rev1-right-cold",
        Kind::Arc(0.7, 44.0, 1, Branch::Right, false),
    ),
    case(
        "arc-rev3-left-cold",
        Kind::Arc(0.7, 90.0, 3, Branch::Left, false),
    ),
    case(
        "arc-rev3-right-cold",
        Kind::Arc(0.7, 90.0, 3, Branch::Right, false),
    ),
    case(
        "arc-rev3-right-warm",
        Kind::Arc(0.7, 90.0, 3, Branch::Right, true),
    ),
    case("well-1", Kind::Well(0.7, 5.0, 1)),
    case("well-4", Kind::Well(0.7, 5.0, 4)),
    case("well-4-wide", Kind::Well(20.0, 10_000.0, 4)),
    case("drift-at", Kind::DriftAt(9.0, 90.0)),
    case("drift-price", Kind::DriftPrice(9.0, 90.0)),
    case("radial-eval", Kind::RadialEval(0.3)),
    case("radial-eval-high", Kind::RadialEval(0.7)),
    case("radial-eval-max", Kind::RadialEval(0.9)),
    case("drift-max-depth-r10", Kind::DriftMaxDepth(9.0, 5.0, 10)),
    case("drift-max-depth-r200", Kind::DriftMaxDepth(9.0, 5.0, 200)),
    case(
        "drift-max-depth-uncapped-r10",
        Kind::DriftMaxDepth(64.5, f64::INFINITY, 10),
    ),
    case("radial-r10", Kind::Radial(0.2, 10)),
    case("radial-r200", Kind::Radial(0.2, 200)),
    case("hohmann", Kind::Hohmann(0.5)),
    case(
        "leg-table-stay",
        Kind::LegTable(0.0, MethodPolicy::ByCost, 200),
    ),
    case(
        "leg-table-by-cost-r10",
        Kind::LegTable(2.0, MethodPolicy::ByCost, 10),
    ),
    case(
        "leg-table-by-cost-r200",
        Kind::LegTable(2.0, MethodPolicy::ByCost, 200),
    ),
    case(
        "leg-table-rule-radial-r10",
        Kind::LegTable(0.2, MethodPolicy::PaperRule, 10),
    ),
    case("price-curve", Kind::PriceCurve(9.0)),
    case("price-step-r0", Kind::PriceStep(0)),
    case("price-step-r1", Kind::PriceStep(1)),
    case("price-step-r200", Kind::PriceStep(200)),
    case("bounds-r10", Kind::Bounds(10)),
    case("bounds-r200", Kind::Bounds(200)),
    case("allocate-r2", Kind::Allocate(2)),
    case("allocate-r200", Kind::Allocate(200)),
    case("solve-budget-1", Kind::Solve(1)),
    case("solve-west-ordering-only", Kind::SolveWestOrderingOnly),
    case("solve-budget-100k", Kind::Solve(100_000)),
    case("solve-budget-150k", Kind::Solve(150_000)),
    case("solve-budget-300k", Kind::Solve(300_000)),
    case("solve-budget-1m", Kind::Solve(1_000_000)),
    case("solve-budget-default", Kind::Solve(0)),
];

/// The 16-client tour the table cases use (the `geo-servicing-16-targets` fixture: the
/// published case with five more clients, 80 days, 5 m/s).
fn sixteen_clients() -> Problem {
    let mut targets = heapless::Vec::new();
    for lon in [
        50.0, 59.0, 60.0, 60.12, 60.5, 75.0, 90.5, 100.0, 125.0, 128.0, 129.93, 130.0, 140.0,
        160.0, 160.2, 175.0,
    ] {
        // 16 = the capacity.
        let _ = targets.push(lon * DEG);
    }
    Problem {
        start_lon_rad: 48.0 * DEG,
        targets_lon_rad: targets,
        mission_time_s: 80.0 * 86_400.0,
        max_burn_mps: 5.0,
        sweep: SweepChoice::Cheaper,
        policy: MethodPolicy::ByCost,
    }
}

/// What [`prepare`] made for [`run`].
#[derive(Clone, Copy, Debug, Default)]
pub struct Prepared {
    /// Legs of the prepared tables.
    legs: usize,
    /// The allocation's price on them.
    price: f64,
    /// A warm start for an arc.
    guess: Option<f64>,
}

fn with_root(root_max_iter: u16) -> Settings {
    Settings {
        root_max_iter,
        ..Settings::default()
    }
}

/// Build and finish the east sweep's tables of the 16-client tour in `ws`; the leg count.
fn tables_of_sixteen(ws: &mut Workspace) -> usize {
    let g = Geo::standard();
    let s = Settings::default();
    let problem = sixteen_clients();
    let mut meter = Meter::new(u64::MAX);
    let Ok(legs) = build_tables(&g, Direction::East, &problem, &s, ws, &mut meter) else {
        return 0;
    };
    if let Some(tables) = ws.tables.get_mut(..legs) {
        let _ = finish_tables(&g, tables, problem.policy, &s, &mut meter);
    }
    legs
}

/// The set-up of case `index`, outside the measured span: a warm start's guess; for the cases
/// over 16 legs, the east sweep's tables of the 16-client tour (built and finished) in `ws`
/// and the price the allocation finds on them.
pub fn prepare(index: usize, ws: &mut Workspace) -> Prepared {
    let Some(c) = CASES.get(index) else {
        return Prepared::default();
    };
    match c.kind {
        Kind::Arc(phase_deg, tau_h, revs, branch, true) => {
            let g = Geo::standard();
            let b = bounds(&Settings::default());
            let guess = arc(
                &g,
                Direction::East,
                phase_deg * DEG,
                tau_h * HOUR * 1.001,
                revs,
                branch,
                b,
                None,
                &mut Gauge::paid(),
            )
            .map(|(_, _, x)| x);
            Prepared {
                guess,
                ..Prepared::default()
            }
        }
        Kind::PriceStep(_) => {
            let legs = tables_of_sixteen(ws);
            let s = Settings::default();
            let mut meter = Meter::new(u64::MAX);
            let (mut picks, mut lo, mut trial) = (ws.picks, ws.lo_picks, ws.trial);
            let price = ws.tables.get_mut(..legs).map_or(1e-7, |tables| {
                allocate(
                    tables,
                    80.0 * 86_400.0,
                    &s,
                    (&mut picks, &mut lo, &mut trial),
                    &mut meter,
                )
                .map_or(1e-7, |a| a.price)
            });
            // The allocation re-priced wells: the tables again, as the price step sees them.
            let legs = tables_of_sixteen(ws);
            Prepared {
                legs,
                price,
                guess: None,
            }
        }
        Kind::Bounds(_) | Kind::Allocate(_) => Prepared {
            legs: tables_of_sixteen(ws),
            ..Prepared::default()
        },
        _ => Prepared::default(),
    }
}

/// Run case `index` (after [`prepare`]) and return the units the solve charges for what it
/// ran (0 for an index past the cases).
pub fn run(index: usize, ws: &mut Workspace, prepared: &Prepared) -> u64 {
    let Some(c) = CASES.get(index) else {
        return 0;
    };
    let g = black_box(Geo::standard());
    let d = Settings::default();
    let mut meter = Meter::new(u64::MAX);
    match black_box(c.kind) {
        Kind::HouseholderStep(x, lam, m, t) => {
            black_box(lambert::householder_step(x, lam, m, t));
            if m > 0.0 {
                wu::LAMBERT_STEP
            } else {
                wu::LAMBERT_STEP_DIRECT
            }
        }
        Kind::HalleyStep(x, lam, m) => {
            black_box(lambert::halley_step(x, lam, m, 0.0));
            wu::LAMBERT_STEP
        }
        Kind::Arc(phase_deg, tau_h, revs, branch, _) => {
            black_box(arc(
                &g,
                Direction::East,
                phase_deg * DEG,
                tau_h * HOUR,
                revs,
                branch,
                bounds(&d),
                black_box(prepared.guess),
                &mut Gauge::metered(&mut meter),
            ));
            meter.used()
        }
        Kind::ArcBound(phase_deg, tau_h, revs, branch, max_iter) => {
            let b = LambertBounds { max_iter, tol: 0.0 };
            black_box(arc(
                &g,
                Direction::East,
                phase_deg * DEG,
                tau_h * HOUR,
                revs,
                branch,
                b,
                Some(0.999),
                &mut Gauge::metered(&mut meter),
            ));
            meter.used()
        }
        Kind::Well(phase_deg, cap, m) => {
            let _ = meter.spend(wu::WELL);
            let skipped = well_skipped(&g, Direction::East, phase_deg * DEG, m, cap);
            if !skipped {
                black_box(well_minimum(
                    &g,
                    Direction::East,
                    phase_deg * DEG,
                    m,
                    0.0,
                    cap,
                    d.well_iterations,
                    bounds(&d),
                    &mut Gauge::metered(&mut meter),
                ));
            }
            meter.used()
        }
        Kind::DriftAt(phase_deg, x) => {
            black_box(drift(&g, phase_deg).at(x));
            wu::DRIFT_EVAL
        }
        Kind::DriftPrice(phase_deg, x) => {
            black_box(drift(&g, phase_deg).price_and_point(x));
            wu::DRIFT_EVAL
        }
        Kind::RadialEval(e) => {
            black_box(radial_arc(&g, Direction::East, e));
            wu::RADIAL_EVAL
        }
        Kind::DriftMaxDepth(phase_deg, cap, r) => {
            black_box(drift(&g, phase_deg).max_depth_km(
                cap,
                d.min_radius_km,
                r,
                &mut Gauge::metered(&mut meter),
            ));
            meter.used()
        }
        Kind::Radial(phase_deg, r) => {
            black_box(radial_gauged(
                &g,
                Direction::East,
                phase_deg * DEG,
                d.min_radius_km,
                r,
                &mut Gauge::metered(&mut meter),
            ));
            meter.used()
        }
        Kind::Hohmann(phase_deg) => {
            black_box(hohmann(
                &g,
                Direction::East,
                phase_deg * DEG,
                d.min_radius_km,
            ));
            wu::HOHMANN
        }
        Kind::LegTable(phase_deg, policy, r) => {
            let s = with_root(r);
            let phase = phase_deg * DEG;
            let allowed = if phase > 0.0 {
                wu::allowed_methods(policy, table::rule_method(phase, &s))
            } else {
                [false; 4]
            };
            let _ = meter.spend(wu::leg_table(allowed));
            black_box(table::build(
                &g,
                Direction::East,
                0,
                0.0,
                phase,
                phase,
                5.0,
                policy,
                &s,
                &mut Gauge::metered(&mut meter),
            ));
            meter.used()
        }
        Kind::PriceCurve(phase_deg) => {
            let model = drift(&g, phase_deg);
            let x_max =
                model.max_depth_km(5.0, d.min_radius_km, d.root_max_iter, &mut Gauge::paid());
            let x_max = black_box(x_max.unwrap_or(100.0));
            let _ = meter.spend(PriceCurve::work_units());
            black_box(PriceCurve::new(&model, x_max));
            meter.used()
        }
        Kind::PriceStep(r) => {
            let s = with_root(r);
            let legs = prepared.legs;
            let tables = ws.tables.get(..legs).unwrap_or(&[]);
            let mut picks = ws.picks;
            let _ = black_box(pick_all(
                tables,
                prepared.price,
                &s,
                picks.get_mut(..legs).unwrap_or(&mut []),
                &mut meter,
            ));
            meter.used()
        }
        Kind::Bounds(r) => {
            let s = with_root(r);
            let legs = prepared.legs;
            let tables = ws.tables.get(..legs).unwrap_or(&[]);
            let policy = MethodPolicy::ByCost;
            let mission = 80.0 * 86_400.0;
            let _ = meter.spend(wu::bounds(&s, legs));
            let fastest_lb = |t: &table::LegTable| table::fastest_lower_bound_s(&g, t, policy, &s);
            let bound: f64 = tables.iter().map(fastest_lb).sum();
            let mut gauge = Gauge::metered(&mut meter);
            let mut dv = 0.0;
            for t in tables {
                let avail_s = mission - (bound - fastest_lb(t));
                dv += table::dv_lower_bound_mps(&g, t, policy, &s, avail_s, &mut gauge);
            }
            black_box((bound, dv));
            meter.used()
        }
        Kind::Allocate(r) => {
            let s = with_root(r);
            let legs = prepared.legs;
            let (mut picks, mut lo, mut trial) = (ws.picks, ws.lo_picks, ws.trial);
            let tables = ws.tables.get_mut(..legs).unwrap_or(&mut []);
            let _ = black_box(allocate(
                tables,
                80.0 * 86_400.0,
                &s,
                (&mut picks, &mut lo, &mut trial),
                &mut meter,
            ));
            meter.used()
        }
        Kind::SolveWestOrderingOnly => {
            let mut problem = sixteen_clients();
            problem.sweep = SweepChoice::West;
            let budget = wu::SOLVE
                .saturating_add(wu::reserve(&d, problem.targets_lon_rad.len()))
                .saturating_add(wu::SWEEP);
            let s = Settings {
                work_budget: budget,
                ..d
            };
            let mut out = Solution::new();
            let _ = solve(black_box(&problem), black_box(&s), ws, &mut out);
            black_box(&out);
            out.info.work_units
        }
        Kind::Solve(budget) => {
            let s = Settings {
                work_budget: if budget == 0 { d.work_budget } else { budget },
                ..d
            };
            let problem = sixteen_clients();
            let mut out = Solution::new();
            let _ = solve(black_box(&problem), black_box(&s), ws, &mut out);
            black_box(&out);
            out.info.work_units
        }
    }
}

fn drift(g: &Geo, phase_deg: f64) -> Drift {
    Drift {
        g: *g,
        dir: Direction::East,
        phase_rad: phase_deg * DEG,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    extern crate std;

    #[test]
    fn every_case_runs_and_charges() {
        let mut ws = std::boxed::Box::new(Workspace::new());
        for (i, c) in CASES.iter().enumerate() {
            let p = prepare(i, &mut ws);
            let units = run(i, &mut ws, &p);
            std::println!("{} {units}", c.name);
            assert!(units > 0, "{}", c.name);
        }
    }
}
