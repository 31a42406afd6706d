//! Campaigns: one fixture, many dispersed cases, each answered through the core's one request
//! path (`wire::answer`, the same call as `reconfig solve` and the flight service), in parallel
//! on every core, one table row per case (issue 32).
//!
//! * [`dispersion`]: which numbers of the fixture vary and how ([`Dispersion`]);
//! * [`table`]: the rows as CSV and the campaign's summary.
//!
//! Determinism: case `k`'s numbers are drawn from its own random stream (ChaCha8, the
//! campaign's seed, stream `k`), so a case is the same file whatever thread answers it and
//! whatever the thread count; the rows are collected in case order. Only `solve_time_s`
//! differs between runs (`campaign_is_the_same_on_one_thread_and_on_every_core` in
//! `host/tests/campaign.rs`).

pub mod dispersion;
pub mod table;

use crate::drivers::answer::{answer, buffers, status_text};
use crate::fixture::{self};
use anyhow::{bail, Context, Result};
use dispersion::Dispersion;
use indicatif::{ProgressBar, ProgressStyle};
use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;
use rayon::prelude::*;
use reconfig_core::limits::Limits;
use reconfig_core::wire::{AllPlanners, OutcomeRef};

/// A campaign: the fixture's document, its dispersions, the seed and the number of cases.
#[derive(Debug, Clone)]
pub struct Campaign {
    base: toml::Value,
    dispersions: Vec<Dispersion>,
    seed: u64,
    cases: u64,
    limits: Limits,
}

/// One case's answer: a row of the table.
#[derive(Debug, Clone, PartialEq)]
pub struct Row {
    /// The case's index (its random stream).
    pub case: u64,
    /// The dispersed numbers, in the order of the dispersions.
    pub inputs: Vec<f64>,
    /// The planner's status (`Solved`, `BudgetExhausted { verified: true }`, ...), or
    /// `LimitExceeded` (refused by the limits), `Rejected` (refused by the planner or by the
    /// fixture's own checks).
    pub status: String,
    /// Whether the plan may be flown (the status's verdict); `None` when nothing was planned.
    pub usable: Option<bool>,
    /// The plan's objective (planner A: J; the others: total Δv, m/s) when it is usable.
    pub cost: Option<f64>,
    /// The work units the planner used; `None` when nothing was planned.
    pub work_units: Option<u64>,
    /// Wall time of the answer, s: the only column that differs between runs.
    pub solve_time_s: f64,
    /// Why nothing was planned (the refusal, naming the field, value and limit).
    pub message: String,
}

impl Campaign {
    /// A campaign of `cases` cases of the fixture `text` (named `name` in messages).
    ///
    /// # Errors
    /// The fixture does not parse, stands for more than one request (a LEO tour of several
    /// arcs), or a dispersion names no float of it.
    pub fn new(
        name: &str,
        text: &str,
        dispersions: Vec<Dispersion>,
        seed: u64,
        cases: u64,
        limits: Limits,
    ) -> Result<Self> {
        let fixture = fixture::parse(text).with_context(|| format!("in fixture {name}"))?;
        let requests = fixture.requests()?;
        if requests.len() != 1 {
            bail!(
                "{name} stands for {} requests; a campaign answers fixtures of one request \
                 (a LEO tour of two clients, one arc)",
                requests.len()
            );
        }
        let base: toml::Value = toml::from_str(text).with_context(|| format!("in {name}"))?;
        let campaign = Self {
            base,
            dispersions,
            seed,
            cases,
            limits,
        };
        // Every path checked once, before any case runs: it names a number, and the fixture
        // still reads with that number in float form (a field of integers, such as an
        // impulse's `revolutions`, is refused here, named, not in every row).
        campaign.case_document(0)?;
        for d in &campaign.dispersions {
            let mut doc = campaign.base.clone();
            d.path.as_float(&mut doc)?;
            fixture::from_value(doc)
                .with_context(|| format!("path `{}` cannot be dispersed", d.path))?;
        }
        Ok(campaign)
    }

