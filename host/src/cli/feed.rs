//! `reconfig feed`: send fixtures, generated scenarios or faults to a running flight service,
//! check every answer against a local solve, and report timing against the budget.

use crate::fixture::{self, Fixture};
use crate::harness::feeder::{self, FeedOptions, FeedRun, Item, Payload};
use crate::harness::{check, faults, report, Instance};
use anyhow::{anyhow, Result};
use reconfig_core::impulsive;
use reconfig_core::wire::{Planner, Request};
use serde::Serialize;
use std::path::{Path, PathBuf};
use std::process::ExitCode;
use std::time::Duration;

/// Arguments of `reconfig feed`.
#[derive(clap::Args, Debug)]
pub struct Args {
    /// Fixture file to send (repeatable).
    #[arg(long = "fixture", value_name = "FILE")]
    pub fixtures: Vec<PathBuf>,
    /// Generated scenarios to send (sizes within capacity).
    #[arg(long, default_value_t = 0)]
    pub random: usize,
    /// Seed of the generated scenarios.
    #[arg(long, default_value_t = 2026)]
    pub seed: u64,
    /// Also send the fault set (malformed, truncated, oversized, wrong-version and wrong-CRC
    /// frames; NaN, over-capacity and infeasible problems).
    #[arg(long)]
    pub faults: bool,
    /// Requests per second (default: each as soon as the window allows).
    #[arg(long)]
    pub rate: Option<f64>,
    /// Requests kept in flight (1 = sequential).
    #[arg(long, default_value_t = 1)]
    pub window: usize,
    /// Per-request timeout, ms: no answer by then is a lost request.
    #[arg(long, default_value_t = 5000)]
    pub timeout_ms: u64,
    /// How long to wait for a flight service, ms.
    #[arg(long, default_value_t = 10_000)]
    pub wait_service_ms: u64,
    /// On-board time budget per request, ms.
    #[arg(long, default_value_t = report::DEFAULT_BUDGET_MS)]
    pub budget_ms: f64,
    /// Pin the feeder to this CPU.
    #[arg(long)]
    pub feeder_cpu: Option<usize>,
    /// First sequence number.
    #[arg(long, default_value_t = 1)]
    pub first_seq: u64,
    /// Write the report (timing, counters, per-request results) as JSON to this file.
    #[arg(long, value_name = "FILE")]
    pub json: Option<PathBuf>,
    /// Rows of the results table to print.
    #[arg(long, default_value_t = 40)]
    pub rows: usize,
    /// No progress bar.
    #[arg(long)]
    pub quiet: bool,
    /// Print `sent SEQ`, `answered SEQ` and `lost SEQ` lines as they happen, with the time.
    #[arg(long)]
    pub verbose: bool,
    /// Deadline of each request in the service's queue, ms (default: the service's own): a
    /// request still queued then is answered `Expired`, unsolved.
    #[arg(long)]
    pub deadline_ms: Option<u64>,
    /// Instead of feeding requests, flood the service with garbage frames and wake-ups (a
    /// hostile client, for the fairness checks) until killed or after `--flood-count` attempts:
    /// `read` reads the answers, `abandon` drops each request unread, `ignore` keeps requests
    /// open unread. Prints a `flooding: ...` line every 1000 attempts.
    #[arg(long, value_name = "MODE")]
    pub flood: Option<crate::harness::flood::FloodMode>,
    /// With `--flood`: stop after this many attempts.
    #[arg(long)]
    pub flood_count: Option<u64>,
    /// The service's limits file, for checking its answers locally.
    #[command(flatten)]
    pub limits: crate::limits::LimitsArg,
    #[command(flatten)]
    pub instance: Instance,
}

/// Machine-readable feed results.
#[derive(Serialize)]
pub struct JsonOut<'a> {
    /// Timing reports.
    pub reports: Vec<&'a report::Report>,
    /// One per request.
    pub results: Vec<JsonResult>,
    /// Every answer was correct.
    pub all_correct: bool,
}

/// One request's result.
#[derive(Serialize)]
pub struct JsonResult {
    /// Request label.
    pub label: String,
    /// Status or error text.
    pub status: String,
    /// Correct answer.
    pub correct: bool,
    /// Round trip, us.
    pub rtt_us: Option<f64>,
    /// Sequence number sent.
    pub seq: u64,
    /// The request's turn in the service's order of service (none when not answered in a
    /// turn: lost, or expired in the queue).
    pub turn: Option<u64>,
    /// Turns the service had given when it received the request.
    pub received_at_turn: Option<u64>,
}

