//! Timing against the on-board budget: HDR histograms of the solve alone and of the full
//! round trip, per planner and per problem size; deadline misses; throughput.

use super::feeder::{Fate, FeedRun, Item};
use hdrhistogram::Histogram;
use serde::Serialize;
use std::collections::BTreeMap;
use std::time::Duration;

/// Default on-board time budget per request, ms (reasoning in docs/harness.md).
pub const DEFAULT_BUDGET_MS: f64 = 100.0;

/// Latency statistics of one group, microseconds.
#[derive(Clone, Debug, Serialize)]
pub struct Row {
    /// Planner name, or `faults` for raw frames.
    pub planner: String,
    /// Problem size class (`all` for the planner's total).
    pub size: String,
    /// Answered requests.
    pub count: u64,
    /// Solve alone: median, us.
    pub solve_p50_us: f64,
    /// Solve alone: 99th percentile, us.
    pub solve_p99_us: f64,
    /// Solve alone: maximum, us.
    pub solve_max_us: f64,
    /// Round trip: median, us.
    pub rtt_p50_us: f64,
    /// Round trip: 99th percentile, us.
    pub rtt_p99_us: f64,
    /// Round trip: maximum, us.
    pub rtt_max_us: f64,
    /// Round trips over the budget.
    pub deadline_misses: u64,
    /// Worst round trip minus the budget, us (0 when none missed).
    pub worst_overrun_us: f64,
}

/// Throughput of a run that kept every worker busy.
#[derive(Clone, Debug, Serialize)]
pub struct Throughput {
    /// Requests answered.
    pub requests: u64,
    /// Wall time, s.
    pub seconds: f64,
    /// Requests per second.
    pub per_second: f64,
    /// Requests kept in flight.
    pub window: usize,
}

/// The timing report of one run.
#[derive(Clone, Debug, Serialize)]
pub struct Report {
    /// What was measured (e.g. "sequential, feeder unpinned").
    pub title: String,
    /// Budget per request, ms.
    pub budget_ms: f64,
    /// One row per planner and size, then one per planner (`all`).
    pub rows: Vec<Row>,
    /// Set for runs that kept the workers busy.
    pub throughput: Option<Throughput>,
    /// Counters of the run.
    pub counters: super::feeder::Counters,
    /// Every request whose round trip exceeded the budget, by name, in the order sent.
    pub over_budget: Vec<OverBudget>,
}

/// A request over the budget.
#[derive(Clone, Debug, Serialize)]
pub struct OverBudget {
    /// The item's label (fixture or scenario name).
    pub label: String,
    /// Round trip, us.
    pub rtt_us: f64,
    /// The solve alone, us.
    pub solve_us: f64,
}

/// Most over-budget requests [`print`] names (the JSON holds all).
const OVER_BUDGET_PRINTED: usize = 20;

struct Group {
    solve: Histogram<u64>,
    rtt: Histogram<u64>,
    misses: u64,
    worst_overrun_ns: u64,
}

impl Group {
    fn new() -> Self {
        // 1 ns .. 100 s at 3 significant figures.
        let h = || {
            Histogram::<u64>::new_with_bounds(1, 100_000_000_000, 3)
                .expect("constant bounds are valid")
        };
        Self {
            solve: h(),
            rtt: h(),
            misses: 0,
            worst_overrun_ns: 0,
        }
    }
    fn record(&mut self, solve_ns: u64, rtt_ns: u64, budget_ns: u64) {
        let _ = self.solve.record(solve_ns.max(1));
        let _ = self.rtt.record(rtt_ns.max(1));
        if rtt_ns > budget_ns {
            self.misses += 1;
            self.worst_overrun_ns = self.worst_overrun_ns.max(rtt_ns - budget_ns);
        }
    }
    fn row(&self, planner: &str, size: &str) -> Row {
        let us = |v: u64| v as f64 / 1000.0;
        Row {
            planner: planner.into(),
            size: size.into(),
            count: self.rtt.len(),
            solve_p50_us: us(self.solve.value_at_quantile(0.5)),
            solve_p99_us: us(self.solve.value_at_quantile(0.99)),
            solve_max_us: us(self.solve.max()),
            rtt_p50_us: us(self.rtt.value_at_quantile(0.5)),
            rtt_p99_us: us(self.rtt.value_at_quantile(0.99)),
            rtt_max_us: us(self.rtt.max()),
            deadline_misses: self.misses,
            worst_overrun_us: us(self.worst_overrun_ns),
        }
    }
}

fn planner_name(item: &Item) -> String {
    item.planner.map_or("faults", |p| p.name()).into()
}