    /// The dispersions.
    pub fn dispersions(&self) -> &[Dispersion] {
        &self.dispersions
    }

    /// Number of cases.
    pub const fn cases(&self) -> u64 {
        self.cases
    }

    /// Case `case`'s document and its dispersed numbers.
    ///
    /// # Errors
    /// A dispersion names no float of the fixture.
    pub fn case_document(&self, case: u64) -> Result<(toml::Value, Vec<f64>)> {
        let mut rng = ChaCha8Rng::seed_from_u64(self.seed);
        rng.set_stream(case);
        let mut doc = self.base.clone();
        let inputs = self
            .dispersions
            .iter()
            .map(|d| d.apply(&mut doc, &mut rng))
            .collect::<Result<Vec<f64>>>()?;
        Ok((doc, inputs))
    }

    /// Case `case` as fixture text: `reconfig solve` on it gives the case's row.
    ///
    /// # Errors
    /// As [`Self::case_document`].
    pub fn case_text(&self, case: u64) -> Result<String> {
        Ok(toml::to_string(&self.case_document(case)?.0)?)
    }

    /// Answer case `case` with `buffers`.
    pub fn answer_case(&self, case: u64, buffers: &mut AllPlanners) -> Row {
        self.answer(case, buffers, false).0
    }

    /// Answer case `case` with `buffers`: its row and the JSON object `reconfig solve --json`
    /// prints for it (`None` when the case's fixture was refused before its request was
    /// made: the row says why; an error for an answer no request of a fixture can have).
    pub fn answer_case_json(
        &self,
        case: u64,
        buffers: &mut AllPlanners,
    ) -> (Row, Option<Result<serde_json::Value>>) {
        self.answer(case, buffers, true)
    }

    /// Answer case `case`; its JSON object too when `json`.
    fn answer(
        &self,
        case: u64,
        buffers: &mut AllPlanners,
        json: bool,
    ) -> (Row, Option<Result<serde_json::Value>>) {
        // A dispersion that does not apply was refused when the campaign was made.
        let (doc, inputs) = match self.case_document(case) {
            Ok(d) => d,
            Err(e) => return (refused_row(case, &e), None),
        };
        let (mut row, report) = match fixture::from_value(doc) {
            Ok(fixture) => answer_fixture(&fixture, &self.limits, buffers, json),
            // The fixture's own checks refused the dispersed file (an eccentricity below 0,
            // say): a row that says so, named, and the campaign goes on.
            Err(e) => (refused_row(case, &e), None),
        };
        // Every row carries its case's numbers, a refused one too (the table stays square).
        row.case = case;
        row.inputs = inputs;
        (row, report)
    }

    /// Answer every case on `threads` threads (0: one per core), in case order.
    ///
    /// # Errors
    /// The thread pool cannot start.
    pub fn run(&self, threads: usize, progress: &ProgressBar) -> Result<Vec<Row>> {
        self.run_range(0, self.cases, threads, progress)
    }

    /// Answer cases `first .. first + count` on `threads` threads (0: one per core), in case
    /// order: a part of the campaign (a cluster's partition), the same rows as those of
    /// [`Self::run`].
    ///
    /// # Errors
    /// The range is not within the campaign's cases (named), or the thread pool cannot start.
    pub fn run_range(
        &self,
        first: u64,
        count: u64,
        threads: usize,
        progress: &ProgressBar,
    ) -> Result<Vec<Row>> {
        let end = first
            .checked_add(count)
            .filter(|&end| end <= self.cases)
            .with_context(|| {
                format!(
                    "cases {first} + {count} are not within the campaign's {} cases",
                    self.cases
                )
            })?;
        // The flight service's workers' stack: a solve's values pass through the stack on
        // their way into the boxed buffers (rayon's default 2 MB overflowed in the tests).
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .stack_size(crate::harness::worker::WORKER_STACK_BYTES)
            .build()
            .context("cannot start the campaign's threads")?;
        Ok(pool.install(|| {
            (first..end)
                .into_par_iter()
                .map_init(buffers, |b, case| {
                    let row = self.answer_case(case, b);
                    progress.inc(1);
                    row
                })
                .collect()
        }))
    }
}