/// Feed items for every fixture file, either planner. A fixture that does not load is reported
/// and skipped.
pub fn fixture_items(paths: &[PathBuf]) -> Vec<Item> {
    let mut items = Vec::new();
    for path in paths {
        let text = std::fs::read_to_string(path).unwrap_or_default();
        // The LEO tour: a `[sequence]` fixture as one request for its order, any other as
        // one request per arc of its order.
        if fixture::leo_tour::is_leo_tour(&text) {
            match fixture::leo_tour::load(path).and_then(|f| leo_items(&f)) {
                Ok(leo) => items.extend(leo),
                Err(e) => eprintln!("skipped {}: {e:#}", path.display()),
            }
            continue;
        }
        if fixture::geo_tour::is_geo_tour(&text) {
            match fixture::geo_tour::load(path) {
                Ok(f) => items.push(Item {
                    label: f.name.clone(),
                    planner: Some(Planner::GeoTour),
                    size: format!("T{}", f.problem.targets_lon_rad.len()),
                    payload: Payload::Request(Box::new(Request::GeoTour {
                        problem: f.problem,
                        settings: f.settings,
                    })),
                }),
                Err(e) => eprintln!("skipped {}: {e:#}", path.display()),
            }
            continue;
        }
        match fixture::load(path) {
            Ok(Fixture::Pseudospectral(f)) => {
                let size = format!("M{} N{}", f.problem.spacecraft.len(), f.problem.degree);
                items.push(Item {
                    label: f.name.clone(),
                    planner: Some(Planner::Pseudospectral),
                    size,
                    payload: Payload::Request(Box::new(Request::Pseudospectral {
                        problem: f.problem,
                        settings: f.settings,
                    })),
                });
            }
            Ok(Fixture::Impulsive(f)) => {
                let size = match &f.problem.plan {
                    impulsive::ImpulsePlan::Fixed(points) => format!("K{}", points.len()),
                    impulsive::ImpulsePlan::Search { impulses, .. } => {
                        format!("K{impulses} search")
                    }
                };
                items.push(Item {
                    label: f.name.clone(),
                    planner: Some(Planner::Impulsive),
                    size,
                    // In the fixture's own forms when it uses any (converted in the service).
                    payload: Payload::Request(Box::new(f.request())),
                });
            }
            Err(e) => eprintln!("skipped {}: {e:#}", path.display()),
        }
    }
    items
}

/// The feed items of a LEO tour fixture: with a `[sequence]` table one request for its
/// order, else one request per arc of its order. With a `[schedule]` table the order (chosen
/// here first for a `[sequence]` fixture) and its durations are chosen here, on the host, and
/// each arc of that schedule is one request: the schedule is a planning step, not a request
/// of the flight service.
pub fn leo_items(f: &fixture::leo_tour::LeoTourFixture) -> Result<Vec<Item>> {
    if f.schedule.is_some() {
        let mut scheduled = crate::cli::leo_tour_sequence::prepare(f)?.fixture;
        scheduled.sequence = None;
        scheduled.schedule = None;
        return leo_items(&scheduled);
    }
    if f.sequence.is_some() {
        return Ok(vec![Item {
            label: format!("{} order", f.name),
            planner: Some(Planner::LeoSequence),
            size: format!("N{}", f.clients.len()),
            payload: Payload::Request(Box::new(leo_sequence_request(f)?)),
        }]);
    }
    let arcs = crate::cli::solve_leo_tour::arc_problems(f)?;
    Ok(arcs
        .into_iter()
        .enumerate()
        .map(|(k, (from, to, _, problem))| Item {
            label: format!("{} arc {} ({}->{})", f.name, k + 1, from + 1, to + 1),
            planner: Some(Planner::LeoArc),
            size: format!("M{}", problem.impulses),
            payload: Payload::Request(Box::new(Request::LeoArc {
                problem,
                settings: f.settings,
            })),
        })
        .collect())
}

/// The sequencing request of a `[sequence]` LEO tour fixture.
///
/// # Errors
/// A fixture without a `[sequence]` table or with more clients than a request carries.
pub fn leo_sequence_request(f: &fixture::leo_tour::LeoTourFixture) -> Result<Request> {
    // The on-board part's request without the arcs' settings: the order alone.
    let p = crate::cli::leo_tour_sequence::onboard_problem(f)?;
    Ok(Request::LeoSequence {
        problem: p.tour,
        settings: p.sequence,
        arc_settings: p.estimates,
    })
}

/// Every `*.toml` in a folder, sorted.
pub fn fixture_files(dir: &Path) -> Result<Vec<PathBuf>> {
    let mut files: Vec<PathBuf> = std::fs::read_dir(dir)
        .map_err(|e| anyhow!("cannot read {}: {e}", dir.display()))?
        .filter_map(|e| e.ok().map(|e| e.path()))
        .filter(|p| p.extension().is_some_and(|x| x == "toml"))
        .collect();
    files.sort();
    Ok(files)
}

