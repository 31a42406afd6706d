//! Planner B's charged steps, one at a time, for the work-unit bound (issue 33 item 1; the GEO
//! tour's `geo_tour/kernels.rs` and planner A's `pseudospectral/kernels.rs` are the models).
//! Not part of the planner's interface: the kernel image (`firmware/src/kb_main.rs`) runs every
//! case between its instruction markers and divides each case's M7 instructions by the units
//! the solve charges for it.
//!
//! Each case runs the solve's own code for one metered step, on a state [`prepare`] made outside
//! the measured span (the context, the impulse points, the minimum-norm and the least-fuel impulses
//! of a fixed-point solve, the incumbent's dual certificate), and returns the units the solve
//! charges for what it ran: one fixed-point iteration (Cholesky path, and the SVD path at
//! coincident points), one least-fuel fixed-point iteration, an SVD (cut after one and two sweeps,
//! and to convergence), cone programs cut after 1 iteration and run to the 40-iteration cap, search
//! evaluations (a sample's, a local search's with the incumbent's dual bound computed and not
//! conclusive, four linearisations), a search with its sampling and bookkeeping, an osculating
//! evaluation, a Jacobian column, the correction (Jacobian and k Broyden steps), the final checks,
//! and whole solves. The problems are Wang 2018's (e = 0.0678) at the capacity of 6 impulses and at
//! 2, the same in the classical set, and a high-eccentricity chief (e = 0.75). The image also
//! counts each case's Kepler solves and Newton steps (feature `kernel-counters`), and its test
//! holds each case to every solve at `kepler_max_iter`'s limit.

use super::elements::M_PER_KM;
use super::kepler::true_anomaly;
use super::returned::write_solution;
use super::search::{search, Phases, Score, Scorer, SearchScratch};
use super::settings::{ElementSet, Settings};
use super::solution::Solution;
use super::solver::{conditioning_at, correct, fixed_point, nonlinear_error, solve_points};
use super::transfer::{build_system, propagate, Context, ImpulseModel, Points, XVector};
use super::types::{ImpulsePlan, ImpulsePoint, MeanElements, Problem, RelativeElements};
use super::workspace::Workspace;
use super::{osculating, pinv, socp, validate, work_units};
use crate::capacity::MAX_IMPULSES;
use crate::work::Meter;
use core::hint::black_box;

/// One degree, rad.
const DEG: f64 = core::f64::consts::PI / 180.0;

/// The chief of a case.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Chief {
    /// Wang 2018's chief (a = 7178.137 km, e = 0.0678, i = 63.43 deg).
    Paper,
    /// A high-eccentricity chief (a = 30000 km, e = 0.75, perigee altitude 1122 km).
    HighEcc,
}

/// A problem of the cases.
#[derive(Clone, Copy, Debug)]
pub struct Shape {
    chief: Chief,
    impulses: usize,
    /// Every point at the same argument of latitude (F rank-deficient: the SVD path).
    coincident: bool,
    set: ElementSet,
}

const fn shape(chief: Chief, impulses: usize, coincident: bool, set: ElementSet) -> Shape {
    Shape {
        chief,
        impulses,
        coincident,
        set,
    }
}

const N6: Shape = shape(Chief::Paper, MAX_IMPULSES, false, ElementSet::Equinoctial);
const N2: Shape = shape(Chief::Paper, 2, false, ElementSet::Equinoctial);
const N6_CLASSICAL: Shape = shape(Chief::Paper, MAX_IMPULSES, false, ElementSet::Classical);
const N6_HIGH_E: Shape = shape(Chief::HighEcc, MAX_IMPULSES, false, ElementSet::Equinoctial);
const N6_COINCIDENT: Shape = shape(Chief::Paper, MAX_IMPULSES, true, ElementSet::Equinoctial);

