//! `reconfig fairness`: two feeders at once against one flight service, to show that clients
//! are served in turn (round-robin per client) and that a cheap client keeps its latency next
//! to an expensive one.
//!
//! Starts `serve` as a child (like the demo), then runs two phases of `--seconds` each, two
//! feeder threads per phase (each its own iceoryx2 node and client):
//! 1. *mixed*: client `expensive` sends only 8-spacecraft crossings (planner A, N = 16, tens of
//!    ms each) with `--window` in flight; client `cheap` sends only planner-B fixed-point plans
//!    (sub-millisecond) one at a time at `--cheap-rate`. The cheap client's p99 round trip must
//!    stay within `--budget-ms`.
//! 2. *same kind*: both clients send the crossings with the same window; neither client's
//!    throughput may fall below half of the other's.
//!
//! Every answer is checked byte for byte against a local solve (one per distinct request), and
//! nothing may be lost, late, duplicated, malformed or expired. Exit 0 only if all holds.

use crate::harness::child::ServiceChild;
use crate::harness::feeder::{self, Fate, FeedOptions, FeedRun, Item};
use crate::harness::items::request_item;
use crate::harness::worker::{local_outcome, Worker, WORKER_STACK_BYTES};
use crate::harness::{report, Instance};
use anyhow::{anyhow, Result};
use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;
use reconfig_core::wire::Request;
use reconfig_core::{impulsive, pseudospectral};
use serde::Serialize;
use std::path::PathBuf;
use std::process::ExitCode;
use std::time::Duration;

/// Arguments of `reconfig fairness`.
#[derive(clap::Args, Debug)]
pub struct Args {
    /// Length of each of the two phases, s.
    #[arg(long, default_value_t = 60.0)]
    pub seconds: f64,
    /// Requests the expensive clients keep in flight.
    #[arg(long, default_value_t = 4)]
    pub window: usize,
    /// Requests per second of the cheap client.
    #[arg(long, default_value_t = 50.0)]
    pub cheap_rate: f64,
    /// Budget of the cheap client's round trip, ms (its p99 must stay within it).
    #[arg(long, default_value_t = report::DEFAULT_BUDGET_MS)]
    pub budget_ms: f64,
    /// CPUs of the flight service (default: the first two this process may use).
    #[arg(long)]
    pub cpus: Option<String>,
    /// Do not pin the service's workers.
    #[arg(long)]
    pub no_pin: bool,
    /// Write the results as JSON to this file.
    #[arg(long, value_name = "FILE")]
    pub json: Option<PathBuf>,
}

/// One client's figures in one phase.
#[derive(Clone, Debug, Serialize)]
pub struct ClientFigures {
    /// Client name.
    pub client: String,
    /// Requests sent.
    pub sent: u64,
    /// Answered correctly (byte-identical to a local solve).
    pub correct: u64,
    /// Answered, but not correctly (including `Expired`).
    pub wrong: u64,
    /// Lost, late, duplicated or malformed.
    pub lost: u64,
    /// Answers per second.
    pub throughput_per_s: f64,
    /// Round trip, us.
    pub rtt_p50_us: f64,
    /// Round trip, us.
    pub rtt_p99_us: f64,
    /// Round trip, us.
    pub rtt_max_us: f64,
}

/// Both phases.
#[derive(Clone, Debug, Serialize)]
pub struct FairnessOut {
    /// Phase length, s.
    pub seconds: f64,
    /// Cheap client's budget, ms.
    pub budget_ms: f64,
    /// Phase 1: expensive and cheap.
    pub mixed: Vec<ClientFigures>,
    /// Phase 2: both expensive.
    pub same_kind: Vec<ClientFigures>,
    /// Smaller throughput over the larger in phase 2.
    pub same_kind_throughput_ratio: f64,
    /// Every check held.
    pub passed: bool,
}

/// Distinct expensive requests: 8-spacecraft crossings at N = 16.
fn expensive_templates() -> Vec<Item> {
    let mut rng = ChaCha8Rng::seed_from_u64(11);
    (0..8)
        .map(|k| {
            let problem = crate::scenario::crossing(&mut rng, 8, 16);
            let settings = pseudospectral::Settings::default();
            let request = Request::Pseudospectral { problem, settings };
            request_item(format!("crossing M8 N16 #{k}"), "M8 N16".into(), request)
        })
        .collect()
}

