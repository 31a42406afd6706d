//! `reconfig solve FILE [--json]`: solve one fixture of either planner and report.

use crate::fixture::{self, Fixture};
use anyhow::Result;
use std::path::PathBuf;
use std::process::ExitCode;

/// Exit code: the plan is usable (its status is `Solved`).
pub const EXIT_USABLE: u8 = 0;
/// Exit code: the planner ran but the plan is not usable (any other status).
pub const EXIT_NOT_USABLE: u8 = 1;
/// Exit code: the input was rejected (unreadable fixture, or the planner's `PlanError`).
pub const EXIT_REJECTED: u8 = 2;

/// Arguments of `reconfig solve`.
#[derive(clap::Args, Debug)]
#[command(
    after_help = "Exit codes (both planners): 0 the plan is usable (status Solved); \
1 the planner ran and the plan is not usable (any other status: it is still printed); \
2 the input was rejected (fixture unreadable or invalid, or the planner's PlanError)."
)]
pub struct Args {
    /// Fixture file (TOML).
    pub file: PathBuf,
    /// Print one JSON object instead of the readable report.
    #[arg(long)]
    pub json: bool,
}

/// Run `reconfig solve`. Exit codes [`EXIT_USABLE`], [`EXIT_NOT_USABLE`], [`EXIT_REJECTED`]
/// (a fixture that does not load is an error, which `main` turns into 2 as well).
pub fn run(args: &Args) -> Result<ExitCode> {
    match fixture::load(&args.file)? {
        Fixture::Pseudospectral(f) => crate::cli::solve_pseudospectral::run(&f, args.json),
        Fixture::Impulsive(f) => crate::cli::solve_impulsive::run(&f, args.json),
    }
}
