//! What every generated kind shares: the keep-out and the clearance of the ends, the common
//! draws (horizon, degree, the control bound's factor, the lattice spacing) and the control
//! bound set from the least force the ends need, so that every problem is feasible.
//!
//! The need of one axis of one spacecraft, in FU: at rest at both ends, `m 4 |D| / T^2` for
//! the distance `D` (bang-bang, the least bound that reaches it); otherwise the peak of the
//! minimum-energy cubic that meets both ends, `m max(|a(0)|, |a(T)|)` with
//! `a(0) = 6 dp / T^2 - 2 dv / T`, `a(T) = -6 dp / T^2 + 4 dv / T`, `dp = D - v0 T`,
//! `dv = v1 - v0` (that cubic stays within the bound, so the ends are reachable). A problem's
//! need is the largest over its spacecraft and axes; its bound is `max(factor * need, floor,
//! 0.05)`, where a kind whose spacecraft must swerve to get by each other at all may set a
//! floor that pays for the swerve (`overtaking`; 0 otherwise).

use super::geometry::Vec3;
use rand::Rng;
use rand_chacha::ChaCha8Rng;
use reconfig_core::pseudospectral::{Problem, Spacecraft};

/// Keep-out distance d of every generated kind, LU.
pub const KEEP_OUT_LU: f64 = 2.0;

/// Least distance between two spacecraft's initial (or final) positions: d + 0.1 LU (the
/// planner rejects ends closer than d).
pub const END_CLEARANCE_LU: f64 = KEEP_OUT_LU + 0.1;

/// Lattice spacings (and the shapes' least gaps) are drawn from d + 0.2 to d + 1.5 LU.
pub const SPACING_LU: std::ops::Range<f64> = KEEP_OUT_LU + 0.2..KEEP_OUT_LU + 1.5;

/// Horizons T are drawn from this range, TU.
pub const HORIZON_TU: std::ops::Range<f64> = 6.0..20.0;

/// Degrees N are drawn from this range.
pub const DEGREES: std::ops::RangeInclusive<u16> = 8..=24;

/// The control bound's factor over the need, for the tight kinds.
pub const TIGHT_FACTOR: std::ops::Range<f64> = 1.15..1.5;

/// The control bound's factor over the need, for the other kinds.
pub const LOOSE_FACTOR: std::ops::Range<f64> = 1.5..4.0;

/// The least control bound set, FU.
pub const MIN_CONTROL_FU: f64 = 0.05;

/// Offsets of a shape's or a scene's centre are drawn in a cube of this half-width, LU.
pub const OFFSET_REACH_LU: f64 = 10.0;

/// The draws every kind makes first, in this order.
#[derive(Clone, Copy, Debug)]
pub struct Common {
    /// Horizon T, TU (a kind may change it before [`finish`]).
    pub horizon_tu: f64,
    /// Degree N.
    pub degree: u16,
    /// The control bound over the need.
    pub factor: f64,
    /// The shape's spacing (least gap), LU.
    pub spacing_lu: f64,
    /// A tight kind: rest to rest at both ends, factor from [`TIGHT_FACTOR`].
    pub tight: bool,
    /// The least control bound the kind's manoeuvre asks beyond its ends' need (a swerve), FU;
    /// 0 unless the kind sets it.
    pub floor_fu: f64,
}

impl Common {
    /// The common draws of a kind (`tight` picks the factor's range).
    pub fn draw(rng: &mut ChaCha8Rng, tight: bool) -> Common {
        let horizon_tu = rng.random_range(HORIZON_TU);
        let degree = rng.random_range(DEGREES);
        let factor = rng.random_range(if tight { TIGHT_FACTOR } else { LOOSE_FACTOR });
        let spacing_lu = rng.random_range(SPACING_LU);
        Common {
            horizon_tu,
            degree,
            factor,
            spacing_lu,
            tight,
            floor_fu: 0.0,
        }
    }
}

/// One spacecraft of mass `mass` from `a` (position, velocity) to `b`.
pub fn craft(mass: f64, a: (Vec3, Vec3), b: (Vec3, Vec3)) -> Spacecraft {
    let state = |(p, v): (Vec3, Vec3)| [p[0], p[1], p[2], v[0], v[1], v[2]];
    Spacecraft {
        mass_mu: mass,
        initial_state: state(a),
        final_state: state(b),
    }
}

