//! Planner A's small shared arithmetic: the dense vector of free coefficients and its dot
//! product, scaling and update; a boundary state split per axis; an index as a `u8`. Every
//! other file of the planner takes these from here, none from a file with a larger job.
//!
//! The loops walk the live `blocks x free` part of the fixed-size arrays with zips (no index
//! that could miss), each sum in block order and coefficient order within a block: the same
//! operations in the same order wherever they are used, so the same bits.

use crate::capacity::{MAX_FREE_PER_AXIS, MAX_SPACECRAFT};

/// Blocks of variables: one per spacecraft per axis.
pub(crate) const MAX_BLOCKS: usize = MAX_SPACECRAFT * 3;

/// A dense vector of all free coefficients (`MAX_FREE_PER_AXIS` per block, `MAX_BLOCKS`
/// blocks); a problem uses the first `free` coefficients of its first `blocks` blocks.
pub(crate) type Coefficients = [[f64; MAX_FREE_PER_AXIS]; MAX_BLOCKS];

/// The live part of a [`Coefficients`]: `(blocks, free)`.
pub(crate) type Live = (usize, usize);

/// `a . b` over the live part.
pub(crate) fn dot(a: &Coefficients, b: &Coefficients, (blocks, free): Live) -> f64 {
    let mut sum = 0.0;
    for (x, y) in a.iter().zip(b.iter()).take(blocks) {
        for (p, q) in x.iter().zip(y.iter()).take(free) {
            sum += p * q;
        }
    }
    sum
}

/// `a += alpha b` over the live part.
pub(crate) fn axpy(a: &mut Coefficients, alpha: f64, b: &Coefficients, (blocks, free): Live) {
    for (x, y) in a.iter_mut().zip(b.iter()).take(blocks) {
        for (p, q) in x.iter_mut().zip(y.iter()).take(free) {
            *p += alpha * q;
        }
    }
}

/// `a *= factor` over the live part.
pub(crate) fn scale(a: &mut Coefficients, factor: f64, (blocks, free): Live) {
    for row in a.iter_mut().take(blocks) {
        for v in row.iter_mut().take(free) {
            *v *= factor;
        }
    }
}

/// A count or index as a `u8` (every planner-A index fits: the capacities are below 256);
/// `u8::MAX` past it, which names no spacecraft, axis, node, pair or check.
pub(crate) fn u8_of(value: usize) -> u8 {
    u8::try_from(value).unwrap_or(u8::MAX)
}

/// Position and velocity per axis of a state `[x, y, z, vx, vy, vz]`: valid by construction, no
/// index that could miss.
pub(crate) fn per_axis(state: &[f64; 6]) -> [(f64, f64); 3] {
    let [x, y, z, vx, vy, vz] = *state;
    [(x, vx), (y, vy), (z, vz)]
}
