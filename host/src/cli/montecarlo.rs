//! `reconfig montecarlo`: Huang 2012 Table 2 with a fixed seed.

use anyhow::{bail, Result};
use std::process::ExitCode;

/// Arguments of `reconfig montecarlo`.
#[derive(clap::Args, Debug)]
pub struct Args {
    /// Random seed.
    #[arg(long, default_value_t = 2012)]
    pub seed: u64,
}

/// Run `reconfig montecarlo`.
pub fn run(_args: &Args) -> Result<ExitCode> {
    bail!("not built yet")
}
