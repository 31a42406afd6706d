//! The planner-A sweep's reports (`reconfig sweep`): one table row per family or kind (the
//! statuses, the usable answers for the kinds' sets, the refusals by class, the largest QP working set, the saddle escapes, the answers
//! from an alternative start, the cost and the solve time, median and worst), and one JSON
//! line per answer for `--write-answers` (the oracle restarts from its node positions).

use super::set_record::Counts;
use super::sweep_oracle::percentile;
use reconfig_core::pseudospectral::{Problem, Solution, SolveStatus};
use std::collections::BTreeMap;

/// The table's two header lines; `first` names the row's column (`family` or `kind`), and
/// `usable` adds the column of usable answers (`SolveStatus::is_usable()`, the kinds' sets: the
/// families' table stays as it was); `with_times` adds the solve time's column (not in the
/// docs' tables, which a test holds to the code: a time is not deterministic).
pub fn table_header(first: &str, usable: bool, with_times: bool) -> String {
    let (usable, rule) = if usable {
        (" usable (`is_usable()`) |", " --- |")
    } else {
        ("", "")
    };
    let (times, times_rule) = if with_times {
        (" ms median / worst |", " --- |")
    } else {
        ("", "")
    };
    format!(
        "| {first} | problems | Solved | Feasible |{usable} other (status: count) | rejected | largest working set | saddle escapes (helped) | answers from an alternative start | J median / worst |{times}\n\
         | --- | --- | --- | --- |{rule} --- | --- | --- | --- | --- | --- |{times_rule}"
    )
}

/// One row's tally: what became of each problem of a family or kind.
#[derive(Debug, Default)]
pub struct Tally {
    /// The statuses (the part a set's record keeps: `set_record`).
    counts: Counts,
    reasons: BTreeMap<String, usize>,
    times_ms: Vec<f64>,
    costs: Vec<f64>,
    working: u16,
    escapes: usize,
    helped: usize,
    from_alternative: usize,
}

impl Tally {
    /// A problem the planner rejected, with the core's message (its class is named from it).
    pub fn rejected(&mut self, message: &str) {
        self.counts.add(None);
        let class = if message.contains("cannot meet its boundary conditions") {
            "ManoeuvreInfeasible"
        } else if message.contains("closer than") {
            "BoundaryTooClose"
        } else {
            "other"
        };
        *self.reasons.entry(class.to_string()).or_default() += 1;
    }

    /// An answered problem: its solution, the solve time and whether the answer came from an
    /// alternative start.
    pub fn answered(&mut self, s: &Solution, time_s: f64, from_alternative: bool) {
        self.counts.add(Some(s.info.status));
        if from_alternative {
            self.from_alternative += 1;
        }
        self.times_ms.push(time_s * 1e3);
        self.working = self.working.max(s.info.max_active);
        if s.info.saddle_escapes > 0 {
            self.escapes += 1;
            if s.info.status == SolveStatus::Solved {
                self.helped += 1;
            }
        }
        if matches!(s.info.status, SolveStatus::Solved | SolveStatus::Feasible) {
            self.costs.push(s.cost);
        }
    }

    /// The statuses counted so far.
    pub fn counts(&self) -> &Counts {
        &self.counts
    }

    /// The table row of `name`, with the column of usable answers when `usable` and the
    /// solve times when `with_times` (as [`table_header`]).
    pub fn row(&self, name: &str, usable: bool, with_times: bool) -> String {
        let mut times = self.times_ms.clone();
        let mut costs = self.costs.clone();
        times.sort_by(f64::total_cmp);
        costs.sort_by(f64::total_cmp);
        let listed = |map: &BTreeMap<String, usize>| -> Vec<String> {
            map.iter().map(|(k, v)| format!("{k}: {v}")).collect()
        };
        let (others, reasons) = (listed(&self.counts.other), listed(&self.reasons));
        let usable = if usable {
            format!(" {} |", self.counts.usable)
        } else {
            String::new()
        };
        let times = if with_times {
            format!(
                " {:.2} / {:.2} |",
                percentile(&times, 0.5),
                times.last().copied().unwrap_or(f64::NAN)
            )
        } else {
            String::new()
        };
        format!(
            "| {name} | {} | {} | {} |{usable} {} | {}{} | {} | {} ({}) | {} | {:.4} / {:.4} |{times}",
            self.counts.problems,
            self.counts.solved,
            self.counts.feasible,
            if others.is_empty() { "-".to_string() } else { others.join(", ") },
            self.counts.rejected,
            if reasons.is_empty() { String::new() } else { format!(" ({})", reasons.join(", ")) },
            self.working,
            self.escapes,
            self.helped,
            self.from_alternative,
            percentile(&costs, 0.5),
            costs.last().copied().unwrap_or(f64::NAN),
        )
    }
}

/// The answer line of a rejected problem.
pub fn rejection_json(index: usize, family: &str, message: &str) -> serde_json::Value {
    serde_json::json!({ "index": index, "family": family, "status": "Rejected", "error": message })
}

/// One answer as JSON: status, cost, time, the iteration counters and certificate measures, and
/// the node positions of every spacecraft.
pub fn answer_json(
    index: usize,
    family: &str,
    p: &Problem,
    s: &Solution,
    time_s: f64,
) -> serde_json::Value {
    let nodes = usize::from(s.degree) + 1;
    let positions: Vec<Vec<[f64; 3]>> = s
        .states
        .iter()
        .take(p.spacecraft.len())
        .map(|craft| {
            craft
                .iter()
                .take(nodes)
                .map(|x| [x[0], x[1], x[2]])
                .collect()
        })
        .collect();
    serde_json::json!({
        "index": index,
        "family": family,
        "status": format!("{:?}", s.info.status),
        "cost": s.cost,
        "min_separation_lu": s.min_separation_lu,
        "time_ms": time_s * 1e3,
        // Why an answer is not Solved (the diagnosis of issue 9): the iteration's counters and
        // the certificate's measures.
        "sqp_iterations": s.info.sqp_iterations,
        "max_active": s.info.max_active,
        "verify_rounds": s.info.verify_rounds,
        "saddle_escapes": s.info.saddle_escapes,
        "work_units": s.info.work_units,
        "stationarity": s.certificate.stationarity,
        "complementarity": s.certificate.complementarity,
        "min_reduced_eigenvalue": s.certificate.min_reduced_eigenvalue,
        "max_violation": s.certificate.max_violation,
        "first_order_evaluated": s.certificate.first_order_evaluated,
        "second_order_evaluated": s.certificate.second_order_evaluated,
        "flat_direction_probed": s.certificate.flat_direction_probed,
        "symmetry_directions": s.certificate.symmetry_directions,
        "nodes": positions,
    })
}
