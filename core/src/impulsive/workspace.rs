//! Planner-B workspace: every scratch buffer of a solve, sized by the capacities.

use super::search::SearchScratch;
use super::transfer::{Points, Sequence};

/// Scratch memory for planner B. Build once (it can live in a `static`), reuse for every
/// solve; about 3 KiB, no heap.
#[derive(Clone, Debug)]
pub struct Workspace {
    /// The propagated sequence and its linear system.
    pub(crate) seq: Sequence,
    /// The impulse points being solved.
    pub(crate) points: Points,
    /// The search's candidates.
    pub(crate) search: SearchScratch,
}

impl Workspace {
    /// A fresh workspace.
    pub const fn new() -> Self {
        Self {
            seq: Sequence::new(),
            points: Points::new(),
            search: SearchScratch::new(),
        }
    }
}

impl Default for Workspace {
    fn default() -> Self {
        Self::new()
    }
}
