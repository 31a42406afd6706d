//! COMPILE-ONLY PLACEHOLDER, replaced at merge by planner B's real `Settings`, `Solution`,
//! `Workspace`, `PlanError` and `solve` (same names and signature). It plans nothing.
//!
//! Harness branch: a superset of the firmware branch's placeholder (the same items, plus the
//! fields of the pinned contract the host harness reads: `Solution::total_dv_mps`,
//! `terminal_error_m`, `info.status`, `info.iterations`, and `Display` for `PlanError`). At a
//! merge with the firmware branch's version, keep this one.

use super::types::Problem;
use serde::{Deserialize, Serialize};

/// Placeholder planner-B settings.
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct Settings {
    /// Placeholder bound.
    pub max_iter: u16,
}

/// Placeholder status.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[repr(u8)]
pub enum SolveStatus {
    /// No solve has written this solution.
    #[default]
    Unsolved = 0,
    /// Converged.
    Solved = 1,
}

/// Placeholder counters.
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct SolveInfo {
    /// Outcome.
    pub status: SolveStatus,
    /// Fixed-point iterations.
    pub iterations: u16,
}

/// Placeholder planner-B result.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct Solution {
    /// Placeholder count of impulses.
    pub impulses: u8,
    /// Sum of impulse magnitudes, m/s.
    pub total_dv_mps: f64,
    /// Residual of the end condition, m.
    pub terminal_error_m: f64,
    /// Counters and status.
    pub info: SolveInfo,
}

impl Solution {
    /// An empty solution.
    pub const fn new() -> Self {
        Self {
            impulses: 0,
            total_dv_mps: 0.0,
            terminal_error_m: 0.0,
            info: SolveInfo {
                status: SolveStatus::Unsolved,
                iterations: 0,
            },
        }
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

impl core::fmt::Display for PlanError {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        write!(f, "planner B is not built yet (placeholder)")
    }
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
