//! The largest eigenvalue of the certificate's projected curvature `P S P` (see `certificate`)
//! by the Lanczos method: the certificate's smallest reduced-Hessian eigenvalue is one minus it.
//!
//! Why Lanczos: `S` is the identity's complement of rank at most two per active keep-out check
//! plus one per envelope correction, so the Krylov space from any start has dimension at most
//! that rank plus one, and Lanczos is exact (in exact arithmetic) once it has spanned it: about
//! ten products on the paper's case, where the power method took up to `POWER_ITERATIONS` (120).
//! After `k` steps its largest Ritz value is at least the Rayleigh quotient of the power method's
//! `k`-th iterate from the same start (that iterate lies in the same Krylov space), and in exact
//! arithmetic never exceeds the true largest eigenvalue. In floating point that holds while the
//! Lanczos vectors stay near orthogonal: the run stops at the Krylov dimension
//! (`Curvature::krylov_dimension`), because a step past it normalises rounding into a vector
//! that is not orthogonal to the earlier ones, and then a Ritz value can leave the spectrum
//! (measured, issue 28: 48 steps on a three-spacecraft swap put one 1.25e-6 above a flat
//! direction's 1.0, a dense eigen-decomposition of `P S P` gives 1.0 to 4e-16; stopped at the
//! dimension, 10 steps, 1.0 to 2e-15). At the dimension the space is exhausted and the smallest
//! Ritz value bounds every power iterate from the same start (`Estimate::smallest_exhausted`).
//! The certificate reports the larger of this and the power method's value (both from below).
//!
//! Deterministic: a fixed start, a fixed step bound (the Krylov dimension, at most
//! `LANCZOS_STEPS`), a fixed Laguerre bound (`LAGUERRE_STEPS`).

use super::curvature::Curvature;
use super::kernel::{dot, scale, Coefficients};

/// Most Lanczos steps (each one product with `P S P`). Stops earlier when the Krylov space is
/// exhausted or the largest Ritz value has settled (`SETTLED_REL`).
pub const LANCZOS_STEPS: usize = 60;
/// The largest Ritz value is recomputed every this many steps (each a few Laguerre steps on the
/// tridiagonal matrix, below).
const CHECK_EVERY: usize = 4;
/// Settled: changed by at most this, relative to `1 + |value|`, over `CHECK_EVERY` steps (far
/// below `CURVATURE_TOL`, 1e-6, the certificate's resolution).
const SETTLED_REL: f64 = 1e-12;
/// The Krylov space is exhausted when a new direction's norm falls below this times the
/// operator's scale seen so far (rounding level, not a tolerance of the answer).
const EXHAUSTED_REL: f64 = 1e-13;
/// Laguerre steps for the tridiagonal's largest eigenvalue at most. From the right of the
/// spectrum Laguerre's method converges monotonically to the largest eigenvalue, cubically once
/// it is isolated and in one step where the eigenvalues coincide; measured on the fixtures' and
/// the generated families' certificates: at most 7 steps (`tests`, below, holds a worst case).
const LAGUERRE_STEPS: usize = 40;
/// Laguerre stops when its step is this small relative to `1 + |value|`: far below
/// `SETTLED_REL` and the certificate's `CURVATURE_TOL`.
const STEP_REL: f64 = 1e-14;
/// Starts tried above the previous value before falling back to the Gershgorin bound (each one
/// Sturm sweep; the reach grows 16-fold per try, so 8 tries span 2e9 times the first).
const START_TRIES: usize = 8;

/// What the Lanczos run found.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) struct Estimate {
    /// The largest Ritz value: not above the largest eigenvalue of `P S P` (up to rounding).
    pub largest: f64,
    /// The smallest Ritz value, from below, when the Krylov space of the start was exhausted:
    /// then the Ritz values are the eigenvalues of `P S P` on that space, the space every power
    /// iterate from the same start stays in, so the power method may be shifted by it exactly
    /// (`certificate`). `None` when the run stopped before exhausting the space.
    pub smallest_exhausted: Option<f64>,
    /// Products with `P S P` taken.
    pub steps: usize,
}

