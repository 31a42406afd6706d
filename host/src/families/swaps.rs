//! The swap kinds, rest to rest: antipodal swaps (every spacecraft to the point opposite it
//! through a shape's centre, so all paths meet there) on a circle, a tilted circle, a sphere,
//! a cube and one or two tetrahedra; and the cube's symmetries (a mirror, a rotation, a
//! permutation of its corners).
//!
//! Each shape is drawn at unit size, scaled so that its least gap is at least the common
//! spacing (and at least a drawn size), then rotated and moved to a random offset.

use super::bound::{rest_to_rest, Common, OFFSET_REACH_LU};
use super::geometry::{
    circle, circle_radius_for_gap, cube_corners, fibonacci_sphere, min_gap, permutation, scale,
    tetrahedron, Placement, Rotation, Vec3,
};
use rand::Rng;
use rand_chacha::ChaCha8Rng;
use reconfig_core::pseudospectral::Spacecraft;
use std::f64::consts::{FRAC_PI_2, PI, TAU};

/// Every point of the unit shape `unit` to its antipode, the shape scaled to `size` (or up to
/// the common spacing where that is larger) and placed.
fn antipodal(unit: &[Vec3], size: f64, c: &Common, place: &Placement) -> Vec<Spacecraft> {
    let k = size.max(c.spacing_lu / min_gap(unit));
    unit.iter()
        .map(|p| rest_to_rest(place.apply(scale(*p, k)), place.apply(scale(*p, -k))))
        .collect()
}

/// `antipodal-circle`: 2-8 evenly spaced on a horizontal circle (radius 3-12 LU or more, any
/// phase), each to its antipode.
pub fn antipodal_circle(rng: &mut ChaCha8Rng, c: &mut Common) -> Vec<Spacecraft> {
    let m = rng.random_range(2..=8usize);
    let unit = circle(m, rng.random_range(0.0..TAU));
    let radius = rng
        .random_range(3.0f64..12.0)
        .max(circle_radius_for_gap(m, c.spacing_lu));
    let place = Placement {
        rotation: Rotation::IDENTITY,
        offset: super::geometry::random_in_box(rng, OFFSET_REACH_LU),
    };
    antipodal(&unit, radius, c, &place)
}

/// `antipodal-tilted-circle`: as `antipodal-circle`, the circle tilted 10-80 deg about a
/// random horizontal axis.
pub fn antipodal_tilted_circle(rng: &mut ChaCha8Rng, c: &mut Common) -> Vec<Spacecraft> {
    let m = rng.random_range(2..=8usize);
    let unit = circle(m, rng.random_range(0.0..TAU));
    let radius = rng
        .random_range(3.0f64..12.0)
        .max(circle_radius_for_gap(m, c.spacing_lu));
    let heading: f64 = rng.random_range(0.0..TAU);
    let tilt = rng.random_range(10.0f64..80.0).to_radians();
    let place = Placement {
        rotation: Rotation::about([heading.cos(), heading.sin(), 0.0], tilt),
        offset: super::geometry::random_in_box(rng, OFFSET_REACH_LU),
    };
    antipodal(&unit, radius, c, &place)
}

/// `antipodal-sphere`: 2-8 on a Fibonacci lattice of a sphere (radius 3-10 LU or more),
/// randomly rotated, each to its antipode.
pub fn antipodal_sphere(rng: &mut ChaCha8Rng, c: &mut Common) -> Vec<Spacecraft> {
    let m = rng.random_range(2..=8usize);
    let radius = rng.random_range(3.0..10.0);
    let place = Placement::random(rng, OFFSET_REACH_LU);
    antipodal(&fibonacci_sphere(m), radius, c, &place)
}

/// `antipodal-cube`: 2-8 of a cube's corners (edge: the spacing), randomly rotated, each to
/// the opposite corner.
pub fn antipodal_cube(rng: &mut ChaCha8Rng, c: &mut Common) -> Vec<Spacecraft> {
    let m = rng.random_range(2..=8usize);
    let corners = cube_corners();
    let unit: Vec<Vec3> = permutation(rng, 8)[..m]
        .iter()
        .map(|&k| corners[k])
        .collect();
    let place = Placement::random(rng, OFFSET_REACH_LU);
    // Unit edge: the scale is the edge.
    antipodal(&unit, c.spacing_lu, c, &place)
}

/// `antipodal-tetrahedron`: up to 4 of a regular tetrahedron's vertices (radius 2-8 LU or
/// more) and, past 4, vertices of its dual at 1.3-1.8 times that radius; randomly rotated,
/// each to its antipode (2-8 spacecraft).
pub fn antipodal_tetrahedron(rng: &mut ChaCha8Rng, c: &mut Common) -> Vec<Spacecraft> {
    let m = rng.random_range(2..=8usize);
    let inner = tetrahedron();
    let outer_ratio = rng.random_range(1.3..1.8);
    let mut unit: Vec<Vec3> = permutation(rng, 4)[..m.min(4)]
        .iter()
        .map(|&k| inner[k])
        .collect();
    for &k in &permutation(rng, 4)[..m.saturating_sub(4)] {
        unit.push(scale(inner[k], -outer_ratio));
    }
    let radius = rng.random_range(2.0..8.0);
    let place = Placement::random(rng, OFFSET_REACH_LU);
    antipodal(&unit, radius, c, &place)
}

