//! `reconfig demo`: the main job. Starts the flight service as a child process, feeds it the
//! published cases of both planners, the fault set and a few hundred generated scenarios
//! (first one at a time, then with every worker busy), prints the results table and the timing
//! report, stops the service, and exits 0 only if every request was answered correctly.

use crate::harness::check::conclude;
use crate::harness::child::ServiceChild;
use crate::harness::feeder::{self, FeedOptions};
use crate::harness::items::{default_fixtures_dir, fixture_files, fixture_items};
use crate::harness::{faults, leo_onboard, report, Instance};
use anyhow::{anyhow, Result};
use reconfig_core::limits::Limits;
use std::path::PathBuf;
use std::process::ExitCode;
use std::time::{Duration, Instant};

/// Arguments of `reconfig demo`.
#[derive(clap::Args, Debug)]
pub struct Args {
    /// Generated scenarios to send after the fixtures.
    #[arg(long, default_value_t = 300)]
    pub random: usize,
    /// Seed of the generated scenarios.
    #[arg(long, default_value_t = 2026)]
    pub seed: u64,
    /// CPUs of the flight service, one pinned worker each (default: the first two CPUs this
    /// process may use).
    #[arg(long)]
    pub cpus: Option<String>,
    /// Do not pin the service's workers.
    #[arg(long)]
    pub no_pin: bool,
    /// On-board time budget per request, ms.
    #[arg(long, default_value_t = report::DEFAULT_BUDGET_MS)]
    pub budget_ms: f64,
    /// Per-request timeout, ms.
    #[arg(long, default_value_t = 10_000)]
    pub timeout_ms: u64,
    /// Folder of fixtures (default: `fixtures/` of the repository).
    #[arg(long)]
    pub fixtures: Option<PathBuf>,
    /// Write the report as JSON to this file.
    #[arg(long, value_name = "FILE")]
    pub json: Option<PathBuf>,
    /// Rows of the results table to print.
    #[arg(long, default_value_t = 30)]
    pub rows: usize,
    /// Write the README's demo figures (`fixtures/golden/figures/harness-demo.toml`,
    /// `leo-on-board-host.toml`) and the harness document's timing tables
    /// (`fixtures/golden/tables/harness-demo-*.md`) from this run.
    #[arg(long)]
    pub record_figures: bool,
}

/// Run `reconfig demo`.
pub fn run(args: &Args) -> Result<ExitCode> {
    let started = Instant::now();
    let instance = Instance {
        prefix: format!("reconfig_demo_{}_", std::process::id()),
        service: "demo".into(),
    };
    let dir = args.fixtures.clone().unwrap_or_else(default_fixtures_dir);
    let limits = Limits::default();
    let mut items = fixture_items(&fixture_files(&dir)?, &limits);
    let published = items.len();
    items.extend(faults::items(1_000_000));
    items.extend(crate::scenario::generate(args.random, args.seed));
    println!(
        "demo: {} published cases from {}, {} faults, {} generated scenarios",
        published,
        dir.display(),
        items.len() - published - args.random,
        args.random
    );

    let cpus = args
        .cpus
        .clone()
        .unwrap_or_else(crate::harness::affinity::default_cpu_list);
    let workers = crate::harness::parse_cpus(&cpus)?.len();
    let service = ServiceChild::start(&instance, &cpus, args.no_pin, &[])?;
    let budget = Duration::from_secs_f64(args.budget_ms / 1e3);

    let mut opts = FeedOptions::new(instance.clone());
    opts.timeout = Duration::from_millis(args.timeout_ms);
    opts.progress = true;
    opts.window = 1;
    let sequential = feeder::run(&items, &opts);
    opts.window = 2 * workers;
    opts.first_seq = 1 + items.len() as u64;
    let saturated = sequential.as_ref().ok().map(|_| feeder::run(&items, &opts));
    // The LEO tour's on-board part: the sequencing, then its arcs on every worker (when the
    // fixtures folder has Example I's sequencing fixture).
    let has_onboard = dir.join(leo_onboard::FIXTURE).is_file();
    let onboard = has_onboard.then(|| {
        leo_onboard::run(
            &instance,
            &dir,
            workers,
            1 + 2 * items.len() as u64,
            &limits,
        )
    });
    let stopped_cleanly = service.stop()?;
    let _ = crate::harness::remove_instance_segment(&instance);
    let sequential = sequential?;
    let saturated = saturated.ok_or_else(|| anyhow!("no saturated run"))??;

    let rep1 = report::build(
        "one request at a time (latency), feeder unpinned",
        &items,
        &sequential,
        budget,
        None,
    );
    let rep2 = report::build(
        &format!("{} in flight, every worker busy (throughput)", 2 * workers),
        &items,
        &saturated,
        budget,
        Some(2 * workers),
    );
    let tables = [report::table(&rep1), report::table(&rep2)];
    let throughput = rep2.throughput.as_ref().map(|t| {
        format!(
            "{} requests in {:.3} s = {:.0} requests/s with {} in flight",
            t.requests, t.seconds, t.per_second, t.window
        )
    });
    let ok = conclude(
        &items,
        &[(&sequential, rep1), (&saturated, rep2)],
        args.rows,
        args.json.as_deref(),
        &limits,
    )?;
    let onboard_ok = match &onboard {
        Some(Ok(r)) => {
            leo_onboard::print(r, workers);
            r.correct
        }
        Some(Err(e)) => {
            println!("LEO on-board part FAILED: {e:#}");
            false
        }
        None => {
            println!(
                "LEO on-board part skipped: no {} in {}",
                leo_onboard::FIXTURE,
                dir.display()
            );
            true
        }
    };
    let ok = ok && onboard_ok;
    println!(
        "flight service stopped {}",
        if stopped_cleanly {
            "cleanly"
        } else {
            "UNCLEANLY"
        }
    );
    let ok = ok && stopped_cleanly;
    println!(
        "demo {} in {:.1} s: {} requests x 2 runs, {}",
        if ok { "passed" } else { "FAILED" },
        started.elapsed().as_secs_f64(),
        items.len(),
        if ok {
            "every answer correct"
        } else {
            "NOT every answer correct"
        }
    );
    if args.record_figures {
        record_figures(
            ok,
            started.elapsed().as_secs_f64(),
            items.len(),
            onboard.as_ref().and_then(|r| r.as_ref().ok()),
            workers,
        )?;
        record_tables(
            ok,
            started.elapsed().as_secs_f64(),
            items.len(),
            &tables,
            throughput.as_deref().unwrap_or("not measured"),
            args.budget_ms,
        )?;
    }
    Ok(if ok {
        ExitCode::SUCCESS
    } else {
        ExitCode::FAILURE
    })
}