/// Distinct cheap requests: planner-B fixed-point plans (3 impulses).
fn cheap_templates() -> Vec<Item> {
    let mut rng = ChaCha8Rng::seed_from_u64(12);
    (0..8)
        .map(|k| {
            let problem = crate::scenario::perturbed_impulsive(&mut rng, 3);
            let settings = impulsive::Settings::default();
            let request = Request::Impulsive { problem, settings };
            request_item(format!("fixed point K3 #{k}"), "K3".into(), request)
        })
        .collect()
}

/// `count` items cycling through `templates`.
fn cycle(templates: &[Item], count: usize) -> Vec<Item> {
    templates.iter().cycle().take(count).cloned().collect()
}

/// The local outcome of each template (bodies carry no sequence number).
fn expected_bodies(templates: &[Item]) -> Result<Vec<Vec<u8>>> {
    std::thread::Builder::new()
        .stack_size(WORKER_STACK_BYTES)
        .spawn({
            let frames: Vec<Vec<u8>> = templates
                .iter()
                .map(|t| feeder::frame_of(t, 1))
                .collect::<Result<_>>()?;
            move || {
                let mut worker = Worker::new();
                frames
                    .iter()
                    .map(|f| local_outcome(&mut worker, f))
                    .collect()
            }
        })?
        .join()
        .map_err(|_| anyhow!("the local solve panicked"))
}

fn figures(name: &str, run: &FeedRun, templates: usize, expected: &[Vec<u8>]) -> ClientFigures {
    let mut rtts: Vec<u64> = Vec::new();
    let (mut correct, mut wrong) = (0u64, 0u64);
    for r in &run.records {
        if let Fate::Answered { rtt_ns, body, .. } = &r.fate {
            rtts.push(*rtt_ns);
            if expected.get(r.index % templates) == Some(body) {
                correct += 1;
            } else {
                wrong += 1;
            }
        }
    }
    rtts.sort_unstable();
    let at = |q: f64| -> f64 {
        if rtts.is_empty() {
            return 0.0;
        }
        let i = ((rtts.len() as f64 * q).ceil() as usize).clamp(1, rtts.len()) - 1;
        rtts[i] as f64 / 1e3
    };
    let c = &run.counters;
    ClientFigures {
        client: name.into(),
        sent: c.sent,
        correct,
        wrong,
        lost: c.lost + c.late + c.duplicated + c.malformed,
        throughput_per_s: c.answered as f64 / run.elapsed.as_secs_f64().max(1e-9),
        rtt_p50_us: at(0.5),
        rtt_p99_us: at(0.99),
        rtt_max_us: at(1.0),
    }
}

/// Two feeders at once; returns their runs in order.
fn two_feeders(
    instance: &Instance,
    clients: [(&[Item], usize, Option<f64>); 2],
    seconds: f64,
) -> Result<[FeedRun; 2]> {
    let runs: Vec<Result<FeedRun>> = std::thread::scope(|scope| {
        let handles: Vec<_> = clients
            .iter()
            .enumerate()
            .map(|(k, (items, window, rate))| {
                let mut opts = FeedOptions::new(instance.clone());
                opts.window = *window;
                opts.rate = *rate;
                opts.timeout = Duration::from_secs(10);
                opts.first_seq = 1 + 10_000_000 * k as u64;
                opts.stop_after = Some(Duration::from_secs_f64(seconds));
                scope.spawn(move || feeder::run(items, &opts))
            })
            .collect();
        handles
            .into_iter()
            .map(|h| {
                h.join()
                    .unwrap_or_else(|_| Err(anyhow!("a feeder panicked")))
            })
            .collect()
    });
    let mut runs = runs.into_iter();
    let a = runs.next().ok_or_else(|| anyhow!("no run"))??;
    let b = runs.next().ok_or_else(|| anyhow!("no run"))??;
    Ok([a, b])
}

