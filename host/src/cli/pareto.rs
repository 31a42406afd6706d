//! `reconfig pareto FIXTURE --walk tf|kappa|theta|phase --to X --step S [--free-last]
//! [-o pareto.svg] [--record NAME]`: the hybrid transfer's continuation on the ground (issue
//! 30). From the fixture's design, walk the time of flight, κ, θ or the arrival point's phase
//! along the halo orbit to `--to` in steps of `--step`, each step a request through the one
//! request path started from the last converged answer extrapolated along the secant (and
//! walking inside the planner where one step is too long); a step that does not converge is
//! halved (at most ten times in a row); print each point (t_f, m_f, κ, θ, status), stop where no
//! halving converges and say why, and draw the (t_f, m_f) curve. `--free-last` then frees the
//! walked parameter at its optimum along the walk (its transversality condition's root).

use crate::drivers::hybrid::plan;
use crate::fixture::hybrid::HybridFixture;
use crate::fixture::{self, Fixture};
use crate::plot::{chart, range};
use crate::table_record::Table;
use anyhow::{anyhow, bail, Result};
use plotters::prelude::*;
use reconfig_core::hybrid::halo::{arrival_transversality, state_at_phase};
use reconfig_core::hybrid::units::{days, time_tu};
use reconfig_core::hybrid::{secant_start, transversality, Objective, Problem, Solution};
use reconfig_core::limits::Limits;
use std::path::PathBuf;
use std::process::ExitCode;

/// Which parameter the continuation walks.
#[derive(clap::ValueEnum, Clone, Copy, Debug, PartialEq, Eq)]
pub enum Walk {
    /// The time of flight, days (fixed-time objectives).
    Tf,
    /// The impulse ratio κ (any objective; minimum time gives Table 2's trade).
    Kappa,
    /// The impulse's phase θ on the parking orbit, rad (any objective; κ free or fixed as the
    /// fixture says): the path to the κ and θ free optimum, which Newton does not reach in one
    /// go from θ = −2 (the final mass is steep in θ).
    Theta,
    /// The arrival point's phase along the halo orbit, days from the fixture's point (either
    /// way; fixed-time objectives): the path to the optimum arrival, which the paper fixes.
    Phase,
}

/// Arguments of `reconfig pareto`.
#[derive(clap::Args, Debug)]
pub struct Args {
    /// A hybrid fixture: the walk starts from its answer.
    pub fixture: PathBuf,
    /// The parameter walked.
    #[arg(long, value_enum, default_value = "tf")]
    pub walk: Walk,
    /// Where the walk ends (days for `tf`).
    #[arg(long)]
    pub to: f64,
    /// The step (positive; its sign follows the direction to `--to`).
    #[arg(long, default_value_t = 0.05)]
    pub step: f64,
    /// Draw the (t_f, m_f) curve here (SVG).
    #[arg(short, long)]
    pub output: Option<PathBuf>,
    /// Write the points as the record `fixtures/golden/tables/hybrid-pareto-NAME.md`.
    #[arg(long)]
    pub record: Option<String>,
    /// After the walk, free the walked parameter (κ, θ or the phase): the optimum in it by its
    /// transversality condition, from where the walk brought it (fixed-time objectives; the
    /// table's last row; `pareto::free_last`).
    #[arg(long)]
    pub free_last: bool,
    /// Write the last point (the freed one with `--free-last`) as a fixture here: the design,
    /// a request to plan, upload or walk from again (its name the file's stem).
    #[arg(long)]
    pub write_fixture: Option<PathBuf>,
}

/// One point of the walk.
pub struct Point {
    /// The walked parameter's value.
    pub value: f64,
    /// The answer there.
    pub solution: Solution,
}

/// A walk's points (the fixture's own answer first) and, when it stopped before `to`, why.
pub struct Walked {
    /// The points, the last one the first that did not converge when the walk stopped.
    pub points: Vec<Point>,
    /// Why it stopped before `to`.
    pub stop: Option<String>,
}

/// The answer of `fixture`'s request under the built-in limits.
fn solve(fixture: &HybridFixture) -> Result<Solution> {
    plan(fixture, &Limits::default()).map(|s| *s)
}