/// Build the report of a run.
pub fn build(
    title: &str,
    items: &[Item],
    run: &FeedRun,
    budget: Duration,
    window: Option<usize>,
) -> Report {
    let budget_ns = budget.as_nanos() as u64;
    let mut by_size: BTreeMap<(String, String), Group> = BTreeMap::new();
    let mut by_planner: BTreeMap<String, Group> = BTreeMap::new();
    let mut over_budget = Vec::new();
    for record in &run.records {
        let Fate::Answered {
            rtt_ns, solve_ns, ..
        } = record.fate
        else {
            continue;
        };
        let item = &items[record.index];
        if rtt_ns > budget_ns {
            over_budget.push(OverBudget {
                label: item.label.clone(),
                rtt_us: rtt_ns as f64 / 1e3,
                solve_us: solve_ns as f64 / 1e3,
            });
        }
        let planner = planner_name(item);
        by_size
            .entry((planner.clone(), item.size.clone()))
            .or_insert_with(Group::new)
            .record(solve_ns, rtt_ns, budget_ns);
        by_planner
            .entry(planner)
            .or_insert_with(Group::new)
            .record(solve_ns, rtt_ns, budget_ns);
    }
    let mut rows = Vec::new();
    for (planner, total) in &by_planner {
        for ((p, size), g) in &by_size {
            if p == planner {
                rows.push(g.row(p, size));
            }
        }
        rows.push(total.row(planner, "all"));
    }
    let throughput = window.map(|window| {
        let seconds = run.elapsed.as_secs_f64();
        Throughput {
            requests: run.counters.answered,
            seconds,
            per_second: run.counters.answered as f64 / seconds.max(1e-9),
            window,
        }
    });
    Report {
        title: title.into(),
        budget_ms: budget.as_secs_f64() * 1e3,
        rows,
        throughput,
        counters: run.counters.clone(),
        over_budget,
    }
}

/// The report's rows as a markdown table (µs), for a record of `docs/` (see
/// [`crate::table_record`]).
pub fn table(report: &Report) -> crate::table_record::Table {
    let mut t = crate::table_record::Table::new(
        &[
            "planner",
            "size",
            "count",
            "solve p50",
            "p99",
            "max",
            "rtt p50",
            "p99",
            "max",
            "misses (worst overrun)",
        ],
        "llrrrrrrrl",
    );
    for r in &report.rows {
        t.push(vec![
            r.planner.clone(),
            r.size.clone(),
            r.count.to_string(),
            format!("{:.1}", r.solve_p50_us),
            format!("{:.1}", r.solve_p99_us),
            format!("{:.1}", r.solve_max_us),
            format!("{:.1}", r.rtt_p50_us),
            format!("{:.1}", r.rtt_p99_us),
            format!("{:.1}", r.rtt_max_us),
            format!("{} ({:.1})", r.deadline_misses, r.worst_overrun_us),
        ]);
    }
    t
}

/// Print a report as a table.
pub fn print(report: &Report) {
    println!(
        "\n== timing: {} (budget {} ms; times in us)",
        report.title, report.budget_ms
    );
    print!("{}", table(report).markdown());
    if let Some(t) = &report.throughput {
        println!(
            "throughput: {} requests in {:.3} s = {:.0} requests/s with {} in flight",
            t.requests, t.seconds, t.per_second, t.window
        );
    }
    if !report.over_budget.is_empty() {
        println!(
            "over the {} ms budget ({} requests):",
            report.budget_ms,
            report.over_budget.len()
        );
        for o in report.over_budget.iter().take(OVER_BUDGET_PRINTED) {
            println!(
                "    {}: rtt {:.1} ms (solve {:.1} ms)",
                o.label,
                o.rtt_us / 1e3,
                o.solve_us / 1e3
            );
        }
        if report.over_budget.len() > OVER_BUDGET_PRINTED {
            println!(
                "    ... and {} more (all in the JSON report)",
                report.over_budget.len() - OVER_BUDGET_PRINTED
            );
        }
    }
    let c = &report.counters;
    println!(
        "sent {} answered {} lost {} late {} duplicated {} malformed {} not-sent {} undelivered {}",
        c.sent, c.answered, c.lost, c.late, c.duplicated, c.malformed, c.not_sent, c.undelivered
    );
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::harness::feeder::{Counters, Payload, Record};

    #[test]
    fn requests_over_the_budget_are_named() {
        let item = |label: &str| Item {
            label: label.into(),
            planner: None,
            size: "x".into(),
            payload: Payload::Raw(Vec::new()),
        };
        let items = [item("fast"), item("slow"), item("lost")];
        let answered = |index: usize, ms: u64| Record {
            index,
            seq: index as u64,
            frame: Vec::new(),
            fate: Fate::Answered {
                rtt_ns: ms * 1_000_000,
                solve_ns: ms * 900_000,
                body: Vec::new(),
                order: Default::default(),
            },
        };
        let run = FeedRun {
            records: vec![
                answered(0, 5),
                answered(1, 150),
                Record {
                    index: 2,
                    seq: 2,
                    frame: Vec::new(),
                    fate: Fate::Lost,
                },
            ],
            counters: Counters::default(),
            elapsed: Duration::from_secs(1),
        };
        let r = build("t", &items, &run, Duration::from_millis(100), None);
        assert_eq!(r.over_budget.len(), 1);
        assert_eq!(r.over_budget[0].label, "slow");
        assert!((r.over_budget[0].rtt_us - 150_000.0).abs() < 1e-6);
        assert!((r.over_budget[0].solve_us - 135_000.0).abs() < 1e-6);
    }
}