/// The harness document's timing tables (one request at a time; every worker busy), from
/// this run.
fn record_tables(
    ok: bool,
    elapsed_s: f64,
    requests: usize,
    tables: &[crate::table_record::Table; 2],
    throughput: &str,
    budget_ms: f64,
) -> Result<()> {
    use crate::table_record::write_reconfig;
    let outcome = format!(
        "The demo {} in {elapsed_s:.1} s: {requests} requests x 2 runs, {}. Microseconds; \
         misses are round trips over the {} ms budget, with the worst overrun.",
        if ok { "passed" } else { "FAILED" },
        if ok {
            "every answer correct"
        } else {
            "NOT every answer correct"
        },
        budget_ms
    );
    let [latency, busy] = tables;
    write_reconfig(
        "harness-demo-latency",
        RECORD_ARGUMENTS,
        &format!("{outcome} One request at a time (latency):"),
        &[latency],
    )?;
    write_reconfig(
        "harness-demo-busy",
        RECORD_ARGUMENTS,
        &format!("Every worker busy (throughput: {throughput}):"),
        &[busy],
    )
}

/// The `reconfig` arguments that write the demo's records.
const RECORD_ARGUMENTS: &str = "demo --record-figures";

/// The README's demo figures, from this run (timings: written by the run, never by a test).
fn record_figures(
    ok: bool,
    elapsed_s: f64,
    requests: usize,
    onboard: Option<&leo_onboard::OnboardRun>,
    workers: usize,
) -> Result<()> {
    use crate::figure_record::{write, Figure};
    let command = format!("{} {RECORD_ARGUMENTS}", crate::table_record::RECONFIG);
    write(
        "harness-demo",
        &Figure {
            what: "harness demo (`reconfig demo`)".into(),
            target: "every answer correct, < 1 min".into(),
            measured: format!(
                "{elapsed_s:.1} s, {requests} requests x 2 runs, {}",
                if ok {
                    "every answer correct"
                } else {
                    "NOT every answer correct"
                }
            ),
            met: ok && elapsed_s < 60.0,
            doc: "harness".into(),
            command: command.clone(),
        },
    )
    .map_err(|e| anyhow!(e))?;
    if let Some(r) = onboard {
        write(
            "leo-on-board-host",
            &Figure {
                what: format!(
                    "LEO tour on board (Example I: order + arcs), host, {workers} workers"
                ),
                target: format!("≤ {} ms", leo_onboard::BUDGET_MS),
                measured: format!("{:.0} ms", r.total_ms()),
                met: r.correct && r.total_ms() <= leo_onboard::BUDGET_MS,
                doc: "leo-tour".into(),
                command: command.clone(),
            },
        )
        .map_err(|e| anyhow!(e))?;
    }
    Ok(())
}
