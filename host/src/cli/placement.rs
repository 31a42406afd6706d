//! `reconfig placement`: where the flight service's workers and the feeder should sit. Starts a
//! service per placement (the workers on one or both of the first two CPUs, the feeder pinned
//! or not, one request at a time or every worker busy), feeds each the same generated
//! requests, checks every answer against a local solve and prints the harness's share of the
//! round trip (the round trip less the solve) per placement (`--record`: as the harness
//! document's table).

use crate::harness::check::{expected, verify};
use crate::harness::child::ServiceChild;
use crate::harness::feeder::{self, FeedOptions};
use crate::harness::{affinity, report, Instance};
use crate::table_record::Table;
use anyhow::{anyhow, Result};
use reconfig_core::limits::Limits;
use std::process::ExitCode;
use std::time::Duration;

/// Arguments of `reconfig placement`.
#[derive(clap::Args, Debug)]
pub struct Args {
    /// Generated requests per placement.
    #[arg(long, default_value_t = 1000)]
    pub random: usize,
    /// Seed of the generated requests.
    #[arg(long, default_value_t = 7)]
    pub seed: u64,
    /// Write the table for the harness document (`fixtures/golden/tables/harness-placement.md`).
    #[arg(long)]
    pub record: bool,
}

/// One placement: the service's CPUs, the feeder's CPU, the requests in flight.
struct Placement {
    service_cpus: String,
    feeder_cpu: Option<usize>,
    window: usize,
}

/// The placements measured, on the first two CPUs `a` and `b` this process may use.
fn placements(a: usize, b: usize) -> [Placement; 5] {
    let p = |service_cpus: String, feeder_cpu, window| Placement {
        service_cpus,
        feeder_cpu,
        window,
    };
    [
        p(format!("{a},{b}"), None, 1),
        p(format!("{b}"), Some(a), 1),
        p(format!("{a}"), Some(a), 1),
        p(format!("{a},{b}"), Some(a), 1),
        p(format!("{a},{b}"), None, 4),
    ]
}

/// The harness's share of each answered request's round trip (the round trip less the solve
/// the worker timed): median, 99th percentile and maximum, µs.
fn harness_share_us(run: &feeder::FeedRun) -> (f64, f64, f64) {
    let mut share: Vec<u64> = run
        .records
        .iter()
        .filter_map(|r| match r.fate {
            feeder::Fate::Answered {
                rtt_ns, solve_ns, ..
            } => Some(rtt_ns.saturating_sub(solve_ns)),
            _ => None,
        })
        .collect();
    share.sort_unstable();
    let at = |q: f64| {
        let i = ((share.len() as f64 * q).ceil() as usize).clamp(1, share.len().max(1)) - 1;
        share.get(i).map_or(0.0, |&v| v as f64 / 1e3)
    };
    (at(0.5), at(0.99), at(1.0))
}

/// Run `reconfig placement`.
pub fn run(args: &Args) -> Result<ExitCode> {
    let cpus = affinity::allowed_cpus();
    let (&a, &b) = match cpus.as_slice() {
        [a, b, ..] => (a, b),
        _ => {
            return Err(anyhow!(
                "placement needs two CPUs; this process may use {cpus:?}"
            ))
        }
    };
    let items = crate::scenario::generate(args.random, args.seed);
    let limits = Limits::default();
    let mut table = Table::new(
        &[
            "service CPUs",
            "feeder",
            "in flight",
            "correct",
            "harness share p50 us",
            "p99",
            "max",
            "planner-A rtt p50 us",
            "requests/s",
        ],
        "llrrrrrrr",
    );
    let mut all_correct = true;
    let mut wanted: Option<Vec<Vec<u8>>> = None;
    for (k, p) in placements(a, b).iter().enumerate() {
        let instance = Instance {
            prefix: format!("reconfig_place_{}_{k}_", std::process::id()),
            service: "placement".into(),
        };
        let service = ServiceChild::start(&instance, &p.service_cpus, false, &[])?;
        let mut opts = FeedOptions::new(instance.clone());
        opts.window = p.window;
        opts.cpu = p.feeder_cpu;
        // A thread of its own: pinning the feeder must not pin this one (and the next
        // placement's "unpinned" feeder with it).
        let run = std::thread::scope(|scope| {
            scope
                .spawn(|| feeder::run(&items, &opts))
                .join()
                .unwrap_or_else(|_| Err(anyhow!("the feeder panicked")))
        });
        let stopped = service.stop()?;
        let _ = crate::harness::remove_instance_segment(&instance);
        let run = run?;
        // One local solve per request serves every placement (frames differ only in `seq`).
        let wanted = wanted.get_or_insert_with(|| expected(&run, &limits));
        let correct = verify(&items, &run, wanted)
            .iter()
            .filter(|v| v.correct)
            .count();
        all_correct &= correct == items.len() && stopped;
        let rep = report::build("", &items, &run, Duration::from_millis(100), None);
        let a_row = rep
            .rows
            .iter()
            .find(|r| r.planner == "pseudospectral" && r.size == "all")
            .ok_or_else(|| anyhow!("no planner-A requests among the generated ones"))?;
        let share = harness_share_us(&run);
        table.push(vec![
            p.service_cpus.clone(),
            p.feeder_cpu
                .map_or_else(|| "unpinned".into(), |c| format!("CPU {c}")),
            p.window.to_string(),
            format!("{correct} / {}", items.len()),
            format!("{:.1}", share.0),
            format!("{:.1}", share.1),
            format!("{:.1}", share.2),
            format!("{:.1}", a_row.rtt_p50_us),
            format!(
                "{:.0}",
                run.counters.answered as f64 / run.elapsed.as_secs_f64().max(1e-9)
            ),
        ]);
    }
    println!("{}", table.markdown());
    if args.record {
        crate::table_record::write_reconfig(
            "harness-placement",
            &format!(
                "placement --random {} --seed {} --record",
                args.random, args.seed
            ),
            &format!(
                "{} generated requests (seed {}) per placement; every answer compared with a \
                 local solve: {}.",
                items.len(),
                args.seed,
                if all_correct {
                    "all correct"
                } else {
                    "NOT all correct"
                }
            ),
            &[&table],
        )?;
    }
    Ok(if all_correct {
        ExitCode::SUCCESS
    } else {
        ExitCode::FAILURE
    })
}
