//! The kinds of shared motion: a ring that rotates (and climbs), a line that reverses, head-on
//! pairs under a tight bound, two streams flying through each other, and a convergence from
//! afar to a tight cluster (the overtaking in one lane is `overtaking.rs`). Each scene is built in its own frame
//! (the motion along x, the ring in the xy-plane), then rotated and moved at random.

use super::bound::{craft, rest_to_rest, Common, KEEP_OUT_LU, OFFSET_REACH_LU};
use super::geometry::{
    add, circle, circle_radius_for_gap, fibonacci_sphere, permutation, random_in_box, scale,
    spread_in_ball, Placement, Vec3,
};
use rand::Rng;
use rand_chacha::ChaCha8Rng;
use reconfig_core::pseudospectral::Spacecraft;
use std::f64::consts::TAU;

/// A ring of 2-12 slots (radius 3-10 LU, or more for the spacing), 2-8 spacecraft in random
/// slots, each moving on by the same 1 to slots - 1 slots and climbing `climb` LU along the
/// ring's axis.
fn ring(rng: &mut ChaCha8Rng, c: &Common, climb: f64) -> Vec<Spacecraft> {
    let m = rng.random_range(2..=8usize);
    let slots = rng.random_range(m..=m + 4);
    let unit = circle(slots, rng.random_range(0.0..TAU));
    let radius = rng
        .random_range(3.0f64..10.0)
        .max(circle_radius_for_gap(slots, c.spacing_lu));
    let shift = rng.random_range(1..slots);
    let place = Placement::random(rng, OFFSET_REACH_LU);
    let lift = [0.0, 0.0, -0.5 * climb];
    permutation(rng, slots)[..m]
        .iter()
        .map(|&s| {
            let a = add(scale(unit[s], radius), lift);
            let b = add(scale(unit[(s + shift) % slots], radius), scale(lift, -1.0));
            rest_to_rest(place.apply(a), place.apply(b))
        })
        .collect()
}

/// `ring-rotation`: spacecraft on a ring move on by k slots.
pub fn ring_rotation(rng: &mut ChaCha8Rng, c: &mut Common) -> Vec<Spacecraft> {
    ring(rng, c, 0.0)
}

/// `ring-rotation-climb`: as `ring-rotation`, climbing 2-10 LU (either way) along the axis.
pub fn ring_rotation_climb(rng: &mut ChaCha8Rng, c: &mut Common) -> Vec<Spacecraft> {
    let sign = if rng.random_bool(0.5) { 1.0 } else { -1.0 };
    let climb = sign * rng.random_range(2.0..10.0);
    ring(rng, c, climb)
}

/// `collinear-reversal`: 2-8 on a line (gaps 1-1.6 times the spacing), the order reversed;
/// with an odd count the middle spacecraft stays at rest between the others' paths.
pub fn collinear_reversal(rng: &mut ChaCha8Rng, c: &mut Common) -> Vec<Spacecraft> {
    let m = rng.random_range(2..=8usize);
    let mut xs = vec![0.0];
    for k in 1..m {
        let gap = c.spacing_lu * rng.random_range(1.0..1.6);
        xs.push(xs[k - 1] + gap);
    }
    let mid = 0.5 * (xs[0] + xs[m - 1]);
    let place = Placement::random(rng, OFFSET_REACH_LU);
    let at = |x: f64| place.apply([x - mid, 0.0, 0.0]);
    (0..m)
        .map(|k| rest_to_rest(at(xs[k]), at(xs[m - 1 - k])))
        .collect()
}

/// `head-on-tight`: 1-4 pairs, each two spacecraft 6-16 LU apart on one lane swapping places
/// head on (lanes side by side on a 2 x 2 grid of the spacing, lengths and centres per pair);
/// tight bound.
pub fn head_on_tight(rng: &mut ChaCha8Rng, c: &mut Common) -> Vec<Spacecraft> {
    let pairs = rng.random_range(1..=4usize);
    let lane = c.spacing_lu * rng.random_range(1.0..1.5);
    let place = Placement::random(rng, OFFSET_REACH_LU);
    let mut out = Vec::with_capacity(2 * pairs);
    for &cell in &permutation(rng, 4)[..pairs] {
        let (y, z) = (
            lane * ((cell & 1) as f64 - 0.5),
            lane * ((cell >> 1) as f64 - 0.5),
        );
        let length = rng.random_range(6.0..16.0);
        let centre = rng.random_range(-2.0..2.0);
        let a = [centre - 0.5 * length, y, z];
        let b = [centre + 0.5 * length, y, z];
        out.push(rest_to_rest(place.apply(a), place.apply(b)));
        out.push(rest_to_rest(place.apply(b), place.apply(a)));
    }
    out
}