/// Check, print and report one run; returns whether every answer was correct.
pub fn conclude(
    items: &[Item],
    runs: &[(&FeedRun, report::Report)],
    rows: usize,
    json: Option<&Path>,
    limits: &reconfig_core::limits::Limits,
) -> Result<bool> {
    let mut all_correct = true;
    let mut results = Vec::new();
    let mut first = true;
    // One local solve per item serves every run: frames differ only in their sequence numbers.
    let expected = runs
        .first()
        .map(|(run, _)| check::expected(run, limits))
        .unwrap_or_default();
    for (run, _) in runs {
        let verdicts = check::verify(items, run, &expected);
        if first {
            check::print_table(items, &verdicts, rows);
            first = false;
        }
        for (v, record) in verdicts.iter().zip(&run.records) {
            all_correct &= v.correct;
            let order = match &record.fate {
                crate::harness::feeder::Fate::Answered { order, .. } => Some(*order),
                _ => None,
            };
            results.push(JsonResult {
                label: items[v.index].label.clone(),
                status: v.outcome.as_ref().map_or_else(
                    || v.reason.clone(),
                    |o| crate::harness::worker::summarize(o).0,
                ),
                correct: v.correct,
                rtt_us: v.rtt_us,
                seq: record.seq,
                turn: order
                    .map(|o| o.turn)
                    .filter(|t| *t != crate::harness::dispatch::NO_TURN),
                received_at_turn: order.map(|o| o.received_at_turn),
            });
        }
        let c = &run.counters;
        all_correct &= c.lost == 0 && c.late == 0 && c.duplicated == 0 && c.malformed == 0;
    }
    for (_, r) in runs {
        report::print(r);
    }
    if let Some(path) = json {
        let out = JsonOut {
            reports: runs.iter().map(|(_, r)| r).collect(),
            results,
            all_correct,
        };
        std::fs::write(path, serde_json::to_string_pretty(&out)?)?;
        println!("report written to {}", path.display());
    }
    Ok(all_correct)
}

/// Run `reconfig feed`.
pub fn run(args: &Args) -> Result<ExitCode> {
    if let Some(mode) = args.flood {
        let stats = crate::harness::flood::run(&crate::harness::flood::FloodOptions {
            instance: args.instance.clone(),
            mode,
            count: args.flood_count,
            report_every: 1000,
            wait_service: Duration::from_millis(args.wait_service_ms),
            seed: args.seed,
        })?;
        println!(
            "flood done: {} attempts, {} frames sent, {} answers read, {} refused",
            stats.attempts, stats.sent, stats.answered, stats.refused
        );
        return Ok(ExitCode::SUCCESS);
    }
    let mut items = fixture_items(&args.fixtures);
    items.extend(crate::scenario::generate(args.random, args.seed));
    if args.faults {
        items.extend(faults::items(args.first_seq + 1_000_000));
    }
    if items.is_empty() {
        return Err(anyhow!(
            "nothing to send: give --fixture, --random N or --faults"
        ));
    }
    let mut opts = FeedOptions::new(args.instance.clone());
    opts.timeout = Duration::from_millis(args.timeout_ms);
    opts.window = args.window;
    opts.rate = args.rate;
    opts.wait_service = Duration::from_millis(args.wait_service_ms);
    opts.cpu = args.feeder_cpu;
    opts.first_seq = args.first_seq;
    opts.progress = !args.quiet && !args.verbose;
    opts.verbose = args.verbose;
    opts.deadline = args.deadline_ms.map(Duration::from_millis);
    let limits = args.limits.load()?;
    let run = feeder::run(&items, &opts)?;
    let title = format!(
        "window {}{}, feeder {}",
        opts.window,
        args.rate
            .map_or(String::new(), |r| format!(", {r} requests/s")),
        args.feeder_cpu
            .map_or("unpinned".into(), |c| format!("on CPU {c}"))
    );
    let budget = Duration::from_secs_f64(args.budget_ms / 1e3);
    let rep = report::build(
        &title,
        &items,
        &run,
        budget,
        (args.window > 1).then_some(args.window),
    );
    let ok = conclude(
        &items,
        &[(&run, rep)],
        args.rows,
        args.json.as_deref(),
        &limits,
    )?;
    println!(
        "{}",
        if ok {
            "all answers correct"
        } else {
            "NOT all answers correct"
        }
    );
    Ok(if ok {
        ExitCode::SUCCESS
    } else {
        ExitCode::FAILURE
    })
}
