//! Point sets for the generated kinds: vectors, rotations, the regular shapes (circle, Fibonacci
//! sphere, cube, tetrahedron, lattices) and seeded sampling (points spread in a box or a ball,
//! permutations). Every draw comes from the caller's ChaCha8 stream, in a fixed order.

use rand::Rng;
use rand_chacha::ChaCha8Rng;
use std::f64::consts::{PI, TAU};

/// A position or a direction, LU.
pub type Vec3 = [f64; 3];

/// `a + b`.
pub fn add(a: Vec3, b: Vec3) -> Vec3 {
    [a[0] + b[0], a[1] + b[1], a[2] + b[2]]
}

/// `k a`.
pub fn scale(a: Vec3, k: f64) -> Vec3 {
    [k * a[0], k * a[1], k * a[2]]
}

/// `|a - b|`.
pub fn distance(a: Vec3, b: Vec3) -> f64 {
    ((a[0] - b[0]).powi(2) + (a[1] - b[1]).powi(2) + (a[2] - b[2]).powi(2)).sqrt()
}

/// The least distance between two of `points` (infinite for fewer than two).
pub fn min_gap(points: &[Vec3]) -> f64 {
    let mut least = f64::INFINITY;
    for (i, a) in points.iter().enumerate() {
        for b in &points[i + 1..] {
            least = least.min(distance(*a, *b));
        }
    }
    least
}

/// A proper rotation (orthonormal rows, determinant 1).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Rotation(pub [[f64; 3]; 3]);

impl Rotation {
    /// No rotation.
    pub const IDENTITY: Rotation = Rotation([[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]]);

    /// A rotation drawn uniformly (a uniform unit quaternion, Shoemake's method).
    pub fn random(rng: &mut ChaCha8Rng) -> Rotation {
        let (u1, u2, u3): (f64, f64, f64) = (
            rng.random_range(0.0..1.0),
            rng.random_range(0.0..TAU),
            rng.random_range(0.0..TAU),
        );
        let (a, b) = ((1.0 - u1).sqrt(), u1.sqrt());
        let q = [a * u2.sin(), a * u2.cos(), b * u3.sin(), b * u3.cos()];
        Rotation::from_quaternion(q)
    }

    /// The rotation by `angle` (rad) about the unit vector `axis` (right hand).
    pub fn about(axis: Vec3, angle: f64) -> Rotation {
        let (s, c) = (0.5 * angle).sin_cos();
        Rotation::from_quaternion([c, s * axis[0], s * axis[1], s * axis[2]])
    }

    /// The rotation of a unit quaternion `[w, x, y, z]`.
    fn from_quaternion([w, x, y, z]: [f64; 4]) -> Rotation {
        Rotation([
            [
                1.0 - 2.0 * (y * y + z * z),
                2.0 * (x * y - w * z),
                2.0 * (x * z + w * y),
            ],
            [
                2.0 * (x * y + w * z),
                1.0 - 2.0 * (x * x + z * z),
                2.0 * (y * z - w * x),
            ],
            [
                2.0 * (x * z - w * y),
                2.0 * (y * z + w * x),
                1.0 - 2.0 * (x * x + y * y),
            ],
        ])
    }

    /// `R p`.
    pub fn apply(&self, p: Vec3) -> Vec3 {
        let r = &self.0;
        [
            r[0][0] * p[0] + r[0][1] * p[1] + r[0][2] * p[2],
            r[1][0] * p[0] + r[1][1] * p[1] + r[1][2] * p[2],
            r[2][0] * p[0] + r[2][1] * p[1] + r[2][2] * p[2],
        ]
    }
}

/// Where a shape is put: rotated, then moved by `offset`.
#[derive(Clone, Copy, Debug)]
pub struct Placement {
    /// The shape's orientation.
    pub rotation: Rotation,
    /// The shape's centre, LU.
    pub offset: Vec3,
}

