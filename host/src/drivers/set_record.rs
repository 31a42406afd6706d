//! The record of a generated set's statuses (issue 28): per kind and over the set, how many
//! problems planner A ends `Solved`, usable, `Feasible`, rejected, and with each other status,
//! at one work budget. Deterministic (no timing), so a test can hold the code to it
//! (`tests/tests/planner_a_heldout.rs`) and the docs can quote it without drifting:
//! `reconfig sweep --set held-out --record FILE` writes it, `fixtures/golden/` keeps it.

use crate::families::kinds::KINDS;
use crate::families::sets::{self, Set};
use reconfig_core::pseudospectral::{self, Settings, Solution, SolveStatus, Workspace};
use serde::{Deserialize, Serialize};
use std::collections::BTreeMap;

/// What became of the problems of one kind (or of the whole set).
#[derive(Clone, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
pub struct Counts {
    pub problems: usize,
    pub solved: usize,
    pub usable: usize,
    pub feasible: usize,
    pub rejected: usize,
    /// Every other status, by its `Debug` name.
    pub other: BTreeMap<String, usize>,
}

impl Counts {
    /// Count one problem: its status, or `None` when the planner rejected it.
    pub fn add(&mut self, status: Option<SolveStatus>) {
        self.problems += 1;
        match status {
            None => self.rejected += 1,
            Some(status) => {
                if status.is_usable() {
                    self.usable += 1;
                }
                match status {
                    SolveStatus::Solved => self.solved += 1,
                    SolveStatus::Feasible => self.feasible += 1,
                    other => *self.other.entry(format!("{other:?}")).or_default() += 1,
                }
            }
        }
    }
}

/// A set's record at one work budget.
#[derive(Clone, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub struct SetRecord {
    pub set: String,
    pub seed: u64,
    pub count: usize,
    pub work_budget: u64,
    pub all: Counts,
    /// Per kind, by name.
    pub kinds: BTreeMap<String, Counts>,
}

impl SetRecord {
    /// An empty record of `set` (every kind listed, nothing counted yet).
    pub fn new(set: Set, seed: u64, count: usize, work_budget: u64) -> Self {
        Self {
            set: set.name().to_string(),
            seed,
            count,
            work_budget,
            all: Counts::default(),
            kinds: KINDS
                .iter()
                .map(|k| (k.name.to_string(), Counts::default()))
                .collect(),
        }
    }

    /// Solve every problem of the set with planner A's default settings at `work_budget`.
    pub fn measure(set: Set, seed: u64, count: usize, work_budget: u64) -> Self {
        let mut record = Self::new(set, seed, count, work_budget);
        let settings = Settings {
            work_budget,
            ..Settings::default()
        };
        let mut workspace = Box::new(Workspace::new());
        let mut solution = Box::new(Solution::new());
        for index in 0..count {
            let (kind, problem) = sets::problem(set, seed, index);
            let status = pseudospectral::solve(&problem, &settings, &mut workspace, &mut solution)
                .ok()
                .map(|()| solution.info.status);
            record.all.add(status);
            record
                .kinds
                .entry(kind.to_string())
                .or_default()
                .add(status);
        }
        record
    }

    /// The one-line summary the docs quote (`docs/planner-a.md`).
    pub fn summary(&self) -> String {
        let percent = |n: usize| 100.0 * n as f64 / self.all.problems.max(1) as f64;
        format!(
            "{} set, seed {}, {} problems, work budget {} units: {} `Solved` ({:.1} %), {} usable ({:.1} %)",
            self.set,
            self.seed,
            self.all.problems,
            self.work_budget,
            self.all.solved,
            percent(self.all.solved),
            self.all.usable,
            percent(self.all.usable),
        )
    }

    /// The record as TOML, with a header saying what wrote it.
    ///
    /// # Errors
    /// Never for these types (TOML serialisation of maps of strings and integers).
    pub fn to_toml(&self) -> anyhow::Result<String> {
        Ok(format!(
            "# Planner A's statuses on a generated set (issue 28), written by\n\
             # `reconfig sweep --set {} --count {} --seed {} --work-budget {} --record FILE`;\n\
             # tests/tests/planner_a_heldout.rs holds the code to it.\n{}",
            self.set,
            self.count,
            self.seed,
            self.work_budget,
            toml::to_string(self)?
        ))
    }
}
