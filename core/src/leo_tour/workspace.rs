//! The arc search's caller-owned buffers.

use super::arc::Point;
use super::track::Track;
use super::types::{MAX_CANDIDATES, MAX_HOPS};

/// Every large buffer of one arc's search ([`super::solve_arc`], [`super::solve_arc_warm`],
/// [`super::estimate_arc_mps`]): the two clients' checkpoint tracks in the planning model and
/// the search's candidate lists (the grid's or the warm start's candidates, the hops). Built
/// once by the caller (`Workspace::new()` is a `const fn`: it can sit in a `static`) and
/// reused: every solve overwrites what it reads, so no answer depends on an earlier solve.
#[derive(Clone, Debug)]
pub struct Workspace {
    /// Client A's (the chaser's start) checkpoints.
    pub(crate) a: Track,
    /// Client B's checkpoints.
    pub(crate) b: Track,
    /// The grid's candidates (or the warm start's one), cheapest first.
    pub(crate) candidates: [Option<Point>; MAX_CANDIDATES],
    /// The hops from the best refined plan.
    pub(crate) hops: [Option<Point>; MAX_HOPS],
}

impl Workspace {
    /// Empty buffers.
    pub const fn new() -> Self {
        Self {
            a: Track::empty(),
            b: Track::empty(),
            candidates: [None; MAX_CANDIDATES],
            hops: [None; MAX_HOPS],
        }
    }
}

impl Default for Workspace {
    fn default() -> Self {
        Self::new()
    }
}