impl Placement {
    /// A uniform rotation and an offset in a cube of half-width `reach`.
    pub fn random(rng: &mut ChaCha8Rng, reach: f64) -> Placement {
        let rotation = Rotation::random(rng);
        Placement {
            rotation,
            offset: random_in_box(rng, reach),
        }
    }

    /// `rotation p + offset`.
    pub fn apply(&self, p: Vec3) -> Vec3 {
        add(self.rotation.apply(p), self.offset)
    }

    /// Every point placed.
    pub fn apply_all(&self, points: &[Vec3]) -> Vec<Vec3> {
        points.iter().map(|p| self.apply(*p)).collect()
    }
}

/// A point in the cube of half-width `half` about the origin (the origin when `half` is 0).
pub fn random_in_box(rng: &mut ChaCha8Rng, half: f64) -> Vec3 {
    if half <= 0.0 {
        return [0.0; 3];
    }
    [
        rng.random_range(-half..half),
        rng.random_range(-half..half),
        rng.random_range(-half..half),
    ]
}

/// A point in the ball of radius `radius` (uniform by rejection from the cube).
pub fn random_in_ball(rng: &mut ChaCha8Rng, radius: f64) -> Vec3 {
    loop {
        let p = random_in_box(rng, radius);
        if p[0] * p[0] + p[1] * p[1] + p[2] * p[2] <= radius * radius {
            return p;
        }
    }
}

/// A unit vector drawn uniformly.
pub fn random_direction(rng: &mut ChaCha8Rng) -> Vec3 {
    let z: f64 = rng.random_range(-1.0..1.0);
    let phi: f64 = rng.random_range(0.0..TAU);
    let r = (1.0 - z * z).sqrt();
    [r * phi.cos(), r * phi.sin(), z]
}

/// Fisher-Yates: a uniform permutation of `items`.
pub fn shuffle<T>(rng: &mut ChaCha8Rng, items: &mut [T]) {
    for i in (1..items.len()).rev() {
        items.swap(i, rng.random_range(0..=i));
    }
}

/// A uniform permutation of `0..n`.
pub fn permutation(rng: &mut ChaCha8Rng, n: usize) -> Vec<usize> {
    let mut order: Vec<usize> = (0..n).collect();
    shuffle(rng, &mut order);
    order
}

/// A uniform permutation of `0..n` that moves at least one index (for `n` >= 2).
pub fn moving_permutation(rng: &mut ChaCha8Rng, n: usize) -> Vec<usize> {
    let mut order = permutation(rng, n);
    if n >= 2 && order.iter().enumerate().all(|(i, j)| i == *j) {
        order.swap(0, n - 1);
    }
    order
}

/// `count` points in the cube of half-width `half`, pairwise at least `gap` apart; the cube
/// grows by 5 % after every 500 refused draws, so the set is always complete.
pub fn spread_in_box(rng: &mut ChaCha8Rng, count: usize, half: f64, gap: f64) -> Vec<Vec3> {
    spread(rng, count, half, gap, random_in_box)
}

/// `count` points in the ball of radius `radius`, pairwise at least `gap` apart; the ball grows
/// as in [`spread_in_box`].
pub fn spread_in_ball(rng: &mut ChaCha8Rng, count: usize, radius: f64, gap: f64) -> Vec<Vec3> {
    spread(rng, count, radius, gap, random_in_ball)
}

fn spread(
    rng: &mut ChaCha8Rng,
    count: usize,
    mut size: f64,
    gap: f64,
    draw: fn(&mut ChaCha8Rng, f64) -> Vec3,
) -> Vec<Vec3> {
    let mut points: Vec<Vec3> = Vec::with_capacity(count);
    let mut refused = 0u32;
    while points.len() < count {
        let p = draw(rng, size);
        if points.iter().all(|q| distance(p, *q) >= gap) {
            points.push(p);
        } else {
            refused += 1;
            if refused % 500 == 0 {
                size *= 1.05;
            }
        }
    }
    points
}

/// `count` points evenly spaced on the unit circle in the xy-plane, the first at `phase` (rad).
pub fn circle(count: usize, phase: f64) -> Vec<Vec3> {
    (0..count)
        .map(|k| {
            let a = phase + TAU * k as f64 / count as f64;
            [a.cos(), a.sin(), 0.0]
        })
        .collect()
}

