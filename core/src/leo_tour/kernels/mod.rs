//! The per-arc search's charged steps, one at a time, for the work-unit bound (issue 33; the
//! GEO tour's and planners A's and B's `kernels.rs` are the models). Not part of the planner's
//! interface: the kernel image (`reconfig-firmware-kl`, feature `kernels_leo`) runs every
//! case between its instruction markers and its test divides each case's M7 instructions by
//! the units the solve charges for it (`tests/tests/qemu_firmware/kernels_leo_image.rs`).
//!
//! Each case runs the solve's own code for one metered step, on a state [`prepare`] made
//! outside the measured span (the clients' tracks and mean orbits, the client's arrival, a
//! grid candidate of the paper's arc), and returns the units the solve charges for what it
//! ran: planning-model flights of 1 and 4,096 RK4 steps; search-model flights, client states
//! and mean orbits (Table 1's near-circular orbit, and an e = 0.75 orbit whose Kepler solves
//! take the most Newton steps); Lambert solves (direct and 14 revolutions, each branch, cold
//! and warm, and with no tolerance); the grid's two-body propagation cut
//! after 1, 2 and 60 iterations; compass-search evaluations in both models (and one refused
//! at its epochs, and one repeated, its coast and client state looked up); the cheapest last-leg family over every family; a shooting cut after one
//! aim-point iteration and one to convergence in the search model; a grid epoch (with the
//! default families and with 200 revolutions allowed); a bounded refinement; three iterations of
//! the descent on four impulses; a round of hops;
//! the final check of a plan; whole solves and an estimate cut at several budgets; three whole
//! sequencings (Example I at the defaults, eight clients whose estimates are all refused, eight
//! clients with one-epoch estimates). The image
//! also counts each case's Kepler solves and Newton steps (feature `kernel-counters`), and its
//! test holds each case to every solve at `mean_j2`'s limit of Newton steps.

use super::arc::{Coast, Ctx, Point, StartCache};
use super::flight::Model;
use super::j2::{pos, propagate_steps, step_count, State};
use super::mean_j2::MeanOrbit;
use super::sequence::Sequence;
use super::shoot::{metered_lambert, shoot, Family, Offset, Secant};
use super::tour_order::{solve_sequence, SequenceWorkspace};
use super::types::{ArcProblem, ArcSolution, Settings, MAX_IMPULSES};
use super::work_units as wu;
use super::workspace::Workspace;
use super::{estimate_arc_mps, solve_arc};
use crate::lambert::{self, Branch};
use crate::work::Meter;
use core::hint::black_box;

mod inputs;

pub use inputs::paper_arc;
use inputs::{orbit_state, sequence_case, Orbit, Tour};

/// What a case runs.
#[derive(Clone, Copy, Debug)]
enum Kind {
    /// A planning-model flight of this many RK4 steps.
    Flight(u32),
    /// A search-model flight of half a day.
    MeanFlight(Orbit),
    /// A client's state from its mean orbit, half a day on.
    MeanState(Orbit),
    /// A client's mean orbit from its state.
    MeanOrbit(Orbit),
    /// `kepler::true_anomaly` at e = 0.75 with this many Newton steps (not charged alone: part
    /// of every search-model flight; the difference of two cases is one step).
    Kepler(u16),
    /// A Lambert solve of the paper's arc's last leg (revolutions, branch, warm started).
    Lambert(u16, Branch, bool),
    /// The same with `lambert_max_iter` 200 and no tolerance: every step is made until one
    /// leaves x unchanged.
    LambertBound(u16, Branch),
    /// The grid's two-body propagation cut after this many iterations (charged as such).
    TwoBody(u16),
    /// A compass-search evaluation of the grid's best candidate in this model.
    Evaluation(Model),
    /// An evaluation whose epochs are out of order (refused before any flight).
    EvaluationRefused,
    /// The same evaluation again: its coast and client state found among the last
    /// evaluation's (looked up, not flown).
    EvaluationAgain,
    /// The cheapest last-leg family of the grid's best candidate over every family.
    BestFamily,
    /// A shooting of the paper's arc's last leg in this model, at most this many iterations.
    Shoot(Model, u16),
    /// One grid epoch with this many revolutions allowed.
    GridEpoch(u16),
    /// A refinement of the grid's best candidate with this many evaluations.
    Refine(u32),
    /// A descent of this many iterations from the grid's best candidate of the paper's arc
    /// with four impulses (nine variables, the most), refined first.
    Descent(u32),
    /// A round of hops from the grid's best candidate.
    Hops,
    /// A node seed at the arc start, its last leg's family chosen among all (the dearest
    /// path: a grid epoch with no two-impulse family).
    NodeSeed,
    /// The node seed's own arithmetic alone (the node's epoch, the transfer and its split),
    /// what `NODE_SEED` pays for.
    NodeSeedArithmetic,
    /// The final check of the grid's best candidate (the planning model's flight and shooting).
    Finish,
    /// A whole solve of the paper's arc with this budget.
    Solve(u64),
    /// A whole solve of the paper's arc searched in the planning model throughout (the slow
    /// reference search), at the default budget: it runs to the budget, the most any arc
    /// request may spend.
    SolvePlanningModel,
    /// A whole estimate of the paper's arc with this budget.
    Estimate(u64),
    /// A whole sequencing ([`solve_sequence`]).
    Sequence(Tour),
}