/// 2-8 distinct corners of the unit cube, and their indices.
fn some_corners(rng: &mut ChaCha8Rng) -> Vec<usize> {
    let m = rng.random_range(2..=8usize);
    permutation(rng, 8)[..m].to_vec()
}

/// Rest-to-rest moves from `starts` to `ends` on the unit cube, its edge the common spacing
/// times 1-1.4, placed at random.
fn on_cube(rng: &mut ChaCha8Rng, c: &Common, starts: &[Vec3], ends: &[Vec3]) -> Vec<Spacecraft> {
    let edge = c.spacing_lu * rng.random_range(1.0..1.4);
    let place = Placement::random(rng, OFFSET_REACH_LU);
    starts
        .iter()
        .zip(ends)
        .map(|(a, b)| rest_to_rest(place.apply(scale(*a, edge)), place.apply(scale(*b, edge))))
        .collect()
}

/// The mirror images of a point through one of the cube's 9 symmetry planes: 3 through its
/// centre normal to an axis, 6 through two opposite edges (`x = +-y`, `y = +-z`, `z = +-x`).
fn mirror(p: Vec3, plane: usize) -> Vec3 {
    let [x, y, z] = p;
    match plane {
        0 => [-x, y, z],
        1 => [x, -y, z],
        2 => [x, y, -z],
        3 => [y, x, z],
        4 => [-y, -x, z],
        5 => [x, z, y],
        6 => [x, -z, -y],
        7 => [z, y, x],
        _ => [-z, y, -x],
    }
}

/// `cube-mirror`: 2-8 cube corners, each to its mirror image through one of the cube's 9
/// symmetry planes (corners on a diagonal plane stay, at rest; not all of them).
pub fn cube_mirror(rng: &mut ChaCha8Rng, c: &mut Common) -> Vec<Spacecraft> {
    let corners = cube_corners();
    let chosen = some_corners(rng);
    let starts: Vec<Vec3> = chosen.iter().map(|&k| corners[k]).collect();
    // Redrawn while every chosen corner lies on the plane (an axis plane moves them all).
    let mut ends = starts.clone();
    while ends == starts {
        let plane = rng.random_range(0..9usize);
        ends = starts.iter().map(|p| mirror(*p, plane)).collect();
    }
    on_cube(rng, c, &starts, &ends)
}

/// `cube-rotation`: 2-8 cube corners rotated by 90, 180 or 270 deg about a face axis, or by
/// 180 deg about an axis through two opposite edges' midpoints.
pub fn cube_rotation(rng: &mut ChaCha8Rng, c: &mut Common) -> Vec<Spacecraft> {
    let corners = cube_corners();
    let chosen = some_corners(rng);
    let h = std::f64::consts::FRAC_1_SQRT_2;
    let axis_pick = rng.random_range(0..9usize);
    let turn = match axis_pick {
        0..=2 => {
            let mut axis = [0.0; 3];
            axis[axis_pick] = 1.0;
            let quarters = rng.random_range(1..=3u8);
            Rotation::about(axis, FRAC_PI_2 * f64::from(quarters))
        }
        3 => Rotation::about([h, h, 0.0], PI),
        4 => Rotation::about([h, -h, 0.0], PI),
        5 => Rotation::about([0.0, h, h], PI),
        6 => Rotation::about([0.0, h, -h], PI),
        7 => Rotation::about([h, 0.0, h], PI),
        _ => Rotation::about([-h, 0.0, h], PI),
    };
    let starts: Vec<Vec3> = chosen.iter().map(|&k| corners[k]).collect();
    let ends: Vec<Vec3> = starts.iter().map(|p| turn.apply(*p)).collect();
    on_cube(rng, c, &starts, &ends)
}

/// `cube-permutation`: 2-8 cube corners, each to a corner of a random permutation of the 8
/// (redrawn until at least one spacecraft moves).
pub fn cube_permutation(rng: &mut ChaCha8Rng, c: &mut Common) -> Vec<Spacecraft> {
    let corners = cube_corners();
    let chosen = some_corners(rng);
    let mut sigma = permutation(rng, 8);
    while chosen.iter().all(|&k| sigma[k] == k) {
        sigma = permutation(rng, 8);
    }
    let starts: Vec<Vec3> = chosen.iter().map(|&k| corners[k]).collect();
    let ends: Vec<Vec3> = chosen.iter().map(|&k| corners[sigma[k]]).collect();
    on_cube(rng, c, &starts, &ends)
}
