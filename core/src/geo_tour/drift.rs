//! Drift phasing: Hohmann transfer from the ring to a drift orbit of radius
//! `a_m = a0 - s x` (s = +1 east: below the ring), drift, Hohmann transfer back (4 tangential
//! burns). Digest eqs. (5)-(8), exact in two-body and parametrised by the depth `x > 0`:
//!
//! * the two half transfers take `T_t` (period of the transfer orbit) and gain `2 pi - n0 T_t`,
//! * the drift gains `(n_m - n0) t_d`, so `t_d = (s du - (2 pi - n0 T_t)) / (n_m - n0)`,
//! * the leg takes `t(x) = T_t + t_d` and costs `D(x) = 2 (|b1| + |b2|)`.
//!
//! `t` falls and `D` grows with `x`, so "the drift orbit solved from the leg's duration" is a
//! bounded bisection on `x`, and the price problem `min D + lambda t` is the root of
//! `-D'(x) / t'(x) = lambda` (marginal Δv per second of the leg), found by bisection too.

use super::geo::{Dual, Geo};
use super::maneuver::{Burn, Direction, Maneuver, Method};
use super::work_units::{self, Gauge};
use crate::astro::{M_PER_KM, TWO_PI};

/// One leg's drift model.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Drift {
    pub g: Geo,
    pub dir: Direction,
    pub phase_rad: f64,
}

/// Values at a depth x.
#[derive(Clone, Copy, Debug)]
pub(crate) struct DriftPoint {
    /// Total of the four burns, m/s.
    pub dv_mps: f64,
    /// Duration of the leg, s.
    pub duration_s: f64,
    /// Largest burn, m/s.
    pub max_burn_mps: f64,
    /// Drift time alone (negative: the transfers overshoot the phase), s.
    pub drift_s: f64,
}

impl Drift {
    // `Dual` is f64 arithmetic; the integer-overflow lint does not apply.
    #[allow(clippy::arithmetic_side_effects)]
    fn burns_dual(&self, x: Dual) -> (Dual, Dual, Dual, Dual) {
        let g = &self.g;
        let s = self.dir.sign();
        let a0 = Dual::cst(g.a0);
        let am = a0 - x * s;
        let at = (a0 + am) * 0.5;
        let mu = Dual::cst(g.mu);
        let two = Dual::cst(2.0);
        // Burns 1 (leave the ring) and 2 (enter the drift orbit); 3 and 4 mirror them.
        let vt0 = (mu * (two / a0 - at.recip())).sqrt();
        let vtm = (mu * (two / am - at.recip())).sqrt();
        let vm = (mu / am).sqrt();
        let b1 = (vt0 - Dual::cst(g.v0)) * M_PER_KM;
        let b2 = (vm - vtm) * M_PER_KM;
        let tt = (at * at * at / mu).sqrt() * TWO_PI;
        let nm = (mu / (am * am * am)).sqrt();
        let td = (Dual::cst(s * self.phase_rad) - (Dual::cst(TWO_PI) - tt * g.n0))
            / (nm - Dual::cst(g.n0));
        (b1, b2, tt, td)
    }

    /// Cost, duration, largest burn at depth `x_km`.
    pub fn at(&self, x_km: f64) -> DriftPoint {
        let (b1, b2, tt, td) = self.burns_dual(Dual::cst(x_km));
        DriftPoint {
            dv_mps: 2.0 * (b1.v.abs() + b2.v.abs()),
            duration_s: tt.v + td.v,
            max_burn_mps: b1.v.abs().max(b2.v.abs()),
            drift_s: td.v,
        }
    }

    /// Marginal cost of time at depth `x_km`: `-dD/dt`, m/s per s (positive).
    pub fn price_at(&self, x_km: f64) -> f64 {
        self.price_and_point(x_km).0
    }

    /// [`Drift::price_at`] with the cost and the duration at the same depth, from one
    /// evaluation (the value parts are computed exactly as [`Drift::at`] computes them).
    pub fn price_and_point(&self, x_km: f64) -> (f64, f64, f64) {
        let (b1, b2, tt, td) = self.burns_dual(Dual::var(x_km));
        // |b| = -s b for both burns (east: both retrograde).
        let s = self.dir.sign();
        let dd = -2.0 * s * (b1.d + b2.d);
        let dt = tt.d + td.d;
        (-dd / dt, 2.0 * (b1.v.abs() + b2.v.abs()), tt.v + td.v)
    }