/// A kernel case: its name (the record's key) and what it runs.
#[derive(Clone, Copy, Debug)]
pub struct Case {
    /// Name in the firmware's output.
    pub name: &'static str,
    kind: Kind,
}

impl Case {
    /// Whether the solve charges what the case runs: every case but the Kepler solves (part of
    /// every search-model flight; two of them give the cost of one Newton step).
    pub const fn charged(&self) -> bool {
        !matches!(self.kind, Kind::Kepler(_))
    }
}

const fn case(name: &'static str, kind: Kind) -> Case {
    Case { name, kind }
}

const LEFT: Branch = Branch::Left;
const RIGHT: Branch = Branch::Right;

/// Every case, in the order the kernel image runs them.
pub const CASES: &[Case] = &[
    case("flight-1-step", Kind::Flight(1)),
    case("flight-4096-steps", Kind::Flight(4096)),
    case("mean-flight", Kind::MeanFlight(Orbit::Paper)),
    case("mean-flight-high-e", Kind::MeanFlight(Orbit::HighEcc)),
    case("mean-state", Kind::MeanState(Orbit::Paper)),
    case("mean-state-high-e", Kind::MeanState(Orbit::HighEcc)),
    case("mean-orbit", Kind::MeanOrbit(Orbit::Paper)),
    case("mean-orbit-high-e", Kind::MeanOrbit(Orbit::HighEcc)),
    case("kepler-1", Kind::Kepler(1)),
    case("kepler-2", Kind::Kepler(2)),
    case("lambert-direct", Kind::Lambert(0, LEFT, false)),
    case("lambert-14rev-left", Kind::Lambert(14, LEFT, false)),
    case("lambert-14rev-right", Kind::Lambert(14, RIGHT, false)),
    case("lambert-14rev-warm", Kind::Lambert(14, LEFT, true)),
    case("lambert-direct-no-tolerance", Kind::LambertBound(0, LEFT)),
    case("lambert-14rev-no-tolerance", Kind::LambertBound(14, RIGHT)),
    case("two-body-1", Kind::TwoBody(1)),
    case("two-body-2", Kind::TwoBody(2)),
    case("two-body-60", Kind::TwoBody(wu::TWO_BODY_MAX_ITER)),
    case("evaluation-search", Kind::Evaluation(Model::MeanElements)),
    case("evaluation-planning", Kind::Evaluation(Model::Planning)),
    case("evaluation-refused", Kind::EvaluationRefused),
    case("evaluation-again", Kind::EvaluationAgain),
    case("best-family", Kind::BestFamily),
    case("shoot-1-iteration", Kind::Shoot(Model::Planning, 1)),
    case("shoot-search-model", Kind::Shoot(Model::MeanElements, 30)),
    case("grid-epoch", Kind::GridEpoch(40)),
    case("grid-epoch-200-revs", Kind::GridEpoch(200)),
    case("refine-200", Kind::Refine(200)),
    case("descent-4-impulses-3", Kind::Descent(3)),
    case("hops", Kind::Hops),
    case("node-seed", Kind::NodeSeed),
    case("node-seed-arithmetic", Kind::NodeSeedArithmetic),
    case("finish", Kind::Finish),
    case("solve-budget-1", Kind::Solve(1)),
    case("solve-budget-2m", Kind::Solve(2_000_000)),
    case("solve-default", Kind::Solve(wu::DEFAULT_WORK_BUDGET)),
    case("estimate-budget-2m", Kind::Estimate(2_000_000)),
    case("solve-planning-model-default", Kind::SolvePlanningModel),
    case("sequence-example-1", Kind::Sequence(Tour::ExampleOne)),
    case("sequence-8-refused", Kind::Sequence(Tour::EightRefused)),
    case("sequence-8-coarse", Kind::Sequence(Tour::EightCoarse)),
];

