//! A lower bound on the Δv of any impulsive rendezvous arc between two clients on
//! near-circular orbits under J2: the plane change that the impulses must make and the
//! semi-major-axis change, combined root-sum-square. The sequencing prunes with it.
//!
//! **Plane part.** An impulse `Δv` at transverse velocity `v_t` turns the orbit normal by an
//! angle `φ` with `tan φ = |Δv_n| / v_t'` (`v_t'` the transverse velocity after it), so
//! `|Δv_n| >= v_lo sin φ`, where `v_lo` is the least transverse velocity the chaser can have.
//! The rotations add up (triangle inequality on the sphere) and `sin` is subadditive on
//! `[0, π]`, so `Σ|Δv_n| >= v_lo sin θ` with `θ` the angle that the impulses must turn.
//! Between the impulses J2 turns the normal about the polar axis (the node drifts) at the
//! secular rate `Ω̇(a, i)` of the orbit flown; with the chaser's orbits inside a band of
//! semi-major axis and inclination the drift over the arc lies in `[Ω̇_lo T, Ω̇_hi T]`, so `θ`
//! is at least the angle between the start plane (drifted by any value of that interval) and
//! the client's plane at the arrival: the smallest node difference of the interval.
//!
//! **Semi-major-axis part.** The in-plane components must at least make Hohmann's transfer
//! between the two radii (optimal between coplanar circular orbits for radius ratios below
//! 11.94); `Σ|Δv| >= sqrt((Σ|Δv_n|)^2 + (Σ|Δv_p|)^2)` (Minkowski).
//!
//! **What is assumed** (first order): the chaser's orbits stay inside the band (the clients'
//! semi-major axes widened by the band margin on each side, their inclinations by one
//! degree), `v_lo` is the circular velocity at the band's top reduced by the clients' largest
//! eccentricity, the node drift is the first-order secular one, and the whole bound is
//! multiplied by `1 - margin` for what the first-order picture leaves out. The bound is not
//! proven for every transfer; the sequencing checks it against every arc it plans and says
//! so when one is cheaper than its bound (`SequenceStatus::BoundViolated`).

use super::j2::{pos, vel, State};
use crate::astro::Gravity;
use crate::vec3::{cross, dot, norm};
use core::f64::consts::PI;
use serde::{Deserialize, Serialize};

/// The plane and size of a client's orbit at the tour epoch, with its secular node rate.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Plane {
    /// Semi-major axis (osculating), km.
    pub a_km: f64,
    /// Eccentricity (osculating).
    pub e: f64,
    /// Inclination, rad.
    pub i_rad: f64,
    /// Right ascension of the ascending node at the tour epoch, rad.
    pub raan_rad: f64,
    /// First-order secular J2 node rate, rad/s.
    pub raan_rate_rad_s: f64,
}

/// The first-order secular J2 node rate of an orbit, rad/s (planner B's secular theory, the
/// one implementation).
pub fn raan_rate_rad_s(g: &Gravity, a_km: f64, e: f64, i_rad: f64) -> f64 {
    let [_, _, _, raan, _, _] =
        crate::impulsive::secular::rates_with(g, &[a_km, e, i_rad, 0.0, 0.0, 0.0]);
    raan
}

/// The plane of `s`; `None` for a degenerate or non-elliptic state.
pub fn plane_of(g: &Gravity, s: &State) -> Option<Plane> {
    let r = pos(s);
    let v = vel(s);
    let rn = norm(&r);
    let h = cross(&r, &v);
    let hn = norm(&h);
    if !(rn > 0.0 && hn > 0.0) {
        return None;
    }
    let energy = 0.5 * dot(&v, &v) - g.mu_km3_s2 / rn;
    if energy.is_nan() || energy >= 0.0 {
        return None;
    }
    let a_km = -g.mu_km3_s2 / (2.0 * energy);
    let p = hn * hn / g.mu_km3_s2;
    let e = libm::sqrt((1.0 - p / a_km).max(0.0));
    let i_rad = libm::acos((h[2] / hn).clamp(-1.0, 1.0));
    let raan_rad = libm::atan2(h[0], -h[1]);
    let plane = Plane {
        a_km,
        e,
        i_rad,
        raan_rad,
        raan_rate_rad_s: raan_rate_rad_s(g, a_km, e, i_rad),
    };
    [a_km, e, i_rad, raan_rad, plane.raan_rate_rad_s]
        .iter()
        .all(|x| x.is_finite())
        .then_some(plane)
}