/// The largest eigenvalue of `P S P` on the null space, from `start` (projected, not
/// normalised; overwritten) with `other` as the second Lanczos vector's buffer. Returns the
/// estimate (`Estimate`), or `None` when a value is not finite.
pub(super) fn largest(
    op: &Curvature<'_>,
    start: &mut Coefficients,
    other: &mut Coefficients,
    size: (usize, usize),
) -> Option<Estimate> {
    let norm = libm::sqrt(dot(start, start, size));
    if norm <= 1e-12 {
        // The null space holds no curvature direction from this start: as the power method.
        return Some(Estimate {
            largest: 0.0,
            smallest_exhausted: None,
            steps: 0,
        });
    }
    scale(start, 1.0 / norm, size);
    *other = [[0.0; crate::capacity::MAX_FREE_PER_AXIS]; super::kernel::MAX_BLOCKS];
    let (mut v, mut u) = (start, other);
    // In exact arithmetic the space is exhausted after `krylov_dimension` steps; a step past
    // it divides rounding by rounding, and the vectors that follow are no longer orthogonal to
    // the earlier ones, which can put a Ritz value above the spectrum (issue 28: 1.25e-6 above
    // a flat direction's 1.0 after 48 steps, which made a certified flat point a saddle).
    let dimension = op.krylov_dimension();
    let bound = dimension.min(LANCZOS_STEPS);
    let mut alpha = [0.0; LANCZOS_STEPS];
    let mut beta = [0.0; LANCZOS_STEPS];
    let mut steps = 0usize;
    let mut previous_beta = 0.0;
    let mut operator_scale = 0.0f64;
    let mut settled_value = f64::NAN;
    let mut exhausted = false;
    // How far the value rose over the last check: where the next one starts looking.
    let mut rise = f64::NAN;
    for k in 0..bound {
        // u <- P S v - beta_{k-1} q_{k-1} (u held q_{k-1}, which lies in the null space).
        scale(u, -previous_beta, size);
        // v is projected again before the curvature acts on it: rounding moves the Lanczos
        // vectors off the null space and the curvature amplifies that part, so the operator
        // Lanczos saw was not quite the symmetric `P S P` and its Ritz value could rise above
        // the spectrum (issue 28: the collinear exchange moved by 1e-13 to 1e-9 LU read 0.2530 to
        // 0.2585 against the dense decomposition's 0.2525; projected, equal to 4e-15).
        if !op.project(v) {
            return None;
        }
        op.accumulate(v, u);
        if !op.project(u) {
            return None;
        }
        op.deflate(v, u);
        let a = dot(v, u, size);
        for (ur, vr) in u.iter_mut().zip(v.iter()).take(size.0) {
            for (x, y) in ur.iter_mut().zip(vr.iter()).take(size.1) {
                *x -= a * y;
            }
        }
        let b = libm::sqrt(dot(u, u, size));
        if !a.is_finite() || !b.is_finite() {
            return None;
        }
        if let (Some(a_slot), Some(b_slot)) = (alpha.get_mut(k), beta.get_mut(k)) {
            *a_slot = a;
            *b_slot = b;
        }
        steps = k.saturating_add(1);
        operator_scale = operator_scale.max(libm::fabs(a) + b + previous_beta);
        if b <= EXHAUSTED_REL * operator_scale || steps == dimension {
            exhausted = true;
            break;
        }
        if steps % CHECK_EVERY == 0 {
            let value = tridiagonal_largest(&alpha, &beta, steps, settled_value, rise);
            if libm::fabs(value - settled_value) <= SETTLED_REL * (1.0 + libm::fabs(value)) {
                break;
            }
            rise = value - settled_value;
            settled_value = value;
        }
        scale(u, 1.0 / b, size);
        core::mem::swap(&mut v, &mut u);
        previous_beta = b;
    }
    let value = tridiagonal_largest(&alpha, &beta, steps, settled_value, rise);
    if !value.is_finite() {
        return None;
    }
    // The smallest eigenvalue of T is minus the largest of -T (same off-diagonal magnitudes);
    // found from above for -T, so from below for T: the side a power-method shift needs.
    // `alpha` is negated in place: it is not needed again.
    let smallest_exhausted = if exhausted {
        for a in alpha.iter_mut().take(steps) {
            *a = -*a;
        }
        let top = tridiagonal_largest(&alpha, &beta, steps, f64::NAN, f64::NAN);
        top.is_finite().then_some(-top)
    } else {
        None
    };
    Some(Estimate {
        largest: value,
        smallest_exhausted,
        steps,
    })
}

