//! The exchange search after the time price ([`super::allocate`]): for the price's
//! assignment, every alternative of every leg with a negative first-order effect at the price
//! (Lambert wells re-priced first) is evaluated exactly, the drift legs' time re-allocated,
//! and kept when the total falls; when no one leg's change pays, two legs change at once
//! ([`super::exchange_pairs`]).

use super::exchange_pairs::pair_stage;
use super::geo::Geo;
use super::lambert_phasing::{well_minimum, well_window_s};
use super::pick::{drift_beaten, drift_pick, point_pick, Choice, Pick};
use super::reallocate::{trial_improves, WellSearches};
use super::table::{bounds, direction_of, LegTable, MAX_POINTS};
use super::types::{PointKind, Settings, MAX_TARGETS};
use super::well_price::well_leg_count;
use super::work_units::{self, spend, Cut, Gauge};
use crate::indexed::IndexedExt as _;
use crate::work::Meter;

/// Searches moving the wells ([`super::well_price`]) one leg's alternatives may start per
/// round: the first alternative (in the table's order: the shorter wells first) that fits only
/// with the wells moved. Each search is a golden section per well leg per price step (about
/// 30,000 units on a 12-leg tour of wells, 3 steps when its bound drops it, 10 when it fits),
/// and a leg's longer wells, tried after a shorter one failed, were measured to rarely pay.
const WELL_SEARCHES_PER_LEG: u8 = 1;
/// Searches moving the wells the whole exchange search may start (over its rounds): a tour of
/// 14 Lambert legs and no drift tried one per leg per round for 3.3 M units (held-out seed
/// 2087 of `examples/geo_revolutions.rs`; 235,000 before the wells could move).
const WELL_SEARCHES_PER_SOLVE: u8 = 16;

/// Of [`WELL_SEARCHES_PER_SOLVE`], those a trial that frees time (a leg moved earlier, not to
/// a drift) may start: the wells moved into the freed time show what it is worth (three
/// Lambert legs in 1.2 days: the middle leg's 0.48-day arc beats its radial transfer only so).
const FREEING_SEARCHES_PER_SOLVE: u8 = 4;
/// Searches moving the wells the pair stages ([`pair_stage`]) may start over the solve.
const PAIR_WELL_SEARCHES_PER_SOLVE: u8 = 2;
/// The freeing and pair searches run only on assignments with at most this many well legs: a
/// search's cost grows with them (one on the 120-day sixteen-client capacity tour of
/// `tests/geo_tour_wire.rs`, sixteen well legs, took 1.02 M units, and two of them took that
/// tour from 2.9 M units past the 4 M budget), and the tours they were measured to pay on have
/// two to six.
pub(super) const DEAR_SEARCH_MAX_WELL_LEGS: usize = 6;

/// A leg's alternatives in the exchange search (point index or drift, with time and cost).
/// Lambert wells are first re-priced: moved to the minimum of `dv + price t` of their well
/// (written into the table, so each well is searched again only when the price has moved by
/// more than 1 %), each well charged first. [`Cut`] when the budget runs out.
fn alternatives(
    t: &mut LegTable,
    cur: &Pick,
    price: f64,
    s: &Settings,
    out: &mut heapless::Vec<Pick, { MAX_POINTS + 1 }>,
    meter: &mut Meter,
) -> Result<(), Cut> {
    spend(meter, work_units::alternatives_leg())?;
    out.clear();
    let g = Geo::standard();
    let dir = direction_of(t);
    let (phase, cap) = (t.phase_rad, t.cap_mps);
    for (i, p) in t.points.iter_mut().indexed() {
        if let PointKind::Well(m) = p.kind {
            // Whether the well may beat the current pick at the price: by its stored point's
            // estimate, and for the direct family (well 1) by a bound, its bottom's Δv plus
            // the price of its window's earliest time. That family's window spans a whole
            // period from a minute, so at a high price its best point is far from its bottom
            // (three Lambert legs in 1.2 days: the middle leg's direct family, whose bottom at
            // 0.99 d is 2 m/s dearer by the estimate, has at 0.48 d a point that beats its
            // radial transfer). The bound on every well re-priced so many more that the
            // sixteen-client fixture took 14 % more work for no lower total.
            let estimate = (p.dv_mps - cur.dv_mps) + price * (p.duration_s - cur.duration_s);
            let bound = if m == 1 {
                let earliest_s = well_window_s(&g, dir, phase, m).0;
                (p.floor_dv_mps - cur.dv_mps) + price * (earliest_s - cur.duration_s)
            } else {
                estimate
            };
            let stale = (p.price - price).abs() > 0.01 * price;
            if bound < s.exchange_margin_mps && stale {
                spend(meter, work_units::WELL)?;
                let mut gauge = Gauge::metered(meter);
                let w = well_minimum(
                    &g,
                    dir,
                    phase,
                    m,
                    price,
                    cap,
                    s.well_iterations,
                    bounds(s),
                    &mut gauge,
                );
                if gauge.stopped() {
                    return Err(Cut);
                }
                if let Some(mv) = w {
                    if mv.dv_mps + price * mv.transfer_s <= p.dv_mps + price * p.duration_s {
                        p.duration_s = mv.transfer_s;
                        p.dv_mps = mv.dv_mps;
                    }
                }
                p.price = price;
            }
        }
        let alt = point_pick(i, p);
        let est = (alt.dv_mps - cur.dv_mps) + price * (alt.duration_s - cur.duration_s);
        let moved = alt.choice == cur.choice
            && (alt.duration_s - cur.duration_s).abs() > 1e-9 * cur.duration_s;
        if (alt.choice != cur.choice || moved) && est < 0.0 {
            let _ = out.push(alt);
        }
    }
    let cur_score = cur.dv_mps + price * cur.duration_s;
    if cur.choice != Choice::Drift && !drift_beaten(t, price, cur_score) {
        let mut gauge = Gauge::metered(meter);
        let picked = drift_pick(t, price, s, &mut gauge);
        if gauge.stopped() {
            return Err(Cut);
        }
        if let Some(d) = picked {
            // At a zero price (no drift leg yet, time not binding) the drift's pick is the
            // infinitely long one and the estimate is NaN (0 x inf): try it, its re-allocation
            // gives it the time the other legs leave (a Lambert leg with a day to spare beside
            // it was never offered the drift before).
            let est = (d.dv_mps - cur.dv_mps) + price * (d.duration_s - cur.duration_s);
            if est.is_nan() || est < 0.0 {
                let _ = out.push(d);
            }
        }
    }
    Ok(())
}

