//! `reconfig montecarlo`: Huang 2012 Table 2 with a fixed seed.
//!
//! For each N, R random initial guesses: the analytic Pontryagin controls at the nodes plus
//! Gaussian noise (the guess is projected onto the polynomials that meet the boundary
//! conditions), passed to the solver as its starting point. Three configurations per guess:
//! the paper's transcription without test points (keep-out at nodes only), with the Gaussian
//! test points, and with test points plus our continuous verification.

use crate::fixture::{self, Fixture};
use anyhow::{bail, Result};
use indicatif::{ProgressBar, ProgressStyle};
use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;
use rand_distr::{Distribution, Normal};
use rayon::prelude::*;
use reconfig_core::pseudospectral::{self, Problem, Settings, Solution, SolveStatus, Workspace};
use std::path::PathBuf;
use std::process::ExitCode;
use std::time::Instant;

/// Arguments of `reconfig montecarlo`.
#[derive(clap::Args, Debug)]
pub struct Args {
    /// Planner-A fixture whose boundary conditions are used (N is overridden).
    #[arg(long, default_value = "fixtures/huang2012-three-sats-n10.toml")]
    pub fixture: PathBuf,
    /// Polynomial degrees N to run (the paper: 10, 20, 30; capacity is 24).
    #[arg(long, value_delimiter = ',', default_values_t = [10u16, 20, 24])]
    pub degrees: Vec<u16>,
    /// Random initial guesses per N (the paper: 200).
    #[arg(long, default_value_t = 200)]
    pub runs: usize,
    /// Standard deviation of the control noise added to the analytic guess, in units of Umax.
    #[arg(long, default_value_t = 0.3)]
    pub sigma: f64,
    /// Random seed.
    #[arg(long, default_value_t = 2012)]
    pub seed: u64,
    /// Print one JSON object instead of the table.
    #[arg(long)]
    pub json: bool,
    /// Write the table for docs/planner-a.md (`fixtures/golden/tables/planner-a-montecarlo.md`).
    #[arg(long)]
    pub record: bool,
    /// Threads (0: one per core). The counts, separations and costs are the same whatever the
    /// number; the per-solve times are measured while the other threads run, so the recorded
    /// table (`--record`) is measured on one, the default.
    #[arg(long, default_value_t = 1)]
    pub threads: usize,
}

/// One run's figures, in the order the runs are tallied.
struct RunFigures {
    separation: f64,
    cost: f64,
    elapsed_s: f64,
    max_active: u16,
    subproblems: u16,
    status: SolveStatus,
}

/// One configuration's statistics for one N.
#[derive(Debug, Clone, serde::Serialize)]
pub struct Row {
    /// Polynomial degree.
    pub degree: u16,
    /// Configuration name.
    pub configuration: &'static str,
    /// Runs.
    pub runs: usize,
    /// Mean continuous minimum separation.
    pub mean_min_separation: f64,
    /// Least continuous minimum separation.
    pub min_min_separation: f64,
    /// Mean cost J over runs.
    pub mean_cost: f64,
    /// Mean solve time, seconds.
    pub mean_time_s: f64,
    /// Largest solve time, seconds.
    pub max_time_s: f64,
    /// Largest active set any QP held.
    pub max_active: u16,
    /// Largest number of convex subproblems in one solve.
    pub max_subproblems: u16,
    /// Runs whose continuous separation is below d - 1e-6 or whose status is not usable.
    pub failures: usize,
}

const CONFIGURATIONS: [(&str, bool, bool); 3] = [
    ("nodes only (paper, no test points)", false, false),
    ("test points (paper's method)", true, false),
    ("test points + continuous verification", true, true),
];

