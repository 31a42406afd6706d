//! The exchange search's pair stage ([`super::exchange`]): when no single leg's alternative
//! lowers the total, two legs change at once.
//!
//! One leg at a time misses the tours whose optimum needs two legs to change method together:
//! one takes a cheaper, longer option and the other gives it the time (tuning seed 82 of
//! `examples/geo_revolutions.rs`: a drift and a three-revolution well, where two
//! four-revolution wells, one moved 0.3 d early, are 0.74 % cheaper; either change alone is
//! dearer). Every pair of legs and every pair of their alternatives is scored by the sum of
//! the two first-order effects `d(dv) + lambda d(t)` at the current price; the
//! [`PAIR_TRIALS`] best with a negative sum are evaluated exactly, their time re-allocated
//! with the wells moved when that is what pays.

use super::exchange::DEAR_SEARCH_MAX_WELL_LEGS;
use super::pick::{drift_beaten, drift_pick, point_pick, Choice, Pick};
use super::reallocate::{trial_improves, WellSearches};
use super::table::{LegTable, MAX_POINTS};
use super::types::{Settings, MAX_TARGETS};
use super::well_price::well_leg_count;
use super::work_units::{self, spend, Cut, Gauge};
use crate::indexed::IndexedExt as _;
use crate::work::Meter;

/// Pairs evaluated exactly per pair stage, the best-scored first.
pub(super) const PAIR_TRIALS: usize = 8;

/// One pair of changes and its first-order score.
#[derive(Clone, Copy, Debug)]
struct PairTrial {
    score_mps: f64,
    legs: (usize, usize),
    picks: (Pick, Pick),
}

/// A leg's alternatives with their optimistic first-order effects.
type Scored = heapless::Vec<(Pick, f64), { MAX_POINTS + 1 }>;

/// Leg `t`'s alternatives to `cur` (every other point of its table, then its drift at
/// `price` when it has one) into `out`, each with its first-order effect
/// `d(dv) + price d(t)` at its stored point (a Lambert well where the single-leg stage last
/// re-priced it). Ranking a well by the bound of its whole window instead (its bottom's Δv
/// at its earliest time) was tried: it filled the eight trials with wells that do not pay and
/// lost tuning seed 82's pair.
fn score_alternatives(
    t: &LegTable,
    cur: &Pick,
    drift: Option<&Pick>,
    price: f64,
    out: &mut Scored,
) {
    out.clear();
    let effect = |alt: &Pick| (alt.dv_mps - cur.dv_mps) + price * (alt.duration_s - cur.duration_s);
    for (i, p) in t.points.iter().indexed() {
        let alt = point_pick(i, p);
        if alt.choice == cur.choice {
            continue;
        }
        // At most MAX_POINTS points and one drift: the push cannot fail.
        let _ = out.push((alt, effect(&alt)));
    }
    if let Some(d) = drift {
        if cur.choice != Choice::Drift {
            let _ = out.push((*d, effect(d)));
        }
    }
}

/// Keep `trial` among the best-scored `PAIR_TRIALS` of `best` (ascending score): it replaces
/// the worst when the list is full and it beats it, then sinks into place (no index, so no
/// bounds check: the abort-proof C library links no panic path).
fn keep_best(best: &mut heapless::Vec<PairTrial, PAIR_TRIALS>, trial: PairTrial) {
    if best.is_full() {
        match best.last_mut() {
            Some(worst) if trial.score_mps < worst.score_mps => *worst = trial,
            _ => return,
        }
    } else {
        let _ = best.push(trial);
    }
    let mut rest = best.as_mut_slice();
    while let Some((last, init)) = rest.split_last_mut() {
        let Some(prev) = init.last_mut() else {
            break;
        };
        if last.score_mps < prev.score_mps {
            core::mem::swap(last, prev);
            rest = init;
        } else {
            break;
        }
    }
}