/// What a case runs.
#[derive(Clone, Copy, Debug)]
enum Kind {
    /// One minimum-norm fixed-point iteration from zero impulses.
    FixedPoint,
    /// One least-fuel fixed-point iteration from the minimum-norm impulses, with the least-fuel
    /// tolerance in m/s (0: the default).
    MinFuelIteration(f64),
    /// `pinv::solve_min_norm` on F at the minimum-norm impulses, cut after this many sweeps
    /// (0: `svd_max_iter`, to convergence). The first sweeps rotate every column pair, the
    /// dearest a sweep can be.
    Svd(u16),
    /// `socp::least_fuel` on F at the minimum-norm impulses (tolerance m/s, iteration cap).
    Cone(f64, u16),
    /// One search evaluation of the points' phases (linearisations, tolerance m/s, with the
    /// incumbent's dual bound computed and not conclusive).
    Evaluation(u16, f64, bool),
    /// A search with 16 samples, 4 starts and this many evaluations.
    Search(u32),
    /// One short-period evaluation of the osculating <-> mean conversion.
    Osculating,
    /// One exact propagation and defect (a column of the Jacobian).
    JacobianColumn,
    /// The correction from the least-fuel plan with this many Broyden steps (tolerance 0: every
    /// step is made).
    Correct(u16),
    /// The final checks: rank and condition at the plan, the plan written out (its nonlinear
    /// re-check), the nonlinear check that starts the correction.
    FinalChecks,
    /// `kepler::true_anomaly` at e = 0.75 with this many Newton steps (not charged alone: it
    /// is part of every propagation; the difference of two cases is one step).
    Kepler(u16),
    /// A whole solve at fixed points (budget; 0: the default).
    Solve(u64),
    /// A whole search solve with this budget (0: the default).
    SolveSearch(u64),
}

/// A kernel case: its name (the record's key), its problem and what it runs.
#[derive(Clone, Copy, Debug)]
pub struct Case {
    /// Name in the firmware's output.
    pub name: &'static str,
    shape: Shape,
    kind: Kind,
}

impl Case {
    /// Whether the solve charges what the case runs: every case but the Kepler solves (part of
    /// every propagation; two of them give the cost of one Newton step).
    pub const fn charged(&self) -> bool {
        !matches!(self.kind, Kind::Kepler(_))
    }
}

const fn case(name: &'static str, shape: Shape, kind: Kind) -> Case {
    Case { name, shape, kind }
}

/// Every case, in the order the kernel image runs them.
pub const CASES: &[Case] = &[
    case("fixed-point-n6", N6, Kind::FixedPoint),
    case("fixed-point-n2", N2, Kind::FixedPoint),
    case("fixed-point-n6-classical", N6_CLASSICAL, Kind::FixedPoint),
    case("fixed-point-n6-high-e", N6_HIGH_E, Kind::FixedPoint),
    case("fixed-point-n6-coincident", N6_COINCIDENT, Kind::FixedPoint),
    case("min-fuel-iteration-n6", N6, Kind::MinFuelIteration(0.0)),
    case(
        "min-fuel-iteration-n6-cap",
        N6,
        Kind::MinFuelIteration(1e-300),
    ),
    case(
        "min-fuel-iteration-n2-cap",
        N2,
        Kind::MinFuelIteration(1e-300),
    ),
    case("svd-1-sweep-n6", N6, Kind::Svd(1)),
    case("svd-2-sweeps-n6", N6, Kind::Svd(2)),
    case("svd-1-sweep-n2", N2, Kind::Svd(1)),
    case("svd-n6", N6, Kind::Svd(0)),
    case("svd-n2", N2, Kind::Svd(0)),
    case("svd-n6-coincident", N6_COINCIDENT, Kind::Svd(0)),
    case("cone-1-n6", N6, Kind::Cone(1e-9, 1)),
    case("cone-1-n2", N2, Kind::Cone(1e-9, 1)),
    case("cone-default-n6", N6, Kind::Cone(1e-9, 40)),
    case("cone-40-n6", N6, Kind::Cone(1e-300, 40)),
    case("cone-40-n2", N2, Kind::Cone(1e-300, 40)),
    case("evaluation-screen-n6", N6, Kind::Evaluation(1, 1e-3, false)),
    case("evaluation-local-n6", N6, Kind::Evaluation(1, 1e-7, true)),
    case("evaluation-local-n2", N2, Kind::Evaluation(1, 1e-7, true)),
    case("evaluation-lin4-n6", N6, Kind::Evaluation(4, 1e-7, true)),
    case("search-64-n6", N6, Kind::Search(64)),
    case("search-64-n2", N2, Kind::Search(64)),
    case("osculating-evaluation", N6, Kind::Osculating),
    case("jacobian-column-n6", N6, Kind::JacobianColumn),
    case("jacobian-column-n6-high-e", N6_HIGH_E, Kind::JacobianColumn),
    case("correct-0-n6", N6, Kind::Correct(0)),
    case("correct-6-n6", N6, Kind::Correct(6)),
    case("correct-6-n2", N2, Kind::Correct(6)),
    case("final-checks-n6", N6, Kind::FinalChecks),
    case("final-checks-n2", N2, Kind::FinalChecks),
    case("final-checks-n6-high-e", N6_HIGH_E, Kind::FinalChecks),
    case("kepler-1", N6, Kind::Kepler(1)),
    case("kepler-2", N6, Kind::Kepler(2)),
    case("solve-fixed-n6", N6, Kind::Solve(0)),
    case("solve-fixed-n2", N2, Kind::Solve(0)),
    case("solve-fixed-n6-high-e", N6_HIGH_E, Kind::Solve(0)),
    case("solve-fixed-n6-coincident", N6_COINCIDENT, Kind::Solve(0)),
    case("solve-search-n6-1m", N6, Kind::SolveSearch(1_000_000)),
    case("solve-search-n2-1m", N2, Kind::SolveSearch(1_000_000)),
    // The worst planner-B request within the built-in limits, whole, at the default budget:
    // `fixtures/worst-case/wang2018-search-6imp.toml`'s problem (a test holds them equal).
    case("solve-search-n6-default", N6, Kind::SolveSearch(0)),
];

