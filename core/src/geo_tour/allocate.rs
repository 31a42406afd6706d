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

use super::exchange::exchange;
use super::root::illinois;
use super::table::{LegTable, Point};
use super::types::{Settings, MAX_TARGETS};
use super::well_price::{dv_floor_mps, has_well_leg, wells_allocate};
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

/// Drift legs' time for the choices in `picks` (points fixed): the price at which their
/// durations fill `budget_s`, durations written into `picks`. `None` when the drift legs'
/// fastest durations exceed the budget. `hint` (a price near the answer, e.g. the current
/// one when a single leg's choice changes) starts the bracket there, widening it
/// geometrically, instead of from the fastest drifts.
///
/// Every step (one drift root per drift leg) is charged first; [`Cut`] when the budget runs
/// out (`picks` then holds a partial re-allocation: the caller discards it).
pub(super) fn drift_allocate(
    tables: &[LegTable],
    picks: &mut [Pick],
    budget_s: f64,
    s: &Settings,
    iterations: &mut u32,
    hint: Option<f64>,
    meter: &mut Meter,
) -> Result<Option<f64>, Cut> {
    let mut fixed = 0.0;
    let mut fastest = 0.0;
    let mut top = 0.0_f64;
    let mut any = false;
    for (t, p) in tables.iter().zip(picks.iter()) {
        match (p.choice, t.drift.as_ref()) {
            (Choice::Drift, Some(d)) => {
                any = true;
                fastest += d.t_min_s;
                let Some(c) = d.curve.as_ref() else {
                    return Ok(None);
                };
                top = top.max(c.top_price);
            }
            (Choice::Drift, None) => return Ok(None),
            (Choice::Point(_), _) => fixed += p.duration_s,
        }
    }
    let budget = budget_s - fixed;
    if !any {
        return Ok((budget >= 0.0).then_some(0.0));
    }
    if fastest > budget {
        return Ok(None);
    }
    // The legs' drift picks (a pick beyond the legs is not the tour's).
    let drift_legs = tables.iter().zip(picks.iter()).fold(0_usize, |n, (_, p)| {
        n.saturating_add(usize::from(p.choice == Choice::Drift))
    });
    let step_units = work_units::price_step(tables.len(), drift_legs);
    // Every evaluation of the drift legs' time is charged first, its roots' evaluations as
    // they run (`?`: the budget ran out).
    let mut drift_time = |price: f64, picks: &mut [Pick]| -> Result<f64, Cut> {
        spend(meter, step_units)?;
        let mut gauge = Gauge::metered(meter);
        let mut sum = 0.0;
        for (t, p) in tables.iter().zip(picks.iter_mut()) {
            if p.choice == Choice::Drift {
                let q = drift_pick(t, price, s, &mut gauge);
                if gauge.stopped() {
                    return Err(Cut);
                }
                if let Some(q) = q {
                    sum += q.duration_s;
                    *p = q;
                }
            }
        }
        Ok(sum)
    };
    // w = 1/sqrt(price); the drift legs' time grows with w. w_top: every drift leg at its
    // fastest (time <= budget). The bracket [w_a, w_b] has time <= budget at w_a and above it
    // at w_b.
    let w_top = 1.0 / libm::sqrt(top);
    let (mut w_a, mut fa, mut w_b, mut fb) = (w_top, f64::NAN, w_top, f64::NAN);
    let mut bracketed = false;
    if let Some(h) = hint.filter(|h| h.is_finite() && *h > 0.0 && *h < top) {
        // Widen from the hint by factors 1.001, 1.004, 1.016, ... until the sign changes.
        let w0 = 1.0 / libm::sqrt(h);
        let f0 = drift_time(h, picks)? - budget;
        let mut step = 1.001;
        if f0 <= 0.0 {
            (w_a, fa) = (w0, f0);
            for _ in 0..64 {
                let w = w_a * step;
                let f = drift_time(1.0 / (w * w), picks)? - budget;
                if f > 0.0 {
                    (w_b, fb, bracketed) = (w, f, true);
                    break;
                }
                (w_a, fa) = (w, f);
                step = 1.0 + 4.0 * (step - 1.0);
            }
        } else if f0 > 0.0 {
            (w_b, fb) = (w0, f0);
            for _ in 0..64 {
                let w = w_b / step;
                if w <= w_top {
                    break;
                }
                let f = drift_time(1.0 / (w * w), picks)? - budget;
                if f <= 0.0 {
                    (w_a, fa, bracketed) = (w, f, true);
                    break;
                }
                (w_b, fb) = (w, f);
                step = 1.0 + 4.0 * (step - 1.0);
            }
            if !bracketed {
                // Down to the fastest drifts: the bracket's lower end is w_top.
                fa = drift_time(top, picks)? - budget;
                if fa >= -s.time_tol_s {
                    return Ok(Some(top));
                }
                w_a = w_top;
                bracketed = fa <= 0.0;
            }
        }
    }
    if !bracketed {
        // From the fastest drifts up by factors of 4.
        w_a = w_top;
        fa = drift_time(top, picks)? - budget;
        if fa >= -s.time_tol_s {
            return Ok(Some(top));
        }
        w_b = w_a;
        fb = fa;
        for _ in 0..64 {
            w_b *= 4.0;
            fb = drift_time(1.0 / (w_b * w_b), picks)? - budget;
            if fb > 0.0 {
                break;
            }
        }
    }
    if fb.is_nan() || fb <= 0.0 || fa.is_nan() || fa > 0.0 {
        return Ok(None);
    }
    let ((w, _, _, _, steps), cut) = weight_search(
        |price| drift_time(price, picks),
        budget,
        (w_a, fa),
        (w_b, fb),
        s,
        s.time_tol_s,
    );
    if cut {
        return Err(Cut);
    }
    *iterations = iterations.saturating_add(u32::from(steps));
    let price = 1.0 / (w * w);
    drift_time(price, picks)?;
    Ok(Some(price))
}

