//! A leg's choice at a time price: each leg independently minimises `dv_j(t) + lambda t` over
//! its options (the drift at the depth the price sets, the table's points), and the tour's
//! time and Δv of an assignment. The layer every allocation step builds on
//! ([`super::allocate`], [`super::exchange`], [`super::well_price`]).

use super::table::{LegTable, Point};
use super::types::Settings;
use super::work_units::{self, spend, Cut, Gauge};
use crate::indexed::IndexedExt as _;
use crate::work::Meter;

/// What a leg does.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Choice {
    /// The drift method at a depth set by the price.
    Drift,
    /// Point option i of the leg's table.
    Point(u8),
}

/// A leg's choice with its time and cost.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Pick {
    pub choice: Choice,
    pub duration_s: f64,
    pub dv_mps: f64,
    /// Drift depth (km) when `choice == Drift`.
    pub x_km: f64,
}

impl Pick {
    pub const fn none() -> Self {
        Self {
            choice: Choice::Point(0),
            duration_s: 0.0,
            dv_mps: 0.0,
            x_km: 0.0,
        }
    }
}

/// The leg's drift at `price`, its root's evaluations metered by `gauge` (its point is
/// charged with the step that asks, `work_units::price_step`).
pub(super) fn drift_pick(
    t: &LegTable,
    price: f64,
    s: &Settings,
    gauge: &mut Gauge<'_>,
) -> Option<Pick> {
    let d = t.drift.as_ref()?;
    // Every table is finished (curve built) before the allocation runs.
    let x = d
        .curve
        .as_ref()?
        .depth_for_price(&d.model, price, s.root_max_iter, gauge);
    let p = d.model.at(x);
    Some(Pick {
        choice: Choice::Drift,
        duration_s: p.duration_s,
        dv_mps: p.dv_mps,
        x_km: x,
    })
}

pub(super) fn point_pick(i: usize, p: &Point) -> Pick {
    Pick {
        choice: Choice::Point(u8::try_from(i).unwrap_or(u8::MAX)),
        duration_s: p.duration_s,
        dv_mps: p.dv_mps,
        x_km: 0.0,
    }
}

/// Whether the leg's drift option provably scores more than `score` at `price` (its root
/// then need not be searched): the price curve's lower bound on its best score exceeds it.
pub(super) fn drift_beaten(t: &LegTable, price: f64, score: f64) -> bool {
    t.drift
        .as_ref()
        .and_then(|d| d.curve.as_ref())
        .is_some_and(|c| score < c.score_lower_bound(price))
}

/// The leg's best option at `price` (ties: drift first, then the table's order). The drift's
/// root is searched only when the best point does not provably beat it.
fn pick(t: &LegTable, price: f64, s: &Settings, gauge: &mut Gauge<'_>) -> Option<Pick> {
    let score = |b: &Pick| b.dv_mps + price * b.duration_s;
    let mut best_point: Option<Pick> = None;
    for (i, p) in t.points.iter().indexed() {
        let candidate = point_pick(i, p);
        if best_point.is_none_or(|b| score(&candidate) < score(&b)) {
            best_point = Some(candidate);
        }
    }
    if let Some(bp) = best_point {
        if drift_beaten(t, price, score(&bp)) {
            return best_point;
        }
    }
    match (drift_pick(t, price, s, gauge), best_point) {
        (Some(d), Some(bp)) if score(&bp) < score(&d) => Some(bp),
        (Some(d), _) => Some(d),
        (None, bp) => bp,
    }
}

/// How many of `items` satisfy `pred`. Not `filter().count()`: with overflow checks on (the
/// release profiles) its sum is an overflow panic path the abort-proof C library must not link.
fn count_where<T>(items: &[T], pred: impl Fn(&T) -> bool) -> usize {
    items
        .iter()
        .fold(0_usize, |n, item| n.saturating_add(usize::from(pred(item))))
}

/// Every leg's best option at `price` into `picks`; returns the tour's time. Charged first
/// (the legs' scans and points), the drift roots' evaluations as they run; [`Cut`] when the
/// budget runs out (`picks` then partly written: the caller discards them).
pub(crate) fn pick_all(
    tables: &[LegTable],
    price: f64,
    s: &Settings,
    picks: &mut [Pick],
    meter: &mut Meter,
) -> Result<f64, Cut> {
    let drift_legs = count_where(tables, |t| t.drift.is_some());
    spend(meter, work_units::price_step(tables.len(), drift_legs))?;
    let mut gauge = Gauge::metered(meter);
    let total = pick_all_metered(tables, price, s, picks, &mut gauge);
    if gauge.stopped() {
        Err(Cut)
    } else {
        Ok(total)
    }
}

/// [`pick_all`] once its step is charged; stops at a refused evaluation.
fn pick_all_metered(
    tables: &[LegTable],
    price: f64,
    s: &Settings,
    picks: &mut [Pick],
    gauge: &mut Gauge<'_>,
) -> f64 {
    let mut total = 0.0;
    for (t, slot) in tables.iter().zip(picks.iter_mut()) {
        let picked = pick(t, price, s, gauge);
        if gauge.stopped() {
            return f64::NAN;
        }
        match picked {
            Some(p) => {
                total += p.duration_s;
                *slot = p;
            }
            None => return f64::INFINITY,
        }
    }
    total
}

/// The tour's time and Δv: each leg's pick summed, leg by leg (`picks` beyond the legs are
/// not the tour's).
pub(super) fn totals(tables: &[LegTable], picks: &[Pick]) -> (f64, f64) {
    tables.iter().zip(picks).fold((0.0, 0.0), |(t, v), (_, p)| {
        (t + p.duration_s, v + p.dv_mps)
    })
}
