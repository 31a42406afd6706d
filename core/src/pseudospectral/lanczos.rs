//! The largest eigenvalue of the certificate's projected curvature `P S P` (see `certificate`)
//! by the Lanczos method: the certificate's smallest reduced-Hessian eigenvalue is one minus it.
//!
//! Why Lanczos: `S` is the identity's complement of rank at most two per active keep-out check
//! plus one per envelope correction, so the Krylov space from any start has dimension at most
//! that rank plus one, and Lanczos is exact (in exact arithmetic) once it has spanned it: about
//! ten products on the paper's case, where the power method took up to `POWER_ITERATIONS` (120).
//! After `k` steps its largest Ritz value is at least the Rayleigh quotient of the power method's
//! `k`-th iterate from the same start (that iterate lies in the same Krylov space), and like it
//! never exceeds the true largest eigenvalue (up to rounding: without reorthogonalisation the
//! lost orthogonality only repeats converged Ritz values, it adds none outside the spectrum). So
//! the certificate's promise is unchanged: the reported eigenvalue is an estimate from above,
//! at least as close as the power method's after as many steps.
//!
//! Deterministic: a fixed start, a fixed step bound (`LANCZOS_STEPS`), a fixed bisection.

use super::certificate::{add_curvature, dot, project, scale, Envelope};
use super::qp::QpState;
use super::transcription::{Coefficients, RowId, Transcription};
use crate::capacity::MAX_ACTIVE;
use crate::indexed::IndexedExt as _;

/// Most Lanczos steps (each one product with `P S P`). Stops earlier when the Krylov space is
/// exhausted or the largest Ritz value has settled (`SETTLED_REL`).
pub const LANCZOS_STEPS: usize = 60;
/// The largest Ritz value is recomputed every this many steps (each a bisection: a serial chain
/// of divisions: run to the double-precision end, about a quarter of the paper case's host
/// time, hence the stop at `BRACKET_REL` and the floor from the previous value).
const CHECK_EVERY: usize = 4;
/// Settled: changed by at most this, relative to `1 + |value|`, over `CHECK_EVERY` steps (far
/// below `CURVATURE_TOL`, 1e-6, the certificate's resolution).
const SETTLED_REL: f64 = 1e-12;
/// The Krylov space is exhausted when a new direction's norm falls below this times the
/// operator's scale seen so far (rounding level, not a tolerance of the answer).
const EXHAUSTED_REL: f64 = 1e-13;
/// Bisection steps for the tridiagonal's largest eigenvalue at most (each halves the bracket; 100
/// reach the double-precision resolution of any bracket a finite operator gives).
const BISECTION_STEPS: usize = 100;
/// The bisection stops when the bracket is this narrow relative to `1 + |ends|`: far below
/// `SETTLED_REL` and the certificate's `CURVATURE_TOL`.
const BRACKET_REL: f64 = 1e-14;

/// `S` less the envelope terms (the curvature of the active keep-out checks at the iterate), for
/// the projected products.
pub(super) struct Curvature<'a> {
    pub tr: &'a Transcription,
    pub qp: &'a QpState,
    /// `|r|` at each active row's check (`certificate::check_lengths`).
    pub lengths: &'a [f64; MAX_ACTIVE],
    pub corrections: &'a [Envelope],
}

impl Curvature<'_> {
    /// `out += S v - sum_e w_e (f_e . v) f_e`: every active keep-out check's curvature in the
    /// QP's row order, then the envelope corrections (the order the power method always used).
    pub(super) fn accumulate(&self, v: &Coefficients, out: &mut Coefficients) {
        let (tr, qp) = (self.tr, self.qp);
        for ((&id, &value), &length) in qp
            .active
            .iter()
            .zip(qp.multiplier.iter())
            .zip(self.lengths.iter())
            .take(qp.count)
        {
            if let RowId::KeepOut { pair, check } = id {
                let p = usize::from(pair);
                if let Some(c) = tr.checks.get(p).and_then(|row| row.get(usize::from(check))) {
                    add_curvature(tr, (p, c), length, value, v, out);
                }
            }
        }
        for envelope in self.corrections {
            let along = envelope.weight * envelope.dot(tr, v);
            envelope.axpy(tr, -along, out);
        }
    }
}

