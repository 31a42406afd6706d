//! A bounded bracketing root finder (Illinois regula falsi with a bisection every fourth
//! step, so a step function cannot stall it), and the metered bisection that finishes a search.

use super::work_units::Gauge;

/// Bisection of `[lo, hi]` down to adjacent floats, at most `max_iter` steps: `keep_lo(mid)`
/// moves `lo` to `mid`, else `hi` moves there. Each evaluation is taken from `gauge` first;
/// `None` when one is refused (the search stops where it is). Returns the final `(lo, hi)`.
pub(crate) fn metered_bisection(
    mut lo: f64,
    mut hi: f64,
    max_iter: u16,
    gauge: &mut Gauge<'_>,
    eval: u64,
    mut keep_lo: impl FnMut(f64) -> bool,
) -> Option<(f64, f64)> {
    for _ in 0..max_iter {
        let mid = 0.5 * (lo + hi);
        if mid <= lo || mid >= hi {
            break;
        }
        if !gauge.take(eval) {
            return None;
        }
        if keep_lo(mid) {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    Some((lo, hi))
}

/// [`illinois`] from `(a, f(a))` to `(b, f(b))` with the geometric searches' tolerances
/// (adjacent floats, no tolerance on `f`), each evaluation taken from `gauge` first: a refused
/// one reads NaN, which stops the search, and the answer is `None`. Else the final bracket.
pub(crate) fn metered_illinois(
    mut f: impl FnMut(f64) -> f64,
    (a, fa): (f64, f64),
    (b, fb): (f64, f64),
    max_iter: u16,
    gauge: &mut Gauge<'_>,
    eval: u64,
) -> Option<(f64, f64, f64, f64)> {
    let (a, fa, b, fb, _) = illinois(
        |x| if gauge.take(eval) { f(x) } else { f64::NAN },
        a,
        fa,
        b,
        fb,
        max_iter,
        1e-15,
        0.0,
    );
    (!gauge.stopped()).then_some((a, fa, b, fb))
}

/// Root of a non-decreasing `f` on `[a, b]` given `fa = f(a) <= 0 < fb = f(b)`. Returns the
/// final bracket `(a, fa, b, fb, steps)`: `f(a) <= 0 < f(b)` always holds, so `a` is the
/// "feasible" end when `f <= 0` means feasible. Stops after `max_iter` steps, when the bracket
/// is narrower than `xtol * (1 + |a|)`, or when `-ftol <= f(a) <= 0`.
#[allow(clippy::too_many_arguments)]
pub(crate) fn illinois<F: FnMut(f64) -> f64>(
    mut f: F,
    mut a: f64,
    mut fa: f64,
    mut b: f64,
    mut fb: f64,
    max_iter: u16,
    xtol: f64,
    ftol: f64,
) -> (f64, f64, f64, f64, u16) {
    // Illinois weights (halved end values) are kept apart from the true values.
    let (mut wa, mut wb) = (fa, fb);
    let mut side = 0i8;
    let mut steps = 0u16;
    for k in 0..max_iter {
        if (b - a).abs() <= xtol * (1.0 + a.abs()) || (fa <= 0.0 && -fa <= ftol) {
            break;
        }
        steps = steps.saturating_add(1);
        let mut c = (a * wb - b * wa) / (wb - wa);
        if k % 4 == 3 || !(c > a && c < b) {
            c = 0.5 * (a + b);
        }
        let fc = f(c);
        if fc.is_nan() {
            break;
        }
        if fc <= 0.0 {
            a = c;
            fa = fc;
            wa = fc;
            if side < 0 {
                wb *= 0.5;
            }
            side = -1;
        } else {
            b = c;
            fb = fc;
            wb = fc;
            if side > 0 {
                wa *= 0.5;
            }
            side = 1;
        }
    }
    (a, fa, b, fb, steps)
}

/// Root of a non-decreasing `f` on `[a, b]` given `fa = f(a) <= 0 < fb = f(b)`, for a smooth,
/// nearly linear `f` bracketed closely: secant steps through the two latest points (order
/// 1.6, where regula falsi keeps a stale end), kept inside the bracket (a bisection instead
/// when the secant leaves it). Stops after `max_iter` evaluations, when `|f| <= ftol`, or
/// when the bracket is narrower than `xtol * (1 + |a|)`. Returns the point with the smaller
/// `|f|` (the bracket's positive end only when `a` is 0, the caller's excluded origin).
#[allow(clippy::too_many_arguments)]
pub(crate) fn secant_root<F: FnMut(f64) -> f64>(
    mut f: F,
    mut a: f64,
    mut fa: f64,
    mut b: f64,
    mut fb: f64,
    max_iter: u16,
    xtol: f64,
    ftol: f64,
) -> f64 {
    // The two latest points, (p, fp) the older.
    let (mut p, mut fp, mut q, mut fq) = (a, fa, b, fb);
    for _ in 0..max_iter {
        if (b - a).abs() <= xtol * (1.0 + a.abs()) {
            break;
        }
        let mut c = q - fq * (q - p) / (fq - fp);
        if !(c > a && c < b) {
            c = 0.5 * (a + b);
        }
        let fc = f(c);
        if fc.is_nan() {
            break;
        }
        if fc <= 0.0 {
            (a, fa) = (c, fc);
        } else {
            (b, fb) = (c, fc);
        }
        (p, fp, q, fq) = (q, fq, c, fc);
        if fc.abs() <= ftol {
            break;
        }
    }
    if fa.abs() <= fb.abs() && a > 0.0 {
        a
    } else {
        b
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn finds_smooth_roots_and_steps() {
        let (a, _, b, _, n) = illinois(|x| x * x * x - 2.0, 0.0, -2.0, 2.0, 6.0, 100, 1e-15, 0.0);
        assert!((a - libm::cbrt(2.0)).abs() < 1e-14 && b >= a, "{a} {b}");
        assert!(n < 40, "{n}");
        let step = |x: f64| if x < 0.3 { -1.0 } else { 1.0 };
        let (a, fa, b, fb, _) = illinois(step, 0.0, -1.0, 1.0, 1.0, 200, 1e-12, 0.0);
        assert!(fa <= 0.0 && fb > 0.0 && (b - a) < 1e-11 && (a - 0.3).abs() < 1e-11);
    }

    #[test]
    fn secant_finds_smooth_roots_and_survives_a_step() {
        let x = secant_root(|x| x * x * x - 2.0, 1.0, -1.0, 2.0, 6.0, 100, 1e-15, 0.0);
        assert!((x - libm::cbrt(2.0)).abs() < 1e-14, "{x}");
        let step = |x: f64| if x < 0.3 { -1.0 } else { 1.0 };
        let x = secant_root(step, 0.1, -1.0, 1.0, 1.0, 200, 1e-12, 0.0);
        assert!((x - 0.3).abs() < 1e-11, "{x}");
    }
}
