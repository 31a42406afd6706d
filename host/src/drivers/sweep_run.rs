//! One sweep of planner A over named generated problems (`reconfig sweep`, and the test that
//! holds the docs' family tables): every problem solved, its outcome tallied per family or
//! kind and in all, and, where the oracle solved the very same problem, kept for the oracle
//! table (cost gap, rates, and with times IPOPT's against ours).

use super::pseudospectral::{solve_timed_with_starts, Timed};
use super::sweep_oracle::{percentile, relative_gap, OracleAnswer, GAP_REPORT_REL};
use super::sweep_report::Tally;
use crate::families::Named;
use anyhow::Result;
use rayon::prelude::*;
use reconfig_core::pseudospectral::{AlternativeStarts, Problem, Settings, SolveStatus};
use std::collections::BTreeMap;

/// The oracle's answers by problem index, and the stored problems they belong to.
pub type OracleData = (BTreeMap<usize, OracleAnswer>, Vec<(String, Problem)>);

/// One generated problem's outcome, for the oracle table.
#[derive(Clone, Debug)]
pub struct Outcome {
    /// Its family or kind.
    pub family: &'static str,
    /// Oracle's best cost when the problem is the stored one and the oracle solved it.
    pub oracle: Option<f64>,
    /// IPOPT's time for one solve, ms.
    pub ipopt_ms: Option<f64>,
    /// `Some(status)` when the planner accepted the problem.
    pub status: Option<SolveStatus>,
    /// Our cost (NaN when rejected).
    pub cost: f64,
    /// Our solve time, ms (NaN when rejected).
    pub time_ms: f64,
}

/// What a sweep measured.
#[derive(Debug, Default)]
pub struct Swept {
    /// Per family or kind.
    pub tallies: BTreeMap<&'static str, Tally>,
    /// Over every problem.
    pub all: Tally,
    /// Per problem, in order.
    pub outcomes: Vec<Outcome>,
}

/// Problems solved side by side before their answers are tallied in order: bounds the
/// answers held at once (each a boxed planner-A solution).
const CHUNK: usize = 64;