/// The fixed points of the cases (deg, revolutions): Table 5's four, two more.
const POINTS: [(f64, i32); MAX_IMPULSES] = [
    (266.683_882_912, 2),
    (281.328_967_107, 4),
    (236.538_571_157, 5),
    (287.665_882_973, 2),
    (100.0, 3),
    (200.0, 1),
];

/// The problem of `shape` with `plan`.
fn problem(shape: Shape, search: bool) -> Problem {
    let chief = match shape.chief {
        Chief::Paper => MeanElements {
            sma_km: 7178.137,
            ecc: 0.0678,
            inc_rad: 63.4349 * DEG,
            raan_rad: 112.0 * DEG,
            argp_rad: 0.0,
            mean_anomaly_rad: 0.0,
        },
        Chief::HighEcc => MeanElements {
            sma_km: 30_000.0,
            ecc: 0.75,
            inc_rad: 63.4349 * DEG,
            raan_rad: 112.0 * DEG,
            argp_rad: 0.3,
            mean_anomaly_rad: 0.0,
        },
    };
    let rel = |v: [f64; 6]| RelativeElements {
        dsma_km: v[0],
        decc: v[1],
        dinc_rad: v[2] * DEG,
        draan_rad: v[3] * DEG,
        dargp_rad: v[4] * DEG,
        dmean_anomaly_rad: v[5] * DEG,
    };
    let plan = if search {
        ImpulsePlan::Search {
            impulses: u8::try_from(shape.impulses).unwrap_or(1),
            max_revolutions: 100,
        }
    } else {
        let mut points = heapless::Vec::new();
        for (k, (u, revs)) in POINTS.iter().take(shape.impulses).enumerate() {
            let (u, revs) = if shape.coincident {
                (100.0, i32::from(k == 0))
            } else {
                (*u, *revs)
            };
            let _ = points.push(ImpulsePoint {
                arg_latitude_rad: u * DEG,
                revolutions: revs,
            });
        }
        ImpulsePlan::Fixed(points)
    };
    Problem {
        chief,
        initial: rel([
            4.0940e-4, -1.3888e-4, -1.0831e-3, 1.5409e-2, -1.6134e-2, 9.2428e-3,
        ]),
        target: rel([
            -1.6389e-4, 5.5597e-4, 4.3361e-3, 7.1228e-2, -6.3572e-2, 3.1718e-2,
        ]),
        plan,
    }
}

fn settings_of(shape: Shape) -> Settings {
    Settings {
        element_set: shape.set,
        ..Settings::default()
    }
}

/// What [`prepare`] made for a case.
#[derive(Clone, Debug)]
pub struct Prepared {
    /// The set-up failed (the case then runs nothing).
    failed: bool,
    ctx: Option<Context>,
    points: Points,
    /// The minimum-norm impulses of the fixed point.
    min_norm: XVector,
    /// The least-fuel impulses.
    least_fuel: XVector,
    /// The phases of the points (cumulative, rad) for the search's evaluations.
    phases: Phases,
    /// The incumbent's dual certificate.
    dual: [f64; 6],
}

impl Prepared {
    fn failed() -> Self {
        Self {
            failed: true,
            ctx: None,
            points: Points::new(),
            min_norm: XVector::zeros(),
            least_fuel: XVector::zeros(),
            phases: [0.0; MAX_IMPULSES],
            dual: [0.0; 6],
        }
    }
}