/// The pair stage: scores every pair of alternatives of every pair of legs at `price`, then
/// evaluates the best [`PAIR_TRIALS`] with a negative score exactly (time re-allocated, wells
/// moved when that pays), and keeps the first that lowers the total below `best_dv`: its price
/// and total, with `picks` updated. `None` when none does. Every step is charged to `meter`
/// first; [`Cut`] when the budget runs out (`picks` unchanged).
pub(super) fn pair_stage(
    tables: &[LegTable],
    (picks, trial): (&mut [Pick; MAX_TARGETS], &mut [Pick; MAX_TARGETS]),
    budget_s: f64,
    s: &Settings,
    (price, best_dv): (f64, f64),
    (iterations, exchanges, well_searches_left): (&mut u32, &mut u32, &mut u8),
    meter: &mut Meter,
) -> Result<Option<(f64, f64)>, Cut> {
    let n = tables.len().min(MAX_TARGETS);
    // Each leg's drift at the price (at a zero price the drift is the infinitely long one:
    // its score is not a number and a pair cannot be ranked by it).
    let mut drifts: [Option<Pick>; MAX_TARGETS] = [None; MAX_TARGETS];
    for ((t, cur), slot) in tables.iter().zip(picks.iter()).zip(drifts.iter_mut()) {
        spend(meter, work_units::alternatives_leg())?;
        if price <= 0.0
            || cur.choice == Choice::Drift
            || drift_beaten(t, price, cur.dv_mps + price * cur.duration_s)
        {
            continue;
        }
        let mut gauge = Gauge::metered(meter);
        let d = drift_pick(t, price, s, &mut gauge);
        if gauge.stopped() {
            return Err(Cut);
        }
        *slot = d.filter(|d| d.duration_s.is_finite());
    }
    // Each leg's least effect: a pair of legs whose two least effects cannot make a score below
    // the list's worst (or below zero) is passed over without scanning its alternatives (the
    // same list as a full scan, at a fraction of its cost on sixteen legs).
    let (mut alts_j, mut alts_k) = (Scored::new(), Scored::new());
    let mut least = [f64::INFINITY; MAX_TARGETS];
    for (((t, cur), d), slot) in tables
        .iter()
        .zip(picks.iter())
        .zip(drifts.iter())
        .zip(least.iter_mut())
    {
        spend(meter, work_units::pair_leg(t.points.len()))?;
        score_alternatives(t, cur, d.as_ref(), price, &mut alts_j);
        *slot = alts_j.iter().fold(f64::INFINITY, |m, (_, e)| m.min(*e));
    }
    let mut best: heapless::Vec<PairTrial, PAIR_TRIALS> = heapless::Vec::new();
    for j in 0..n {
        let (Some(tj), Some(cj), Some(dj), Some(lj)) =
            (tables.get(j), picks.get(j), drifts.get(j), least.get(j))
        else {
            continue;
        };
        let mut scored_j = false;
        for k in j.saturating_add(1)..n {
            let (Some(tk), Some(ck), Some(dk), Some(lk)) =
                (tables.get(k), picks.get(k), drifts.get(k), least.get(k))
            else {
                continue;
            };
            spend(meter, work_units::PAIR_TEST)?;
            let cutoff = match best.last() {
                Some(worst) if best.is_full() => worst.score_mps,
                _ => 0.0,
            };
            // A NaN sum is passed over too.
            if (lj + lk).partial_cmp(&cutoff) != Some(core::cmp::Ordering::Less) {
                continue;
            }
            if !scored_j {
                spend(meter, work_units::pair_leg(tj.points.len()))?;
                score_alternatives(tj, cj, dj.as_ref(), price, &mut alts_j);
                scored_j = true;
            }
            spend(
                meter,
                work_units::pair_scan(tj.points.len(), tk.points.len()),
            )?;
            score_alternatives(tk, ck, dk.as_ref(), price, &mut alts_k);
            for (a, ea) in alts_j.iter() {
                for (b, eb) in alts_k.iter() {
                    let score_mps = ea + eb;
                    if score_mps < 0.0 {
                        keep_best(
                            &mut best,
                            PairTrial {
                                score_mps,
                                legs: (j, k),
                                picks: (*a, *b),
                            },
                        );
                    }
                }
            }
        }
    }
    // A pair that frees or takes time may need the wells moved to show its worth; such
    // searches are dear (a golden section per well leg per price step), so the caller's
    // allowance bounds them over the solve.
    let affordable = well_leg_count(tables, picks) <= DEAR_SEARCH_MAX_WELL_LEGS;
    let mut well_searches = WellSearches {
        left: if affordable { *well_searches_left } else { 0 },
        retry_fitting: true,
    };
    for pair in best.iter() {
        spend(meter, work_units::ASSIGNMENT)?;
        *trial = *picks;
        let (j, k) = pair.legs;
        // j < k < n <= MAX_TARGETS: both slots exist.
        if let Some(slot) = trial.get_mut(j) {
            *slot = pair.picks.0;
        }
        if let Some(slot) = trial.get_mut(k) {
            *slot = pair.picks.1;
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
        if affordable {
            *well_searches_left = well_searches.left;
        }
        if let Some((p, dv)) = result? {
            *picks = *trial;
            return Ok(Some((p, dv)));
        }
    }
    Ok(None)
}