/// Half a day, s: the span of the search-model cases.
const HALF_DAY_S: f64 = 43_200.0;

/// The settings of a case: the defaults, with the revolutions of a grid epoch.
fn settings_of(kind: Kind) -> Settings {
    let mut s = Settings::default();
    if let Kind::GridEpoch(revs) = kind {
        s.max_revolutions = revs;
        s.grid_points = 1;
    }
    if let Kind::LambertBound(..) = kind {
        s.lambert_max_iter = 200;
        s.lambert_tol = 0.0;
    }
    s
}

/// What a case needs, made outside the measured span.
#[derive(Clone, Copy, Debug)]
pub struct Prepared {
    settings: Settings,
    problem: ArcProblem,
    mean_a: Option<MeanOrbit>,
    mean_b: Option<MeanOrbit>,
    /// Client B's arrival in the planning model.
    b_end: State,
    /// The grid's best candidate (default settings).
    point: Option<Point>,
    /// A Lambert solution's x for the warm start.
    guess: Option<f64>,
    /// The orbit of a search-model case: its state and mean orbit.
    orbit: Option<(State, MeanOrbit)>,
    /// The caches of a search-model evaluation of `point` (the repeated evaluation's start).
    caches: ([Option<Coast>; MAX_IMPULSES], StartCache),
}

/// The context of the paper's arc from `prepared` (no work: the tracks, mean orbits and
/// arrival were made by [`prepare`]) with flights in `model` and a meter of `budget`.
fn ctx<'a>(
    p: &'a Prepared,
    ws: (&'a super::track::Track, &'a super::track::Track),
    model: Model,
    budget: u64,
) -> Ctx<'a> {
    Ctx {
        settings: &p.settings,
        g: p.settings.gravity(),
        impulses: usize::from(p.problem.impulses),
        tf: p.problem.duration_s,
        a: Some(ws.0),
        b: Some(ws.1),
        b_end: p.b_end,
        flight: p.settings.flight(model),
        mean_a: p.mean_a,
        mean_b: p.mean_b,
        meter: Meter::new(budget),
        evals: 0,
        secant: Secant::default(),
        lambert_guess: None,
        start_cache: None,
        coasts: [None; MAX_IMPULSES],
        polish_follows: true,
    }
}

/// The paper's last leg: 14 revolutions from the arc start (the shooting's test).
const LAST_LEG_REVS: u16 = 14;