/// Exchange search after the price. The Lagrangian solution can miss the optimum where point
/// options switch (a duality gap wider than the legs switching at the critical price), and a
/// Lambert well's best time moves with the price. For the current assignment and its drift
/// price `lambda`, every alternative of every leg whose first-order effect
/// `d(dv) + lambda d(t)` is negative (Lambert wells: below `exchange_margin_mps`, refined at
/// `lambda` first) is evaluated exactly (drift time re-allocated) and kept when the total
/// falls. At most `exchange_rounds` rounds, each at most `MAX_POINTS + 1` alternatives per leg,
/// every step charged to the meter first; when the budget runs out the search stops (`cut`
/// set) with the best assignment so far in `picks`. Returns the new price and total when
/// anything changed.
pub(super) fn exchange(
    tables: &mut [LegTable],
    (picks, trial): (&mut [Pick; MAX_TARGETS], &mut [Pick; MAX_TARGETS]),
    budget_s: f64,
    s: &Settings,
    (mut price, mut best_dv): (f64, f64),
    (iterations, exchanges, refined): (&mut u32, &mut u32, &mut u8),
    (meter, cut): (&mut Meter, &mut bool),
) -> Option<(f64, f64)> {
    let n = tables.len();
    let mut changed = false;
    let mut alts = heapless::Vec::new();
    let mut searches_left = WELL_SEARCHES_PER_SOLVE;
    let mut freeing_left = FREEING_SEARCHES_PER_SOLVE;
    let mut pair_searches_left = PAIR_WELL_SEARCHES_PER_SOLVE;
    'rounds: for _ in 0..s.exchange_rounds {
        let mut improved = false;
        for j in 0..n {
            let (Some(cur), Some(t)) = (picks.get(j).copied(), tables.get_mut(j)) else {
                continue;
            };
            if alternatives(t, &cur, price, s, &mut alts, meter).is_err() {
                *cut = true;
                break 'rounds;
            }
            let leg_searches = WELL_SEARCHES_PER_LEG.min(searches_left);
            let mut well_searches = WellSearches {
                left: leg_searches,
                retry_fitting: false,
            };
            for alt in alts.iter() {
                // A leg turned to a drift sets a price the other legs' wells were not placed
                // for (with no drift before, none did): such a trial that its drifts fit but
                // do not make cheaper is tried with the wells moved too. Other trials keep
                // the price, at which the wells are already placed (re-priced above).
                // Likewise a trial that frees time (a leg moved earlier) for the other legs'
                // wells: only moving them shows what the time is worth.
                let frees_time = alt.choice != Choice::Drift
                    && alt.duration_s < cur.duration_s * (1.0 - 1e-9)
                    && freeing_left > 0
                    && well_leg_count(tables, picks) <= DEAR_SEARCH_MAX_WELL_LEGS;
                well_searches.retry_fitting = alt.choice == Choice::Drift || frees_time;
                let left_before = well_searches.left;
                if spend(meter, work_units::ASSIGNMENT).is_err() {
                    *cut = true;
                    break 'rounds;
                }
                *trial = *picks;
                if let Some(slot) = trial.get_mut(j) {
                    *slot = *alt;
                }
                *exchanges = exchanges.saturating_add(1);
                let result = trial_improves(
                    tables,
                    trial,
                    budget_s,
                    s,
                    iterations,
                    price,
                    (best_dv, &mut well_searches),
                    meter,
                );
                if frees_time && well_searches.left < left_before {
                    freeing_left = freeing_left.saturating_sub(1);
                }
                match result {
                    Ok(None) => {}
                    Ok(Some((p, dv))) => {
                        best_dv = dv;
                        price = p;
                        *picks = *trial;
                        improved = true;
                        changed = true;
                        if alt.choice == cur.choice {
                            *refined = refined.saturating_add(1);
                        }
                        break;
                    }
                    Err(Cut) => {
                        *cut = true;
                        break 'rounds;
                    }
                }
            }
            searches_left =
                searches_left.saturating_sub(leg_searches.saturating_sub(well_searches.left));
        }
        if !improved {
            // No one leg's change pays: two legs' together (at most once per round).
            match pair_stage(
                tables,
                (picks, trial),
                budget_s,
                s,
                (price, best_dv),
                (iterations, exchanges, &mut pair_searches_left),
                meter,
            ) {
                Ok(Some((p, dv))) => {
                    price = p;
                    best_dv = dv;
                    changed = true;
                }
                Ok(None) => break,
                Err(Cut) => {
                    *cut = true;
                    break;
                }
            }
        }
    }
    changed.then_some((price, best_dv))
}
