//! `reconfig solve FILE [--json]`: solve one fixture of either planner and report.

use crate::fixture::{self, Fixture};
use anyhow::Result;
use std::path::PathBuf;
use std::process::ExitCode;

/// Arguments of `reconfig solve`.
#[derive(clap::Args, Debug)]
pub struct Args {
    /// Fixture file (TOML).
    pub file: PathBuf,
    /// Print one JSON object instead of the readable report.
    #[arg(long)]
    pub json: bool,
}

/// Run `reconfig solve`.
pub fn run(args: &Args) -> Result<ExitCode> {
    match fixture::load(&args.file)? {
        Fixture::Pseudospectral(f) => crate::cli::solve_pseudospectral::run(&f, args.json),
        Fixture::Impulsive(f) => crate::cli::solve_impulsive::run(&f, args.json),
    }
}