/// The largest eigenvalue of the symmetric tridiagonal matrix with diagonal `alpha[..m]` and
/// off-diagonal `beta[..m - 1]`, from above: at or above the eigenvalue, the certificate's side.
/// `known_below` is a value already known not above it (the previous, smaller Lanczos
/// matrix's: by interlacing the largest Ritz value never decreases), or NaN; `rise` is how much
/// the value rose at the previous check (NaN if unknown), a hint of where to start.
///
/// Laguerre's method on `det(T - x I)` from above. Its step from any `x` right of every
/// eigenvalue lands between the largest eigenvalue and `x`, so the iterates fall monotonically
/// onto it (cubically once it is isolated, in one step onto a repeated one). Each iterate is
/// checked, not trusted: `x` is an upper bound exactly when every pivot of `T - x I = L D L^T`
/// is negative (Sturm), and only checked iterates are kept, so rounding can cost precision,
/// never the side. The start is the lowest checked point of `known_below + 2 rise 16^k`
/// (k = 0, 1, ... while below the Gershgorin bound), else the Gershgorin bound: from far above a
/// cluster of Ritz values Laguerre only crawls (measured on the paper case: 13 to 16 sweeps per
/// call from the Gershgorin bound, 45 halvings per call for the bisection this replaced).
fn tridiagonal_largest(alpha: &[f64], beta: &[f64], m: usize, known_below: f64, rise: f64) -> f64 {
    let resolution = |x: f64| STEP_REL * (1.0 + libm::fabs(x));
    // Each row's diagonal with the off-diagonal magnitudes before and after it (none past
    // the block's edges).
    let before = core::iter::once(0.0).chain(off_diagonal(beta, m));
    let after = off_diagonal(beta, m).chain(core::iter::once(0.0));
    let mut hi = f64::NEG_INFINITY;
    for ((&a, b), c) in alpha.iter().take(m).zip(before).zip(after) {
        hi = hi.max(a + b + c);
    }
    if !hi.is_finite() {
        return f64::NAN;
    }
    // Gershgorin's bound is an upper bound in exact arithmetic; the margin covers its rounding
    // (and puts the start strictly right of the spectrum, where Laguerre's step is defined).
    let mut upper = hi + resolution(hi);
    let mut at = None;
    if known_below.is_finite() {
        let mut reach = (2.0 * rise).max(16.0 * resolution(known_below));
        for _ in 0..START_TRIES {
            let x = known_below + reach;
            // Not below the Gershgorin start (NaN included): nothing to gain.
            if x.partial_cmp(&upper) != Some(core::cmp::Ordering::Less) {
                break;
            }
            at = log_derivatives(alpha, beta, m, x);
            if at.is_some() {
                upper = x;
                break;
            }
            reach *= 16.0;
        }
    }
    if at.is_none() {
        at = log_derivatives(alpha, beta, m, upper);
    }
    let n = m as f64;
    for _ in 0..LAGUERRE_STEPS {
        if known_below.is_finite() && upper - known_below <= resolution(upper) {
            break;
        }
        // g = sum 1 / (x - mu), h = sum 1 / (x - mu)^2: both positive right of the spectrum.
        let Some((g, h)) = at else {
            break;
        };
        let spread = libm::sqrt(((n - 1.0) * (n * h - g * g)).max(0.0));
        let step = n / (g + spread);
        if !(step.is_finite() && step > 0.0) {
            break;
        }
        let next = upper - step;
        at = log_derivatives(alpha, beta, m, next);
        if at.is_none() {
            // Onto the eigenvalue, and past it by rounding (cubic convergence lands there):
            // one resolution above it is the answer when checked, else the last checked point.
            let nudged = next + resolution(next);
            if nudged < upper && log_derivatives(alpha, beta, m, nudged).is_some() {
                upper = nudged;
            }
            break;
        }
        upper = next;
        if step <= resolution(upper) {
            break;
        }
    }
    upper
}

/// `|beta_0|, ..., |beta_(m-2)|`: the off-diagonal magnitudes of the leading `m x m` block.
fn off_diagonal(beta: &[f64], m: usize) -> impl Iterator<Item = f64> + '_ {
    beta.iter()
        .take(m.saturating_sub(1))
        .map(|b| libm::fabs(*b))
}

