//! The time price when Lambert wells must make room.
//!
//! An assignment fits the mission time at a drift price when its points' stored times (each
//! Lambert well at its bottom, or where the exchange search last re-priced it) leave the drift
//! legs enough time. When they do not — no drift leg at all, or drift legs already at their
//! fastest — [`super::drift_time::drift_allocate`] has no price to offer, and the wells stayed at
//! their bottoms: the assignment was dropped, and the tour kept a dearer method where moving two
//! Lambert legs earlier along their wells would have fitted (issue 31: start 75° E, clients at
//! 75.05° and 75.12° E, 1.5 d, 5 m/s cap: a radial leg and a well bottom, 1.7400 m/s, where both
//! wells moved to fit cost 1.2735 m/s, the brute force's 1.273451).
//!
//! Here the wells set the price with the drifts: at a price λ every well leg of the assignment
//! takes the minimum of Δv + λτ over its well (`well_minimum`, the same golden section that
//! built the table) and every drift leg its depth at λ. Each leg's time does not increase with
//! λ, so neither does the tour's, and the bracketing search in w = 1/√λ of the allocation finds
//! the least price at which the tour fits. For fixed methods with convex costs this is the
//! optimum (the drift argument of docs/geo-tour.md); a well's cost is smooth and unimodal on its
//! window, which the brute force of the tests checks.

use super::drift_time::weight_search;
use super::geo::Geo;
use super::lambert_phasing::{well_minimum, well_window_s};
use super::pick::{drift_pick, Choice, Pick};
use super::table::{bounds, direction_of, LegTable, Point};
use super::types::{PointKind, Settings};
use super::work_units::{self, spend, Cut, Gauge};
use crate::work::Meter;

/// The first price tried without a hint, m/s per s (about 0.01 m/s per day: below the prices
/// at which a well leg moves noticeably, above rounding).
const FIRST_PRICE: f64 = 1e-7;
/// The bracketing's least step in w = 1/sqrt(price) (0.1 %), and its largest and first (a
/// factor 16 in the price).
const FIRST_W_STEP: f64 = 1.001;
const MAX_W_STEP: f64 = 4.0;
/// Most bracketing steps (4^24 = 2.8e14 in w, 7.9e28 in the price: every well at its
/// window's start, or at its bottom, to rounding).
const BRACKET_STEPS: u16 = 24;
/// The Lagrangian bound must clear the best total by this before an assignment is dropped,
/// m/s (the golden sections' minima are above the true ones by about 1e-8 m/s).
const BOUND_MARGIN_MPS: f64 = 1e-6;

/// The Lambert well of leg `t` that `p` picks, if it picks one.
///
/// The direct arc (K = 0 at `lambert_direct_time_s`) is a point of well 1's family: where the
/// leg has that well (its policy lets Lambert legs take any time, and the cap admits it) the
/// direct arc moves along it like the well's own point (three Lambert legs squeezed into 1.2
/// days kept two of them at the rule's 9 h, 2 % above the brute force).
fn well_of(t: &LegTable, p: &Pick) -> Option<u16> {
    let Choice::Point(i) = p.choice else {
        return None;
    };
    match t.points.get(usize::from(i)).map(|pt| pt.kind) {
        Some(PointKind::Well(m)) => Some(m),
        Some(PointKind::Direct) if first_well(t).is_some() => Some(1),
        _ => None,
    }
}

/// The leg's well 1 point, if its table has one.
fn first_well(t: &LegTable) -> Option<&Point> {
    t.points.iter().find(|q| q.kind == PointKind::Well(1))
}

/// A lower bound on the Δv of the assignment `picks` however its wells and drifts are moved:
/// fixed points at their cost, wells at their bottoms (the least Δv their table found), drift
/// legs at 0.
pub(super) fn dv_floor_mps(tables: &[LegTable], picks: &[Pick]) -> f64 {
    tables.iter().zip(picks).fold(0.0, |sum, (t, p)| {
        sum + match p.choice {
            Choice::Drift => 0.0,
            Choice::Point(i) => {
                let own = t
                    .points
                    .get(usize::from(i))
                    .map_or(p.dv_mps, |pt| pt.floor_dv_mps.min(p.dv_mps));
                // A direct arc moves along well 1: that well's bottom bounds it.
                match well_of(t, p).zip(first_well(t)) {
                    Some((1, w)) => own.min(w.floor_dv_mps),
                    _ => own,
                }
            }
        }
    })
}

