//! `reconfig fairness`: clients at once against one flight service, to show that they are
//! served in turn (round-robin per client), that a cheap client keeps its latency next to an
//! expensive one, and (`--flood MODE`) that a client flooding garbage neither starves a good
//! client nor outlives its own death.
//!
//! Starts `serve` as a child (like the demo). Without `--flood`, two phases of `--seconds`
//! each, two feeder threads per phase (each its own iceoryx2 node and client):
//! 1. *mixed*: client `expensive` sends only 8-spacecraft crossings (planner A, N = 16, tens of
//!    ms each) with `--window` in flight; client `cheap` sends only planner-B fixed-point plans
//!    (sub-millisecond) one at a time at `--cheap-rate`. The cheap client's p99 round trip must
//!    stay within `--budget-ms`.
//! 2. *same kind*: both clients send the crossings with the same window; neither client's
//!    throughput may fall below half of the other's.
//!
//! With `--flood MODE`: a flooder process (`reconfig feed --flood MODE`) floods the service with
//! garbage frames and wake-ups; phase *during*: the cheap client runs for `--seconds` beside it;
//! then the flooder is killed (SIGKILL); phase *after*: the cheap client runs `--seconds` more.
//! Its p99 must stay within `--budget-ms` in both.
//!
//! Every answer is checked byte for byte against a local solve (one per distinct request), and
//! nothing may be lost, late, duplicated, malformed or expired. Every answer carries its place
//! in the order of service (`harness::order`): no request may wait for more turns of the other
//! client than the round-robin allows (*served in turn*; *starved* counts the requests lost or
//! served out of turn). Exit 0 only if all holds; the JSON report says which check failed.

mod table;

use crate::harness::child::ServiceChild;
use crate::harness::dispatch::{ServiceOrder, NO_TURN};
use crate::harness::feeder::{self, Fate, FeedOptions, FeedRun, Item};
use crate::harness::flood::{FloodMode, FlooderProcess};
use crate::harness::items::request_item;
use crate::harness::worker::{local_outcome, Worker, WORKER_STACK_BYTES};
use crate::harness::{order, report, Instance};
use anyhow::{anyhow, Result};
use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;
use reconfig_core::wire::Request;
use reconfig_core::{impulsive, pseudospectral};
use serde::Serialize;
use std::path::PathBuf;
use std::process::ExitCode;
use std::time::Duration;
use table::{mode_name, phase_table, print_phase, print_stopped, record};

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
    /// Instead of the two phases: the cheap client during and after a flood of garbage by a
    /// flooder process in this mode (`read`, `abandon`, `ignore`; see `reconfig feed --flood`).
    #[arg(long, value_name = "MODE")]
    pub flood: Option<FloodMode>,
    /// Write this run's tables for the harness document (`fixtures/golden/tables/
    /// harness-fairness.md`, or `harness-flood-MODE.md` with `--flood`).
    #[arg(long)]
    pub record: bool,
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
    /// Requests that waited for more turns of the other clients than the round-robin allows.
    pub out_of_turn: usize,
    /// Requests not answered (lost, late, duplicated, malformed) or served out of turn.
    pub starved: u64,
    /// Most turns of other clients one request waited for (between its receipt and its turn).
    pub most_other_turns_waited: u64,
    /// Turns given to other clients between this client's first receipt and its last turn.
    pub other_turns: u64,
    /// Each answer's `[received_at_turn, turn]` (answers given in a turn), in send order.
    pub served: Vec<[u64; 2]>,
}

/// The checks, each on its own.
#[derive(Clone, Debug, Serialize)]
pub struct Checks {
    /// Every request answered, every answer byte-identical to a local solve.
    pub all_correct: bool,
    /// No request waited for more turns of other clients than the round-robin allows.
    pub served_in_turn: bool,
    /// The cheap client's p99 round trip within `--budget-ms` (a measurement, machine-dependent).
    pub cheap_within_budget: bool,
    /// Same-kind throughput ratio at least 0.5 (a measurement; true with `--flood`).
    pub throughput_ratio_ok: bool,
    /// The flight service stopped cleanly on SIGTERM.
    pub stopped_cleanly: bool,
}

/// The `--flood` run.
#[derive(Clone, Debug, Serialize)]
pub struct FloodOut {
    /// Flooder mode.
    pub mode: String,
    /// The flooder's last `flooding:` line before it was killed.
    pub flooder: String,
    /// The cheap client while the flooder runs.
    pub during: ClientFigures,
    /// The cheap client after the flooder was killed.
    pub after: ClientFigures,
}

/// Both phases, or the flood run.
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
    /// With `--flood` (then `mixed` and `same_kind` are empty).
    pub flood: Option<FloodOut>,
    /// Each check.
    pub checks: Checks,
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

