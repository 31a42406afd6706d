//! `reconfig sweep`: planner A over seeded generated problems, one table row per family or kind.
//!
//! `--set families` (the default): the six families of issue 9 (`families::six`), on which
//! planner A's settings were tuned: `random` (2-8 spacecraft, random ends in a 20 LU box),
//! `symmetric` (2-8 spacecraft on a circle, each to the antipode, so all meet at the centre),
//! `tight` (random, with Umax 1.15 times the least that reaches every axis rest to rest),
//! `fly-through` (two files of spacecraft passing through each other with initial velocity),
//! `dense` (8 spacecraft on a 2.4 LU lattice, permuted), `mixed` (random with masses 0.5-2,
//! degrees 8-24), `--per-family` each.
//!
//! `--set tuning` and `--set held-out` (issue 28): `--count` problems (default 2000) of the 22
//! kinds of `families::kinds`, every kind in both sets, the sets disjoint (`families::sets`):
//! the held-out set measures planner A on problems its settings were never tuned on.
//!
//! The generators are seeded (ChaCha8; `--seed`), so the same arguments give the same
//! problems; `--write` stores them as JSON (one `{family, problem}` per line, `family` the
//! family's or the kind's name) for other tools such as the oracle, and `--write-answers` our
//! answers.
//!
//! Per family or kind the table gives the statuses, the largest QP working set, the saddle
//! escapes and the solve time (median, worst; `drivers::sweep_report`); for the kinds' sets
//! also the usable answers (`is_usable()`), and a row of all. For the families, when
//! the oracle's golden file is found (`--golden`, default
//! `fixtures/golden/planner-a-oracle.jsonl`) and the generated problems are the checked-in ones
//! (`fixtures/generated/planner-a-families.jsonl`, compared problem by problem), a second table
//! gives per family the cost gap to the oracle's best, the Solved / usable rates of the problems
//! the oracle solves and the time against IPOPT's (`sweep_oracle.rs`).

use crate::drivers::set_record::SetRecord;
use crate::drivers::sweep_oracle;
use crate::drivers::sweep_report::{answer_json, rejection_json, table_header, Tally};
use crate::drivers::sweep_run::{oracle_table, sweep, OracleData};
use crate::families::sets::{self, Set};
use crate::families::{kinds, six, Named};
use anyhow::{bail, Context, Result};
use reconfig_core::pseudospectral::{AlternativeStarts, Settings};
use std::io::Write;
use std::path::PathBuf;
use std::process::ExitCode;

/// Which generated problems `reconfig sweep` runs.
#[derive(clap::ValueEnum, Clone, Copy, Debug, PartialEq, Eq)]
pub enum SweepSet {
    /// The six families of issue 9 (`--per-family` each), planner A's tuning families.
    Families,
    /// The tuning set of the 22 kinds (`--count` problems).
    Tuning,
    /// The held-out set of the 22 kinds (`--count` problems), disjoint from the tuning set.
    HeldOut,
}

impl SweepSet {
    /// The seeded set of kinds, `None` for the families.
    fn kinds(self) -> Option<Set> {
        match self {
            SweepSet::Families => None,
            SweepSet::Tuning => Some(Set::Tuning),
            SweepSet::HeldOut => Some(Set::HeldOut),
        }
    }
}

/// Problems in a tuning or held-out set when `--count` is not given.
pub const DEFAULT_COUNT: usize = 2000;

/// Arguments of `reconfig sweep`.
#[derive(clap::Args, Debug)]
pub struct Args {
    /// Which problems: the six families, or the tuning or held-out set of the kinds.
    #[arg(long, value_enum, default_value_t = SweepSet::Families)]
    pub set: SweepSet,
    /// Problems per family (`--set families`).
    #[arg(long, default_value_t = 42)]
    pub per_family: usize,
    /// Problems in the set (`--set tuning` or `held-out`; default 2000).
    #[arg(long)]
    pub count: Option<usize>,
    /// Random seed (for the kinds' sets it shifts the set's base seed).
    #[arg(long, default_value_t = 9)]
    pub seed: u64,
    /// Also write the generated problems here (JSON, one `{family, problem}` per line).
    #[arg(long)]
    pub write: Option<PathBuf>,
    /// Also write our answers here (JSON, one `{index, family, status, cost, time_ms, nodes}` per
    /// line; `nodes` = node positions per spacecraft, for the oracle's restart from ours).
    #[arg(long)]
    pub write_answers: Option<PathBuf>,
    /// The oracle's golden answers (`tests/oracle/planner_a_ipopt.py`); the default path is used
    /// when it exists.
    #[arg(long, default_value = sweep_oracle::GOLDEN_DEFAULT)]
    pub golden: PathBuf,
    /// The problems the golden answers belong to (`reconfig sweep --write`); a generated
    /// problem is compared with the oracle only when it equals the stored one.
    #[arg(long, default_value = sweep_oracle::PROBLEMS_DEFAULT)]
    pub problems: PathBuf,
    /// For the kinds' sets: also write the record of the statuses per kind here (TOML,
    /// deterministic; `drivers::set_record`, the file `fixtures/golden/` keeps and a test holds
    /// the code to).
    #[arg(long)]
    pub record: Option<PathBuf>,
    /// Planner A's work budget in work units (`Settings::work_budget`); default: the core's
    /// default, which bounds a solve to 400 M Cortex-M7 instructions. A larger budget measures
    /// the planner's answers without the on-board time bound.
    #[arg(long)]
    pub work_budget: Option<u64>,
    /// Alternative starts after the analytic guess's solve (0, 1 or 2): the guess lifted
    /// sideways (y, then z), the best answer kept
    /// (`pseudospectral::solve_with_alternative_starts`).
    #[arg(long, default_value_t = 0, value_parser = clap::value_parser!(u8).range(0..=2))]
    pub alternative_starts: u8,
    /// Threads solving side by side (0: one per core). The answers and the tables' counts and
    /// costs are the same whatever the number; the times are each solve's own, measured while
    /// the other threads run.
    #[arg(long, default_value_t = 0)]
    pub threads: usize,
}