/// A row of a case whose fixture was refused before its request was made.
fn refused_row(case: u64, e: &anyhow::Error) -> Row {
    Row {
        case,
        inputs: Vec::new(),
        status: "Rejected".into(),
        usable: None,
        cost: None,
        work_units: None,
        solve_time_s: 0.0,
        message: format!("{e:#}"),
    }
}

/// Answer a fixture of one request with `buffers` under `limits`: its row (case 0, no
/// dispersed numbers) and, when `json`, the JSON object `reconfig solve --json` prints for it
/// (an error for an answer no request of a fixture can have). A fixture of several requests
/// (a LEO tour of several arcs) is a `Rejected` row, named. What every case of a campaign
/// runs, and a front end's single solve (the Python package's).
pub fn answer_fixture(
    fixture: &fixture::Fixture,
    limits: &Limits,
    buffers: &mut AllPlanners,
    json: bool,
) -> (Row, Option<Result<serde_json::Value>>) {
    let request = fixture
        .requests()
        .and_then(|mut requests| match requests.pop() {
            Some(r) if requests.is_empty() => Ok(r.request),
            _ => bail!(
                "{} stands for {} requests, not one",
                fixture.name(),
                requests.len() + 1
            ),
        });
    let request = match request {
        Ok(r) => r,
        Err(e) => return (refused_row(0, &e), None),
    };
    let answered = answer(&request, limits, buffers);
    let outcome = answered.outcome;
    let mut row = Row {
        case: 0,
        inputs: Vec::new(),
        status: String::new(),
        usable: outcome.usable(),
        cost: None,
        work_units: outcome.work_units(),
        solve_time_s: answered.time_s,
        message: String::new(),
    };
    match &outcome {
        OutcomeRef::LimitExceeded(v) => {
            row.status = "LimitExceeded".into();
            row.message = v.to_string();
        }
        _ => {
            if let Some(e) = outcome.rejection() {
                row.status = "Rejected".into();
                row.message = e.to_string();
            } else {
                row.status =
                    status_text(&outcome).unwrap_or_else(|| format!("Unexpected {outcome:?}"));
                if row.usable == Some(true) {
                    row.cost = cost(&outcome);
                }
            }
        }
    }
    let report = json.then(|| crate::drivers::json::of(fixture, &answered));
    (row, report)
}

/// A progress bar of `cases` cases on standard error (hidden unless `shown`), the one the CLI
/// and the Python package show.
pub fn progress_bar(cases: u64, shown: bool) -> ProgressBar {
    if !shown {
        return ProgressBar::hidden();
    }
    let bar = ProgressBar::new(cases);
    if let Ok(style) =
        ProgressStyle::with_template("{bar:40} {pos}/{len} cases {elapsed_precise} ({per_sec})")
    {
        bar.set_style(style);
    }
    bar
}

/// The plan's objective: planner A's J, the hybrid transfer's propellant fraction `1 − m_f`
/// (minimum time: t_f in days), the others' total Δv (m/s).
fn cost(outcome: &OutcomeRef) -> Option<f64> {
    match outcome {
        OutcomeRef::Pseudospectral(s) => Some(s.cost),
        OutcomeRef::Impulsive(s) | OutcomeRef::ImpulsiveForm { solution: s, .. } => {
            Some(s.total_dv_mps)
        }
        OutcomeRef::GeoTour(s) => Some(s.total_dv_mps),
        OutcomeRef::LeoArc(s) => Some(s.total_dv_mps),
        OutcomeRef::LeoSequence(q) => q.total_dv_mps,
        OutcomeRef::Hybrid(s) => match s.objective {
            reconfig_core::hybrid::Objective::MinTime => {
                Some(reconfig_core::hybrid::units::days(s.duration_tu))
            }
            _ => s.flown.map(|f| 1.0 - f.final_mass),
        },
        _ => None,
    }
}
