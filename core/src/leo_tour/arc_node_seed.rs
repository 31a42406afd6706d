//! The node seed of the per-arc grid (three or more impulses): a Hohmann transfer to the
//! client's orbit that leaves at a crossing of the client's plane (a relative node) and splits
//! the plane change between its two burns as the two speeds make cheapest; the last leg then
//! only phases along the client's orbit. The grid's own epochs fall anywhere on the orbit, up
//! to a quarter revolution from a node, where a plane change costs far more; ranked there, the
//! plans of this shape (the cheapest on the published arcs: the transfer made at the nodes, a
//! small last burn) were not among the candidates refined.

use super::arc::{period_s, semi_major_km, Client, Ctx, Point};
use super::j2::{pos, vel, State};
use super::shoot::Family;
use super::types::MAX_VARS;
use super::work_units;
use crate::indexed::IndexedExt as _;
use crate::vec3::{add, cross, dot, norm, scale, sub, Vec3};
use core::f64::consts::{FRAC_PI_2, PI};

/// Golden-section iterations of the plane-change split (the interval shrinks to 0.618^24 =
/// 1e-5 of the plane change).
const SPLIT_ITERATIONS: u32 = 24;

/// Planes closer than this (sine of the angle between them) have no node: no seed.
const MIN_PLANE_SINE: f64 = 1e-9;

fn unit(v: &Vec3) -> Option<Vec3> {
    let n = norm(v);
    (n > 0.0 && n.is_finite()).then(|| scale(v, 1.0 / n))
}

/// The relative geometry of the chaser's and the client's planes at one epoch.
struct Planes {
    /// The chaser's orbit normal (unit).
    ha: Vec3,
    /// The line of nodes, `ha x hb` (unit).
    k: Vec3,
    /// The angle from the chaser's plane to the client's about `k`, rad.
    theta_rad: f64,
}

fn planes(sa: &State, sb: &State) -> Option<Planes> {
    let ha = unit(&cross(&pos(sa), &vel(sa)))?;
    let hb = unit(&cross(&pos(sb), &vel(sb)))?;
    let k = cross(&ha, &hb);
    let sine = norm(&k);
    if sine.is_nan() || sine <= MIN_PLANE_SINE {
        return None;
    }
    Some(Planes {
        ha,
        k: scale(&k, 1.0 / sine),
        theta_rad: libm::atan2(sine, dot(&ha, &hb)),
    })
}

/// The share `f` of the plane change `theta` made by the first burn of a Hohmann transfer
/// (first burn from `v1` to `vp` turning `f theta`, second from `va` to `v2` turning the
/// rest) that makes the two burns cheapest: golden section on `[0, 1]`. When the burns change
/// speed the sum is unimodal in `f` (for small angles a sum of norms of affine functions of
/// `f`); with no speed change a plane change is cheapest in one burn, at an end, which the
/// section also finds.
fn split_cost(v1: f64, vp: f64, va: f64, v2: f64, theta: f64, f: f64) -> f64 {
    let burn = |u: f64, w: f64, angle: f64| {
        libm::sqrt((u * u + w * w - 2.0 * u * w * libm::cos(angle)).max(0.0))
    };
    burn(v1, vp, f * theta) + burn(va, v2, (1.0 - f) * theta)
}

fn plane_change_split(v1: f64, vp: f64, va: f64, v2: f64, theta: f64) -> f64 {
    let cost = |f: f64| split_cost(v1, vp, va, v2, theta, f);
    let ratio = 0.5 * (libm::sqrt(5.0) - 1.0);
    let (mut lo, mut hi) = (0.0, 1.0);
    // The two inner points, each kept with its cost: one new cost per iteration.
    let mut a = hi - ratio * (hi - lo);
    let mut b = lo + ratio * (hi - lo);
    let (mut ca, mut cb) = (cost(a), cost(b));
    for _ in 0..SPLIT_ITERATIONS {
        if ca <= cb {
            hi = b;
            (b, cb) = (a, ca);
            a = hi - ratio * (hi - lo);
            ca = cost(a);
        } else {
            lo = a;
            (a, ca) = (b, cb);
            b = lo + ratio * (hi - lo);
            cb = cost(b);
        }
    }
    0.5 * (lo + hi)
}

/// The epoch of the chaser's crossing of the client's plane nearest `t1` (from the two-body
/// angular rate of the chaser's orbit at `sa`, its state at `t1`; `sb` the client's), moved
/// half a revolution on when it falls before the arc start.
fn node_epoch(mu: f64, t1: f64, sa: &State, sb: &State) -> Option<f64> {
    let p = planes(sa, sb)?;
    // Angle from the chaser to the line of nodes in the direction of motion; the nearer of
    // its two ends.
    let ra_hat = unit(&pos(sa))?;
    let mut ang = libm::atan2(dot(&cross(&ra_hat, &p.k), &p.ha), dot(&ra_hat, &p.k));
    if ang > FRAC_PI_2 {
        ang -= PI;
    } else if ang < -FRAC_PI_2 {
        ang += PI;
    }
    let period = period_s(mu, sa);
    if period.is_nan() || period <= 0.0 {
        return None;
    }
    let tn = t1 + ang / (2.0 * PI) * period;
    Some(if tn < 0.0 { tn + 0.5 * period } else { tn })
}