/// The golden answers and stored problems, when both are there.
fn load_oracle(args: &Args) -> Option<OracleData> {
    if !args.golden.exists() || !args.problems.exists() {
        return None;
    }
    match (
        sweep_oracle::load_golden(&args.golden),
        sweep_oracle::load_problems(&args.problems),
    ) {
        (Ok(g), Ok(p)) => Some((g, p)),
        (Err(e), _) | (_, Err(e)) => {
            eprintln!("oracle comparison skipped: {e:#}");
            None
        }
    }
}

/// The problems of `args`' set, each named by its family or kind, and the table's rows.
///
/// # Errors
/// `--count` with the families.
fn problems_of(args: &Args) -> Result<(Vec<&'static str>, Vec<Named>)> {
    let Some(set) = args.set.kinds() else {
        if args.count.is_some() {
            bail!("--count is for --set tuning or held-out; the families take --per-family");
        }
        return Ok((
            six::FAMILIES.to_vec(),
            six::generate_all(args.per_family, args.seed),
        ));
    };
    let count = args.count.unwrap_or(DEFAULT_COUNT);
    Ok((kinds::names(), sets::generate_set(set, args.seed, count)))
}

fn create(path: Option<&PathBuf>) -> Result<Option<std::fs::File>> {
    path.map(|path| {
        std::fs::File::create(path).with_context(|| format!("creating {}", path.display()))
    })
    .transpose()
}

/// Run the sweep and print the tables.
///
/// # Errors
/// `--count` with the families; writing the problem or answer file.
pub fn run(args: &Args) -> Result<ExitCode> {
    let (rows, problems) = problems_of(args)?;
    let families = args.set == SweepSet::Families;
    let mut file = create(args.write.as_ref())?;
    let mut answers = create(args.write_answers.as_ref())?;
    let oracle = if families { load_oracle(args) } else { None };
    let mut settings = Settings::default();
    if let Some(budget) = args.work_budget {
        settings.work_budget = budget;
    }
    let starts = match args.alternative_starts {
        0 => None,
        1 => Some(AlternativeStarts::One),
        _ => Some(AlternativeStarts::Two),
    };
    if let Some(set) = args.set.kinds() {
        let count = problems.len();
        println!("set: {}, {count} problems, seed {}", set.name(), args.seed);
    }
    println!(
        "work budget: {} units; alternative starts: {}",
        settings.work_budget, args.alternative_starts
    );
    // The kinds' sets add the usable answers and a row of all; the families' table is as it was.
    let per_kind = !families;
    println!(
        "{}",
        table_header(if families { "family" } else { "kind" }, per_kind, true)
    );
    let set = args.set.kinds();
    if args.record.is_some() && (set.is_none() || args.alternative_starts > 0) {
        anyhow::bail!(
            "--record is for the kinds' sets (--set tuning|held-out) solved from the guess alone \
             (no --alternative-starts)"
        );
    }
    // The campaigns' progress bar (drawn only on a terminal).
    let bar = crate::campaign::progress_bar(problems.len() as u64, true);
    let swept = sweep(
        &problems,
        oracle.as_ref(),
        &settings,
        starts,
        args.threads,
        |this, family, p, answer| {
            bar.inc(1);
            if let Some(f) = file.as_mut() {
                writeln!(
                    f,
                    "{}",
                    serde_json::json!({ "family": family, "problem": p })
                )?;
            }
            if let Some(f) = answers.as_mut() {
                let line = match answer {
                    Ok((timed, _)) => {
                        answer_json(this, family, p, &timed.solution, timed.solve_time_s)
                    }
                    Err(e) => rejection_json(this, family, &e.to_string()),
                };
                writeln!(f, "{line}")?;
            }
            Ok(())
        },
    )?;
    bar.finish_and_clear();
    let (tallies, all) = (&swept.tallies, &swept.all);
    let none = Tally::default();
    for row in &rows {
        println!(
            "{}",
            tallies.get(row).unwrap_or(&none).row(row, per_kind, true)
        );
    }
    if per_kind {
        println!("{}", all.row("all", true, true));
    }
    if let (Some(path), Some(set)) = (args.record.as_ref(), set) {
        // The record is the tallies' statuses (every kind listed, as `SetRecord::measure` has).
        let mut record = SetRecord::new(set, args.seed, problems.len(), settings.work_budget);
        record.all = all.counts().clone();
        for (kind, tally) in tallies {
            record
                .kinds
                .insert((*kind).to_string(), tally.counts().clone());
        }
        std::fs::write(path, record.to_toml()?)
            .with_context(|| format!("writing {}", path.display()))?;
        println!("{}", record.summary());
    }
    if oracle.is_some() {
        println!();
        print!("{}", oracle_table(&swept.outcomes, &six::FAMILIES, true));
    } else if families {
        eprintln!(
            "no oracle comparison: {} or {} not found",
            args.golden.display(),
            args.problems.display()
        );
    }
    Ok(ExitCode::SUCCESS)
}