/// Solve every problem, on `threads` threads (0: one per core); `each` sees each one's index,
/// family, problem and answer (for the answer file and progress), in the problems' order,
/// before it is tallied. Each solve has its own workspace, so the answers (all but their
/// times) are the same whatever the thread count.
///
/// # Errors
/// What `each` returns, or the threads cannot start.
pub fn sweep(
    problems: &[Named],
    oracle: Option<&OracleData>,
    settings: &Settings,
    starts: Option<AlternativeStarts>,
    threads: usize,
    mut each: impl FnMut(usize, &'static str, &Problem, &Result<(Timed, u8)>) -> Result<()>,
) -> Result<Swept> {
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .stack_size(crate::harness::worker::WORKER_STACK_BYTES)
        .build()?;
    let mut swept = Swept::default();
    let mut answers = Vec::with_capacity(CHUNK);
    for (this, (family, p)) in problems.iter().enumerate() {
        if this % CHUNK == 0 {
            let chunk = problems.get(this..).unwrap_or_default();
            answers = pool.install(|| {
                chunk
                    .par_iter()
                    .take(CHUNK)
                    .map(|(_, q)| Some(solve_timed_with_starts(q, settings, starts)))
                    .collect::<Vec<_>>()
            });
        }
        let Some(answer) = answers.get_mut(this % CHUNK).and_then(Option::take) else {
            anyhow::bail!("sweep: no answer for problem {this}");
        };
        let family: &'static str = family;
        // The oracle's answer counts only for the very problem it solved.
        let stored = oracle.and_then(|(golden, stored)| {
            let same = stored
                .get(this)
                .is_some_and(|(f, q)| f == family && super::sweep_oracle::same_problem(q, p));
            if same {
                golden.get(&this)
            } else {
                None
            }
        });
        let mut outcome = Outcome {
            family,
            oracle: stored.and_then(|a| a.cost),
            ipopt_ms: stored.and_then(|a| a.ipopt_time_ms),
            status: None,
            cost: f64::NAN,
            time_ms: f64::NAN,
        };
        each(this, family, p, &answer)?;
        let tally = swept.tallies.entry(family).or_default();
        match answer {
            Ok((timed, kept)) => {
                let s = &timed.solution;
                tally.answered(s, timed.solve_time_s, kept > 0);
                swept.all.answered(s, timed.solve_time_s, kept > 0);
                outcome.status = Some(s.info.status);
                outcome.cost = s.cost;
                outcome.time_ms = timed.solve_time_s * 1e3;
            }
            Err(e) => {
                let message = e.to_string();
                tally.rejected(&message);
                swept.all.rejected(&message);
            }
        }
        swept.outcomes.push(outcome);
    }
    Ok(swept)
}

fn pct(part: usize, whole: usize) -> String {
    if whole == 0 {
        "-".to_string()
    } else {
        format!("{:.1} %", 100.0 * part as f64 / whole as f64)
    }
}

/// The oracle table: per row (family) and in all, over the problems the oracle solves; with
/// `with_times`, our solve times and IPOPT's against them.
pub fn oracle_table(outcomes: &[Outcome], rows: &[&str], with_times: bool) -> String {
    let mut md = String::from(
        "| family | oracle solves | Solved | usable (`is_usable()`) | gap median | gap p95 | gap worst | Solved > 0.5 % above |",
    );
    md.push_str(if with_times {
        " ours ms median / worst | IPOPT ms median | IPOPT / ours (medians) |\n| --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- |\n"
    } else {
        "\n| --- | --- | --- | --- | --- | --- | --- | --- |\n"
    });
    for family in rows.iter().copied().chain(["all"]) {
        let set: Vec<&Outcome> = outcomes
            .iter()
            .filter(|o| o.oracle.is_some() && (family == "all" || o.family == family))
            .collect();
        let solved = set
            .iter()
            .filter(|o| o.status == Some(SolveStatus::Solved))
            .count();
        let usable = set
            .iter()
            .filter(|o| o.status.is_some_and(|s| s.is_usable()))
            .count();
        let mut gaps: Vec<f64> = set
            .iter()
            .filter(|o| o.status.is_some_and(|s| s.is_usable()))
            .filter_map(|o| o.oracle.map(|j| relative_gap(o.cost, j)))
            .collect();
        gaps.sort_by(f64::total_cmp);
        let above = set
            .iter()
            .filter(|o| o.status == Some(SolveStatus::Solved))
            .filter(|o| {
                o.oracle
                    .is_some_and(|j| relative_gap(o.cost, j) > GAP_REPORT_REL)
            })
            .count();
        md.push_str(&format!(
            "| {family} | {} | {solved} ({}) | {usable} ({}) | {:.4} % | {:.4} % | {:.4} % | {above} of {solved} |",
            set.len(),
            pct(solved, set.len()),
            pct(usable, set.len()),
            100.0 * percentile(&gaps, 0.5),
            100.0 * percentile(&gaps, 0.95),
            100.0 * gaps.last().copied().unwrap_or(f64::NAN),
        ));
        if with_times {
            let mut ours: Vec<f64> = set
                .iter()
                .filter(|o| o.status.is_some())
                .map(|o| o.time_ms)
                .collect();
            ours.sort_by(f64::total_cmp);
            let mut ipopt: Vec<f64> = set.iter().filter_map(|o| o.ipopt_ms).collect();
            ipopt.sort_by(f64::total_cmp);
            let (ours_median, ipopt_median) = (percentile(&ours, 0.5), percentile(&ipopt, 0.5));
            md.push_str(&format!(
                " {:.2} / {:.2} | {:.0} | {:.0}x |",
                ours_median,
                ours.last().copied().unwrap_or(f64::NAN),
                ipopt_median,
                ipopt_median / ours_median,
            ));
        }
        md.push('\n');
    }
    md
}
