//! What a solve's first run keeps of its best verified answer (the anytime answer of
//! `anytime.rs`): the record only, which the workspace holds.

/// What the run keeps. All zero bits when off (`Kept::OFF`), as the whole workspace is, so a
/// static workspace stays in `.bss` (an enum with an `Option<f64>` made it `.data`, measured:
/// 191 KB of M7 flash and a copy at boot).
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Kept {
    /// Keeping (a solve's first run only: afterwards `saved` belongs to the saddle escape or
    /// the flat probe).
    keeping: bool,
    /// `Iterates::saved` holds a verified accepted answer of cost `best_cost`.
    has_best: bool,
    best_cost: f64,
    /// The pair that dipped in the last search, searched first in the next (a dip tends to
    /// stay with its pair, so a failing search mostly costs one pair).
    dipping_pair: usize,
}

impl Kept {
    /// Keeping nothing.
    pub(crate) const OFF: Self = Self {
        keeping: false,
        has_best: false,
        best_cost: 0.0,
        dipping_pair: 0,
    };

    /// Keeping, nothing kept yet.
    pub(crate) const START: Self = Self {
        keeping: true,
        ..Self::OFF
    };

    /// The kept answer's cost, if one is kept.
    pub(crate) fn cost(self) -> Option<f64> {
        (self.keeping && self.has_best).then_some(self.best_cost)
    }

    /// Whether an accepted answer of cost `cost` is worth a search: keeping, and none kept yet
    /// or cheaper than the kept one by the fraction `improvement_rel`.
    pub(crate) fn worth_searching(self, cost: f64, improvement_rel: f64) -> bool {
        self.keeping && (!self.has_best || cost < self.best_cost - improvement_rel * self.best_cost)
    }

    /// The pair to search first: the one that dipped in the last search.
    pub(crate) fn dipping_pair(self) -> usize {
        self.dipping_pair
    }

    /// The last search stopped at `pair`, which dipped.
    pub(crate) fn dipped_at(&mut self, pair: usize) {
        self.dipping_pair = pair;
    }

    /// An answer of cost `cost` is kept (in `Iterates::saved`).
    pub(crate) fn keep(&mut self, cost: f64) {
        self.has_best = true;
        self.best_cost = cost;
    }
}
