//! The second-order step of the SQP: a Newton step on the KKT conditions of the last QP's
//! active set, with the Hessian of the Lagrangian, used as the next linearisation point.
//!
//! Why: the convex-concave QP uses the cost metric (the identity) as its Hessian and ignores the
//! curvature of the keep-out constraints, so its fixed-point iteration converges only linearly
//! (slowly where many checks are active, as on dense formations). The Hessian of the Lagrangian
//! is `H = I - S`, `S = sum_k l_k J_k^T (I - n_k n_k^T) J_k / |r_k|` over the active keep-out
//! checks (l_k their multipliers, J_k the check's position rows, n_k the unit separation): the
//! identity plus a term of rank at most two per active check, never formed.
//!
//! At the QP's answer `y` with active rows `A` (the constraint gradients at `y`) and residuals
//! `c` (`|r_k| - d` for keep-out, 0 for control bounds), the step is `p = p_R + p_N`:
//! `p_R = -A^T G^-1 c` (G = A A^T, the QP's Gram factor, refactored at `y`) restores the active
//! constraints to first order, and `p_N` solves the reduced Newton system
//! `(P H P) p_N = -P (y + H p_R)` on the null space of `A` (`P = I - A^T G^-1 A`) by conjugate
//! gradients with the operator applied matrix-free (`curvature::add_curvature`, one
//! projection per step). On that null space the reduced Hessian is `I - P S P`: its eigenvalues
//! are 1 except on the span of `P S P`, so CG ends in at most `rank + 1` steps, bounded by
//! `2 (active checks) + 2`.
//!
//! **Indefiniteness** is handled where it occurs, not by a global shift: CG stops as soon as a
//! search direction `d` has reduced curvature `d^T (I - PSP) d < NEWTON_CURVATURE_FLOOR |d|^2`
//! (the truncated Newton-CG rule). The step then holds the Newton step on the Krylov subspace
//! built so far, on which the reduced Hessian is positive definite; the direction of negative
//! curvature itself is left out (at the first CG step the step falls back to the identity
//! metric there: the convex-concave direction). Where the reduced Hessian is positive definite
//! the step is the exact Newton step, unmodified.
//!
//! The step only chooses the next linearisation point: the next QP's answer meets every check
//! whatever point it is linearised at (each linearised keep-out is a tangent half-space inside
//! the keep-out's complement), and the iteration (`iteration.rs`) accepts it only if it lowers
//! the cost. Near a nondegenerate local optimum the linearisation point and the QP's answer
//! converge superlinearly together.

use super::curvature::{
    add_curvature, check_lengths, keep_out_term, project, Envelope, MAX_ENVELOPES,
};
use super::kernel::{axpy, dot, scale, Coefficients, MAX_BLOCKS};
use super::linearise::unit_normals_at;
use super::qp_state::{Mode, QpState};
use super::transcription::{row_axpy, row_dot, RowId, Transcription};
use super::work_units;
use crate::capacity::{MAX_ACTIVE, MAX_FREE_PER_AXIS};
use crate::work::Meter;

/// Smallest reduced curvature (relative to the identity part, 1) a CG direction may have.
pub(crate) const NEWTON_CURVATURE_FLOOR: f64 = 1e-2;
/// Relative residual at which CG stops.
const CG_TOL_REL: f64 = 1e-10;

/// Three idle dense buffers for CG (the Anderson memory's, see `Anderson::lend`).
pub(super) struct Scratch<'a> {
    pub residual: &'a mut Coefficients,
    pub direction: &'a mut Coefficients,
    pub product: &'a mut Coefficients,
}

