//! GEO-tour workspace: the leg tables and the allocation's working copies.

use super::pick::Pick;
use super::solution::Solution;
use super::table::LegTable;
use super::types::MAX_TARGETS;

/// Scratch memory of a GEO tour solve. Build once (it can live in a `static`), reuse.
#[derive(Clone, Debug)]
pub struct Workspace {
    pub(crate) tables: [LegTable; MAX_TARGETS],
    pub(crate) picks: [Pick; MAX_TARGETS],
    pub(crate) lo_picks: [Pick; MAX_TARGETS],
    pub(crate) trial: [Pick; MAX_TARGETS],
    /// The other sweep's plan when both are planned.
    pub(crate) other: Solution,
}

impl Workspace {
    /// A fresh workspace.
    pub const fn new() -> Self {
        Self {
            tables: [const { LegTable::empty() }; MAX_TARGETS],
            picks: [Pick::none(); MAX_TARGETS],
            lo_picks: [Pick::none(); MAX_TARGETS],
            trial: [Pick::none(); MAX_TARGETS],
            other: Solution::new(),
        }
    }
}

impl Default for Workspace {
    fn default() -> Self {
        Self::new()
    }
}