/// How conservative the bound is.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct BoundSettings {
    /// Semi-major-axis band margin on each side of the two clients', km.
    pub band_margin_km: f64,
    /// Inclination band margin on each side, rad.
    pub band_margin_rad: f64,
    /// The bound is multiplied by `1 - margin`.
    pub margin: f64,
}

impl Default for BoundSettings {
    fn default() -> Self {
        Self {
            band_margin_km: 100.0,
            band_margin_rad: 1.0_f64.to_radians(),
            margin: 0.05,
        }
    }
}

/// The angle between two planes of inclinations `i1`, `i2` whose nodes differ by `d_raan`.
fn plane_angle(i1: f64, i2: f64, d_raan: f64) -> f64 {
    let c = libm::cos(i1) * libm::cos(i2) + libm::sin(i1) * libm::sin(i2) * libm::cos(d_raan);
    libm::acos(c.clamp(-1.0, 1.0))
}

/// The value of `[lo, hi]` (mod 2π) closest to zero, as an absolute angle in `[0, π]`.
fn closest_to_zero(lo: f64, hi: f64) -> f64 {
    // A NaN span, or one covering a whole turn, reaches zero.
    if (hi - lo).is_nan() || hi - lo >= 2.0 * PI {
        return 0.0;
    }
    // Shift so that the interval's middle is in (-π, π].
    let mid = 0.5 * (lo + hi);
    let shift = 2.0 * PI * libm::round(mid / (2.0 * PI));
    let (lo, hi) = (lo - shift, hi - shift);
    if lo <= 0.0 && hi >= 0.0 {
        0.0
    } else if lo > 0.0 {
        // Both positive: the nearer of lo and (hi - 2π).
        lo.min((2.0 * PI - hi).max(0.0))
    } else {
        (-hi).min((lo + 2.0 * PI).max(0.0))
    }
}

/// Hohmann's Δv between circular radii `r1`, `r2`, km/s.
fn hohmann_km_s(mu: f64, r1: f64, r2: f64) -> f64 {
    let s = r1 + r2;
    let d1 = libm::sqrt(mu / r1) * (libm::sqrt(2.0 * r2 / s) - 1.0);
    let d2 = libm::sqrt(mu / r2) * (1.0 - libm::sqrt(2.0 * r1 / s));
    d1.abs() + d2.abs()
}

/// The chaser's node-rate range over the band between `a` and `b`, rad/s.
fn drift_range(g: &Gravity, a: &Plane, b: &Plane, bs: &BoundSettings) -> (f64, f64, f64) {
    let a_lo = (a.a_km.min(b.a_km) - bs.band_margin_km).max(g.re_km);
    let a_hi = a.a_km.max(b.a_km) + bs.band_margin_km;
    let i_lo = (a.i_rad.min(b.i_rad) - bs.band_margin_rad).max(0.0);
    let i_hi = (a.i_rad.max(b.i_rad) + bs.band_margin_rad).min(PI);
    let e = a.e.max(b.e);
    let mut lo = f64::INFINITY;
    let mut hi = f64::NEG_INFINITY;
    for ak in [a_lo, a_hi] {
        for ik in [i_lo, i_hi] {
            // The rate is monotone in a and in cos i, and e only scales it by (1 - e^2)^-2.
            for ek in [0.0, e] {
                let w = raan_rate_rad_s(g, ak, ek, ik);
                lo = lo.min(w);
                hi = hi.max(w);
            }
        }
    }
    (lo, hi, a_hi)
}

/// Lower bound (m/s) on an arc from client `a`'s state at `start_s` to client `b`'s at
/// `start_s + duration_s` (both from the tour epoch).
pub fn arc_bound_mps(
    g: &Gravity,
    a: &Plane,
    b: &Plane,
    start_s: f64,
    duration_s: f64,
    bs: &BoundSettings,
) -> f64 {
    let (w_lo, w_hi, a_hi) = drift_range(g, a, b, bs);
    let raan_a = a.raan_rad + a.raan_rate_rad_s * start_s;
    let raan_b = b.raan_rad + b.raan_rate_rad_s * (start_s + duration_s);
    let d_lo = raan_a + w_lo * duration_s - raan_b;
    let d_hi = raan_a + w_hi * duration_s - raan_b;
    combine(g, a, b, closest_to_zero(d_lo, d_hi), a_hi, bs)
}