/// Set up case `index`: the paper's arc's tracks in `ws`, its mean orbits and arrival, the
/// grid's best candidate. Outside the measured span.
pub fn prepare(index: usize, ws: &mut SequenceWorkspace) -> Option<Prepared> {
    let ws = &mut ws.arc;
    let kind = CASES.get(index)?.kind;
    let settings = settings_of(kind);
    let mut problem = paper_arc()?;
    if let Kind::Descent(_) = kind {
        problem.impulses = 4;
    }
    let g = settings.gravity();
    let planning = settings.flight(Model::Planning);
    let mut meter = Meter::new(u64::MAX);
    ws.a.fill(&planning, &problem.from, problem.duration_s, &mut meter)?;
    ws.b.fill(&planning, &problem.to, problem.duration_s, &mut meter)?;
    let n = step_count(
        problem.duration_s,
        settings.step_s,
        settings.max_steps.saturating_mul(64),
    )?;
    let b_end = propagate_steps(&g, &problem.to, problem.duration_s, n)?;
    let mut prepared = Prepared {
        settings,
        problem,
        mean_a: MeanOrbit::of_state(&g, &problem.from),
        mean_b: MeanOrbit::of_state(&g, &problem.to),
        b_end,
        point: None,
        guess: None,
        orbit: None,
        caches: ([None; MAX_IMPULSES], None),
    };
    if let Kind::MeanFlight(orbit) | Kind::MeanState(orbit) | Kind::MeanOrbit(orbit) = kind {
        let s = orbit_state(orbit)?;
        prepared.orbit = Some((s, MeanOrbit::of_state(&g, &s)?));
    }
    let needs_point = matches!(
        kind,
        Kind::Evaluation(_)
            | Kind::EvaluationRefused
            | Kind::EvaluationAgain
            | Kind::BestFamily
            | Kind::Refine(_)
            | Kind::Descent(_)
            | Kind::Hops
            | Kind::Finish
    );
    if needs_point {
        let defaults = Prepared {
            settings: Settings::default(),
            ..prepared
        };
        let Workspace {
            a, b, candidates, ..
        } = ws;
        let mut c = ctx(&defaults, (a, b), Model::MeanElements, u64::MAX);
        c.grid(candidates);
        prepared.point = candidates.first().copied().flatten();
        if let Kind::Descent(_) = kind {
            prepared.point = prepared.point.map(|q| c.refine(q));
        }
        if let (Kind::EvaluationAgain, Some(q)) = (kind, prepared.point) {
            c.cost(&q.x, q.fam, &q.off)?;
            prepared.caches = (c.coasts, c.start_cache);
        }
    }
    if let Kind::Lambert(revs, branch, true) = kind {
        let normal = crate::vec3::cross(&pos(&problem.from), &super::j2::vel(&problem.from));
        let fam = Family { revs, branch };
        // A solve of the leg 60 s longer: the search's neighbouring evaluation.
        let sol = metered_lambert(
            &settings,
            (&pos(&problem.from), &pos(&b_end), problem.duration_s + 60.0),
            fam,
            &normal,
            None,
            &mut meter,
        )?;
        prepared.guess = Some(sol.x);
    }
    Some(prepared)
}