/// `base`'s request started from `s` (its costates, κ, θ, λ0 and t_f), designed for where `s`
/// converged.
fn started_from(base: &HybridFixture, s: &Solution) -> Problem {
    let mut p = base.problem;
    p.costates = s.costates;
    p.kappa = s.kappa;
    p.theta_rad = s.theta_rad;
    p.cost_multiplier = s.cost_multiplier;
    p.design_duration_days = days(s.duration_tu);
    if p.objective == Objective::MinTime {
        p.duration_days = days(s.duration_tu);
    }
    p
}

/// The fixture moved to `value` of the walked parameter, started from `from` (its costates,
/// κ, θ, λ0 and t_f), designed for where `from` converged. With `before`, the converged point
/// one step back (its value and answer), the start is extrapolated along the secant through
/// both (`hybrid::secant_start`, the planner's own walk's predictor: the shooting then corrects
/// from where the family is heading, which lets a step be many times longer where the
/// costates are steep in the walked parameter).
fn step_fixture(
    base: &HybridFixture,
    walk: Walk,
    value: f64,
    from: (f64, &Solution),
    before: Option<(f64, &Solution)>,
) -> Result<HybridFixture> {
    let (at, from) = from;
    let mut f = base.clone();
    f.problem = started_from(base, from);
    if let Some((back, b)) = before {
        f.problem = secant_start(&f.problem, &started_from(base, b), at - back, value - at);
    }
    let p = &mut f.problem;
    match walk {
        Walk::Tf => p.duration_days = value,
        Walk::Kappa => p.kappa = value,
        Walk::Theta => p.theta_rad = value,
        Walk::Phase => {
            let at = arrival_at(base, value)?;
            (p.arrival_r_lu, p.arrival_v_vu) = (at.arrival_r_lu, at.arrival_v_vu);
        }
    }
    Ok(f)
}

/// The fixture's request with its arrival point moved `phase_days` along the halo orbit.
///
/// # Errors
/// The orbit's flight stopped (the settings' step bound).
fn arrival_at(base: &HybridFixture, phase_days: f64) -> Result<Problem> {
    let s = state_at_phase(&base.problem, time_tu(phase_days), &base.settings)
        .map_err(|stop| anyhow!("the halo orbit's flight to {phase_days} d stopped: {stop:?}"))?;
    Ok(Problem {
        arrival_r_lu: s.r_lu,
        arrival_v_vu: s.v_vu,
        ..base.problem
    })
}

/// The points' table.
fn table(points: &[Point]) -> Table {
    let mut t = Table::new(
        &[
            "walked",
            "t_f (d)",
            "m_f",
            "kappa",
            "theta (rad)",
            "status",
            "iterations",
            "work units",
        ],
        "rrrrrlrr",
    );
    for p in points {
        let s = &p.solution;
        t.push(vec![
            format!("{:.4}", p.value),
            format!("{:.5}", days(s.duration_tu)),
            s.flown
                .map_or_else(|| "—".to_owned(), |f| format!("{:.6}", f.final_mass)),
            format!("{:.6}", s.kappa),
            format!("{:.6}", s.theta_rad),
            format!("{:?}", s.info.status),
            s.info.iterations.to_string(),
            s.info.work_units.to_string(),
        ]);
    }
    t
}

/// Draw the converged points' (t_f, m_f).
fn draw(points: &[Point], title: &str, out: &std::path::Path) -> Result<()> {
    let xy: Vec<(f64, f64)> = points
        .iter()
        .filter(|p| p.solution.info.status.is_usable())
        .filter_map(|p| {
            p.solution
                .flown
                .map(|f| (days(p.solution.duration_tu), f.final_mass))
        })
        .collect();
    let root = SVGBackend::new(out, (900, 600)).into_drawing_area();
    root.fill(&WHITE).map_err(|e| anyhow!("{e}"))?;
    let (x0, x1) = range(xy.iter().map(|p| p.0), 0.05);
    let (y0, y1) = range(xy.iter().map(|p| p.1), 0.1);
    let mut c = chart(
        &root,
        Some((title, 18)),
        (10, 40, 70),
        (x0..x1, y0..y1),
        ("time of flight [d]", "final mass (fraction of 3000 kg)"),
    )?;
    c.draw_series(LineSeries::new(xy.iter().copied(), BLUE.stroke_width(2)))
        .map_err(|e| anyhow!("{e}"))?;
    c.draw_series(xy.iter().map(|&p| Circle::new(p, 3, BLUE.filled())))
        .map_err(|e| anyhow!("{e}"))?;
    root.present().map_err(|e| anyhow!("{e}"))?;
    Ok(())
}

