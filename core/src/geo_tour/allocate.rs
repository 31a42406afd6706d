//! Exact time allocation by a Lagrange time price.
//!
//! For a price `lambda` (m/s of Δv per second of time) every leg independently minimises
//! `dv_j(t) + lambda t` over its options: the drift depth (continuous, convex in t) and the
//! point options (Hohmann, radial, direct Lambert, Lambert well bottoms). The tour's time
//! `sum t_j(lambda)` does not increase with lambda; a bracketing search (in `w = 1/sqrt
//! lambda`, where the drift legs' time is nearly linear) finds the price at which the tour
//! just fits the mission time. Where point options switch at that price the Lagrangian leaves
//! a duality gap: the switching legs are tried both ways (2^k assignments), each with the
//! drift legs' time re-allocated exactly for the points it fixes. Then an exchange search tries
//! every alternative with a negative first-order effect at the current price (Lambert wells
//! re-priced first), each evaluated exactly. See docs/geo-tour.md for the proof of exactness on
//! drift legs and the brute-force evidence for the rest.

use super::drift_time::weight_search;
use super::exchange::exchange;
use super::pick::{pick_all, totals, Pick};
use super::reallocate::{reallocate, WellSearches};
use super::table::LegTable;
use super::types::{Settings, MAX_TARGETS};
use super::work_units::{self, spend, Cut};
use crate::indexed::IndexedExt as _;
use crate::work::Meter;

/// The allocation cut short by the budget at `price`, with the feasible assignment `picks`.
fn stopped(
    tables: &[LegTable],
    picks: &[Pick],
    price: f64,
    iterations: u32,
    (assignments, refined): (u32, u8),
) -> Allocation {
    let (time_s, dv_mps) = totals(tables, picks);
    Allocation {
        price,
        dv_mps,
        time_s,
        iterations,
        gap_assignments: assignments,
        refined,
        cut: true,
    }
}

/// Result of an allocation.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Allocation {
    pub price: f64,
    pub dv_mps: f64,
    pub time_s: f64,
    pub iterations: u32,
    pub gap_assignments: u32,
    pub refined: u8,
    /// The work budget ran out: the picks are the best feasible assignment found before.
    pub cut: bool,
}

/// Why an allocation returned no picks.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum NoAllocation {
    /// No feasible assignment was found (the fastest tour fits, so a numerical failure).
    Failed,
    /// The work budget ran out before any feasible assignment was found.
    Cut,
}