/// At `x`, the first two logarithmic derivatives of `det(T - x I)` as `(sum 1 / (x - mu),
/// sum 1 / (x - mu)^2)` over the eigenvalues `mu`, from the pivots of `T - x I = L D L^T` and
/// their derivatives in `x`; `None` unless every pivot is negative, i.e. unless `x` is right of
/// every eigenvalue (Sturm).
fn log_derivatives(alpha: &[f64], beta: &[f64], m: usize, x: f64) -> Option<(f64, f64)> {
    // The previous pivot's reciprocal and its first and second derivatives.
    let (mut recip, mut d1, mut d2) = (0.0f64, 0.0f64, 0.0f64);
    let (mut g, mut h) = (0.0f64, 0.0f64);
    // Each row's diagonal with the off-diagonal magnitude before it (none before the first).
    let before = core::iter::once(0.0).chain(off_diagonal(beta, m));
    for (&a, b) in alpha.iter().take(m).zip(before) {
        let c = b * b;
        // d_i = a_i - x - c / d_{i-1}, and its derivatives in x.
        let d = a - x - c * recip;
        let r2 = recip * recip;
        let dd1 = -1.0 + c * d1 * r2;
        let dd2 = c * r2 * (d2 - 2.0 * d1 * d1 * recip);
        if d >= 0.0 || !d.is_finite() {
            return None;
        }
        recip = 1.0 / d;
        let ratio = dd1 * recip;
        // g = (log |det|)' = sum d_i' / d_i; h = -g'.
        g += ratio;
        h += ratio * ratio - dd2 * recip;
        d1 = dd1;
        d2 = dd2;
    }
    (g.is_finite() && h.is_finite()).then_some((g, h))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn tridiagonal_largest_matches_the_closed_form() {
        // The m x m matrix with 2 on the diagonal and -1 off it: eigenvalues
        // 2 - 2 cos(k pi / (m + 1)), the largest 2 + 2 cos(pi / (m + 1)).
        for m in [1usize, 2, 5, 17, 60] {
            let alpha = [2.0; LANCZOS_STEPS];
            let beta = [-1.0; LANCZOS_STEPS];
            let expected = 2.0 + 2.0 * libm::cos(core::f64::consts::PI / (m as f64 + 1.0));
            let expected = if m == 1 { 2.0 } else { expected };
            let got = tridiagonal_largest(&alpha, &beta, m, f64::NAN, f64::NAN);
            assert!(
                (got - expected).abs() <= 1e-13,
                "m={m}: {got} vs {expected}"
            );
            assert!(got >= expected - 1e-15);
        }
    }

    /// The largest eigenvalue by bisection on Sturm counts (the method this file used before):
    /// the test's independent answer, to 1e-15 relative.
    fn by_bisection(alpha: &[f64], beta: &[f64], m: usize) -> f64 {
        let (mut lo, mut hi) = (-1e3, 1e3);
        for _ in 0..200 {
            let mid = 0.5 * (lo + hi);
            let mut below = 0;
            let mut d = 1.0;
            for i in 0..m {
                let c = if i > 0 {
                    beta[i - 1] * beta[i - 1] / d
                } else {
                    0.0
                };
                d = alpha[i] - mid - c;
                if d == 0.0 {
                    d = -f64::MIN_POSITIVE;
                }
                if d < 0.0 {
                    below += 1;
                }
            }
            if below < m {
                lo = mid;
            } else {
                hi = mid;
            }
        }
        hi
    }

    #[test]
    fn laguerre_matches_bisection_from_above_on_varied_spectra() {
        // Deterministic pseudo-random tridiagonals, some with clustered or repeated diagonals
        // (a cluster at the top is where Newton's method would crawl).
        let mut state = 0x2545_f491_4f6c_dd1du64;
        let mut next = || {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            (state >> 11) as f64 / (1u64 << 53) as f64
        };
        for case in 0..300 {
            let m = 1 + case % LANCZOS_STEPS;
            let mut alpha = [0.0; LANCZOS_STEPS];
            let mut beta = [0.0; LANCZOS_STEPS];
            for i in 0..m {
                alpha[i] = match case % 3 {
                    0 => next() * 2.0 - 1.0,
                    1 => 0.9 + 1e-9 * next(),
                    _ => 1.0 - 1e-3 * (i as f64),
                };
                beta[i] = if case % 5 == 4 {
                    1e-8 * next()
                } else {
                    next() - 0.5
                };
            }
            let expected = by_bisection(&alpha, &beta, m);
            let got = tridiagonal_largest(&alpha, &beta, m, f64::NAN, f64::NAN);
            let scale = 1.0 + expected.abs();
            assert!(
                got >= expected - 1e-15 * scale,
                "case {case}: {got} below {expected}"
            );
            assert!(
                got - expected <= 1e-13 * scale,
                "case {case}: {got} vs {expected}"
            );
            // A floor from a smaller matrix (interlacing) and any rise hint (none, too small,
            // close, beyond the Gershgorin bound) change nothing but the work.
            for rise in [f64::NAN, 1e-15, 1e-6, 10.0] {
                let floored = tridiagonal_largest(&alpha, &beta, m, expected - 1e-9, rise);
                assert!(
                    floored >= expected - 1e-15 * scale && floored - expected <= 1e-13 * scale,
                    "case {case}, rise {rise}: {floored} vs {expected}"
                );
            }
        }
    }

    #[test]
    fn a_diagonal_matrix_with_one_repeated_value_is_answered_at_it() {
        let alpha = [0.75; LANCZOS_STEPS];
        let beta = [0.0; LANCZOS_STEPS];
        for m in [1usize, 2, 30] {
            let got = tridiagonal_largest(&alpha, &beta, m, f64::NAN, f64::NAN);
            assert!(got >= 0.75 && got - 0.75 <= 1e-13, "m={m}: {got}");
        }
    }
}