/// Halvings of a step that did not converge before the walk stops there (a step of
/// `--step` / 2^10 at the finest).
pub const MAX_HALVINGS: u32 = 10;

/// Requests of one walk at most (a bound on its time whatever `--to` and `--step`).
pub const MAX_REQUESTS: u32 = 10_000;

/// Walk `walk` from `base`'s answer to `to` in steps of `step`, each step a request started
/// from the last converged answer. A step that does not converge is halved and tried again
/// from the same answer (at most [`MAX_HALVINGS`] times in a row; after a converged halved
/// step the step doubles back towards `step`); the walk stops at the first value that no
/// halving reaches, that value's answer the last point. At most [`MAX_REQUESTS`] requests.
///
/// # Errors
/// The fixture's own answer is not usable, a step not positive, or a request refused.
pub fn walk(base: &HybridFixture, walk: Walk, to: f64, step: f64) -> Result<Walked> {
    if !(step.is_finite() && step > 0.0) {
        bail!("--step {step}: must be a positive number");
    }
    if !to.is_finite() {
        bail!("--to {to}: must be a number");
    }
    let first = solve(base)?;
    if !first.info.status.is_usable() {
        bail!(
            "{}: the fixture's own answer is {:?}; the walk starts from a converged design",
            base.name,
            first.info.status
        );
    }
    let start = match walk {
        Walk::Tf => base.problem.duration_days,
        Walk::Kappa => first.kappa,
        Walk::Theta => first.theta_rad,
        Walk::Phase => 0.0,
    };
    let direction = if to < start { -1.0 } else { 1.0 };
    let mut points = vec![Point {
        value: start,
        solution: first,
    }];
    let (mut last, mut at, mut halvings) = (first, start, 0u32);
    let mut stop = None;
    for _ in 0..MAX_REQUESTS {
        if (to - at) * direction <= 0.0 {
            break;
        }
        let length = step / f64::from(1u32 << halvings);
        // The last step lands on `to` exactly.
        let value = if (to - at).abs() <= length * (1.0 + 1e-9) {
            to
        } else {
            at + direction * length
        };
        let before = points
            .len()
            .checked_sub(2)
            .and_then(|i| points.get(i))
            .map(|p| (p.value, &p.solution));
        let solution = solve(&step_fixture(base, walk, value, (at, &last), before)?)?;
        if solution.info.status.is_usable() {
            points.push(Point { value, solution });
            (last, at) = (solution, value);
            halvings = halvings.saturating_sub(1);
        } else if halvings < MAX_HALVINGS {
            halvings += 1;
        } else {
            points.push(Point { value, solution });
            stop = Some(format!(
                "Stopped at {value:.6}: {:?} after {MAX_HALVINGS} halvings of the step (the last \
                 converged point is {at:.6})",
                solution.info.status
            ));
            break;
        }
    }
    if stop.is_none() && (to - at) * direction > 0.0 {
        stop = Some(format!(
            "Stopped at {at:.6} after {MAX_REQUESTS} requests, before {to}"
        ));
    }
    Ok(Walked { points, stop })
}

/// The walked parameter freed: its optimum, and how it was found.
pub struct Freed {
    /// The optimum in the parameter (`value`) and the answer there.
    pub point: Point,
    /// The parameter's transversality condition at the answer (`hybrid::transversality`).
    pub condition: f64,
    /// Requests the search made.
    pub requests: u32,
}

/// Requests of the search for θ's optimum at most (regula falsi converges in tens).
pub const MAX_ROOT_REQUESTS: u32 = 60;

/// The condition is met (as the shooting's own tolerance on a residual).
const CONDITION_TOL: f64 = 1e-10;