/// Run case `index` on `prepared`: the units the solve charges for it (0 when it cannot run).
pub fn run(index: usize, sequence_ws: &mut SequenceWorkspace, prepared: &Prepared) -> u64 {
    let Some(case) = CASES.get(index) else {
        return 0;
    };
    let ws = &mut sequence_ws.arc;
    let p = prepared;
    let g = p.settings.gravity();
    let budget = u64::MAX;
    match case.kind {
        Kind::Flight(steps) => {
            let mut meter = Meter::new(budget);
            let flight = p.settings.flight(Model::Planning);
            let dt = f64::from(steps) * p.settings.step_s;
            black_box(flight.fly(&p.problem.from, dt, &mut meter));
            meter.used()
        }
        Kind::MeanFlight(_) => {
            let Some((s, _)) = p.orbit else { return 0 };
            let mut meter = Meter::new(budget);
            let flight = p.settings.flight(Model::MeanElements);
            black_box(flight.fly(&s, HALF_DAY_S, &mut meter));
            meter.used()
        }
        Kind::MeanState(_) => {
            let Some((_, mean)) = p.orbit else { return 0 };
            black_box(mean.state_at(&g, HALF_DAY_S));
            wu::MEAN_STATE
        }
        Kind::MeanOrbit(_) => {
            let Some((s, _)) = p.orbit else { return 0 };
            black_box(MeanOrbit::of_state(&g, &s));
            wu::MEAN_ORBIT
        }
        Kind::Kepler(steps) => {
            black_box(crate::impulsive::kepler::true_anomaly(
                black_box(0.1),
                0.75,
                steps,
            ));
            0
        }
        Kind::Lambert(revs, branch, _) | Kind::LambertBound(revs, branch) => {
            let mut meter = Meter::new(budget);
            let from = &p.problem.from;
            let normal = crate::vec3::cross(&pos(from), &super::j2::vel(from));
            black_box(metered_lambert(
                &p.settings,
                (&pos(from), &pos(&p.b_end), p.problem.duration_s),
                Family { revs, branch },
                &normal,
                p.guess,
                &mut meter,
            ));
            meter.used()
        }
        Kind::TwoBody(iterations) => {
            // The high-eccentricity orbit: its Newton iterations do not stop at the first.
            let Some(s) = orbit_state(Orbit::HighEcc) else {
                return 0;
            };
            black_box(lambert::propagate(
                p.settings.mu_km3_s2,
                &pos(&s),
                &super::j2::vel(&s),
                HALF_DAY_S,
                iterations,
            ));
            wu::TWO_BODY_SET_UP
                .saturating_add(wu::TWO_BODY_ITERATION.saturating_mul(u64::from(iterations)))
        }
        Kind::Evaluation(model) => with_point(p, ws, model, |c, q| {
            black_box(c.cost(&q.x, q.fam, &q.off));
        }),
        Kind::EvaluationAgain => with_point(p, ws, Model::MeanElements, |c, q| {
            (c.coasts, c.start_cache) = p.caches;
            black_box(c.cost(&q.x, q.fam, &q.off));
        }),
        Kind::EvaluationRefused => with_point(p, ws, Model::MeanElements, |c, q| {
            // The first epoch after the second.
            let mut x = q.x;
            if let (Some(first), Some(&second)) = (x.first_mut(), q.x.get(1)) {
                *first = second + 1.0;
            }
            black_box(c.cost(&x, q.fam, &q.off));
        }),
        Kind::BestFamily => with_point(p, ws, Model::MeanElements, |c, q| {
            black_box(c.best_family(&q.x, &q.off));
        }),
        Kind::Shoot(model, iterations) => {
            let settings = Settings {
                shoot_max_iter: iterations,
                ..p.settings
            };
            let flight = settings.flight(model);
            let mut meter = Meter::new(budget);
            let mut secant = Secant::default();
            black_box(shoot(
                &flight,
                &settings,
                &p.problem.from,
                &pos(&p.b_end),
                p.problem.duration_s,
                Family {
                    revs: LAST_LEG_REVS,
                    branch: LEFT,
                },
                &Offset::default(),
                &mut secant,
                &mut meter,
            ));
            meter.used()
        }
        Kind::GridEpoch(_) => {
            let Workspace {
                a, b, candidates, ..
            } = ws;
            let mut c = ctx(p, (a, b), Model::MeanElements, budget);
            c.grid(candidates);
            black_box(&candidates);
            c.meter.used()
        }
        Kind::Refine(evals) => {
            let settings = Settings {
                search_max_evals: evals,
                ..p.settings
            };
            let q = Prepared { settings, ..*p };
            with_point(&q, ws, Model::MeanElements, |c, q| {
                black_box(c.refine(q));
            })
        }
        Kind::Descent(iterations) => with_point(p, ws, Model::MeanElements, |c, q| {
            black_box(c.descend(q, iterations));
        }),
        Kind::Hops => {
            let Some(q) = p.point else { return 0 };
            let Workspace { a, b, hops, .. } = ws;
            let mut c = ctx(p, (a, b), Model::MeanElements, budget);
            c.hops(&q, hops);
            black_box(&hops);
            c.meter.used()
        }
        Kind::NodeSeed => {
            let Workspace { a, b, .. } = ws;
            let mut c = ctx(p, (a, b), Model::MeanElements, budget);
            black_box(c.node_seed(0.0, None));
            c.meter.used()
        }
        Kind::NodeSeedArithmetic => {
            let (from, to) = (&p.problem.from, &p.problem.to);
            black_box(super::arc_node_seed::seed_arithmetic(
                p.settings.mu_km3_s2,
                0.0,
                from,
                to,
            ));
            wu::NODE_SEED
        }
        Kind::Finish => with_point(p, ws, Model::MeanElements, |c, q| {
            black_box(c.finish(&q));
        }),
        Kind::Solve(work_budget) => {
            let settings = Settings {
                work_budget,
                ..p.settings
            };
            let mut out = ArcSolution::new();
            match solve_arc(black_box(&p.problem), &settings, ws, &mut out) {
                Ok(()) => black_box(out).info.work_units,
                Err(_) => 0,
            }
        }
        Kind::SolvePlanningModel => {
            let settings = Settings {
                search_model: Model::Planning,
                ..p.settings
            };
            let mut out = ArcSolution::new();
            match solve_arc(black_box(&p.problem), &settings, ws, &mut out) {
                Ok(()) => black_box(out).info.work_units,
                Err(_) => 0,
            }
        }
        Kind::Estimate(work_budget) => {
            let settings = Settings {
                work_budget,
                ..p.settings
            };
            match estimate_arc_mps(black_box(&p.problem), &settings, ws) {
                Ok(e) => black_box(e).work_units,
                Err(_) => 0,
            }
        }
        Kind::Sequence(tour) => {
            let Some((problem, settings, estimates)) = sequence_case(tour) else {
                return 0;
            };
            let mut out = Sequence::new();
            let tour = black_box(&problem);
            match solve_sequence(tour, &settings, &estimates, sequence_ws, &mut out) {
                Ok(()) => black_box(out).info.work_units,
                Err(_) => 0,
            }
        }
    }
}