    /// Deepest admissible drift orbit: every burn within `cap_mps`, a non-negative drift time,
    /// the drift orbit above `min_radius_km`. These hold for all shallower orbits (each
    /// constraint's violation grows with the depth), so the limit is the root of the largest
    /// scaled violation, found by Illinois regula falsi (a bisection every fourth step, so the
    /// kinks where the binding constraint changes cannot stall it) and finished by bisection
    /// on the admissibility test itself down to adjacent floats: the deepest admissible double,
    /// as a plain bisection over the whole range finds it, in about a quarter of the
    /// evaluations. At most `2 max_iter + 4` evaluations, each taken from `gauge` first
    /// (`DRIFT_EVAL`; when one is refused the search stops and returns `None`). `None` when
    /// even an infinitesimal depth fails (cannot happen for a positive cap).
    pub fn max_depth_km(
        &self,
        cap_mps: f64,
        min_radius_km: f64,
        max_iter: u16,
        gauge: &mut Gauge<'_>,
    ) -> Option<f64> {
        let g = &self.g;
        let ok = |x: f64| {
            let p = self.at(x);
            let am = g.a0 - self.dir.sign() * x;
            p.max_burn_mps <= cap_mps
                && p.drift_s >= 0.0
                && am >= min_radius_km
                && p.duration_s.is_finite()
        };
        // Largest violation, each scaled to order one: <= 0 exactly when `ok` (the duration
        // is finite for every positive depth).
        let violation = |x: f64| {
            let p = self.at(x);
            let am = g.a0 - self.dir.sign() * x;
            let burn = if cap_mps.is_finite() {
                p.max_burn_mps / cap_mps - 1.0
            } else {
                -1.0
            };
            burn.max(-p.drift_s / g.t0).max((min_radius_km - am) / g.a0)
        };
        let eval = work_units::DRIFT_EVAL;
        // Upper end of the search: half the ring radius below (east) or above (west).
        let mut hi = 0.5 * g.a0;
        if !gauge.take(eval) {
            return None;
        }
        if ok(hi) {
            return Some(hi);
        }
        let mut lo = 0.0;
        if !gauge.take(eval) {
            return None;
        }
        let f_hi = violation(hi);
        if f_hi > 0.0 {
            // The origin is admissible in the limit (violation -1 stands for it).
            let (a, _, b, _) = super::root::metered_illinois(
                violation,
                (lo, -1.0),
                (hi, f_hi),
                max_iter,
                gauge,
                eval,
            )?;
            if a > 0.0 {
                if !gauge.take(eval) {
                    return None;
                }
                if ok(a) {
                    lo = a;
                }
            }
            if b > lo {
                if !gauge.take(eval) {
                    return None;
                }
                if !ok(b) {
                    hi = b;
                }
            }
        }
        let (lo, _) = super::root::metered_bisection(lo, hi, max_iter, gauge, eval, ok)?;
        (lo > 0.0).then_some(lo)
    }

    /// Depth whose leg takes `duration_s` (>= the duration at `x_max_km`); bisection, at most
    /// `max_iter` steps, each evaluation taken from `gauge` first (when one is refused the
    /// search stops where it is).
    pub fn depth_for_duration(
        &self,
        duration_s: f64,
        x_max_km: f64,
        max_iter: u16,
        gauge: &mut Gauge<'_>,
    ) -> f64 {
        let (mut lo, mut hi) = (0.0_f64, x_max_km);
        for _ in 0..max_iter {
            let mid = 0.5 * (lo + hi);
            if mid <= lo || mid >= hi {
                break;
            }
            if !gauge.take(work_units::DRIFT_EVAL) {
                break;
            }
            if self.at(mid).duration_s > duration_s {
                lo = mid;
            } else {
                hi = mid;
            }
        }
        0.5 * (lo + hi)
    }

    /// Depth minimising `D(x) + price * t(x)` on `(0, x_max]`: the root of
    /// `price_at(x) = price` (increasing in x), clipped to `x_max`. Regula falsi on
    /// `sqrt(price_at(x)) - sqrt(price)`, nearly linear in x (the first-order price is
    /// proportional to x^2), at most `max_iter` steps, over the whole interval: the
    /// reference the tabulated search (`PriceCurve`) is tested against.
    #[cfg(test)]
    pub fn depth_for_price(&self, price: f64, x_max_km: f64, max_iter: u16) -> f64 {
        let top = self.price_at(x_max_km);
        if top.is_nan() || top <= price {
            return x_max_km;
        }
        let sp = libm::sqrt(price.max(0.0));
        let f = |x: f64| {
            if x <= 0.0 {
                -sp
            } else {
                libm::sqrt(self.price_at(x).max(0.0)) - sp
            }
        };
        let (a, fa, b, fb, _) = super::root::illinois(
            f,
            0.0,
            -sp,
            x_max_km,
            libm::sqrt(top) - sp,
            max_iter,
            1e-14,
            0.0,
        );
        if fa.abs() <= fb.abs() && a > 0.0 {
            a
        } else {
            b
        }
    }