/// A spacecraft of unit mass at rest at `a`, to rest at `b`.
pub fn rest_to_rest(a: Vec3, b: Vec3) -> Spacecraft {
    craft(1.0, (a, [0.0; 3]), (b, [0.0; 3]))
}

/// The least force one axis needs (per unit mass), as the module docs define it.
pub fn axis_need(p0: f64, v0: f64, p1: f64, v1: f64, horizon_tu: f64) -> f64 {
    let t = horizon_tu;
    if v0 == 0.0 && v1 == 0.0 {
        return 4.0 * (p1 - p0).abs() / (t * t);
    }
    let dp = p1 - p0 - v0 * t;
    let dv = v1 - v0;
    let start = 6.0 * dp / (t * t) - 2.0 * dv / t;
    let end = -6.0 * dp / (t * t) + 4.0 * dv / t;
    start.abs().max(end.abs())
}

/// The position at `t` of the minimum-energy cubic of one axis from `(p0, v0)` to `(p1, v1)`
/// in `horizon_tu` (its acceleration runs linearly from `a(0)` to `a(T)`, as [`axis_need`]).
pub fn cubic_position(p0: f64, v0: f64, p1: f64, v1: f64, horizon_tu: f64, t: f64) -> f64 {
    let h = horizon_tu;
    let dp = p1 - p0 - v0 * h;
    let dv = v1 - v0;
    let c0 = 6.0 * dp / (h * h) - 2.0 * dv / h;
    let c1 = (6.0 * dv * h - 12.0 * dp) / (h * h * h);
    p0 + v0 * t + c0 * t * t / 2.0 + c1 * t * t * t / 6.0
}

/// The least force one spacecraft needs on its worst axis, FU.
pub fn craft_need(c: &Spacecraft, horizon_tu: f64) -> f64 {
    let (a, b) = (&c.initial_state, &c.final_state);
    (0..3)
        .map(|k| c.mass_mu * axis_need(a[k], a[k + 3], b[k], b[k + 3], horizon_tu))
        .fold(0.0, f64::max)
}

/// A problem's need: the largest over its spacecraft, FU.
pub fn need(p: &Problem) -> f64 {
    p.spacecraft
        .iter()
        .map(|c| craft_need(c, p.horizon_tu))
        .fold(0.0, f64::max)
}

/// Whether every two spacecraft's initial positions, and final positions, are at least
/// [`END_CLEARANCE_LU`] apart.
pub fn ends_apart(p: &Problem) -> bool {
    let crafts = &p.spacecraft;
    crafts.iter().enumerate().all(|(i, a)| {
        crafts[i + 1..].iter().all(|b| {
            let gap = |x: &[f64; 6], y: &[f64; 6]| {
                ((x[0] - y[0]).powi(2) + (x[1] - y[1]).powi(2) + (x[2] - y[2]).powi(2)).sqrt()
            };
            gap(&a.initial_state, &b.initial_state) >= END_CLEARANCE_LU
                && gap(&a.final_state, &b.final_state) >= END_CLEARANCE_LU
        })
    })
}

/// The problem of `crafts` (at most 8 kept) with the common draws, its control bound
/// `max(factor * need, floor_fu, MIN_CONTROL_FU)`. A tight kind's horizon is shortened first where the
/// floor would otherwise set the bound (its spacecraft are at rest at both ends, so the need
/// grows as `1 / T^2`), keeping the bound `factor` times the need.
pub fn finish(common: &Common, crafts: Vec<Spacecraft>) -> Problem {
    let mut list = heapless::Vec::new();
    for c in crafts.into_iter().take(8) {
        let _ = list.push(c);
    }
    let mut p = Problem {
        horizon_tu: common.horizon_tu,
        max_control_fu: 1.0,
        keep_out_lu: KEEP_OUT_LU,
        degree: common.degree,
        test_points: true,
        spacecraft: list,
    };
    let mut need = need(&p);
    if common.tight && need > 0.0 && common.factor * need < MIN_CONTROL_FU {
        p.horizon_tu *= (common.factor * need / MIN_CONTROL_FU).sqrt();
        need = self::need(&p);
    }
    p.max_control_fu = (common.factor * need)
        .max(common.floor_fu)
        .max(MIN_CONTROL_FU);
    p
}
