//! `reconfig pareto FIXTURE --walk tf|kappa --to X --step S [-o pareto.svg] [--record NAME]`:
//! the hybrid transfer's continuation on the ground (issue 30). From the fixture's design,
//! walk the time of flight (or κ) to `--to` in steps of `--step`, each step a request through
//! the one request path that starts from the last converged answer (and walks from it inside
//! the planner where one step is too long); print each point (t_f, m_f, κ, status), stop at the
//! first step that does not converge and say why, and draw the (t_f, m_f) curve.

use crate::drivers::hybrid::plan;
use crate::fixture::hybrid::HybridFixture;
use crate::fixture::{self, Fixture};
use crate::plot::{chart, range};
use crate::table_record::Table;
use anyhow::{anyhow, bail, Result};
use plotters::prelude::*;
use reconfig_core::hybrid::units::days;
use reconfig_core::hybrid::{Objective, Solution};
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

/// The fixture moved to `value` of the walked parameter, started from `from` (its costates,
/// κ, λ0 and t_f), designed for where `from` converged.
fn step_fixture(base: &HybridFixture, walk: Walk, value: f64, from: &Solution) -> HybridFixture {
    let mut f = base.clone();
    let p = &mut f.problem;
    p.costates = from.costates;
    p.kappa = from.kappa;
    p.theta_rad = from.theta_rad;
    p.cost_multiplier = from.cost_multiplier;
    p.design_duration_days = days(from.duration_tu);
    if p.objective == Objective::MinTime {
        p.duration_days = days(from.duration_tu);
    }
    match walk {
        Walk::Tf => p.duration_days = value,
        Walk::Kappa => p.kappa = value,
    }
    f
}

/// The points' table.
fn table(points: &[Point]) -> Table {
    let mut t = Table::new(
        &[
            "walked",
            "t_f (d)",
            "m_f",
            "kappa",
            "status",
            "iterations",
            "work units",
        ],
        "rrrrlrr",
    );
    for p in points {
        let s = &p.solution;
        t.push(vec![
            format!("{:.4}", p.value),
            format!("{:.5}", days(s.duration_tu)),
            s.flown
                .map_or_else(|| "—".to_owned(), |f| format!("{:.6}", f.final_mass)),
            format!("{:.6}", s.kappa),
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

/// Walk `walk` from `base`'s answer to `to` in steps of `step` (at most 10,000), each step a
/// request started from the last converged answer; stop at the first step not usable.
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
    };
    let direction = if to < start { -1.0 } else { 1.0 };
    // Bounded by the distance over the step (no walk beyond `--to`).
    let steps = ((to - start).abs() / step).ceil().min(10_000.0) as u32;
    let mut points = vec![Point {
        value: start,
        solution: first,
    }];
    let mut last = first;
    let mut stop = None;
    for k in 1..=steps {
        let value = if k == steps {
            to
        } else {
            start + direction * step * f64::from(k)
        };
        let solution = solve(&step_fixture(base, walk, value, &last))?;
        let usable = solution.info.status.is_usable();
        points.push(Point { value, solution });
        if !usable {
            stop = Some(format!(
                "Stopped at {value:.4}: {:?} (the last converged point is {:.4})",
                solution.info.status,
                points
                    .iter()
                    .rev()
                    .find(|p| p.solution.info.status.is_usable())
                    .map_or(start, |p| p.value)
            ));
            break;
        }
        last = solution;
    }
    Ok(Walked { points, stop })
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
    if args.walk == Walk::Tf && base.problem.objective == Objective::MinTime {
        bail!("--walk tf: a minimum-time fixture has no time of flight to walk (walk kappa)");
    }
    let Walked { points, stop } = walk(&base, args.walk, args.to, args.step)?;
    let t = table(&points);
    print!("{}", t.markdown());
    match &stop {
        Some(why) => println!("{why}"),
        None => println!("Reached {:.4}", args.to),
    }
    let walked = match args.walk {
        Walk::Tf => "t_f",
        Walk::Kappa => "kappa",
    };
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
            "pareto {} --walk {walked} --to {} --step {} --record {name}",
            args.fixture.display(),
            args.to,
            args.step
        )
        .replace("--walk t_f", "--walk tf");
        let caption = format!(
            "The hybrid transfer's continuation from the fixture's design: {walked} walked in \
             steps of {}, each step a request through the one request path started from the \
             last converged answer. {}",
            args.step,
            stop.unwrap_or_else(|| format!("Reached {}.", args.to))
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
