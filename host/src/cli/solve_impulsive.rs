//! `reconfig solve` for planner-B fixtures.

use crate::fixture::impulsive::ImpulsiveFixture;
use anyhow::{bail, Result};
use std::process::ExitCode;

/// Solve and report a planner-B fixture.
pub fn run(_fixture: &ImpulsiveFixture, _json: bool) -> Result<ExitCode> {
    bail!("planner \"impulsive\" is not built yet")
}
