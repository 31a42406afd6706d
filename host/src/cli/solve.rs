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
    /// GEO tour: override the fixture's mission time, days.
    #[arg(long)]
    pub mission_days: Option<f64>,
}

/// Run `reconfig solve`.
pub fn run(args: &Args) -> Result<ExitCode> {
    let text = std::fs::read_to_string(&args.file).unwrap_or_default();
    if fixture::geo_tour::is_geo_tour(&text) {
        let f = fixture::geo_tour::load(&args.file)?;
        return crate::cli::solve_geo_tour::run(&f, args.json, args.mission_days);
    }
    match fixture::load(&args.file)? {
        Fixture::Pseudospectral(f) => crate::cli::solve_pseudospectral::run(&f, args.json),
        Fixture::Impulsive(f) => crate::cli::solve_impulsive::run(&f, args.json),
    }
}
