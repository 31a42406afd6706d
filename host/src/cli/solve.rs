//! `reconfig solve FILE [--json] [--limits FILE]`: answer one fixture of any planner and
//! report. The fixture's requests ([`Fixture::requests`]) go through the core's one request
//! path (`wire::answer`: the limits of `--limits` or the built-in ones, the flight service's
//! check, then the planner), and the report is printed from the outcome
//! (`crate::drivers`).

use crate::drivers::answer::{answer, buffers, report_other};
use crate::drivers::{geo_tour, impulsive, leo_report, pseudospectral};
use crate::fixture::{self, Fixture};
use crate::limits::LimitsArg;
use anyhow::{bail, Result};
use std::path::PathBuf;
use std::process::ExitCode;

pub use crate::drivers::answer::{EXIT_NOT_USABLE, EXIT_REJECTED, EXIT_USABLE};

/// Arguments of `reconfig solve`.
#[derive(clap::Args, Debug)]
#[command(
    after_help = "Exit codes (every planner): 0 the plan is usable (status Solved, or one \
the planner's docs call usable such as BudgetExhausted { verified: true }; a LEO tour's arcs \
also confirmed by the truth model within 1 m after their re-plan); 1 the planner ran and the \
plan is not usable (any other status: it is still printed), or a LEO tour's truth-model check \
failed (status TruthMissed, naming the arc and the miss); \
2 the input was rejected (fixture unreadable or invalid, the planner's PlanError, or a setting \
outside the limits, which is named)."
)]
pub struct Args {
    /// Fixture file (TOML).
    pub file: PathBuf,
    /// Print one JSON object instead of the readable report.
    #[arg(long)]
    pub json: bool,
    #[command(flatten)]
    pub limits: LimitsArg,
    /// GEO tour: override the fixture's mission time, days (refused for other planners).
    #[arg(long)]
    pub mission_days: Option<f64>,
}

/// Run `reconfig solve`. Exit codes [`EXIT_USABLE`], [`EXIT_NOT_USABLE`], [`EXIT_REJECTED`]
/// (a fixture that does not load is an error, which `main` turns into 2 as well).
pub fn run(args: &Args) -> Result<ExitCode> {
    let limits = args.limits.load()?;
    let mut fixture = fixture::load(&args.file)?;
    if let Some(days) = args.mission_days {
        // Only a GEO tour has a mission time; any other fixture refuses the flag rather than
        // plan as if it had been applied.
        let Fixture::GeoTour(f) = &mut fixture else {
            bail!(
                "--mission-days applies to geo-tour fixtures; {} is a {} fixture",
                fixture.name(),
                fixture.planner()
            );
        };
        f.problem.mission_time_s = days * fixture::geo_tour::DAY_S;
    }
    // A LEO tour stands for several requests, answered in turn by its driver.
    if let Fixture::LeoTour(f) = &fixture {
        return leo_report::run(f, &limits, args.json);
    }
    let requests = fixture.requests()?;
    let [request] = &requests[..] else {
        bail!(
            "{} stands for {} requests, not one",
            fixture.name(),
            requests.len()
        );
    };
    let mut buffers = buffers();
    let answered = answer(&request.request, &limits, &mut *buffers);
    // The planner's own report; a kind without one prints its outcome as the wire carries it.
    match &fixture {
        Fixture::Pseudospectral(f) => pseudospectral::report(f, &answered, args.json),
        Fixture::Impulsive(f) => impulsive::report(f, &answered, args.json),
        Fixture::GeoTour(f) => geo_tour::report(f, &answered, args.json),
        _ => report_other(fixture.name(), &answered, args.json),
    }
}
