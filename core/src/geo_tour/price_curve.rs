//! A drift leg's marginal price of time, tabulated once per sweep so that each price the
//! allocation asks about needs only a short root search.
//!
//! The allocation asks every drift leg, at every trial price, for the depth `x` where the
//! leg's marginal price `p(x) = -D'(x) / t'(x)` equals the trial price (`Drift::price_at`).
//! `p` increases with the depth, and `sqrt p` is nearly linear in it (the first-order price
//! grows as `x^2`), so regula falsi converges fast once the root is bracketed closely. The
//! curve stores `sqrt p` at `PRICE_NODES` evenly spaced depths; a query brackets its root
//! between two neighbouring nodes and runs the same bounded Illinois search the untabulated
//! root used, to the same tolerance: the answer is the same root (to 1e-14 relative), found
//! in a few evaluations instead of the whole interval's dozen or more.

use super::drift::Drift;
use super::root::secant_root;
use super::work_units::{self, Gauge};

/// Depth nodes of a leg's price curve (the node at depth 0, price 0, is implicit).
pub(crate) const PRICE_NODES: usize = 32;

/// The tabulated price curve of one drift leg on `(0, x_max_km]`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct PriceCurve {
    /// `sqrt(max(p, 0))` at depth `x_max_km * (i + 1) / PRICE_NODES`, i = 0..PRICE_NODES.
    root_price: [f64; PRICE_NODES],
    /// The leg's cost `D` (m/s) and duration `t` (s) at the same depths: they bound the
    /// leg's best score `D + price t` from below before its root is searched.
    dv_mps: [f64; PRICE_NODES],
    duration_s: [f64; PRICE_NODES],
    /// Deepest admissible depth, km.
    x_max_km: f64,
    /// Marginal price at `x_max_km` (m/s per s): beyond it the leg stays at its fastest.
    pub top_price: f64,
}

/// Depth of node `k` (1..=PRICE_NODES), km.
fn node_depth(x_max_km: f64, k: f64) -> f64 {
    // PRICE_NODES is a small constant, exactly representable.
    #[allow(clippy::cast_precision_loss)]
    let n = PRICE_NODES as f64;
    x_max_km * k / n
}

impl PriceCurve {
    /// The work units of building a curve ([`PriceCurve::new`]): `PRICE_NODES + 1` drift
    /// evaluations.
    pub(crate) fn work_units() -> u64 {
        work_units::DRIFT_EVAL.saturating_mul((PRICE_NODES as u64).saturating_add(1))
    }

    /// Tabulate `model`'s price on `(0, x_max_km]` (`PRICE_NODES` evaluations).
    pub fn new(model: &Drift, x_max_km: f64) -> Self {
        let mut root_price = [0.0; PRICE_NODES];
        let mut dv_mps = [0.0; PRICE_NODES];
        let mut duration_s = [0.0; PRICE_NODES];
        let mut k = 0.0;
        for ((r, d), t) in root_price
            .iter_mut()
            .zip(dv_mps.iter_mut())
            .zip(duration_s.iter_mut())
        {
            k += 1.0;
            let (price, dv, duration) = model.price_and_point(node_depth(x_max_km, k));
            *r = libm::sqrt(price.max(0.0));
            (*d, *t) = (dv, duration);
        }
        Self {
            root_price,
            dv_mps,
            duration_s,
            x_max_km,
            top_price: model.price_at(x_max_km),
        }
    }

    /// A lower bound on the leg's best score `min D(x) + price t(x)` over `(0, x_max]`, from
    /// the nodes alone: the minimiser [`PriceCurve::depth_for_price`] returns lies between the
    /// two nodes that bracket the price (or is `x_max`), where `D` is at least its value at
    /// the shallower node (0 at depth 0) and `t` at least its value at the deeper one. Lowered
    /// by 1e-12 relative so that rounding in the root's own evaluation cannot cross it.
    pub fn score_lower_bound(&self, price: f64) -> f64 {
        let sp = libm::sqrt(price.max(0.0));
        // Shallower node's cost, deeper node's duration (the deepest node is x_max).
        let [.., dv_top] = self.dv_mps;
        let [.., t_top] = self.duration_s;
        let mut dv_lo = 0.0;
        let mut t_hi = t_top;
        if !(self.top_price.is_nan() || self.top_price <= price) {
            for ((&r, &d), &t) in self
                .root_price
                .iter()
                .zip(self.dv_mps.iter())
                .zip(self.duration_s.iter())
            {
                if r - sp <= 0.0 {
                    dv_lo = d;
                } else {
                    // As in `depth_for_price`: a NaN node leaves the outer end.
                    if r - sp > 0.0 {
                        t_hi = t;
                    }
                    break;
                }
            }
        } else {
            dv_lo = dv_top;
        }
        let bound = dv_lo + price * t_hi;
        // NaN (cannot happen on an admissible range) gives -inf: no option is ever skipped.
        if bound.is_nan() {
            f64::NEG_INFINITY
        } else {
            bound - 1e-12 * bound.abs()
        }
    }