/// Run `f` on a context of the paper's arc in `model` and the grid's best candidate: the units
/// it charged.
fn with_point(
    p: &Prepared,
    ws: &mut Workspace,
    model: Model,
    f: impl FnOnce(&mut Ctx, Point),
) -> u64 {
    let Some(q) = p.point else { return 0 };
    let Workspace { a, b, .. } = ws;
    let mut c = ctx(p, (a, b), model, u64::MAX);
    f(&mut c, q);
    c.meter.used()
}

/// Whether case `index` is a whole request (a solve, an estimate or a sequencing: seconds in a
/// debug build).
pub fn is_whole_request(index: usize) -> bool {
    CASES.get(index).is_some_and(|c| {
        matches!(
            c.kind,
            Kind::Solve(_) | Kind::SolvePlanningModel | Kind::Estimate(_) | Kind::Sequence(_)
        )
    })
}

/// The problem a case solves (the firmware's host-side check of the whole solves).
pub fn case_problem(index: usize) -> Option<ArcProblem> {
    matches!(
        CASES.get(index)?.kind,
        Kind::Solve(_) | Kind::SolvePlanningModel | Kind::Estimate(_)
    )
    .then(paper_arc)
    .flatten()
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used)]
    use super::*;
    extern crate std;

    #[test]
    fn every_case_prepares_and_runs_and_charges() {
        let mut ws = std::boxed::Box::new(SequenceWorkspace::new());
        for (index, c) in CASES.iter().enumerate() {
            // The whole solves are the QEMU image's and `tests/tests/work_budget.rs`'s (seconds
            // in a debug build).
            if is_whole_request(index) {
                continue;
            }
            let prepared = prepare(index, &mut ws);
            assert!(prepared.is_some(), "{}", c.name);
            let units = run(index, &mut ws, &prepared.unwrap());
            assert_eq!(units > 0, c.charged(), "{}", c.name);
        }
    }

    #[test]
    fn a_lambert_solve_is_charged_by_its_steps() {
        // The same solve warm and cold: fewer steps, fewer units, by whole steps.
        let at = |name: &str| CASES.iter().position(|c| c.name == name).unwrap();
        let mut ws = std::boxed::Box::new(SequenceWorkspace::new());
        let mut units = |name: &str| {
            let i = at(name);
            let p = prepare(i, &mut ws).unwrap();
            run(i, &mut ws, &p)
        };
        let (cold, warm) = (units("lambert-14rev-left"), units("lambert-14rev-warm"));
        let step = crate::lambert::step_units(14);
        assert!(warm < cold, "{warm} vs {cold}");
        assert_eq!((cold - wu::LAMBERT_SOLVE) % step, 0);
        assert_eq!((warm - wu::LAMBERT_SOLVE) % step, 0);
    }
}