/// `fly-through-stream`: two streams of 1-4 each, side by side in lanes of the spacing, flying
/// through each other along x with initial velocity: one from x = -X (X 4-10 LU) to
/// x = +X' (X' 4-10 LU), the other back, members staggered 0-2 LU along the stream, the
/// second stream's lanes offset by up to 1 LU sideways and 0.8 LU up or down (closer than d);
/// speeds 0.6-1.4 times the mean the distance asks, ending at 0.8-1.2 times the initial.
pub fn fly_through_stream(rng: &mut ChaCha8Rng, c: &mut Common) -> Vec<Spacecraft> {
    let counts = [rng.random_range(1..=4usize), rng.random_range(1..=4usize)];
    let lane = c.spacing_lu * rng.random_range(1.0..1.4);
    let (from, to) = (rng.random_range(4.0..10.0), rng.random_range(4.0..10.0));
    let offset = [rng.random_range(-1.0..1.0), rng.random_range(-0.8..0.8)];
    let place = Placement::random(rng, OFFSET_REACH_LU);
    let mean_speed = (from + to) / c.horizon_tu;
    let mut out = Vec::with_capacity(counts[0] + counts[1]);
    for (stream, &n) in counts.iter().enumerate() {
        let dir = if stream == 0 { 1.0 } else { -1.0 };
        let (dy, dz) = if stream == 0 {
            (0.0, 0.0)
        } else {
            (offset[0], offset[1])
        };
        for j in 0..n {
            let y = lane * (j as f64 - 0.5 * (n - 1) as f64) + dy;
            let behind = rng.random_range(0.0..2.0);
            let v0 = dir * mean_speed * rng.random_range(0.6..1.4);
            let v1 = v0 * rng.random_range(0.8..1.2);
            let a = [dir * (-from - behind), y, dz];
            let b = [dir * (to - behind), y, dz];
            let rotate = |v: f64| place.rotation.apply([v, 0.0, 0.0]);
            out.push(craft(
                1.0,
                (place.apply(a), rotate(v0)),
                (place.apply(b), rotate(v1)),
            ));
        }
    }
    out
}

/// `convergence`: 2-8 from 15-35 LU away (a Fibonacci sphere, randomly rotated, each radius
/// jittered 15 %), at rest or already closing at up to 0.8 times the mean speed, to rest in a
/// tight cluster: random points of a small ball spaced d + 0.2-0.6 LU, assigned at random.
pub fn convergence(rng: &mut ChaCha8Rng, c: &mut Common) -> Vec<Spacecraft> {
    let m = rng.random_range(2..=8usize);
    let far = rng.random_range(15.0..35.0);
    let closing = if rng.random_bool(0.5) {
        rng.random_range(0.0..0.8) * far / c.horizon_tu
    } else {
        0.0
    };
    let gap = KEEP_OUT_LU + rng.random_range(0.2..0.6);
    let ball = gap * (0.5 + 0.5 * (m as f64).cbrt());
    let cluster = spread_in_ball(rng, m, ball, gap);
    let centre = random_in_box(rng, 3.0);
    let place = Placement::random(rng, 0.0);
    let order = permutation(rng, m);
    let dirs: Vec<Vec3> = fibonacci_sphere(m)
        .into_iter()
        .map(|d| place.rotation.apply(d))
        .collect();
    (0..m)
        .map(|k| {
            let r = far * rng.random_range(0.85..1.15);
            let a = add(centre, scale(dirs[k], r));
            let v = scale(dirs[k], -closing);
            let b = add(centre, cluster[order[k]]);
            craft(1.0, (a, v), (b, [0.0; 3]))
        })
        .collect()
}