/// Allocate the mission time `budget_s` over the legs. `picks` receives each leg's choice and
/// duration; `lo_picks` and `trial` are working copies. Every step is charged to `meter`
/// first; when the budget runs out the best feasible assignment found so far is returned
/// (`cut`). [`NoAllocation::Failed`] when no feasible assignment is found (the caller has
/// already checked that the fastest tour fits, so this means a numerical failure),
/// [`NoAllocation::Cut`] when the budget ran out before one was.
pub(crate) fn allocate(
    tables: &mut [LegTable],
    budget_s: f64,
    s: &Settings,
    (picks, lo_picks, trial): (
        &mut [Pick; MAX_TARGETS],
        &mut [Pick; MAX_TARGETS],
        &mut [Pick; MAX_TARGETS],
    ),
    meter: &mut Meter,
) -> Result<Allocation, NoAllocation> {
    let n = tables.len();
    let mut iterations = 0u32;
    let cut = |_: Cut| NoAllocation::Cut;
    // Does time bind at all? With no drift leg the cheapest points may fit.
    let any_drift = tables.iter().any(|t| t.drift.is_some());
    if !any_drift {
        let tt = pick_all(tables, 0.0, s, picks, meter).map_err(cut)?;
        if tt <= budget_s {
            let (time_s, dv_mps) = totals(tables, picks);
            return Ok(Allocation {
                price: 0.0,
                dv_mps,
                time_s,
                iterations,
                gap_assignments: 0,
                refined: 0,
                cut: false,
            });
        }
    }
    // Bracket the critical price: w_a feasible (time <= budget), w_b not.
    let mut w_a = 1e3;
    let mut fa = pick_all(tables, 1.0 / (w_a * w_a), s, picks, meter).map_err(cut)? - budget_s;
    for _ in 0..64 {
        if fa <= 0.0 {
            break;
        }
        w_a *= 0.25;
        fa = pick_all(tables, 1.0 / (w_a * w_a), s, picks, meter).map_err(cut)? - budget_s;
    }
    if fa.is_nan() || fa > 0.0 {
        return Err(NoAllocation::Failed);
    }
    // From here `picks` always holds a feasible assignment: a cut returns it.
    let mut price = 1.0 / (w_a * w_a);
    let mut w_b = w_a;
    let mut fb = fa;
    for _ in 0..64 {
        w_b *= 4.0;
        fb = match pick_all(tables, 1.0 / (w_b * w_b), s, lo_picks, meter) {
            Ok(t) => t - budget_s,
            Err(Cut) => return Ok(stopped(tables, picks, price, iterations, (0, 0))),
        };
        if fb > 0.0 {
            break;
        }
    }
    let (wa, wb) = if fb > 0.0 {
        let ((a, _, b, _, steps), was_cut) = weight_search(
            |price| pick_all(tables, price, s, trial, meter),
            budget_s,
            (w_a, fa),
            (w_b, fb),
            s,
            s.time_tol_s,
        );
        iterations = iterations.saturating_add(u32::from(steps));
        if was_cut {
            return Ok(stopped(tables, picks, price, iterations, (0, 0)));
        }
        (a, b)
    } else {
        // Time never binds (points only and all fit at every price tried).
        (w_b, w_b)
    };
    // Into `trial` first: a step cut short leaves its picks half written.
    if pick_all(tables, 1.0 / (wa * wa), s, trial, meter).is_err() {
        return Ok(stopped(tables, picks, price, iterations, (0, 0)));
    }
    *picks = *trial;
    price = 1.0 / (wa * wa);
    if pick_all(tables, 1.0 / (wb * wb), s, lo_picks, meter).is_err() {
        return Ok(stopped(tables, picks, price, iterations, (0, 0)));
    }
    // Duality gap: legs whose choice differs across the bracket, tried both ways.
    let mut switching = [0usize; MAX_TARGETS];
    let mut k = 0usize;
    for j in 0..n {
        let (Some(a), Some(b)) = (picks.get(j), lo_picks.get(j)) else {
            continue;
        };
        if a.choice != b.choice && k < usize::from(s.gap_max_legs) {
            if let Some(slot) = switching.get_mut(k) {
                *slot = j;
                k = k.saturating_add(1);
            }
        }
    }
    let mut best_dv = f64::INFINITY;
    let mut best_price = price;
    let mut assignments = 0u32;
    // 2^k assignments; k <= gap_max_legs <= MAX_GAP_LEGS (6, validated), so 64 at most.
    let mut combos = 1u32;
    for _ in 0..k {
        combos = combos.saturating_mul(2);
    }
    let hi_copy = *picks;
    // Every assignment of the gap (at most 2^6) may have its wells moved when its drifts alone
    // cannot fit it.
    let mut gap_well_searches = WellSearches {
        left: u8::MAX,
        retry_fitting: false,
    };
    for mask in 0..combos {
        let tried = spend(meter, work_units::ASSIGNMENT).and_then(|()| {
            *trial = hi_copy;
            for (bit, &j) in switching.iter().take(k).indexed() {
                if (mask >> bit) & 1 == 1 {
                    if let (Some(t), Some(l)) = (trial.get_mut(j), lo_picks.get(j)) {
                        *t = *l;
                    }
                }
            }
            assignments = assignments.saturating_add(1);
            reallocate(
                tables,
                trial,
                budget_s,
                s,
                &mut iterations,
                Some(price),
                (best_dv, &mut gap_well_searches),
                meter,
            )
        });
        let p = match tried {
            Ok(Some(p)) => p,
            Ok(None) => continue,
            // `picks` holds the best assignment so far (the bracket's feasible end if none).
            Err(Cut) => {
                let at = if best_dv.is_finite() {
                    best_price
                } else {
                    price
                };
                return Ok(stopped(tables, picks, at, iterations, (assignments, 0)));
            }
        };
        let (time_s, dv) = totals(tables, trial);
        if time_s <= budget_s && dv < best_dv {
            best_dv = dv;
            best_price = p;
            *picks = *trial;
        }
    }
    if !best_dv.is_finite() {
        return Err(NoAllocation::Failed);
    }
    price = best_price;
    let mut exchanges = 0u32;
    let mut refined = 0u8;
    let mut exchange_cut = false;
    if let Some((p, _)) = exchange(
        tables,
        (picks, trial),
        budget_s,
        s,
        (price, best_dv),
        (&mut iterations, &mut exchanges, &mut refined),
        (meter, &mut exchange_cut),
    ) {
        price = p;
    }
    let (time_s, dv_mps) = totals(tables, picks);
    Ok(Allocation {
        price,
        dv_mps,
        time_s,
        iterations,
        gap_assignments: assignments.saturating_add(exchanges),
        refined,
        cut: exchange_cut,
    })
}