/// The radius at which `count` evenly spaced points of a circle are `gap` apart (chord).
pub fn circle_radius_for_gap(count: usize, gap: f64) -> f64 {
    if count < 2 {
        return 0.0;
    }
    gap / (2.0 * (PI / count as f64).sin())
}

/// `count` points of the Fibonacci lattice on the unit sphere (near-even spread).
pub fn fibonacci_sphere(count: usize) -> Vec<Vec3> {
    let golden = PI * (3.0 - 5.0f64.sqrt());
    (0..count)
        .map(|k| {
            let z = 1.0 - (2 * k + 1) as f64 / count as f64;
            let r = (1.0 - z * z).sqrt();
            let a = golden * k as f64;
            [r * a.cos(), r * a.sin(), z]
        })
        .collect()
}

/// The 8 corners of the unit cube centred at the origin (edge 1), corner `k` at
/// `((k & 1) - 0.5, (k >> 1 & 1) - 0.5, (k >> 2 & 1) - 0.5)`.
pub fn cube_corners() -> [Vec3; 8] {
    let mut corners = [[0.0; 3]; 8];
    for (k, c) in corners.iter_mut().enumerate() {
        *c = [
            (k & 1) as f64 - 0.5,
            ((k >> 1) & 1) as f64 - 0.5,
            ((k >> 2) & 1) as f64 - 0.5,
        ];
    }
    corners
}

/// The 4 vertices of a regular tetrahedron inscribed in the unit sphere (alternate corners of
/// a cube); their antipodes are the dual tetrahedron's.
pub fn tetrahedron() -> [Vec3; 4] {
    let k = 1.0 / 3.0f64.sqrt();
    [[k, k, k], [k, -k, -k], [-k, k, -k], [-k, -k, k]]
}

/// A `rows x cols` square grid in the xy-plane, spacing `step`, centred at the origin.
pub fn square_grid(rows: usize, cols: usize, step: f64) -> Vec<Vec3> {
    let (r0, c0) = (0.5 * (rows - 1) as f64, 0.5 * (cols - 1) as f64);
    let mut out = Vec::with_capacity(rows * cols);
    for i in 0..rows {
        for j in 0..cols {
            out.push([step * (i as f64 - r0), step * (j as f64 - c0), 0.0]);
        }
    }
    out
}

/// A `rows x cols` patch of the hexagonal (triangular) lattice in the xy-plane, nearest
/// neighbours `step` apart (odd rows shifted by half a step), centred at the origin.
pub fn hexagonal_patch(rows: usize, cols: usize, step: f64) -> Vec<Vec3> {
    let dy = step * 3.0f64.sqrt() / 2.0;
    let mut out = Vec::with_capacity(rows * cols);
    for i in 0..rows {
        let shift = if i % 2 == 1 { 0.5 * step } else { 0.0 };
        for j in 0..cols {
            out.push([step * j as f64 + shift, dy * i as f64, 0.0]);
        }
    }
    centred(out)
}

/// An `nx x ny x nz` cubic lattice, spacing `step`, centred at the origin.
pub fn cubic_lattice(n: [usize; 3], step: f64) -> Vec<Vec3> {
    let mut out = Vec::with_capacity(n[0] * n[1] * n[2]);
    for i in 0..n[0] {
        for j in 0..n[1] {
            for k in 0..n[2] {
                out.push([step * i as f64, step * j as f64, step * k as f64]);
            }
        }
    }
    centred(out)
}

/// The points moved so their mean is the origin.
pub fn centred(points: Vec<Vec3>) -> Vec<Vec3> {
    let n = points.len().max(1) as f64;
    let mut mean = [0.0; 3];
    for p in &points {
        mean = add(mean, scale(*p, 1.0 / n));
    }
    points
        .into_iter()
        .map(|p| add(p, scale(mean, -1.0)))
        .collect()
}