/// The largest eigenvalue of `P S P` on the null space, from `start` (projected, not
/// normalised; overwritten) with `other` as the second Lanczos vector's buffer. Returns the
/// estimate (not above the true value, up to rounding) and the steps taken, or `None` when a
/// value is not finite.
pub(super) fn largest(
    op: &Curvature<'_>,
    start: &mut Coefficients,
    other: &mut Coefficients,
    size: (usize, usize),
) -> Option<(f64, usize)> {
    let norm = libm::sqrt(dot(start, start, size));
    if norm <= 1e-12 {
        // The null space holds no curvature direction from this start: as the power method.
        return Some((0.0, 0));
    }
    scale(start, 1.0 / norm, size);
    *other = [[0.0; crate::capacity::MAX_FREE_PER_AXIS]; super::transcription::MAX_BLOCKS];
    let (mut v, mut u) = (start, other);
    let mut alpha = [0.0; LANCZOS_STEPS];
    let mut beta = [0.0; LANCZOS_STEPS];
    let mut steps = 0usize;
    let mut previous_beta = 0.0;
    let mut operator_scale = 0.0f64;
    let mut settled_value = f64::NAN;
    for k in 0..LANCZOS_STEPS {
        // u <- P S v - beta_{k-1} q_{k-1} (u held q_{k-1}, which lies in the null space).
        scale(u, -previous_beta, size);
        op.accumulate(v, u);
        project(op.tr, op.qp, u);
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
        if b <= EXHAUSTED_REL * operator_scale {
            break;
        }
        if steps % CHECK_EVERY == 0 {
            let value = tridiagonal_largest(&alpha, &beta, steps, settled_value);
            if libm::fabs(value - settled_value) <= SETTLED_REL * (1.0 + libm::fabs(value)) {
                break;
            }
            settled_value = value;
        }
        scale(u, 1.0 / b, size);
        core::mem::swap(&mut v, &mut u);
        previous_beta = b;
    }
    let value = tridiagonal_largest(&alpha, &beta, steps, settled_value);
    value.is_finite().then_some((value, steps))
}

/// The largest eigenvalue of the symmetric tridiagonal matrix with diagonal `alpha[..m]` and
/// off-diagonal `beta[..m - 1]`, by bisection on Sturm counts inside the Gershgorin bounds;
/// returns the bracket's upper end (at or above the eigenvalue: the certificate's side).
/// `known_below` is a value already known not above it (the previous, smaller Lanczos
/// matrix's: by interlacing the largest Ritz value never decreases), or NaN.
fn tridiagonal_largest(alpha: &[f64], beta: &[f64], m: usize, known_below: f64) -> f64 {
    let off = |i: usize| -> f64 {
        if i.saturating_add(1) < m {
            beta.get(i).copied().map_or(0.0, libm::fabs)
        } else {
            0.0
        }
    };
    let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
    for (i, &a) in alpha.iter().indexed().take(m) {
        let before = if i > 0 { off(i.saturating_sub(1)) } else { 0.0 };
        let radius = before + off(i);
        lo = lo.min(a - radius);
        hi = hi.max(a + radius);
    }
    if !(lo.is_finite() && hi.is_finite()) {
        return f64::NAN;
    }
    if known_below.is_finite() {
        // Slightly below it: the earlier value is itself a bracket end, not exact.
        let floor = known_below - BRACKET_REL * (1.0 + libm::fabs(known_below));
        lo = lo.max(floor).min(hi);
    }
    for _ in 0..BISECTION_STEPS {
        let mid = 0.5 * (lo + hi);
        if mid <= lo
            || mid >= hi
            || hi - lo <= BRACKET_REL * (1.0 + libm::fabs(lo).max(libm::fabs(hi)))
        {
            break;
        }
        // Eigenvalues below `mid`: the negative pivots of T - mid I = L D L^T.
        let mut below = 0usize;
        let mut d = 1.0;
        for (i, &a) in alpha.iter().indexed().take(m) {
            let coupling = if i > 0 {
                let b = off(i.saturating_sub(1));
                b * b / d
            } else {
                0.0
            };
            d = a - mid - coupling;
            if d == 0.0 {
                // A zero pivot: perturb it to the negative side (the standard choice).
                d = -f64::MIN_POSITIVE;
            }
            if d < 0.0 {
                below = below.saturating_add(1);
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

#[cfg(test)]
#[allow(clippy::indexing_slicing)]
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
            let got = tridiagonal_largest(&alpha, &beta, m, f64::NAN);
            assert!(
                (got - expected).abs() <= 1e-13,
                "m={m}: {got} vs {expected}"
            );
            assert!(got >= expected - 1e-15);
        }
    }
}
