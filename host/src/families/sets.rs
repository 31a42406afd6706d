//! The two disjoint seeded sets of generated kinds: `tuning` (to set planner A's settings on)
//! and `held-out` (to measure them on, never tuned on). Problem `i` of a set is of kind
//! `KINDS[i % KINDS.len()]` and comes from its own ChaCha8 stream, seeded with
//! `base(set) + seed * 2^32 + i`: the bases are 2^62 apart, so no seed and count below 2^30
//! each reach another set's streams, and a problem does not depend on the count.

use super::kinds::{generate, KINDS};
use super::Named;
use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;

/// A seeded set of generated problems.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Set {
    /// Problems to tune planner A's settings on.
    Tuning,
    /// Problems to measure planner A on, never tuned on.
    HeldOut,
}

impl Set {
    /// The set's name on the command line.
    pub fn name(self) -> &'static str {
        match self {
            Set::Tuning => "tuning",
            Set::HeldOut => "held-out",
        }
    }

    fn base(self) -> u64 {
        match self {
            Set::Tuning => 1 << 62,
            Set::HeldOut => 2 << 62,
        }
    }
}

/// The seed of problem `index` of `set` at `seed`.
pub fn problem_seed(set: Set, seed: u64, index: usize) -> u64 {
    set.base()
        .wrapping_add(seed.wrapping_mul(1 << 32))
        .wrapping_add(index as u64)
}

/// Problem `index` of `set` at `seed`, and its kind's name.
pub fn problem(set: Set, seed: u64, index: usize) -> Named {
    let kind = &KINDS[index % KINDS.len()];
    let mut rng = ChaCha8Rng::seed_from_u64(problem_seed(set, seed, index));
    (kind.name, generate(kind, &mut rng))
}

/// The first `count` problems of `set` at `seed`, each named by its kind.
pub fn generate_set(set: Set, seed: u64, count: usize) -> Vec<Named> {
    (0..count).map(|i| problem(set, seed, i)).collect()
}
