//! Radial-impulse phasing: a radial burn `w` keeps the angular momentum, so the orbit's
//! semi-latus rectum stays `a0` and it meets the ring again at true anomaly `+-pi/2`, half a
//! turn later, with the radial velocity reversed; a second radial burn of the same sign and
//! size recircularises. East (gain phase): inward burns, the arc passes perigee; west: outward
//! burns through apogee. Exact in two-body (digest eqs. 9-14 are its small-e limit):
//! `e = w / v0`, `a = a0 / (1 - e^2)`, arc time `2 (acos e - e sqrt(1 - e^2)) / n` through
//! perigee, and the phase change `|pi - n0 * arc|`.

use super::geo::Geo;
use super::maneuver::{Burn, Direction, Maneuver, Method};
use super::work_units::{self, Gauge};
use crate::astro::{M_PER_KM, TWO_PI};

/// Arc time (s) and phase gained (rad, positive = the direction's way) for eccentricity `e`.
pub(crate) fn arc(g: &Geo, dir: Direction, e: f64) -> (f64, f64) {
    let a = g.a0 / (1.0 - e * e);
    let n = libm::sqrt(g.mu / (a * a * a));
    let half = (libm::acos(e) - e * libm::sqrt(1.0 - e * e)) / n;
    match dir {
        Direction::East => {
            let t = 2.0 * half;
            (t, core::f64::consts::PI - g.n0 * t)
        }
        Direction::West => {
            let t = TWO_PI / n - 2.0 * half;
            (t, g.n0 * t - core::f64::consts::PI)
        }
    }
}

/// The manoeuvre, or `None` when the phase needs a perigee below `min_radius_km`.
/// At most `2 max_iter + 4` evaluations of the arc (Illinois then bisection on e).
pub fn radial(
    g: &Geo,
    dir: Direction,
    phase_rad: f64,
    min_radius_km: f64,
    max_iter: u16,
) -> Option<Maneuver> {
    radial_gauged(
        g,
        dir,
        phase_rad,
        min_radius_km,
        max_iter,
        &mut Gauge::paid(),
    )
}

/// [`radial`] with every evaluation taken from `gauge` first (`RADIAL_EVAL`); when one is
/// refused the search stops and returns `None`.
pub(crate) fn radial_gauged(
    g: &Geo,
    dir: Direction,
    phase_rad: f64,
    min_radius_km: f64,
    max_iter: u16,
    gauge: &mut Gauge<'_>,
) -> Option<Maneuver> {
    let eval = work_units::RADIAL_EVAL;
    // Perigee a0 / (1 + e) above the floor; e below 0.9 keeps the arc well conditioned.
    let e_max = (g.a0 / min_radius_km - 1.0).clamp(0.0, 0.9);
    if !(phase_rad.is_finite() && phase_rad >= 0.0) {
        return None;
    }
    if !gauge.take(eval) || arc(g, dir, e_max).1 < phase_rad {
        return None;
    }
    // Phase gained grows with e: Illinois regula falsi (smooth, so a few steps), then
    // bisection on the same test down to adjacent floats, as a plain bisection over the whole
    // range ends (at most `2 max_iter` evaluations).
    let (mut lo, mut hi) = (0.0_f64, e_max);
    let gain = |e: f64| arc(g, dir, e).1 - phase_rad;
    if !gauge.take(eval.saturating_mul(2)) {
        return None;
    }
    let (f_lo, f_hi) = (gain(lo), gain(hi));
    if f_lo < 0.0 && f_hi >= 0.0 {
        // illinois keeps f(a) <= 0 < f(b); the bisection below keeps gain(lo) < 0 <= gain(hi).
        let (a, fa, b, fb) =
            super::root::metered_illinois(gain, (lo, f_lo), (hi, f_hi), max_iter, gauge, eval)?;
        if fa < 0.0 {
            lo = a;
        }
        if fb >= 0.0 && b > lo {
            hi = b;
        }
    }
    let short = |e: f64| arc(g, dir, e).1 < phase_rad;
    let (lo, hi) = super::root::metered_bisection(lo, hi, max_iter, gauge, eval, short)?;
    let e = 0.5 * (lo + hi);
    if !gauge.take(eval) {
        return None;
    }
    let (t, _) = arc(g, dir, e);
    let w = -dir.sign() * e * g.v0 * M_PER_KM;
    let burns = [
        Burn {
            offset_s: 0.0,
            dv_rtn_mps: [w, 0.0, 0.0],
        },
        Burn {
            offset_s: t,
            dv_rtn_mps: [w, 0.0, 0.0],
        },
    ];
    Some(Maneuver::from_burns(
        Method::Radial,
        t,
        g.a0 / (1.0 - e * e),
        0,
        &burns,
    ))
}