/// Whether the assignment has a leg on a Lambert well.
pub(super) fn has_well_leg(tables: &[LegTable], picks: &[Pick]) -> bool {
    tables
        .iter()
        .zip(picks)
        .any(|(t, p)| well_of(t, p).is_some())
}

/// How many of the assignment's legs are on a Lambert well (each a golden section per price
/// step of a search moving the wells).
pub(super) fn well_leg_count(tables: &[LegTable], picks: &[Pick]) -> usize {
    tables
        .iter()
        .zip(picks)
        .filter(|(t, p)| well_of(t, p).is_some())
        // Not `count`: it inherits the caller's overflow checks, a panic path the abort-proof
        // C library must not link (docs/c-api.md, "Abort-free").
        .fold(0_usize, |n, _| n.saturating_add(1))
}

/// Re-allocate the time of the assignment `picks` with its well legs and drift legs moved by
/// one price (see the module doc): the least price at which the tour fits `budget_s`, the
/// picks' durations and costs written. `None` when it cannot fit (every well at its window's
/// start and every drift at its fastest still too long) or has no well leg.
///
/// Every evaluation of the tour's time is charged first (a price step, a well's set-up per
/// well leg), the wells' arcs and drifts' roots as they run; [`Cut`] when the budget runs out
/// (`picks` then holds a partial re-allocation: the caller discards it).
pub(super) fn wells_allocate(
    tables: &[LegTable],
    picks: &mut [Pick],
    budget_s: f64,
    s: &Settings,
    iterations: &mut u32,
    (hint, best_dv): (Option<f64>, f64),
    meter: &mut Meter,
) -> Result<Option<f64>, Cut> {
    let g = Geo::standard();
    // The least time the assignment can take: fixed points, wells at their windows' starts,
    // drifts at their fastest.
    let mut least_s = 0.0;
    let mut moving = 0_usize;
    for (t, p) in tables.iter().zip(picks.iter()) {
        least_s += match (p.choice, well_of(t, p), t.drift.as_ref()) {
            (Choice::Drift, _, Some(d)) => {
                moving = moving.saturating_add(1);
                d.t_min_s
            }
            (Choice::Drift, _, None) => return Ok(None),
            (Choice::Point(_), Some(m), _) => {
                moving = moving.saturating_add(1);
                well_window_s(&g, direction_of(t), t.phase_rad, m).0
            }
            (Choice::Point(_), None, _) => p.duration_s,
        };
    }
    if !has_well_leg(tables, picks) || least_s.is_nan() || least_s > budget_s {
        return Ok(None);
    }
    // A well's time moves in steps of its golden section's last bracket (its window shrunk
    // `well_iterations` times by 0.618): the tour's time cannot be brought closer to the
    // budget than their sum, and a search asked to would run to its step limit.
    let shrink = libm::pow(0.5 * (libm::sqrt(5.0) - 1.0), f64::from(s.well_iterations));
    let resolution_s = tables.iter().zip(picks.iter()).fold(0.0, |sum, (t, p)| {
        sum + well_of(t, p).map_or(0.0, |m| {
            let (lo, hi) = well_window_s(&g, direction_of(t), t.phase_rad, m);
            (hi - lo) * shrink
        })
    });
    let time_tol_s = s.time_tol_s + resolution_s;
    let step_units = work_units::price_step(tables.len(), moving);
    // The price `picks` were last written at (the search's final point is often its last).
    let last_price = core::cell::Cell::new(f64::NAN);
    // The tour's time at `price`, or `None` once the Lagrangian bound at `price` shows the
    // assignment cannot beat `best_dv`: for any price, sum_j min_t (dv_j + price t) - price
    // budget_s is below every allocation's Δv (weak duality; the golden sections' minima are
    // above the true ones by rounding only, hence the margin).
    let mut tour_time = |price: f64, picks: &mut [Pick]| -> Result<Option<f64>, Cut> {
        spend(meter, step_units)?;
        last_price.set(price);
        let mut sum = 0.0;
        let mut score = 0.0;
        for (t, p) in tables.iter().zip(picks.iter_mut()) {
            let moved = match (p.choice, well_of(t, p)) {
                (Choice::Drift, _) => {
                    let mut gauge = Gauge::metered(meter);
                    let q = drift_pick(t, price, s, &mut gauge);
                    if gauge.stopped() {
                        return Err(Cut);
                    }
                    q
                }
                (Choice::Point(i), Some(m)) => {
                    spend(meter, work_units::WELL)?;
                    let mut gauge = Gauge::metered(meter);
                    let w = well_minimum(
                        &g,
                        direction_of(t),
                        t.phase_rad,
                        m,
                        price,
                        t.cap_mps,
                        s.well_iterations,
                        bounds(s),
                        &mut gauge,
                    );
                    if gauge.stopped() {
                        return Err(Cut);
                    }
                    w.map(|mv| Pick {
                        choice: Choice::Point(i),
                        duration_s: mv.transfer_s,
                        dv_mps: mv.dv_mps,
                        x_km: 0.0,
                    })
                }
                (Choice::Point(_), None) => Some(*p),
            };
            // A well with no admissible arc at this price (its table found one at its
            // bottom, so only at a price that pushes it into the cap's excluded part).
            let Some(q) = moved else {
                return Ok(Some(f64::INFINITY));
            };
            sum += q.duration_s;
            score += q.dv_mps + price * q.duration_s;
            *p = q;
        }
        let bound_mps = score - price * budget_s;
        Ok((bound_mps < best_dv + BOUND_MARGIN_MPS).then_some(sum))
    };
    // Bracket the least fitting price in w = 1/sqrt(price) (time grows with w). From the
    // caller's price (the assignment it came from), a first step of a factor 4 in w (16 in
    // the price), then secant steps aimed 20 % past the root, each at least the previous
    // step's fourth power and at most the first, cross it; the Illinois search closes the
    // bracket. Without a price (no drift leg), from `FIRST_PRICE`; the first step is always
    // the widest (most trials that do not pay are dropped by the bound there).
    let hint = hint.filter(|h| h.is_finite() && *h > 0.0);
    let w0 = 1.0 / libm::sqrt(hint.unwrap_or(FIRST_PRICE));
    let Some(time) = tour_time(1.0 / (w0 * w0), picks)? else {
        return Ok(None);
    };
    let f0 = time - budget_s;
    // Fits: move towards lower prices (larger w) until it does not; else the other way.
    let up = f0 <= 0.0;
    let (mut prev, mut cur) = (None::<(f64, f64)>, (w0, f0));
    let mut crossed = None;
    // The least ratio of the next step: each step at least the previous one to the fourth
    // power (1.001, 1.004, 1.016, 1.07, 1.3, 2.8, 4), so a secant misled by the golden
    // sections' steps in time (a flat or backward slope) still reaches the root.
    let mut least_ratio = FIRST_W_STEP;
    for _ in 0..BRACKET_STEPS {
        let (w, f) = cur;
        let ratio = match prev {
            None => MAX_W_STEP,
            Some((wp, fp)) => {
                // Secant to the root, 20 % beyond, within [least_ratio, MAX_W_STEP].
                let target = w - 1.2 * f * (w - wp) / (f - fp);
                let r = if up { target / w } else { w / target };
                if r.is_finite() {
                    // Not `clamp`: its bounds' check is a panic path the abort-proof C library
                    // must not link.
                    r.max(least_ratio).min(MAX_W_STEP)
                } else {
                    MAX_W_STEP
                }
            }
        };
        let squared = ratio * ratio;
        least_ratio = (squared * squared).min(MAX_W_STEP);
        let next_w = if up { w * ratio } else { w / ratio };
        let Some(time) = tour_time(1.0 / (next_w * next_w), picks)? else {
            return Ok(None);
        };
        let next = (next_w, time - budget_s);
        if (next.1 <= 0.0) != up {
            crossed = Some(next);
            break;
        }
        prev = Some(cur);
        cur = next;
    }
    let Some(other) = crossed else {
        // Up: fits at a price too small to move anything (`picks` hold it). Down: cannot fit.
        return Ok(up.then(|| 1.0 / (cur.0 * cur.0)));
    };
    let (a, b) = if up { (cur, other) } else { (other, cur) };
    if a.1.is_nan() || b.1.is_nan() {
        return Ok(None);
    }
    let mut beaten = false;
    let ((w, _, _, _, steps), cut) = weight_search(
        |p| {
            tour_time(p, picks).map(|t| {
                beaten |= t.is_none();
                t.unwrap_or(f64::NAN)
            })
        },
        budget_s,
        a,
        b,
        s,
        time_tol_s,
    );
    if cut {
        return Err(Cut);
    }
    *iterations = iterations.saturating_add(u32::from(steps));
    if beaten {
        return Ok(None);
    }
    let price = 1.0 / (w * w);
    if last_price.get().to_bits() == price.to_bits() {
        // `picks` hold the bracket's feasible end already.
        return Ok(Some(price));
    }
    let time_s = tour_time(price, picks)?;
    Ok(time_s.filter(|t| *t <= budget_s).map(|_| price))
}