fn print_phase(title: &str, rows: &[ClientFigures]) {
    println!("\n== {title}");
    println!(
        "{:<10} {:>7} {:>7} {:>5} {:>5} {:>10} {:>10} {:>10} {:>10}",
        "client", "sent", "correct", "wrong", "lost", "req/s", "rtt p50", "p99", "max (us)"
    );
    for r in rows {
        println!(
            "{:<10} {:>7} {:>7} {:>5} {:>5} {:>10.1} {:>10.1} {:>10.1} {:>10.1}",
            r.client,
            r.sent,
            r.correct,
            r.wrong,
            r.lost,
            r.throughput_per_s,
            r.rtt_p50_us,
            r.rtt_p99_us,
            r.rtt_max_us
        );
    }
}

/// Run `reconfig fairness`.
pub fn run(args: &Args) -> Result<ExitCode> {
    let instance = Instance {
        prefix: format!("reconfig_fair_{}_", std::process::id()),
        service: "fairness".into(),
    };
    let expensive = expensive_templates();
    let cheap = cheap_templates();
    let expected_expensive = expected_bodies(&expensive)?;
    let expected_cheap = expected_bodies(&cheap)?;
    // More items than a phase can send (a crossing takes at least a few ms).
    let n_expensive = (args.seconds * 400.0) as usize + 16;
    let n_cheap = (args.seconds * args.cheap_rate.max(1.0) * 1.5) as usize + 16;
    let expensive_items = cycle(&expensive, n_expensive);
    let cheap_items = cycle(&cheap, n_cheap);

    let cpus = args
        .cpus
        .clone()
        .unwrap_or_else(crate::harness::affinity::default_cpu_list);
    let service = ServiceChild::start(&instance, &cpus, args.no_pin, &[])?;
    let mixed = two_feeders(
        &instance,
        [
            (&expensive_items, args.window, None),
            (&cheap_items, 1, Some(args.cheap_rate)),
        ],
        args.seconds,
    );
    let same = mixed.as_ref().ok().map(|_| {
        two_feeders(
            &instance,
            [
                (&expensive_items, args.window, None),
                (&expensive_items, args.window, None),
            ],
            args.seconds,
        )
    });
    let stopped = service.stop()?;
    let _ = crate::harness::remove_instance_segment(&instance);
    let [m_exp, m_cheap] = mixed?;
    let [s_a, s_b] = same.ok_or_else(|| anyhow!("no second phase"))??;
    let n_e = expensive.len();
    let mixed = vec![
        figures("expensive", &m_exp, n_e, &expected_expensive),
        figures("cheap", &m_cheap, cheap.len(), &expected_cheap),
    ];
    let same_kind = vec![
        figures("first", &s_a, n_e, &expected_expensive),
        figures("second", &s_b, n_e, &expected_expensive),
    ];
    let (ta, tb) = (same_kind[0].throughput_per_s, same_kind[1].throughput_per_s);
    let ratio = ta.min(tb) / ta.max(tb).max(1e-9);
    let all_right = mixed
        .iter()
        .chain(&same_kind)
        .all(|c| c.wrong == 0 && c.lost == 0 && c.correct == c.sent);
    let cheap_ok = mixed[1].rtt_p99_us <= args.budget_ms * 1e3;
    let passed = all_right && cheap_ok && ratio >= 0.5 && stopped;
    print_phase(
        &format!(
            "mixed, {} s: expensive (M8 N16 crossings, {} in flight) + cheap (planner-B fixed point, {} /s)",
            args.seconds, args.window, args.cheap_rate
        ),
        &mixed,
    );
    println!(
        "cheap p99 {:.1} us, budget {} ms: {}",
        mixed[1].rtt_p99_us,
        args.budget_ms,
        if cheap_ok { "within" } else { "OVER" }
    );
    print_phase(
        &format!(
            "same kind, {} s: both clients send crossings, {} in flight each",
            args.seconds, args.window
        ),
        &same_kind,
    );
    println!("throughput ratio (smaller / larger) {ratio:.3} (must be >= 0.5)");
    println!(
        "flight service stopped {}; fairness {}",
        if stopped { "cleanly" } else { "UNCLEANLY" },
        if passed { "passed" } else { "FAILED" }
    );
    if let Some(path) = &args.json {
        let out = FairnessOut {
            seconds: args.seconds,
            budget_ms: args.budget_ms,
            mixed,
            same_kind,
            same_kind_throughput_ratio: ratio,
            passed,
        };
        std::fs::write(path, serde_json::to_string_pretty(&out)?)?;
    }
    Ok(if passed {
        ExitCode::SUCCESS
    } else {
        ExitCode::FAILURE
    })
}