/// One client's figures; `other_clients` ran beside it.
fn figures(
    name: &str,
    run: &FeedRun,
    templates: usize,
    expected: &[Vec<u8>],
    other_clients: u64,
) -> ClientFigures {
    let mut rtts: Vec<u64> = Vec::new();
    let mut served: Vec<ServiceOrder> = Vec::new();
    let (mut correct, mut wrong) = (0u64, 0u64);
    for r in &run.records {
        if let Fate::Answered {
            rtt_ns,
            body,
            order,
            ..
        } = &r.fate
        {
            rtts.push(*rtt_ns);
            served.push(*order);
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
    let waits = order::waits(&served);
    let out_of_turn = order::out_of_turn(&waits, other_clients);
    let lost = c.lost + c.late + c.duplicated + c.malformed;
    ClientFigures {
        client: name.into(),
        sent: c.sent,
        correct,
        wrong,
        lost,
        throughput_per_s: c.answered as f64 / run.elapsed.as_secs_f64().max(1e-9),
        rtt_p50_us: at(0.5),
        rtt_p99_us: at(0.99),
        rtt_max_us: at(1.0),
        out_of_turn,
        starved: lost + c.not_sent + out_of_turn as u64,
        most_other_turns_waited: waits.iter().map(|w| w.others).max().unwrap_or(0),
        other_turns: order::other_turns(&served),
        served: served
            .iter()
            .filter(|o| o.turn != NO_TURN)
            .map(|o| [o.received_at_turn, o.turn])
            .collect(),
    }
}

/// Answered correctly, nothing lost.
fn all_right(c: &ClientFigures) -> bool {
    c.wrong == 0 && c.lost == 0 && c.correct == c.sent
}

/// Feeders at once, each for `seconds`; returns their runs in order. Client `k`'s sequence
/// numbers start at `first_seq + 10_000_000 k`.
fn feeders(
    instance: &Instance,
    clients: &[(&[Item], usize, Option<f64>)],
    seconds: f64,
    first_seq: u64,
) -> Result<Vec<FeedRun>> {
    let runs: Vec<Result<FeedRun>> = std::thread::scope(|scope| {
        let handles: Vec<_> = clients
            .iter()
            .enumerate()
            .map(|(k, (items, window, rate))| {
                let mut opts = FeedOptions::new(instance.clone());
                opts.window = *window;
                opts.rate = *rate;
                opts.timeout = Duration::from_secs(10);
                opts.first_seq = first_seq + 10_000_000 * k as u64;
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
    runs.into_iter().collect()
}

/// Two feeders at once; returns their runs in order.
fn two_feeders(
    instance: &Instance,
    clients: [(&[Item], usize, Option<f64>); 2],
    seconds: f64,
) -> Result<[FeedRun; 2]> {
    let mut runs = feeders(instance, &clients, seconds, 1)?.into_iter();
    let a = runs.next().ok_or_else(|| anyhow!("no run"))?;
    let b = runs.next().ok_or_else(|| anyhow!("no run"))?;
    Ok([a, b])
}

fn write_json(path: Option<&std::path::Path>, out: &FairnessOut) -> Result<()> {
    if let Some(path) = path {
        std::fs::write(path, serde_json::to_string_pretty(out)?)?;
    }
    Ok(())
}

fn exit(passed: bool) -> ExitCode {
    if passed {
        ExitCode::SUCCESS
    } else {
        ExitCode::FAILURE
    }
}

/// `--flood MODE`: the cheap client during a flood and after the flooder is killed.
fn run_flood(args: &Args, mode: FloodMode, instance: &Instance) -> Result<ExitCode> {
    let cheap = cheap_templates();
    let expected_cheap = expected_bodies(&cheap)?;
    let n_cheap = (args.seconds * args.cheap_rate.max(1.0) * 1.5) as usize + 16;
    let cheap_items = cycle(&cheap, n_cheap);
    let cpus = args
        .cpus
        .clone()
        .unwrap_or_else(crate::harness::affinity::default_cpu_list);
    let service = ServiceChild::start(instance, &cpus, args.no_pin, &[])?;
    let exe = std::env::current_exe()?;
    let flooder = FlooderProcess::start(&exe, instance, mode)?;
    println!(
        "flooder started (pid {}, mode {mode:?}); cheap client for {} s",
        flooder.pid(),
        args.seconds
    );
    let client = [(cheap_items.as_slice(), 1, Some(args.cheap_rate))];
    let during = feeders(instance, &client, args.seconds, 1);
    let flooder_line = flooder.kill();
    println!("flooder killed (SIGKILL) after: {flooder_line}");
    let after = during
        .as_ref()
        .ok()
        .map(|_| feeders(instance, &client, args.seconds, 100_000_001));
    let stopped = service.stop()?;
    let _ = crate::harness::remove_instance_segment(instance);
    let during = during?.pop().ok_or_else(|| anyhow!("no run"))?;
    let after = after
        .ok_or_else(|| anyhow!("no second phase"))??
        .pop()
        .ok_or_else(|| anyhow!("no run"))?;
    let n = cheap.len();
    let during = figures("during", &during, n, &expected_cheap, 1);
    let after = figures("after", &after, n, &expected_cheap, 1);
    let budget_us = args.budget_ms * 1e3;
    let checks = Checks {
        all_correct: all_right(&during) && all_right(&after),
        served_in_turn: during.starved + after.starved == 0,
        cheap_within_budget: during.rtt_p99_us <= budget_us && after.rtt_p99_us <= budget_us,
        throughput_ratio_ok: true,
        stopped_cleanly: stopped,
    };
    let passed = checks.all_correct
        && checks.served_in_turn
        && checks.cheap_within_budget
        && checks.stopped_cleanly;
    print_phase(
        &format!(
            "cheap client (planner-B fixed point, {} /s), {} s during a {mode:?} flood, then {} s \
             after the flooder was killed",
            args.cheap_rate, args.seconds, args.seconds
        ),
        &[during.clone(), after.clone()],
    );
    println!(
        "turns the service gave the flooder while the cheap client was served: {} during, {} \
         after; p99 {:.1} / {:.1} us, budget {} ms: {}",
        during.other_turns,
        after.other_turns,
        during.rtt_p99_us,
        after.rtt_p99_us,
        args.budget_ms,
        if checks.cheap_within_budget {
            "within"
        } else {
            "OVER"
        }
    );
    print_stopped(stopped, "flood fairness", passed);
    if args.record {
        record(
            args,
            &format!("harness-flood-{}", mode_name(mode)),
            &format!(
                "The cheap client (planner-B fixed points, {} /s, one at a time) for {} s beside \
                 a `{}` flooder, then {} s after the flooder was killed (SIGKILL); the flooder's \
                 last line: `{flooder_line}`.",
                args.cheap_rate,
                args.seconds,
                mode_name(mode),
                args.seconds,
            ),
            &checks,
            &[&phase_table(&[during.clone(), after.clone()])],
        )?;
    }
    let out = FairnessOut {
        seconds: args.seconds,
        budget_ms: args.budget_ms,
        mixed: Vec::new(),
        same_kind: Vec::new(),
        same_kind_throughput_ratio: 1.0,
        flood: Some(FloodOut {
            mode: format!("{mode:?}").to_lowercase(),
            flooder: flooder_line,
            during,
            after,
        }),
        checks,
        passed,
    };
    write_json(args.json.as_deref(), &out)?;
    Ok(exit(passed))
}

/// Run `reconfig fairness`.
pub fn run(args: &Args) -> Result<ExitCode> {
    let instance = Instance {
        prefix: format!("reconfig_fair_{}_", std::process::id()),
        service: "fairness".into(),
    };
    if let Some(mode) = args.flood {
        return run_flood(args, mode, &instance);
    }
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
        figures("expensive", &m_exp, n_e, &expected_expensive, 1),
        figures("cheap", &m_cheap, cheap.len(), &expected_cheap, 1),
    ];
    let same_kind = vec![
        figures("first", &s_a, n_e, &expected_expensive, 1),
        figures("second", &s_b, n_e, &expected_expensive, 1),
    ];
    let (ta, tb) = (same_kind[0].throughput_per_s, same_kind[1].throughput_per_s);
    let ratio = ta.min(tb) / ta.max(tb).max(1e-9);
    let cheap_ok = mixed[1].rtt_p99_us <= args.budget_ms * 1e3;
    let checks = Checks {
        all_correct: mixed.iter().chain(&same_kind).all(all_right),
        served_in_turn: mixed.iter().chain(&same_kind).all(|c| c.starved == 0),
        cheap_within_budget: cheap_ok,
        throughput_ratio_ok: ratio >= 0.5,
        stopped_cleanly: stopped,
    };
    let passed = checks.all_correct
        && checks.served_in_turn
        && checks.cheap_within_budget
        && checks.throughput_ratio_ok
        && checks.stopped_cleanly;
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
        "served in turn: {} (requests that waited for more turns of the other client than the \
         round-robin allows: {})",
        if checks.served_in_turn { "yes" } else { "NO" },
        mixed
            .iter()
            .chain(&same_kind)
            .map(|c| c.out_of_turn)
            .sum::<usize>()
    );
    print_stopped(stopped, "fairness", passed);
    if args.record {
        record(
            args,
            "harness-fairness",
            &format!(
                "Two phases of {} s on one flight service: *mixed* (expensive: M8 N16 crossings, \
                 {} in flight; cheap: planner-B fixed points, {} /s, one at a time), then *same \
                 kind* (first and second: crossings, {} in flight each); same-kind throughput \
                 ratio {ratio:.3}.",
                args.seconds, args.window, args.cheap_rate, args.window,
            ),
            &checks,
            &[&phase_table(&mixed), &phase_table(&same_kind)],
        )?;
    }
    let out = FairnessOut {
        seconds: args.seconds,
        budget_ms: args.budget_ms,
        mixed,
        same_kind,
        same_kind_throughput_ratio: ratio,
        flood: None,
        checks,
        passed,
    };
    write_json(args.json.as_deref(), &out)?;
    Ok(exit(passed))
}
