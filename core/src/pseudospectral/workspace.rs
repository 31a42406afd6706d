//! Planner-A workspace: every scratch buffer of a solve, sized by the capacities.

/// Scratch memory for planner A. Build once (it can live in a `static`), reuse for every solve.
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
