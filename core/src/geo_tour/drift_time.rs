//! The drift legs' time for an assignment whose points are fixed: the price at which the drift
//! legs' durations fill the mission time ([`drift_allocate`]), and the Illinois search on the
//! price weight that both it and [`super::well_price`] close their brackets with
//! ([`weight_search`]).

use super::pick::{drift_pick, Choice, Pick};
use super::root::illinois;
use super::table::LegTable;
use super::types::Settings;
use super::work_units::{self, spend, Cut, Gauge};
use crate::work::Meter;

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