impl<'a> Scratch<'a> {
    /// The CG vectors in three lent buffers.
    pub(super) fn from_buffers([residual, direction, product]: [&'a mut Coefficients; 3]) -> Self {
        Self {
            residual,
            direction,
            product,
        }
    }
}

type Envelopes = heapless::Vec<Envelope, MAX_ENVELOPES>;

/// `out = S v` over the active keep-out checks with positive multipliers, less the envelope
/// terms of the semi-infinite keep-out (see `curvature::Envelope`).
fn curvature(
    tr: &Transcription,
    qp: &QpState,
    lengths: &[f64; MAX_ACTIVE],
    envelopes: &Envelopes,
    v: &Coefficients,
    out: &mut Coefficients,
) {
    *out = [[0.0; MAX_FREE_PER_AXIS]; MAX_BLOCKS];
    for envelope in envelopes.iter() {
        // Built for a pair of this transcription, so found (left out, the step is shorter).
        if let Some(pair) = tr.pair(envelope.pair()) {
            let along = envelope.weight * envelope.dot(tr, &pair, v);
            envelope.axpy(tr, &pair, -along, out);
        }
    }
    for ((&id, &value), &length) in qp
        .active
        .iter()
        .zip(qp.multiplier.iter())
        .zip(lengths.iter())
        .take(qp.count)
    {
        if value > 0.0 {
            if let Some((pair, c)) = keep_out_term(tr, id) {
                add_curvature(tr, (&pair, &c), length, value, v, out);
            }
        }
    }
}

/// Whether the last QP has a second-order step: it ended with its Gram factor, and a keep-out
/// check with a positive multiplier is active (otherwise the Hessian of the Lagrangian is the
/// identity and the QP's answer is already the Newton point).
pub(super) fn applies(qp: &QpState) -> bool {
    qp.mode == Mode::Factor
        && qp
            .active
            .iter()
            .zip(qp.multiplier.iter())
            .take(qp.count)
            .any(|(id, &value)| matches!(id, RowId::KeepOut { .. }) && value > 0.0)
}

/// Write `y + p` (the Newton point) into `next`. Returns false, with `next` unspecified, when
/// there is no second-order step: the QP ended in its fallback (no factor), the Gram matrix at
/// `y` is singular, or no keep-out check with a positive multiplier is active (the Hessian is
/// then the identity and the QP's answer is already the Newton point). Leaves the checks'
/// normals at the unit separations at `y` (the next linearisation resets them).
pub(super) fn step(
    tr: &mut Transcription,
    qp: &mut QpState,
    y: &Coefficients,
    next: &mut Coefficients,
    scratch: Scratch<'_>,
    work: &mut Meter,
) -> bool {
    if qp.mode != Mode::Factor {
        return false;
    }
    let mut curved = 0usize;
    for (&id, &value) in qp.active.iter().zip(qp.multiplier.iter()).take(qp.count) {
        if matches!(id, RowId::KeepOut { .. }) && value > 0.0 {
            curved = curved.saturating_add(1);
        }
    }
    if curved == 0 {
        return false;
    }
    unit_normals_at(tr, y);
    if !qp.merge_close_checks(tr) {
        return false;
    }
    let tr: &Transcription = tr;
    let free = tr.basis.free;
    let size = (tr.blocks(), free);
    let Scratch {
        residual,
        direction,
        product,
    } = scratch;
    let mut envelopes = Envelopes::new();
    for (&id, &value) in qp.active.iter().zip(qp.multiplier.iter()).take(qp.count) {
        let RowId::KeepOut { pair, check } = id else {
            continue;
        };
        let p = usize::from(pair);
        let (Some(c), Some(pair)) = (tr.check(p, usize::from(check)), tr.pair(p)) else {
            continue;
        };
        if value > 0.0 {
            if let Some(envelope) = Envelope::new(tr, y, &pair, c.tau, value) {
                // Past the capacity a correction is left out (the step is then shorter).
                let _ = envelopes.push(envelope);
            }
        }
    }
    // Every active row held by the transcription (else no step).
    let mut lengths = [0.0; MAX_ACTIVE];
    if !check_lengths(tr, qp, y, &mut lengths) {
        return false;
    }
    // Range step p_R = -A^T G^-1 c, accumulated in `next`.
    let mut b = [0.0; MAX_ACTIVE];
    for (slot, &id) in b.iter_mut().zip(qp.active.iter()).take(qp.count) {
        let Some(view) = tr.view(id) else {
            return false;
        };
        *slot = view.rhs - row_dot(&view, y, free);
    }
    if !qp.gram_solve(&mut b) {
        return false;
    }
    *next = [[0.0; MAX_FREE_PER_AXIS]; MAX_BLOCKS];
    for (value, &id) in b.iter().zip(qp.active.iter()).take(qp.count) {
        let Some(view) = tr.view(id) else {
            return false;
        };
        row_axpy(&view, *value, next, free);
    }
    // Reduced gradient h = P (S p_R - y).
    curvature(tr, qp, &lengths, &envelopes, next, residual);
    axpy(residual, -1.0, y, size);
    if !project(tr, qp, residual) {
        return false;
    }
    let start = dot(residual, residual, size);
    let tolerance = CG_TOL_REL * CG_TOL_REL * start.max(f64::MIN_POSITIVE);
    *direction = *residual;
    let mut rho = start;
    let bound = curved.saturating_mul(2).saturating_add(2);
    for k in 0..bound {
        if rho <= tolerance {
            break;
        }
        // product = (I - P S P) d, d in the null space. Charged as it runs (the set-up was
        // charged by the caller); the iteration count is bounded above.
        work.charge(work_units::newton_iteration(tr, qp.count));
        curvature(tr, qp, &lengths, &envelopes, direction, product);
        if !project(tr, qp, product) {
            return false;
        }
        for (x, v) in product.iter_mut().zip(direction.iter()).take(size.0) {
            for (p, q) in x.iter_mut().zip(v.iter()).take(free) {
                *p = q - *p;
            }
        }
        let dd = dot(direction, direction, size);
        let curvature_along = dot(direction, product, size);
        if curvature_along < NEWTON_CURVATURE_FLOOR * dd {
            if k == 0 {
                // Not positive definite along the reduced gradient: the identity metric there
                // (the convex-concave direction).
                axpy(next, 1.0, residual, size);
            }
            break;
        }
        let alpha = rho / curvature_along;
        axpy(next, alpha, direction, size);
        axpy(residual, -alpha, product, size);
        let rho_next = dot(residual, residual, size);
        let beta = rho_next / rho;
        rho = rho_next;
        for (x, v) in direction.iter_mut().zip(residual.iter()).take(size.0) {
            for (p, q) in x.iter_mut().zip(v.iter()).take(free) {
                *p = q + beta * *p;
            }
        }
    }
    // A step longer than the iterate itself leaves the region where the linearisation means
    // anything: scale it back (a linearisation point, so any finite point is safe).
    let length = libm::sqrt(dot(next, next, size));
    let limit = libm::sqrt(dot(y, y, size)).max(1e-3);
    if !length.is_finite() {
        return false;
    }
    if length > limit {
        scale(next, limit / length, size);
    }
    axpy(next, 1.0, y, size);
    true
}