/// Lower bound (m/s) on an arc from `a` to `b` starting anywhere in `[0, horizon_s]` and
/// lasting at most `horizon_s`.
pub fn arc_bound_any_mps(
    g: &Gravity,
    a: &Plane,
    b: &Plane,
    horizon_s: f64,
    bs: &BoundSettings,
) -> f64 {
    let (w_lo, w_hi, a_hi) = drift_range(g, a, b, bs);
    // ΔΩ = Ω_a0 - Ω_b0 + (Ω̇_a - Ω̇_b) t0 + (w - Ω̇_b) T: linear in t0, T and w, so its range
    // over the box is spanned by the corners.
    let base = a.raan_rad - b.raan_rad;
    let mut lo = f64::INFINITY;
    let mut hi = f64::NEG_INFINITY;
    for t0 in [0.0, horizon_s] {
        for t in [0.0, horizon_s] {
            for w in [w_lo, w_hi] {
                let d = base
                    + (a.raan_rate_rad_s - b.raan_rate_rad_s) * t0
                    + (w - b.raan_rate_rad_s) * t;
                lo = lo.min(d);
                hi = hi.max(d);
            }
        }
    }
    combine(g, a, b, closest_to_zero(lo, hi), a_hi, bs)
}

fn combine(g: &Gravity, a: &Plane, b: &Plane, d_raan: f64, a_hi: f64, bs: &BoundSettings) -> f64 {
    let theta = plane_angle(a.i_rad, b.i_rad, d_raan).min(0.5 * PI);
    let e = a.e.max(b.e).min(0.99);
    let v_lo = libm::sqrt(g.mu_km3_s2 / a_hi) * libm::sqrt((1.0 - e) / (1.0 + e));
    let plane = v_lo * libm::sin(theta);
    let size = hohmann_km_s(g.mu_km3_s2, a.a_km, b.a_km);
    let bound = (1.0 - bs.margin) * libm::sqrt(plane * plane + size * size) * 1e3;
    if bound.is_finite() {
        bound.max(0.0)
    } else {
        0.0
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::astro::EARTH_MU_KM3_S2;

    #[test]
    fn closest_to_zero_wraps() {
        assert_eq!(closest_to_zero(-0.1, 0.2), 0.0);
        assert!((closest_to_zero(0.1, 0.2) - 0.1).abs() < 1e-15);
        assert!((closest_to_zero(-0.3, -0.2) - 0.2).abs() < 1e-15);
        assert!((closest_to_zero(2.0 * PI + 0.1, 2.0 * PI + 0.3) - 0.1).abs() < 1e-12);
        // Across π: π + 0.5 is -π + 0.5, nearer to zero than π - 0.1.
        assert!((closest_to_zero(PI - 0.1, PI + 0.5) - (PI - 0.5)).abs() < 1e-12);
        assert_eq!(closest_to_zero(0.0, 7.0), 0.0);
    }

    #[test]
    fn the_bound_of_a_pure_plane_change_is_the_rotation() {
        // Two circular orbits of the same radius, 1 degree apart in inclination, no drift
        // difference: sin(1°) times the circular velocity, less the margins.
        let g = Gravity {
            j2: 0.0,
            ..Gravity::EARTH
        };
        let p = |i: f64| Plane {
            a_km: 7000.0,
            e: 0.0,
            i_rad: i.to_radians(),
            raan_rad: 0.3,
            raan_rate_rad_s: 0.0,
        };
        let bs = BoundSettings {
            band_margin_km: 0.0,
            band_margin_rad: 0.0,
            margin: 0.0,
        };
        let b = arc_bound_mps(&g, &p(50.0), &p(51.0), 0.0, 1e5, &bs);
        let v = (EARTH_MU_KM3_S2 / 7000.0).sqrt() * 1e3;
        assert!((b - v * 1.0_f64.to_radians().sin()).abs() < 1e-9, "{b}");
        // And a pure Hohmann when the planes agree.
        let q = Plane {
            a_km: 7100.0,
            ..p(50.0)
        };
        let h = arc_bound_mps(&g, &p(50.0), &q, 0.0, 1e5, &bs);
        assert!((h - hohmann_km_s(EARTH_MU_KM3_S2, 7000.0, 7100.0) * 1e3).abs() < 1e-9);
    }
}
