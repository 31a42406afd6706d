//! The minimum of a polynomial over an interval on which its Bernstein control polygon is
//! convex: the keep-out search's (`verify.rs`) last levels.
//!
//! A convex control polygon makes the polynomial convex on the interval (the second
//! derivative's Bernstein coefficients are the polygon's second differences, times a positive
//! factor), so its minimum is where its derivative vanishes, and every tangent bounds it from
//! below: `p(v) >= p(u) + p'(u) (v - u)`. A safeguarded Newton iteration on `p'` reaches that
//! minimum to rounding in a few steps, each O(degree); subdivision gains one level per halving
//! of the interval, about 15 levels of O(degree^2) each at the keep-out search's tolerance
//! (measured on the paper's case at N = 10: 519 subdivisions in 30 searches).

use crate::indexed::IndexedExt as _;

/// Newton steps tried on one convex interval before it goes back to subdivision.
pub(crate) const MAX_NEWTON_STEPS: u32 = 12;

/// What the Newton iteration found on one convex interval, in its local variable `u` in [0, 1].
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct ConvexMinimum {
    /// Where the least value found is.
    pub at_u: f64,
    /// The least value found (a value of the polynomial, so an upper bound on its minimum).
    pub value: f64,
    /// No value on the interval is below `value - tol`... or below the caller's `best - tol`:
    /// the interval needs no more search.
    pub certified: bool,
    /// Polynomial evaluations spent (each costs about a third of a subdivision's work at
    /// degree 20, so the search's subdivision budget counts them as one each).
    pub steps: u32,
}

/// Whether the control polygon `c` (the coefficients of one interval) is convex: every second
/// difference non-negative.
pub(crate) fn is_convex(c: &[f64]) -> bool {
    c.windows(3).all(|w| match *w {
        [a, b, c] => (c - b) - (b - a) >= 0.0,
        _ => false,
    })
}

/// The polynomial with Bernstein coefficients `terms` (degree `terms.len() - 1`) at `u` in
/// [0, 1], by Horner's scheme in `u / (1 - u)` (or `(1 - u) / u` past the middle, so the ratio
/// stays at most 1 and every term is a convex weight of the coefficients: O(degree) and as
/// well conditioned as de Casteljau's O(degree^2) evaluation). `terms` is an iterator so that a
/// derivative's coefficients (the differences) need no array of their own on the stack.
fn evaluate<I>(terms: I, u: f64) -> f64
where
    I: DoubleEndedIterator<Item = f64> + ExactSizeIterator,
{
    let count = terms.len();
    let degree = count.saturating_sub(1) as f64;
    let mirrored = u > 0.5;
    let (ratio, weight) = if mirrored {
        ((1.0 - u) / u, u)
    } else {
        (u / (1.0 - u), 1.0 - u)
    };
    // Terms from the highest power of `ratio` down; the binomial C(degree, power) follows the
    // power down exactly (integers below 2^53 at degree 48).
    let mut sum = 0.0;
    let mut binomial = 1.0;
    let mut power = degree;
    let mut term = |value: f64| {
        sum = sum * ratio + binomial * value;
        binomial = binomial * power / (degree - power + 1.0);
        power -= 1.0;
    };
    if mirrored {
        terms.for_each(&mut term);
    } else {
        terms.rev().for_each(&mut term);
    }
    let mut scale = 1.0;
    for _ in 1..count {
        scale *= weight;
    }
    sum * scale
}

/// The Bernstein coefficients of the first derivative of `c`, over `degree`.
fn first_differences(c: &[f64]) -> impl DoubleEndedIterator<Item = f64> + ExactSizeIterator + '_ {
    c.windows(2).map(|w| match *w {
        [a, b] => b - a,
        _ => 0.0,
    })
}

/// The Bernstein coefficients of the second derivative of `c`, over `degree (degree - 1)`.
fn second_differences(c: &[f64]) -> impl DoubleEndedIterator<Item = f64> + ExactSizeIterator + '_ {
    c.windows(3).map(|w| match *w {
        [a, b, c] => (c - b) - (b - a),
        _ => 0.0,
    })
}

/// The minimum over the interval of the polynomial with the convex control polygon `c`, by
/// Newton's method on its derivative, kept inside the bracket where the derivative changes
/// sign (bisection when a step would leave it). Stops when the tangent at the last point
/// bounds every value above `min(best, found) - tol`: `certified`. After `MAX_NEWTON_STEPS`
/// evaluations without that, returns the least value found, not certified.
pub(crate) fn convex_minimum(c: &[f64], tol: f64, best: f64) -> ConvexMinimum {
    let (&first, &last) = match (c.first(), c.last()) {
        (Some(first), Some(last)) => (first, last),
        _ => {
            return ConvexMinimum {
                at_u: 0.0,
                value: f64::INFINITY,
                certified: true,
                steps: 0,
            }
        }
    };
    let mut found = ConvexMinimum {
        at_u: 0.0,
        value: f64::INFINITY,
        certified: false,
        steps: 0,
    };
    // A convex polynomial that rises from the start (or falls to the end) is least there.
    let endpoint = |at_u, value| ConvexMinimum {
        at_u,
        value,
        certified: true,
        steps: 0,
    };
    let mut slopes = first_differences(c);
    match (slopes.next(), slopes.next_back()) {
        (Some(slope), _) if slope >= 0.0 => return endpoint(0.0, first),
        (_, Some(slope)) if slope <= 0.0 => return endpoint(1.0, last),
        (None, _) => return endpoint(0.0, first),
        _ => {}
    }
    // Start where the derivative's control polygon crosses zero.
    let degree = c.len().saturating_sub(1) as f64;
    let spans = (degree - 1.0).max(1.0);
    let mut u = 0.5;
    for (k, w) in c.windows(3).indexed() {
        // Consecutive derivative coefficients d_k, d_(k+1) (`first_differences`).
        let &[c0, c1, c2] = w else { continue };
        let (a, b) = (c1 - c0, c2 - c1);
        if a < 0.0 && b >= 0.0 {
            u = (k as f64 + a / (a - b)) / spans;
            break;
        }
    }
    let (mut lo, mut hi) = (0.0, 1.0);
    while found.steps < MAX_NEWTON_STEPS {
        found.steps = found.steps.saturating_add(1);
        let value = evaluate(c.iter().copied(), u);
        let slope = degree * evaluate(first_differences(c), u);
        let curvature = degree * (degree - 1.0) * evaluate(second_differences(c), u);
        if value < found.value {
            found.value = value;
            found.at_u = u;
        }
        // The tangent at u, least at the interval's end it falls toward.
        let lower = value
            + if slope > 0.0 {
                -u * slope
            } else {
                (1.0 - u) * slope
            };
        if lower >= best.min(found.value) - tol {
            found.certified = true;
            return found;
        }
        if slope < 0.0 {
            lo = u;
        } else {
            hi = u;
        }
        let newton = u - slope / curvature;
        u = if curvature > 0.0 && newton > lo && newton < hi {
            newton
        } else {
            0.5 * (lo + hi)
        };
    }
    found
}

