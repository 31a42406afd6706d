//! `reconfig solve` for planner-A fixtures.

use crate::fixture::pseudospectral::PseudospectralFixture;
use anyhow::{bail, Result};
use std::process::ExitCode;

/// Solve and report a planner-A fixture.
pub fn run(_fixture: &PseudospectralFixture, _json: bool) -> Result<ExitCode> {
    bail!("planner \"pseudospectral\" is not built yet")
}