/// The set-up of case `index`, outside the measured span: the context and the points, the
/// minimum-norm and least-fuel impulses at them (two fixed-point solves without the
/// correction), F at the minimum-norm impulses left in the workspace, the incumbent's dual.
pub fn prepare(index: usize, ws: &mut Workspace, _out: &mut Solution) -> Prepared {
    let Some(c) = CASES.get(index) else {
        return Prepared::failed();
    };
    let settings = settings_of(c.shape);
    let p = problem(c.shape, false);
    let Ok(ctx) = validate::validate(&p, &settings) else {
        return Prepared::failed();
    };
    let mut prepared = Prepared::failed();
    let ImpulsePlan::Fixed(points) = &p.plan else {
        return prepared;
    };
    let mut pts = Points::new();
    for (slot, q) in pts.at.iter_mut().zip(points.iter()) {
        *slot = *q;
    }
    pts.n = points.len();
    ws.seq.work = Meter::new(u64::MAX);
    let linear = Settings {
        min_fuel: false,
        nonlinear_correction: false,
        ..settings
    };
    let rep = solve_points(&ctx, &pts, &linear, &mut ws.seq);
    prepared.min_norm = rep.dv;
    let fuel = Settings {
        nonlinear_correction: false,
        ..settings
    };
    let rep = solve_points(&ctx, &pts, &fuel, &mut ws.seq);
    prepared.least_fuel = rep.dv;
    // The phases of the points: cumulative argument of latitude from the deputy's start.
    let u0 = ctx.model.phase_rad(&ctx.deputy0);
    let mut prev_u = u0;
    let mut phi = 0.0;
    for (slot, q) in prepared.phases.iter_mut().zip(pts.at.iter()).take(pts.n) {
        let gap = super::elements::wrap_two_pi(q.arg_latitude_rad - prev_u)
            + super::elements::TWO_PI * f64::from(q.revolutions);
        phi += gap;
        *slot = phi;
        prev_u = q.arg_latitude_rad;
    }
    // The incumbent's dual: a local evaluation of the points.
    let scorer = Scorer {
        ctx: &ctx,
        settings: &settings,
        n: pts.n,
        u0,
        max_revolutions: 100,
    };
    let mut scratch_pts = Points::new();
    let inc = scorer.score(
        &prepared.phases,
        1,
        1e-7,
        None,
        &mut ws.seq,
        &mut scratch_pts,
    );
    prepared.dual = inc.dual;
    // F and dY at the minimum-norm impulses.
    if propagate(
        &ctx,
        &pts,
        &prepared.min_norm,
        ImpulseModel::Linear,
        &settings,
        &mut ws.seq,
    )
    .is_err()
    {
        return Prepared::failed();
    }
    build_system(&ctx, &pts, &mut ws.seq);
    ws.seq.work = Meter::new(u64::MAX);
    prepared.failed = false;
    prepared.ctx = Some(ctx);
    prepared.points = pts;
    prepared
}