/// Free the walked parameter at the walk's optimum in it.
///
/// κ: the request of the last point with κ free (its Newton converges from there). θ: the cost
/// is so steep in θ near the Earth (a step of 1e-4 rad moves the arrival by about 1 LU/TU)
/// that the shooting with θ free stalls even a hundredth of a radian from the optimum, so θ's
/// condition `λ(t0)·∂x0/∂θ = 0` (the cost's derivative in θ along the walked family) is solved
/// as a root in θ alone: the first pair of walked points where it changes sign brackets it,
/// and regula falsi (Illinois) refines it, each trial a fixed-θ request started from the
/// bracket's nearer end with the secant predictor, until the condition is within 1e-10
/// (at most [`MAX_ROOT_REQUESTS`] requests).
///
/// # Errors
/// A time-of-flight walk or a minimum-time fixture (nothing to free), a walk that never
/// passes θ's optimum (no sign change), a trial that does not converge, or a refused request.
pub fn free_last(base: &HybridFixture, walk: Walk, walked: &Walked) -> Result<Freed> {
    if walk == Walk::Tf || base.problem.objective == Objective::MinTime {
        bail!(
            "--free-last: only a kappa, theta or phase walk at a fixed time of flight frees its \
             parameter"
        );
    }
    let last = walked
        .points
        .last()
        .ok_or_else(|| anyhow!("the walk has no point"))?;
    if walk == Walk::Kappa {
        let mut f = step_fixture(base, walk, last.value, (last.value, &last.solution), None)?;
        f.problem.free_kappa = true;
        let solution = solve(&f)?;
        return Ok(Freed {
            point: Point {
                value: solution.kappa,
                solution,
            },
            condition: transversality(&base.problem, &solution)[0],
            requests: 1,
        });
    }
    let condition = |value: f64, s: &Solution| -> Result<f64> {
        if walk == Walk::Phase {
            arrival_transversality(&arrival_at(base, value)?, s, &base.settings)
                .map_err(|stop| anyhow!("the plan's flight stopped: {stop:?}"))
        } else {
            Ok(transversality(&base.problem, s)[1])
        }
    };
    let mut signs = Vec::new();
    for p in walked
        .points
        .iter()
        .filter(|p| p.solution.info.status.is_usable())
    {
        signs.push((p.value, p.solution, condition(p.value, &p.solution)?));
    }
    let Some((mut a, mut b, mut ga, mut gb)) = signs.windows(2).find_map(|w| match w {
        // A minimum of the cost: its derivative from below 0 to above 0 with the parameter
        // (a maximum, where it falls through 0, is passed by).
        [x, y] if x.2 * y.2 <= 0.0 && (y.2 - x.2) * (y.0 - x.0) > 0.0 => {
            Some(((x.0, x.1), (y.0, y.1), x.2, y.2))
        }
        _ => None,
    }) else {
        bail!(
            "--free-last: the cost has no minimum along the walk (its derivative, the \
             condition, does not rise through 0): walk further"
        );
    };
    let mut side = 0i8;
    for requests in 1..=MAX_ROOT_REQUESTS {
        let value = if gb == ga {
            0.5 * (a.0 + b.0)
        } else {
            (a.0 * gb - b.0 * ga) / (gb - ga)
        };
        let (near, far) = if (value - a.0).abs() <= (value - b.0).abs() {
            (&a, &b)
        } else {
            (&b, &a)
        };
        let f = step_fixture(base, walk, value, (near.0, &near.1), Some((far.0, &far.1)))?;
        let mut solution = solve(&f)?;
        if !solution.info.status.is_usable() {
            // Too far for one step from the nearer end: walk there from it, halving as needed.
            let from = step_fixture(base, walk, near.0, (near.0, &near.1), None)?;
            // A phase walk counts from its fixture's arrival point, here the nearer end's.
            let to = if walk == Walk::Phase {
                value - near.0
            } else {
                value
            };
            let there = self::walk(&from, walk, to, (value - near.0).abs() / 4.0)?;
            match (there.stop, there.points.last()) {
                (None, Some(p)) => solution = p.solution,
                (stop, _) => bail!(
                    "--free-last: the requests towards {value:.9} stopped: {}",
                    stop.unwrap_or_default()
                ),
            }
        }
        let g = condition(value, &solution)?;
        if g.abs() <= CONDITION_TOL || (b.0 - a.0).abs() <= 1e-13 {
            return Ok(Freed {
                point: Point { value, solution },
                condition: g,
                requests,
            });
        }
        // Illinois: halve the kept end's value when the same end is kept twice.
        if g * gb < 0.0 {
            (a, ga) = ((value, solution), g);
            if side == 1 {
                gb *= 0.5;
            }
            side = 1;
        } else {
            (b, gb) = ((value, solution), g);
            if side == -1 {
                ga *= 0.5;
            }
            side = -1;
        }
    }
    bail!(
        "--free-last: the condition not within {CONDITION_TOL} after {MAX_ROOT_REQUESTS} requests"
    )
}

