//! The kinds of placed points, rest to rest: random ends in a box (with unit or mixed masses,
//! or under a tight bound) and dense repackings, where the ends are the same points (a ball of
//! points just above d apart) or the cells of one lattice (square, hexagonal, cubic), permuted.

use super::bound::{craft, rest_to_rest, Common, KEEP_OUT_LU, OFFSET_REACH_LU};
use super::geometry::{
    add, cubic_lattice, hexagonal_patch, moving_permutation, permutation, random_in_box,
    spread_in_ball, spread_in_box, square_grid, Placement, Vec3,
};
use rand::Rng;
use rand_chacha::ChaCha8Rng;
use reconfig_core::pseudospectral::Spacecraft;

/// 2-8 starts and ends spread (pairwise the spacing apart) in a box of half-width drawn from
/// `half`, moved by one random offset.
fn random_ends(
    rng: &mut ChaCha8Rng,
    c: &Common,
    half: std::ops::Range<f64>,
) -> (Vec<Vec3>, Vec<Vec3>) {
    let m = rng.random_range(2..=8usize);
    let half = rng.random_range(half);
    let offset = random_in_box(rng, OFFSET_REACH_LU);
    let starts = spread_in_box(rng, m, half, c.spacing_lu);
    let ends = spread_in_box(rng, m, half, c.spacing_lu);
    let moved = |points: Vec<Vec3>| points.into_iter().map(|p| add(p, offset)).collect();
    (moved(starts), moved(ends))
}

/// `random-placements`: 2-8, random ends in a box of half-width 6-14 LU.
pub fn random_placements(rng: &mut ChaCha8Rng, c: &mut Common) -> Vec<Spacecraft> {
    let (starts, ends) = random_ends(rng, c, 6.0..14.0);
    starts
        .iter()
        .zip(&ends)
        .map(|(a, b)| rest_to_rest(*a, *b))
        .collect()
}

/// `random-tight`: as `random-placements` (half-width 6-12 LU), the ends redrawn until some
/// spacecraft moves at least 3 LU along an axis; tight bound.
pub fn random_tight(rng: &mut ChaCha8Rng, c: &mut Common) -> Vec<Spacecraft> {
    loop {
        let (starts, ends) = random_ends(rng, c, 6.0..12.0);
        let longest = starts
            .iter()
            .zip(&ends)
            .flat_map(|(a, b)| (0..3).map(move |k| (b[k] - a[k]).abs()))
            .fold(0.0, f64::max);
        if longest >= 3.0 {
            return starts
                .iter()
                .zip(&ends)
                .map(|(a, b)| rest_to_rest(*a, *b))
                .collect();
        }
    }
}

/// `mixed-masses`: as `random-placements`, masses 0.5-2 MU.
pub fn mixed_masses(rng: &mut ChaCha8Rng, c: &mut Common) -> Vec<Spacecraft> {
    let (starts, ends) = random_ends(rng, c, 6.0..14.0);
    starts
        .iter()
        .zip(&ends)
        .map(|(a, b)| craft(rng.random_range(0.5..2.0), (*a, [0.0; 3]), (*b, [0.0; 3])))
        .collect()
}

/// `repack-ball`: 2-8 random points of a small ball, pairwise d + 0.2-0.6 LU apart (the ball
/// just large enough), each spacecraft to another's point (a permutation moving some).
pub fn repack_ball(rng: &mut ChaCha8Rng, _c: &mut Common) -> Vec<Spacecraft> {
    let m = rng.random_range(2..=8usize);
    let gap = KEEP_OUT_LU + rng.random_range(0.2..0.6);
    let ball = gap * (0.5 + 0.5 * (m as f64).cbrt());
    let offset = random_in_box(rng, OFFSET_REACH_LU);
    let points: Vec<Vec3> = spread_in_ball(rng, m, ball, gap)
        .into_iter()
        .map(|p| add(p, offset))
        .collect();
    let order = moving_permutation(rng, m);
    (0..m)
        .map(|k| rest_to_rest(points[k], points[order[k]]))
        .collect()
}

/// 2-8 spacecraft (at most the cells) in distinct random cells of `cells`, each to a distinct
/// random cell (redrawn until some spacecraft moves), the lattice placed at random.
fn repack(rng: &mut ChaCha8Rng, cells: &[Vec3], m: usize) -> Vec<Spacecraft> {
    let n = cells.len();
    let m = m.min(n);
    let from = permutation(rng, n);
    let mut to = permutation(rng, n);
    while from[..m] == to[..m] {
        to = permutation(rng, n);
    }
    let place = Placement::random(rng, OFFSET_REACH_LU);
    (0..m)
        .map(|k| rest_to_rest(place.apply(cells[from[k]]), place.apply(cells[to[k]])))
        .collect()
}

/// Rows and columns of a 2D patch of at least `m` cells: rows 2-3, columns enough and up to 4.
fn patch_size(rng: &mut ChaCha8Rng, m: usize) -> (usize, usize) {
    let rows = rng.random_range(2..=3usize);
    let least = m.div_ceil(rows).max(2);
    (rows, rng.random_range(least..=least.max(4)))
}

/// `repack-grid`: 2-8 on a square grid of 2-3 by 2-4 cells spaced by the spacing, permuted.
pub fn repack_grid(rng: &mut ChaCha8Rng, c: &mut Common) -> Vec<Spacecraft> {
    let m = rng.random_range(2..=8usize);
    let (rows, cols) = patch_size(rng, m);
    repack(rng, &square_grid(rows, cols, c.spacing_lu), m)
}

/// `repack-hexagonal`: as `repack-grid` on a hexagonal lattice patch.
pub fn repack_hexagonal(rng: &mut ChaCha8Rng, c: &mut Common) -> Vec<Spacecraft> {
    let m = rng.random_range(2..=8usize);
    let (rows, cols) = patch_size(rng, m);
    repack(rng, &hexagonal_patch(rows, cols, c.spacing_lu), m)
}

/// `repack-cubic`: 2-8 on a cubic lattice of 2-3 cells a side (at least 8 cells) spaced by the
/// spacing, permuted.
pub fn repack_cubic(rng: &mut ChaCha8Rng, c: &mut Common) -> Vec<Spacecraft> {
    let m = rng.random_range(2..=8usize);
    let n = [
        rng.random_range(2..=3usize),
        rng.random_range(2..=3usize),
        rng.random_range(2..=3usize),
    ];
    repack(rng, &cubic_lattice(n, c.spacing_lu), m)
}
