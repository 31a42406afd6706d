//! `reconfig feed`: send fixtures, generated scenarios or faults to a running flight service,
//! check every answer against a local solve, and report timing against the budget.

use crate::harness::check::conclude;
use crate::harness::feeder::{self, FeedOptions};
use crate::harness::items::fixture_items;
use crate::harness::{faults, report, Instance};
use anyhow::{anyhow, Result};
use std::path::PathBuf;
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
    let limits = args.limits.load()?;
    let mut items = fixture_items(&args.fixtures, &limits);
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
