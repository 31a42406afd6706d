//! The `overtaking` kind: a file of spacecraft coasting along x, and one or two faster ones
//! in (nearly) the same lane that start behind the file and end ahead of it, so they must
//! swerve past it. The control bound pays for that swerve (`Common::floor_fu`), so every
//! problem is feasible: the fast ones fly their minimum-energy cubics along the lane and,
//! across it, bang-bang out to the keep-out before they close within d of the file's tail and
//! back after they are d clear of its head; the file flies its cubics. The two motions add
//! (scene frame), so `factor * (peak along + peak across)` bounds every world-frame component
//! whatever the scene's rotation.

use super::bound::{axis_need, craft, cubic_position, Common, KEEP_OUT_LU, OFFSET_REACH_LU};
use super::geometry::Placement;
use rand::Rng;
use rand_chacha::ChaCha8Rng;
use reconfig_core::pseudospectral::Spacecraft;

/// Samples of the horizon when finding where the fast ones are within reach of the file.
const SAMPLES: usize = 2000;

/// Extra distance kept in the swerve and in the reach, LU.
const MARGIN_LU: f64 = 0.1;

/// One axis's ends: position, velocity at the start; position, velocity at the end.
type Ends = (f64, f64, f64, f64);

/// The first and last time at which a fast spacecraft (`fast` ends, along x) is within
/// `reach` along x of a file member (`file` ends), both flying their cubics; `None` when never.
fn conflict(fast: &[Ends], file: &[Ends], horizon: f64, reach: f64) -> Option<(f64, f64)> {
    let at = |e: &Ends, t: f64| cubic_position(e.0, e.1, e.2, e.3, horizon, t);
    let mut span: Option<(f64, f64)> = None;
    for k in 0..=SAMPLES {
        let t = horizon * k as f64 / SAMPLES as f64;
        let close = fast
            .iter()
            .any(|f| file.iter().any(|s| (at(f, t) - at(s, t)).abs() < reach));
        if close {
            span = Some(span.map_or((t, t), |(first, _)| (first, t)));
        }
    }
    span
}

/// `overtaking`: a file of 1-7 spacecraft at 0.2-1 LU/TU along x (gaps 1-1.5 times the
/// spacing, the whole file ending up to 1 LU off its coast) and 1 (2 from 4 spacecraft on)
/// faster ones 0-1.5 LU to the side, one spacing apart, starting behind the file's tail and
/// ending ahead of its head by 1-1.4 times `2 d + (file + fast ones' length) / 2` (so the file
/// is reached after about a quarter of the horizon at the earliest), at 0.9-1.1 times the
/// speed that distance asks (at both ends); the bound at least pays for the swerve.
pub fn overtaking(rng: &mut ChaCha8Rng, c: &mut Common) -> Vec<Spacecraft> {
    let m = rng.random_range(2..=8usize);
    let fast = if m >= 4 {
        rng.random_range(1..=2usize)
    } else {
        1
    };
    let slow = m - fast;
    let t = c.horizon_tu;
    let speed = rng.random_range(0.2..1.0);
    let drift = rng.random_range(-1.0..1.0);
    let mut xs = vec![0.0];
    for k in 1..slow {
        let gap = c.spacing_lu * rng.random_range(1.0..1.5);
        xs.push(xs[k - 1] - gap);
    }
    let (head, tail) = (xs[0], xs[slow - 1]);
    let column = (head - tail) + c.spacing_lu * (fast - 1) as f64;
    let least = 2.0 * KEEP_OUT_LU + 0.5 * column;
    let behind = least * rng.random_range(1.0..1.4);
    let ahead = least * rng.random_range(1.0..1.4);
    let side = rng.random_range(0.0..1.5);
    let pace = rng.random_range(0.9..1.1);
    let place = Placement::random(rng, OFFSET_REACH_LU);

    let file: Vec<Ends> = xs
        .iter()
        .map(|&x| (x, speed, x + speed * t + drift, speed))
        .collect();
    let head_end = head + speed * t + drift;
    let spacing = c.spacing_lu;
    let runners: Vec<Ends> = (0..fast)
        .map(|j| {
            let a = tail - behind - spacing * j as f64;
            // The first behind ends first ahead: the fast ones keep their order.
            let b = head_end + ahead + spacing * (fast - 1 - j) as f64;
            let v = (b - a) / t * pace;
            (a, v, b, v)
        })
        .collect();

    // The swerve: out by `lift` across the lane before the first conflict, back after the last.
    let lift = KEEP_OUT_LU + MARGIN_LU - side;
    let across = match conflict(&runners, &file, t, KEEP_OUT_LU + MARGIN_LU) {
        Some((first, last)) => {
            let window = first.min(t - last).max(1e-3 * t);
            4.0 * lift / (window * window)
        }
        None => 0.0,
    };
    let along = runners
        .iter()
        .map(|e| axis_need(e.0, e.1, e.2, e.3, t))
        .fold(0.0, f64::max);
    c.floor_fu = c.factor * (along + across);

    let along = |v: f64| place.rotation.apply([v, 0.0, 0.0]);
    let state = |x: f64, y: f64| place.apply([x, y, 0.0]);
    file.iter()
        .map(|e| (e, 0.0))
        .chain(runners.iter().map(|e| (e, side)))
        .map(|(e, y)| {
            craft(
                1.0,
                (state(e.0, y), along(e.1)),
                (state(e.2, y), along(e.3)),
            )
        })
        .collect()
}