/// Run case `index` on what [`prepare`] made; the units the solve charges for it.
pub fn run(index: usize, ws: &mut Workspace, out: &mut Solution, prepared: &Prepared) -> u64 {
    let Some(c) = CASES.get(index) else {
        return 0;
    };
    let (false, Some(ctx)) = (prepared.failed, prepared.ctx.as_ref()) else {
        return 0;
    };
    let settings = settings_of(c.shape);
    let pts = &prepared.points;
    let n = pts.n;
    let columns = n.saturating_mul(3);
    let before = ws.seq.work.used();
    let metered = |ws: &Workspace| ws.seq.work.used().saturating_sub(before);
    match black_box(c.kind) {
        Kind::FixedPoint => {
            let mut dv = XVector::zeros();
            let r = fixed_point(ctx, pts, &settings, &mut ws.seq, &mut dv, false, 1);
            black_box((r.is_ok(), dv));
            metered(ws)
        }
        Kind::MinFuelIteration(tol) => {
            let s = Settings {
                min_fuel_tol_mps: if tol > 0.0 {
                    tol
                } else {
                    settings.min_fuel_tol_mps
                },
                ..settings
            };
            let mut dv = prepared.min_norm;
            let r = fixed_point(ctx, pts, &s, &mut ws.seq, &mut dv, true, 1);
            black_box((r.is_ok(), dv));
            metered(ws)
        }
        Kind::Svd(max_sweeps) => {
            let mut sweeps = 0;
            let r = pinv::solve_min_norm(
                &ws.seq.f,
                columns,
                &ws.seq.dy,
                settings.rank_rcond,
                if max_sweeps == 0 {
                    settings.svd_max_iter
                } else {
                    max_sweeps
                },
                &mut sweeps,
            );
            black_box(r.is_ok());
            work_units::svd(n, sweeps)
        }
        Kind::Cone(tol_mps, max_iter) => {
            let mut y = [0.0; 6];
            y.copy_from_slice(ws.seq.dy.as_slice());
            let lf = socp::least_fuel(
                &ws.seq.f,
                columns,
                &y,
                tol_mps / M_PER_KM,
                settings.rank_rcond,
                max_iter,
            );
            let iterations = lf.map_or(0, |lf| lf.iterations);
            black_box(lf.map(|lf| lf.total));
            work_units::cone_program(n, iterations)
        }
        Kind::Evaluation(linearisations, tol_mps, with_incumbent) => {
            let s = Settings {
                search_fixed_point_max_iter: linearisations,
                ..settings
            };
            let scorer = Scorer {
                ctx,
                settings: &s,
                n,
                u0: ctx.model.phase_rad(&ctx.deputy0),
                max_revolutions: 100,
            };
            let inc = Score {
                cost: f64::INFINITY,
                dual: prepared.dual,
            };
            let mut scratch = Points::new();
            let sc = scorer.score(
                &prepared.phases,
                linearisations,
                tol_mps,
                with_incumbent.then_some(&inc),
                &mut ws.seq,
                &mut scratch,
            );
            black_box(sc.cost);
            metered(ws)
        }
        Kind::Search(evaluations) => {
            let s = Settings {
                search_samples: 16,
                search_starts: 4,
                search_max_evaluations: evaluations,
                ..settings
            };
            let mut scratch = SearchScratch::new();
            let mut found = Points::new();
            let used = search(ctx, n, 100, &s, &mut ws.seq, &mut found, &mut scratch);
            black_box((used, found.n));
            metered(ws)
        }
        Kind::Osculating => {
            let q = super::equinoctial::from_classical(&ctx.chief0);
            black_box(osculating::short_period(&q, settings.kepler_max_iter));
            work_units::osculating_evaluation()
        }
        Kind::JacobianColumn => {
            let r = nonlinear_error(ctx, pts, &prepared.least_fuel, &settings, &mut ws.seq);
            black_box(r.map(|m| m.pos_m).ok());
            work_units::jacobian_column(n)
        }
        Kind::Correct(steps) => {
            let s = Settings {
                correction_max_iter: steps,
                correction_tol: 1e-300,
                ..settings
            };
            let mut rep = solve_report(prepared.least_fuel);
            let r = correct(ctx, pts, &s, &mut ws.seq, &mut rep);
            black_box((r.is_ok(), rep.dv));
            metered(ws)
        }
        Kind::FinalChecks => {
            let dv = prepared.least_fuel;
            let cond = conditioning_at(ctx, pts, &dv, &settings, &mut ws.seq);
            black_box(cond.is_ok());
            let start = nonlinear_error(ctx, pts, &dv, &settings, &mut ws.seq);
            black_box(start.map(|m| m.pos_m).ok());
            let rep = solve_report(dv);
            write_solution(ctx, pts, &settings, &mut ws.seq, &rep, 1, out);
            // The SVD of `conditioning_at` is metered once done.
            work_units::final_checks(n).saturating_add(metered(ws))
        }
        Kind::Kepler(steps) => {
            let m = black_box(ctx.chief0[super::elements::MA] + 2.0);
            black_box(true_anomaly(m, black_box(0.75), steps));
            0
        }
        Kind::Solve(budget) | Kind::SolveSearch(budget) => {
            let p = problem(c.shape, matches!(c.kind, Kind::SolveSearch(_)));
            let s = Settings {
                work_budget: if budget == 0 {
                    settings.work_budget
                } else {
                    budget
                },
                ..settings
            };
            let r = super::solve(&p, &s, ws, out);
            black_box(r.is_ok());
            out.info.work_units
        }
    }
}

/// The problem a whole-solve case solves (`None` for the other cases).
pub fn case_problem(index: usize) -> Option<Problem> {
    let c = CASES.get(index)?;
    match c.kind {
        Kind::Solve(_) => Some(problem(c.shape, false)),
        Kind::SolveSearch(_) => Some(problem(c.shape, true)),
        _ => None,
    }
}

/// A report holding the plan `dv` (the rest as a fresh solve's), for the steps that follow the
/// fixed point.
fn solve_report(dv: XVector) -> super::solver::Report {
    super::solver::Report {
        min_fuel_used: true,
        ..super::solver::Report::holding(dv)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_case_prepares_and_runs_and_charges() {
        let mut ws = Workspace::new();
        let mut out = Solution::new();
        for (index, c) in CASES.iter().enumerate() {
            let prepared = prepare(index, &mut ws, &mut out);
            assert!(!prepared.failed, "{}", c.name);
            let units = run(index, &mut ws, &mut out, &prepared);
            assert_eq!(units > 0, c.charged(), "{}", c.name);
        }
    }
}