    /// Depth minimising `D(x) + price * t(x)` on `(0, x_max]`: the root of
    /// `sqrt(price_at(x)) = sqrt(price)`, clipped to `x_max`, bracketed between two nodes and
    /// found by secant steps kept in the bracket (at most `max_iter` evaluations, each taken
    /// from `gauge` first: a refused one stops the search where it is; the same tolerance as
    /// an untabulated search over the whole interval).
    pub fn depth_for_price(
        &self,
        model: &Drift,
        price: f64,
        max_iter: u16,
        gauge: &mut Gauge<'_>,
    ) -> f64 {
        let top = self.top_price;
        if top.is_nan() || top <= price {
            return self.x_max_km;
        }
        let sp = libm::sqrt(price.max(0.0));
        // f(a) <= 0 < f(b): the last node at or below the price, the first above it. A NaN
        // node (cannot happen on an admissible range) leaves the outer end as the bracket.
        let (mut a, mut fa) = (0.0, -sp);
        let (mut b, mut fb) = (self.x_max_km, libm::sqrt(top) - sp);
        let mut k = 0.0;
        for &r in &self.root_price {
            k += 1.0;
            let f = r - sp;
            if f <= 0.0 {
                (a, fa) = (node_depth(self.x_max_km, k), f);
            } else {
                if f > 0.0 {
                    (b, fb) = (node_depth(self.x_max_km, k), f);
                }
                break;
            }
        }
        // A refused evaluation reads NaN, which stops the search.
        let f = |x: f64| {
            if !gauge.take(work_units::DRIFT_EVAL) {
                f64::NAN
            } else if x <= 0.0 {
                -sp
            } else {
                libm::sqrt(model.price_at(x).max(0.0)) - sp
            }
        };
        secant_root(f, a, fa, b, fb, max_iter, 1e-14, 1e-13 * sp)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geo_tour::geo::Geo;
    use crate::geo_tour::maneuver::Direction;

    #[test]
    fn tabulated_root_is_the_whole_interval_root() {
        let g = Geo::standard();
        for dir in [Direction::East, Direction::West] {
            for phase in [0.01, 0.3, 1.1] {
                let d = Drift {
                    g,
                    dir,
                    phase_rad: phase,
                };
                let x_max = d
                    .max_depth_km(5.0, 6578.137, 200, &mut Gauge::paid())
                    .unwrap();
                let curve = PriceCurve::new(&d, x_max);
                for k in 0..60 {
                    // Prices from far below the first node to beyond the top.
                    let price = curve.top_price * libm::pow(10.0, -f64::from(k) / 6.0) * 1.5;
                    let x = curve.depth_for_price(&d, price, 200, &mut Gauge::paid());
                    let y = d.depth_for_price(price, x_max, 200);
                    assert!(
                        (x - y).abs() <= 1e-11 * (1.0 + y),
                        "{phase} {price}: {x} {y}"
                    );
                    let (p, q) = (d.at(x), d.at(y));
                    let (sp, sq) = (
                        p.dv_mps + price * p.duration_s,
                        q.dv_mps + price * q.duration_s,
                    );
                    assert!((sp - sq).abs() <= 1e-9, "{phase} {price}: {sp} {sq}");
                    // The node bound never exceeds the best score (the allocation skips the
                    // drift's root only when a point scores below it).
                    let bound = curve.score_lower_bound(price);
                    assert!(
                        bound.is_finite() && bound <= sp,
                        "{phase} {price}: {bound} {sp}"
                    );
                }
            }
        }
    }
}