/// The Hohmann transfer from the chaser at a node (`sa`) to the semi-major axis `a_b_km` of
/// the client (`sb`, at the same epoch), the plane change split between its burns: the first
/// burn (inertial, km/s) and the time of flight, s.
fn node_transfer(mu: f64, sa: &State, sb: &State, a_b_km: f64) -> Option<(Vec3, f64)> {
    let p = planes(sa, sb)?;
    let ra = pos(sa);
    let r1 = norm(&ra);
    let at = 0.5 * (r1 + a_b_km);
    let tof = PI * libm::sqrt(at * at * at / mu);
    let (vp, vapo) = (
        libm::sqrt(mu * (2.0 / r1 - 1.0 / at)),
        libm::sqrt(mu * (2.0 / a_b_km - 1.0 / at)),
    );
    let f = plane_change_split(
        norm(&vel(sa)),
        vp,
        vapo,
        libm::sqrt(mu / a_b_km),
        p.theta_rad,
    );
    // The transfer's plane: the chaser's turned by f theta about the line of nodes.
    let turn = f * p.theta_rad;
    let n = add(
        &scale(&p.ha, libm::cos(turn)),
        &scale(&cross(&p.k, &p.ha), libm::sin(turn)),
    );
    let along = unit(&cross(&n, &ra))?;
    let dv1 = sub(&scale(&along, vp), &vel(sa));
    (dv1.iter().all(|v| v.is_finite()) && tof.is_finite()).then_some((dv1, tof))
}

/// The node seed's own arithmetic, what [`work_units::NODE_SEED`] pays for (the kernel case
/// `node-seed-arithmetic` runs it alone on the M7): the node's epoch from `t1`, then the
/// transfer from the same states.
pub(crate) fn seed_arithmetic(
    mu: f64,
    t1: f64,
    sa: &State,
    sb: &State,
) -> Option<(f64, Vec3, f64)> {
    let tn = node_epoch(mu, t1, sa, sb)?;
    let (dv1, tof) = node_transfer(mu, sa, sb, semi_major_km(mu, sb)?)?;
    Some((tn, dv1, tof))
}

impl Ctx<'_> {
    /// The node seed nearest the grid epoch `t1`: the chaser's nearest crossing of the
    /// client's plane, a Hohmann transfer from there to the client's semi-major axis with the
    /// plane change split between its burns, the last leg's family the cheapest near `near`
    /// (all when `None`). `None` when the planes coincide, the crossing or the transfer falls
    /// outside the arc, or a flight fails.
    pub(crate) fn node_seed(&mut self, t1: f64, near: Option<Family>) -> Option<Point> {
        if !self.meter.spend(work_units::NODE_SEED) {
            return None;
        }
        let mu = self.settings.mu_km3_s2;
        let sa = self.client_state(Client::A, t1)?;
        let sb = self.client_state(Client::B, t1)?;
        let tn = node_epoch(mu, t1, &sa, &sb)?;
        let a_b = semi_major_km(mu, &sb)?;
        let sa = self.client_state(Client::A, tn)?;
        let sb = self.client_state(Client::B, tn)?;
        let (dv1, tof) = node_transfer(mu, &sa, &sb, a_b)?;
        let free = self.impulses.saturating_sub(1);
        let mut x = [0.0; MAX_VARS];
        // The epochs: the node, the Hohmann arrival, any later free impulse (with a zero
        // burn) halfway from there to the arrival.
        let t2 = tn + tof;
        for (k, xi) in x.iter_mut().take(free).indexed() {
            *xi = match k {
                0 => tn,
                1 => t2,
                _ => t2 + 0.5 * (self.tf - t2) * (k as f64 - 1.0) / (free as f64 - 2.0),
            };
        }
        self.epochs(&x)?;
        self.seed_point(x, &dv1, t2, near)
    }
}

#[cfg(test)]
mod tests {
    use super::{plane_change_split, split_cost};

    const MU: f64 = crate::astro::EARTH_MU_KM3_S2;

    /// The least of `split_cost` over 10,001 shares.
    fn scanned(v: (f64, f64, f64, f64), theta: f64) -> f64 {
        (0..=10_000)
            .map(|k| split_cost(v.0, v.1, v.2, v.3, theta, f64::from(k) / 10_000.0))
            .fold(f64::INFINITY, f64::min)
    }

    #[test]
    fn the_split_is_the_cheapest_share_of_the_plane_change() {
        // Example I's arc 2 -> 5: 6878 to 7178 km, 2.6 degrees of plane change.
        let (r1, r2) = (6878.14, 7178.14);
        let at = 0.5 * (r1 + r2);
        let v1 = libm::sqrt(MU / r1);
        let v2 = libm::sqrt(MU / r2);
        let vp = libm::sqrt(MU * (2.0 / r1 - 1.0 / at));
        let va = libm::sqrt(MU * (2.0 / r2 - 1.0 / at));
        let theta = 0.04522;
        let f = plane_change_split(v1, vp, va, v2, theta);
        let c = split_cost(v1, vp, va, v2, theta, f);
        assert!(
            (c - scanned((v1, vp, va, v2), theta)).abs() < 1e-9,
            "{f} {c}"
        );
        // The apoapsis burn is the slower: it takes the larger share of the turn.
        assert!(f > 0.2 && f < 0.5, "{f}");
        // Both ends are dearer by metres per second.
        assert!(split_cost(v1, vp, va, v2, theta, 0.0) > c + 0.005);
        assert!(split_cost(v1, vp, va, v2, theta, 1.0) > c + 0.005);
    }

    #[test]
    fn with_no_speed_change_the_plane_change_is_made_in_one_burn() {
        let theta = 0.045;
        let f = plane_change_split(7.5, 7.5, 7.5, 7.5, theta);
        let c = split_cost(7.5, 7.5, 7.5, 7.5, theta, f);
        let one_burn = 2.0 * 7.5 * libm::sin(0.5 * theta);
        assert!((c - one_burn).abs() < 1e-9, "{f} {c} {one_burn}");
        assert!((c - scanned((7.5, 7.5, 7.5, 7.5), theta)).abs() < 1e-9);
    }
}