/// Run the study and return its rows.
///
/// # Errors
/// A bad fixture or a rejected problem.
pub fn study(args: &Args, progress: bool) -> Result<Vec<Row>> {
    let Fixture::Pseudospectral(base) = fixture::load(&args.fixture)? else {
        bail!("{} is not a planner-A fixture", args.fixture.display());
    };
    let normal = Normal::new(0.0, args.sigma * base.problem.max_control_fu)?;
    let total = args.degrees.len() * args.runs * CONFIGURATIONS.len();
    let bar = if progress {
        ProgressBar::new(total as u64)
    } else {
        ProgressBar::hidden()
    };
    bar.set_style(ProgressStyle::with_template(
        "{bar:40} {pos}/{len} solves {elapsed_precise}",
    )?);
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(args.threads)
        .stack_size(crate::harness::worker::WORKER_STACK_BYTES)
        .build()?;
    let mut rows = Vec::new();
    for &degree in &args.degrees {
        let mut rng = ChaCha8Rng::seed_from_u64(args.seed ^ u64::from(degree));
        let mut problem: Problem = base.problem.clone();
        problem.degree = degree;
        let guesses: Vec<Vec<[f64; 3]>> = (0..args.runs)
            .map(|_| {
                (0..problem.spacecraft.len() * (usize::from(degree) + 1))
                    .map(|_| {
                        [
                            normal.sample(&mut rng),
                            normal.sample(&mut rng),
                            normal.sample(&mut rng),
                        ]
                    })
                    .collect()
            })
            .collect();
        for (name, test_points, verify) in CONFIGURATIONS {
            problem.test_points = test_points;
            let settings = Settings {
                continuous_verification: verify,
                ..Settings::default()
            };
            let mut stats = Row {
                degree,
                configuration: name,
                runs: args.runs,
                mean_min_separation: 0.0,
                min_min_separation: f64::INFINITY,
                mean_cost: 0.0,
                mean_time_s: 0.0,
                max_time_s: 0.0,
                max_active: 0,
                max_subproblems: 0,
                failures: 0,
            };
            // Solved side by side, each thread with its own workspace, then tallied in run
            // order: the same sums, bit for bit, whatever the thread count.
            let runs: Vec<RunFigures> = pool.install(|| {
                guesses
                    .par_iter()
                    .map_init(
                        || {
                            (
                                Box::new(Workspace::new()),
                                Box::new(Solution::new()),
                                Box::new(Solution::new()),
                            )
                        },
                        |(workspace, solution, guess), noise| {
                            analytic_guess(&problem, noise, guess);
                            let start = Instant::now();
                            pseudospectral::solve_warm(
                                &problem, &settings, workspace, guess, solution,
                            )?;
                            bar.inc(1);
                            Ok(RunFigures {
                                // No pair (one spacecraft): nothing to come close to.
                                separation: solution.min_separation_lu.unwrap_or(f64::INFINITY),
                                cost: solution.cost,
                                elapsed_s: start.elapsed().as_secs_f64(),
                                max_active: solution.info.max_active,
                                subproblems: solution.info.sqp_iterations,
                                status: solution.info.status,
                            })
                        },
                    )
                    .collect::<Result<Vec<_>>>()
            })?;
            for run in &runs {
                let separation = run.separation;
                stats.mean_min_separation += separation / args.runs as f64;
                stats.min_min_separation = stats.min_min_separation.min(separation);
                stats.mean_cost += run.cost / args.runs as f64;
                stats.mean_time_s += run.elapsed_s / args.runs as f64;
                stats.max_time_s = stats.max_time_s.max(run.elapsed_s);
                stats.max_active = stats.max_active.max(run.max_active);
                stats.max_subproblems = stats.max_subproblems.max(run.subproblems);
                let separated = separation >= problem.keep_out_lu - 1e-6;
                let usable = matches!(run.status, SolveStatus::Solved)
                    || (!verify && run.status == SolveStatus::SeparationNotVerified);
                if !separated || !usable {
                    stats.failures += 1;
                }
            }
            rows.push(stats);
        }
    }
    bar.finish_and_clear();
    Ok(rows)
}

/// The analytic minimum-energy (cubic) controls at the LGL nodes plus `noise`, as a warm start.
fn analytic_guess(problem: &Problem, noise: &[[f64; 3]], out: &mut Solution) {
    *out = crate::plot::cubic_at_nodes(problem);
    let nodes = usize::from(problem.degree) + 1;
    for (i, controls) in out
        .controls_fu
        .iter_mut()
        .take(problem.spacecraft.len())
        .enumerate()
    {
        for (h, node) in controls.iter_mut().take(nodes).enumerate() {
            for (u, n) in node.iter_mut().zip(noise[i * nodes + h]) {
                *u += n;
            }
        }
    }
}

/// Run `reconfig montecarlo`.
pub fn run(args: &Args) -> Result<ExitCode> {
    let rows = study(args, !args.json)?;
    if args.json {
        println!("{}", serde_json::to_string_pretty(&rows)?);
        return Ok(ExitCode::SUCCESS);
    }
    println!(
        "Huang 2012 Table 2 reproduction: {} random initial guesses per N (analytic guess + N(0, ({} Umax)^2) control noise), seed {}",
        args.runs, args.sigma, args.seed
    );
    let table = table(&rows);
    print!("{}", table.markdown());
    println!("({NOTE})");
    if args.record {
        crate::table_record::write_reconfig(
            "planner-a-montecarlo",
            &format!(
                "montecarlo --runs {} --seed {} --record",
                args.runs, args.seed
            ),
            &format!(
                "Huang 2012 Table 2: {} random initial guesses per N (the analytic guess plus \
                 N(0, ({} Umax)^2) control noise per node and axis), seed {}; {NOTE}.",
                args.runs, args.sigma, args.seed
            ),
            &[&table],
        )?;
    }
    Ok(ExitCode::SUCCESS)
}

/// What the table's separations and failures are.
const NOTE: &str = "separations are the continuous minimum over the interpolated trajectory; a \
                    failure is a run below d - 1e-6 or without a usable status";

/// The rows as a table (times in ms).
fn table(rows: &[Row]) -> crate::table_record::Table {
    let mut t = crate::table_record::Table::new(
        &[
            "N",
            "configuration",
            "mean sep",
            "min sep",
            "mean J",
            "mean ms",
            "max ms",
            "max QPs",
            "max active",
            "failures",
        ],
        "rlrrrrrrrr",
    );
    for r in rows {
        t.push(vec![
            r.degree.to_string(),
            r.configuration.to_string(),
            format!("{:.4}", r.mean_min_separation),
            format!("{:.4}", r.min_min_separation),
            format!("{:.5}", r.mean_cost),
            format!("{:.3}", r.mean_time_s * 1e3),
            format!("{:.3}", r.max_time_s * 1e3),
            r.max_subproblems.to_string(),
            r.max_active.to_string(),
            r.failures.to_string(),
        ]);
    }
    t
}
