//! The LEO tour's on-board part through the flight service (issue 13): Example I's sequencing
//! request, then the arcs of the order the service answers, sent together so that every
//! worker plans one; each answer checked against a local solve. The time it reports is what
//! a flight computer with the service's cores would wait: the sequencing's round trip plus
//! the longest round trip of the arcs.

use super::feeder::{self, Fate, FeedOptions, FeedRun, Item};
use super::items::requests_items;
use super::{check, Instance};
use crate::fixture::{self, leo_tour::LeoTourFixture};
use anyhow::{anyhow, bail, Result};
use reconfig_core::limits::Limits;
use reconfig_core::wire::Outcome;
use std::path::Path;
use std::time::Duration;

/// The fixture whose on-board part is timed.
pub const FIXTURE: &str = "leo-tour-example1-sequence.toml";

/// The on-board budget for the sequencing and the arcs of Example I, ms.
pub const BUDGET_MS: f64 = 200.0;

/// What the on-board part took through the service.
#[derive(Clone, Debug)]
pub struct OnboardRun {
    /// The order the service chose, 1-based.
    pub order: Vec<usize>,
    /// The sequencing's round trip, ms.
    pub sequencing_ms: f64,
    /// The arcs' longest round trip (all sent at once), ms.
    pub arcs_ms: f64,
    /// Each arc's solve time in the service, ms.
    pub arc_solve_ms: Vec<f64>,
    /// The planned arcs' total Δv, m/s.
    pub total_dv_mps: f64,
    /// Every answer was byte-identical to a local solve.
    pub correct: bool,
}

impl OnboardRun {
    /// Sequencing plus arcs, ms.
    pub fn total_ms(&self) -> f64 {
        self.sequencing_ms + self.arcs_ms
    }
}

/// Run the on-board part of `dir`'s Example I through the service of `instance` with
/// `workers` workers, sequence numbers from `first_seq`.
///
/// # Errors
/// The fixture does not load, the service is not there, or an answer is not the expected kind.
pub fn run(
    instance: &Instance,
    dir: &Path,
    workers: usize,
    first_seq: u64,
    limits: &Limits,
) -> Result<OnboardRun> {
    let f: LeoTourFixture = fixture::load_as(&dir.join(FIXTURE))?;
    let mut opts = FeedOptions::new(instance.clone());
    opts.timeout = Duration::from_secs(10);
    opts.first_seq = first_seq;
    // The sequencing request of the `[sequence]` fixture.
    let mut sequencing: Vec<Item> = requests_items(f.requests()?).collect();
    for item in &mut sequencing {
        item.label.push_str(" (on-board part)");
    }
    let seq_run = feeder::run(&sequencing, &opts)?;
    let (seq_rtt_ms, body) = answered(&seq_run, 0)?;
    let Ok(Outcome::LeoSequence(q)) = postcard::from_bytes::<Outcome>(body) else {
        bail!("the sequencing was not answered with an order");
    };
    let arcs: Vec<Item> = requests_items(f.with_order(&q).requests()?).collect();
    opts.window = arcs.len().max(workers);
    opts.first_seq = first_seq.saturating_add(1);
    let arc_run = feeder::run(&arcs, &opts)?;
    let mut arcs_ms: f64 = 0.0;
    let mut arc_solve_ms = Vec::new();
    let mut total_dv_mps = 0.0;
    for k in 0..arcs.len() {
        let (rtt_ms, body) = answered(&arc_run, k)?;
        arcs_ms = arcs_ms.max(rtt_ms);
        let Ok(Outcome::LeoArc(sol)) = postcard::from_bytes::<Outcome>(body) else {
            bail!("arc {} was not answered with a plan", k + 1);
        };
        total_dv_mps += sol.total_dv_mps;
        if let Some(Fate::Answered { solve_ns, .. }) = arc_run.records.get(k).map(|r| &r.fate) {
            arc_solve_ms.push(*solve_ns as f64 / 1e6);
        }
    }
    let correct =
        all_correct(&sequencing, &seq_run, limits) && all_correct(&arcs, &arc_run, limits);
    Ok(OnboardRun {
        order: q
            .order
            .iter()
            .take(usize::from(q.len))
            .map(|&k| usize::from(k) + 1)
            .collect(),
        sequencing_ms: seq_rtt_ms,
        arcs_ms,
        arc_solve_ms,
        total_dv_mps,
        correct,
    })
}

/// Item `k`'s round trip (ms) and answer body.
fn answered(run: &FeedRun, k: usize) -> Result<(f64, &[u8])> {
    match run.records.get(k).map(|r| &r.fate) {
        Some(Fate::Answered { rtt_ns, body, .. }) => Ok((*rtt_ns as f64 / 1e6, body.as_slice())),
        Some(other) => Err(anyhow!("request {} not answered: {other:?}", k + 1)),
        None => Err(anyhow!("request {} has no record", k + 1)),
    }
}

fn all_correct(items: &[Item], run: &FeedRun, limits: &Limits) -> bool {
    let expected = check::expected(run, limits);
    check::verify(items, run, &expected)
        .iter()
        .all(|v| v.correct)
}

/// Print the run: the order, the two times, the total against [`BUDGET_MS`].
pub fn print(r: &OnboardRun, workers: usize) {
    let solves: Vec<String> = r.arc_solve_ms.iter().map(|t| format!("{t:.0}")).collect();
    println!(
        "LEO on-board part (Example I, {workers} workers): order {:?} in {:.0} ms, its {} arcs \
         ({:.3} m/s) in {:.0} ms (sent together; solves {} ms): {:.0} ms against {:.0} ms, {}; \
         answers {}",
        r.order,
        r.sequencing_ms,
        r.arc_solve_ms.len(),
        r.total_dv_mps,
        r.arcs_ms,
        solves.join(" / "),
        r.total_ms(),
        BUDGET_MS,
        if r.total_ms() <= BUDGET_MS {
            "met"
        } else {
            "NOT met"
        },
        if r.correct { "correct" } else { "NOT correct" },
    );
}
