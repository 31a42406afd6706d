//! COMPILE-ONLY PLACEHOLDER on the `firmware` branch, replaced at merge by planner B's real
//! `Settings`, `Solution`, `Workspace`, `PlanError` and `solve` (same names and signature). It
//! exists so that the firmware and its QEMU tests compile against the planner-B API before the
//! planner lands. It plans nothing.

use super::types::Problem;
use serde::{Deserialize, Serialize};

/// Placeholder planner-B settings.
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct Settings {
    /// Placeholder bound.
    pub max_iter: u16,
}

/// Placeholder planner-B result.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct Solution {
    /// Placeholder count of impulses.
    pub impulses: u8,
}

impl Solution {
    /// An empty solution.
    pub const fn new() -> Self {
        Self { impulses: 0 }
    }
}

/// Placeholder planner-B workspace.
#[derive(Clone, Debug, Default)]
pub struct Workspace {
    _private: (),
}

impl Workspace {
    /// A fresh workspace.
    pub const fn new() -> Self {
        Self { _private: () }
    }
}

/// Placeholder planner-B error.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[repr(u8)]
pub enum PlanError {
    /// The placeholder plans nothing.
    NotImplemented = 0,
}

/// Placeholder solve: always [`PlanError::NotImplemented`].
///
/// # Errors
/// Always.
pub fn solve(
    problem: &Problem,
    settings: &Settings,
    workspace: &mut Workspace,
    out: &mut Solution,
) -> Result<(), PlanError> {
    let _ = (problem, settings, workspace, out);
    Err(PlanError::NotImplemented)
}
