//! Is every answer right? An answer is correct when it decodes, answers the sequence number
//! sent, and its outcome is byte-for-byte what a local solve of the same frame gives (which
//! also checks that solves are deterministic across processes).

use super::feeder::{Fate, FeedRun, Item};
use super::report;
use super::worker::{local_outcome, Worker};
use anyhow::Result;
use reconfig_core::limits::Limits;
use reconfig_core::wire::Outcome;
use serde::Serialize;
use std::path::Path;

/// The verdict on one item.
#[derive(Clone, Debug)]
pub struct Verdict {
    /// Index of the item.
    pub index: usize,
    /// The answer is correct.
    pub correct: bool,
    /// The decoded outcome, when the answer decoded.
    pub outcome: Option<Outcome>,
    /// Why not, when not correct.
    pub reason: String,
    /// Round trip, us, when answered.
    pub rtt_us: Option<f64>,
}

/// Local expected outcomes, one per record of `run`, solved on up to two threads (each with its
/// own worker, checking the service's `limits`). Any run of the same items gives the same
/// outcomes: the body of a response does not contain the sequence number.
pub fn expected(run: &FeedRun, limits: &Limits) -> Vec<Vec<u8>> {
    let limits = *limits;
    let threads = super::affinity::available_cpus().clamp(1, 2);
    let chunk = run.records.len().div_ceil(threads).max(1);
    std::thread::scope(|scope| {
        let handles: Vec<_> = run
            .records
            .chunks(chunk)
            .map(|records| {
                std::thread::Builder::new()
                    .stack_size(super::worker::WORKER_STACK_BYTES)
                    .spawn_scoped(scope, move || {
                        let mut worker = Worker::new();
                        worker.limits = limits;
                        records
                            .iter()
                            .map(|r| local_outcome(&mut worker, &r.frame))
                            .collect::<Vec<_>>()
                    })
            })
            .collect();
        handles
            .into_iter()
            .flat_map(|h| match h {
                Ok(h) => h.join().unwrap_or_default(),
                Err(_) => Vec::new(),
            })
            .collect()
    })
}

/// Check every record of `run` against `expected` (from [`expected`] on an equal run).
pub fn verify(items: &[Item], run: &FeedRun, expected: &[Vec<u8>]) -> Vec<Verdict> {
    run.records
        .iter()
        .map(|record| {
            let _ = &items[record.index];
            let mut v = Verdict {
                index: record.index,
                correct: false,
                outcome: None,
                reason: String::new(),
                rtt_us: None,
            };
            match &record.fate {
                Fate::NotSent => v.reason = "not sent (no service)".into(),
                Fate::Lost => v.reason = "lost (timeout)".into(),
                Fate::Malformed(e) => v.reason = format!("malformed response: {e}"),
                Fate::Answered { rtt_ns, body, .. } => {
                    v.rtt_us = Some(*rtt_ns as f64 / 1000.0);
                    match postcard::from_bytes::<Outcome>(body) {
                        Ok(o) => v.outcome = Some(o),
                        Err(e) => v.reason = format!("undecodable outcome: {e}"),
                    }
                    let want = expected.get(record.index).map(Vec::as_slice);
                    if let Some(Outcome::Expired(x)) = &v.outcome {
                        // Truthful, but not a plan: the request waited past its deadline.
                        v.reason = format!(
                            "expired in the service's queue after {:.1} ms (deadline {:.1} ms), not solved",
                            x.queued_us as f64 / 1e3,
                            x.deadline_us as f64 / 1e3
                        );
                    } else if v.outcome.is_some() && want == Some(body.as_slice()) {
                        v.correct = true;
                    } else if v.outcome.is_some() {
                        v.reason = "differs from a local solve of the same request".into();
                    }
                }
            }
            v
        })
        .collect()
}

/// Print the results table: one row per item (planner, size, status, cost or dv, min
/// separation, iterations, round trip, verdict). `limit` rows at most, then a summary.
pub fn print_table(items: &[Item], verdicts: &[Verdict], limit: usize) {
    println!(
        "{:<42} {:<15} {:<7} {:<40} {:>16} {:>16} {:>5} {:>9} ok",
        "request", "planner", "size", "status", "cost / dv", "min sep (pair)", "iter", "rtt us"
    );
    for v in verdicts.iter().take(limit) {
        let item = &items[v.index];
        let (status, cost, sep, iters) = match &v.outcome {
            Some(o) => super::worker::summarize(o),
            None => (v.reason.clone(), "-".into(), "-".into(), "-".into()),
        };
        let planner = item.planner.map_or("fault", |p| p.name());
        println!(
            "{:<42} {:<15} {:<7} {:<40} {:>16} {:>16} {:>5} {:>9} {}",
            truncate(&item.label, 42),
            planner,
            item.size,
            truncate(&status, 40),
            cost,
            sep,
            iters,
            v.rtt_us.map_or("-".into(), |r| format!("{r:.1}")),
            if v.correct { "yes" } else { "NO" }
        );
    }
    if verdicts.len() > limit {
        let rest = &verdicts[limit..];
        let mut by_status = std::collections::BTreeMap::<String, (usize, usize)>::new();
        for v in rest {
            let status = v
                .outcome
                .as_ref()
                .map_or_else(|| v.reason.clone(), |o| super::worker::summarize(o).0);
            let e = by_status.entry(status).or_default();
            e.0 += 1;
            if v.correct {
                e.1 += 1;
            }
        }
        println!("... and {} more requests:", rest.len());
        for (status, (n, ok)) in by_status {
            println!("    {n:>5} x {status} ({ok} correct)");
        }
    }
    let wrong: Vec<_> = verdicts.iter().filter(|v| !v.correct).collect();
    for v in wrong.iter().take(10) {
        println!("WRONG: {}: {}", items[v.index].label, v.reason);
    }
}

fn truncate(s: &str, n: usize) -> String {
    if s.chars().count() <= n {
        s.to_string()
    } else {
        let mut t: String = s.chars().take(n - 1).collect();
        t.push('~');
        t
    }
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
        .map(|(run, _)| expected(run, limits))
        .unwrap_or_default();
    for (run, _) in runs {
        let verdicts = verify(items, run, &expected);
        if first {
            print_table(items, &verdicts, rows);
            first = false;
        }
        for (v, record) in verdicts.iter().zip(&run.records) {
            all_correct &= v.correct;
            let order = match &record.fate {
                Fate::Answered { order, .. } => Some(*order),
                _ => None,
            };
            results.push(JsonResult {
                label: items[v.index].label.clone(),
                status: v
                    .outcome
                    .as_ref()
                    .map_or_else(|| v.reason.clone(), |o| super::worker::summarize(o).0),
                correct: v.correct,
                rtt_us: v.rtt_us,
                seq: record.seq,
                turn: order
                    .map(|o| o.turn)
                    .filter(|t| *t != super::dispatch::NO_TURN),
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