#[cfg(test)]
#[allow(clippy::needless_range_loop)]
mod tests {
    use super::*;
    use crate::pseudospectral::verify::MAX_PRODUCT;

    /// Bernstein coefficients of the polynomial `sum_i power[i] u^i` (the exact conversion).
    fn power_to_bernstein(power: &[f64]) -> [f64; MAX_PRODUCT] {
        // p(u) = sum a_i u^i; b_k = sum_{i <= k} C(k, i) / C(n, i) a_i.
        let n = power.len() - 1;
        let choose = |n: usize, k: usize| -> f64 {
            (0..k).fold(1.0, |acc, j| acc * (n - j) as f64 / (j + 1) as f64)
        };
        let mut out = [0.0; MAX_PRODUCT];
        for k in 0..=n {
            out[k] = (0..=k)
                .map(|i| choose(k, i) / choose(n, i) * power[i])
                .sum();
        }
        out
    }

    #[test]
    fn evaluation_matches_the_power_form_on_both_halves() {
        let power = [0.3, -1.2, 2.5, 0.7, -0.4, 1.1];
        let c = power_to_bernstein(&power);
        for step in 0..=20 {
            let u = f64::from(step) / 20.0;
            let direct: f64 = power
                .iter()
                .enumerate()
                .map(|(i, a)| a * u.powi(i as i32))
                .sum();
            assert!(
                (evaluate(c[..6].iter().copied(), u) - direct).abs() < 1e-14,
                "u {u}"
            );
        }
    }

    #[test]
    fn a_convex_quartic_is_minimised_to_rounding_and_certified() {
        // p(u) = (u - r)^2 + (u - r)^4 / 2 + 0.25: least 0.25 at u = r (its degree-4 polygon is
        // convex; with (u - r)^4 weighted 2 it is not, though the polynomial is).
        let r: f64 = 0.3141;
        let power = [
            r * r + 0.5 * r.powi(4) + 0.25,
            -2.0 * r - 2.0 * r.powi(3),
            1.0 + 3.0 * r * r,
            -2.0 * r,
            0.5,
        ];
        let c = power_to_bernstein(&power);
        assert!(is_convex(&c[..5]));
        let m = convex_minimum(&c[..5], 1e-15, f64::INFINITY);
        assert!(m.certified);
        assert!(m.steps <= 5, "{} steps", m.steps);
        assert!((m.at_u - r).abs() < 1e-7, "{}", m.at_u);
        assert!((m.value - 0.25).abs() < 1e-15, "{}", m.value);
    }

    #[test]
    fn a_monotone_convex_polynomial_is_least_at_its_end() {
        let rising = power_to_bernstein(&[1.0, 0.5, 0.25]);
        let m = convex_minimum(&rising[..3], 1e-12, f64::INFINITY);
        assert_eq!((m.at_u, m.value, m.certified), (0.0, 1.0, true));
        let falling = power_to_bernstein(&[1.0, -3.0, 0.25]);
        let m = convex_minimum(&falling[..3], 1e-12, f64::INFINITY);
        assert_eq!(m.at_u, 1.0);
        assert!((m.value - (-1.75)).abs() < 1e-15);
    }

    #[test]
    fn a_polygon_with_a_dent_is_not_convex() {
        assert!(!is_convex(&[1.0, 0.0, 0.5, 0.4]));
        assert!(is_convex(&[1.0, 0.0, 0.5, 1.5]));
    }

    #[test]
    fn the_minimum_is_never_reported_below_the_polynomial() {
        // Every reported value is a value of the polynomial, and a certified one is within tol
        // of a dense sampling's least value.
        for shift in 1..40 {
            let r = f64::from(shift) / 40.0;
            let c = power_to_bernstein(&[r * r + 0.1, -2.0 * r, 1.0, 0.0, 0.3]);
            let m = convex_minimum(&c[..5], 1e-13, f64::INFINITY);
            let sampled = (0..=4000)
                .map(|k| evaluate(c[..5].iter().copied(), f64::from(k) / 4000.0))
                .fold(f64::INFINITY, f64::min);
            assert!((evaluate(c[..5].iter().copied(), m.at_u) - m.value).abs() < 1e-15);
            assert!(m.certified);
            assert!(
                m.value <= sampled + 1e-13,
                "r {r}: {} vs {sampled}",
                m.value
            );
        }
    }
}
