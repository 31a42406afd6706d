//! PLACEHOLDER, replaced at merge: a compile-only stand-in for the planner-B solver items that
//! the host harness compiles against (`Settings`, `Solution`, `SolveInfo`, `SolveStatus`,
//! `Workspace`, `PlanError`, `solve`). The real planner B (another branch) defines these with the
//! same names and signatures; at merge this file and its two lines in `mod.rs` are deleted.
//! Nothing here is planner B's maths: `solve` always rejects.

use super::types::Problem;
use serde::{Deserialize, Serialize};

/// Placeholder settings.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct Settings {
    /// Most fixed-point iterations.
    pub max_iter: u16,
    /// Stop when the impulses change by less than this, m/s.
    pub tol_mps: f64,
}

impl Default for Settings {
    fn default() -> Self {
        Self {
            max_iter: 50,
            tol_mps: 1e-9,
        }
    }
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

/// Placeholder solution.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct Solution {
    /// Sum of impulse magnitudes, m/s.
    pub total_dv_mps: f64,
    /// Residual of the end condition, m.
    pub terminal_error_m: f64,
    /// Counters and status.
    pub info: SolveInfo,
}

/// Placeholder workspace.
#[derive(Clone, Debug)]
pub struct Workspace {
    _private: (),
}

impl Workspace {
    /// A fresh workspace.
    pub const fn new() -> Self {
        Self { _private: () }
    }
}

impl Default for Workspace {
    fn default() -> Self {
        Self::new()
    }
}

/// Placeholder error.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[repr(u8)]
pub enum PlanError {
    /// Planner B is not in this build.
    NotBuilt = 0,
}

impl core::fmt::Display for PlanError {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        write!(f, "planner B is not built in this branch")
    }
}

/// Placeholder solve: always rejects.
///
/// # Errors
/// Always [`PlanError::NotBuilt`].
pub fn solve(
    problem: &Problem,
    settings: &Settings,
    workspace: &mut Workspace,
    out: &mut Solution,
) -> Result<(), PlanError> {
    let _ = (problem, settings, workspace, out);
    Err(PlanError::NotBuilt)
}