/// Re-allocate the time of the assignment `picks`: its drift legs' by their price
/// ([`drift_allocate`]); when that cannot fit the mission time (or, with
/// `well_searches.retry_fitting`, does not beat `best_dv`) and the assignment has a leg on a
/// Lambert well, its wells and drifts moved by one price ([`wells_allocate`]), unless it cannot
/// beat `best_dv` however they move (`dv_floor_mps`) or `well_searches` (the caller's allowance
/// of such searches, each dear: a golden section per well leg per step) is spent.
/// The price, or `None` when the assignment cannot fit (or cannot beat `best_dv`); [`Cut`] as
/// the two re-allocations.
#[allow(clippy::too_many_arguments)]
pub(super) fn reallocate(
    tables: &[LegTable],
    picks: &mut [Pick],
    budget_s: f64,
    s: &Settings,
    iterations: &mut u32,
    hint: Option<f64>,
    (best_dv, well_searches): (f64, &mut WellSearches),
    meter: &mut Meter,
) -> Result<Option<f64>, Cut> {
    if let Some(price) = drift_allocate(tables, picks, budget_s, s, iterations, hint, meter)? {
        // Kept when it beats `best_dv`; else its wells may still be where another price left
        // them (a drift leg just added sets a price the wells were not searched at), and only
        // moving them with the drifts shows whether the assignment pays.
        if !well_searches.retry_fitting || totals(tables, picks).1 < best_dv {
            return Ok(Some(price));
        }
    }
    if well_searches.left == 0
        || !has_well_leg(tables, picks)
        || dv_floor_mps(tables, picks) >= best_dv
    {
        return Ok(None);
    }
    well_searches.left = well_searches.left.saturating_sub(1);
    wells_allocate(
        tables,
        picks,
        budget_s,
        s,
        iterations,
        (hint, best_dv),
        meter,
    )
}

/// The searches moving the wells ([`wells_allocate`]) a caller of [`reallocate`] allows.
pub(super) struct WellSearches {
    /// How many may still start.
    pub left: u8,
    /// Whether an assignment that fits by its drifts alone but does not beat the best is
    /// searched again with its wells moved (the exchange search, for a leg turned to a
    /// drift).
    pub retry_fitting: bool,
}

/// Illinois on the price weight `w` (the price is `1 / w^2`) for the tour time `time(price)`
/// to meet `budget_s`, from the bracket `(w_a, f(w_a)) .. (w_b, f(w_b))` of `f = time -
/// budget_s`: [`illinois`]'s final bracket and steps, and whether a step was refused (`Cut`
/// reads NaN, which stops the search).
pub(super) fn weight_search(
    mut time: impl FnMut(f64) -> Result<f64, Cut>,
    budget_s: f64,
    (w_a, fa): (f64, f64),
    (w_b, fb): (f64, f64),
    s: &Settings,
    time_tol_s: f64,
) -> ((f64, f64, f64, f64, u16), bool) {
    let mut cut = false;
    let bracket = illinois(
        |w| match time(1.0 / (w * w)) {
            Ok(t) => t - budget_s,
            Err(Cut) => {
                cut = true;
                f64::NAN
            }
        },
        w_a,
        fa,
        w_b,
        fb,
        s.price_max_iter,
        1e-9,
        time_tol_s,
    );
    (bracket, cut)
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