/// Run `reconfig pareto`.
///
/// # Errors
/// Not a hybrid fixture, a step that is not positive, the fixture's own answer not `Solved`,
/// or a plot or record that cannot be written.
pub fn run(args: &Args) -> Result<ExitCode> {
    let Fixture::Hybrid(base) = fixture::load(&args.fixture)? else {
        bail!("{} is not a hybrid fixture", args.fixture.display());
    };
    if matches!(args.walk, Walk::Tf | Walk::Phase) && base.problem.objective == Objective::MinTime {
        bail!(
            "--walk tf|phase: a minimum-time fixture's time of flight is its cost (walk kappa or \
             theta)"
        );
    }
    let walked = match args.walk {
        Walk::Tf => "t_f",
        Walk::Kappa => "kappa",
        Walk::Theta => "theta",
        Walk::Phase => "phase",
    };
    let mut w = walk(&base, args.walk, args.to, args.step)?;
    let mut stop = w.stop.take();
    let mut freed = None;
    if args.free_last {
        match free_last(&base, args.walk, &w) {
            Ok(Freed {
                point: p,
                condition,
                requests,
            }) => {
                freed = Some(format!(
                    "Then {walked} freed (the last row): {:?}, {walked} {:.9}, final mass {}, \
                     its transversality condition {condition:.1e} ({requests} requests)",
                    p.solution.info.status,
                    p.value,
                    p.solution
                        .flown
                        .map_or_else(|| "—".to_owned(), |f| format!("{:.6}", f.final_mass))
                ));
                w.points.push(p);
            }
            Err(e) => freed = Some(format!("Then {walked} not freed: {e}")),
        }
    }
    let points = w.points;
    let t = table(&points);
    print!("{}", t.markdown());
    match &stop {
        Some(why) => println!("{why}"),
        None => println!("Reached {:.4}", args.to),
    }
    if let Some(line) = &freed {
        println!("{line}");
    }
    if let Some(path) = &args.write_fixture {
        let last = points
            .last()
            .ok_or_else(|| anyhow!("the walk has no point"))?;
        let mut f = step_fixture(
            &base,
            args.walk,
            last.value,
            (last.value, &last.solution),
            None,
        )?;
        f.name = path
            .file_stem()
            .map_or_else(|| base.name.clone(), |s| s.to_string_lossy().into_owned());
        let note = format!(
            "Designed by `reconfig pareto {} --walk {walked} --to={} --step {}{}` from {}:\n\
             the walk's last point, {walked} = {} ({:?}, final mass {}).",
            args.fixture.display(),
            args.to,
            args.step,
            if args.free_last { " --free-last" } else { "" },
            base.name,
            last.value,
            last.solution.info.status,
            last.solution
                .flown
                .map_or_else(|| "—".to_owned(), |f| format!("{:.9}", f.final_mass))
        );
        std::fs::write(path, crate::fixture::hybrid::to_toml(&f, &note))?;
        println!("wrote {}", path.display());
    }
    if let Some(out) = &args.output {
        draw(
            &points,
            &format!("{}: m_f against t_f, {walked} walked", base.name),
            out,
        )?;
        println!("wrote {}", out.display());
    }
    if let Some(name) = &args.record {
        let command = format!(
            "pareto {} --walk {walked} --to={} --step {}{} --record {name}",
            args.fixture.display(),
            args.to,
            args.step,
            if args.free_last { " --free-last" } else { "" }
        )
        .replace("--walk t_f", "--walk tf");
        let caption = format!(
            "The hybrid transfer's continuation from the fixture's design: {walked} walked in \
             steps of {}{} (halved where one does not converge), each step a request through \
             the one request path started from the last converged answer extrapolated along \
             the secant through the last two. {}",
            args.step,
            if args.walk == Walk::Phase {
                " d along the halo orbit"
            } else {
                ""
            },
            stop.take()
                .unwrap_or_else(|| format!("Reached {}.", args.to))
                + &freed.map_or_else(String::new, |l| format!(" {l}."))
        );
        crate::table_record::write_reconfig(
            &format!("hybrid-pareto-{name}"),
            &command,
            &caption,
            &[&t],
        )?;
    }
    Ok(ExitCode::SUCCESS)
}