    /// The manoeuvre at depth `x_km`.
    pub fn maneuver(&self, x_km: f64) -> Maneuver {
        let (b1, b2, tt, td) = self.burns_dual(Dual::cst(x_km));
        let half = 0.5 * tt.v;
        let t = |o: f64, v: f64| Burn {
            offset_s: o,
            dv_rtn_mps: [0.0, v, 0.0],
        };
        let burns = [
            t(0.0, b1.v),
            t(half, b2.v),
            t(half + td.v, -b2.v),
            t(tt.v + td.v, -b1.v),
        ];
        let am = self.g.a0 - self.dir.sign() * x_km;
        Maneuver::from_burns(Method::Drift, tt.v + td.v, am, 0, &burns)
    }
}

/// The drift manoeuvre at depth `depth_km` (drift orbit `a0 - s depth`), for any caller
/// (brute-force checks, plots); `None` when the transfers alone overshoot the phase.
pub fn drift_at_depth(g: &Geo, dir: Direction, phase_rad: f64, depth_km: f64) -> Option<Maneuver> {
    let d = Drift {
        g: *g,
        dir,
        phase_rad,
    };
    (d.at(depth_km).drift_s >= 0.0).then(|| d.maneuver(depth_km))
}

/// Convenience for callers outside the allocation: the drift manoeuvre of a leg that takes
/// exactly `duration_s`, or `None` when no admissible drift orbit is that fast.
pub fn drift_for_duration(
    g: &Geo,
    dir: Direction,
    phase_rad: f64,
    duration_s: f64,
    min_radius_km: f64,
    max_iter: u16,
) -> Option<Maneuver> {
    let d = Drift {
        g: *g,
        dir,
        phase_rad,
    };
    let x_max = d.max_depth_km(f64::INFINITY, min_radius_km, max_iter, &mut Gauge::paid())?;
    if duration_s.is_nan() || duration_s < d.at(x_max).duration_s {
        return None;
    }
    Some(d.maneuver(d.depth_for_duration(duration_s, x_max, max_iter, &mut Gauge::paid())))
}

#[cfg(test)]
mod tests {
    use super::*;

    const DAY: f64 = 86_400.0;

    #[test]
    fn published_drift_legs_cost_what_the_digest_says() {
        let g = Geo::standard();
        // (phase deg, duration d, digest total m/s, digest depth km)
        let rows = [
            (2.0, 4.065, 3.183, 43.6),
            (9.0, 8.062, 6.749, 92.4),
            (64.5, 20.708, 18.069, 246.7),
        ];
        for (du, t, dv, depth) in rows {
            let m = drift_for_duration(
                &g,
                Direction::East,
                du * core::f64::consts::PI / 180.0,
                t * DAY,
                6578.0,
                200,
            )
            .unwrap();
            assert!((m.dv_mps - dv).abs() < 2e-3, "{du}: {}", m.dv_mps);
            assert!(((g.a0 - m.orbit_sma_km) - depth).abs() < 0.1, "{du}");
            assert!((m.transfer_s - t * DAY).abs() < 1e-6);
        }
    }

    #[test]
    fn marginal_price_matches_finite_difference_and_grows_with_depth() {
        let g = Geo::standard();
        for dir in [Direction::East, Direction::West] {
            let d = Drift {
                g,
                dir,
                phase_rad: 0.3,
            };
            let mut last = 0.0;
            for k in 1..40 {
                let x = f64::from(k) * 5.0;
                let h = 1e-4;
                let (p, q) = (d.at(x + h), d.at(x - h));
                let fd = -(p.dv_mps - q.dv_mps) / (p.duration_s - q.duration_s);
                let pr = d.price_at(x);
                assert!((pr - fd).abs() < 1e-6 * pr.abs() + 1e-15, "{x}: {pr} {fd}");
                assert!(pr > last);
                last = pr;
            }
        }
    }
}
