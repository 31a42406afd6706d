//! The optimality certificate of a returned iterate: first- and second-order conditions of the
//! transcribed problem, measured on the iterate itself (not taken on trust from the iteration).
//!
//! In the cost-orthonormal coefficients `y` the cost is `J = J_cubic + 1/2 |y|^2`, so its
//! gradient is `y` and its Hessian the identity. A keep-out check `g = |r_i(t) - r_j(t)| - d >= 0`
//! (r linear in y: `r = r_base + J_t y`) has gradient `J_t^T n` (n the unit separation, exactly
//! the QP's row at a feasible iterate) and Hessian `J_t^T (I - n n^T) J_t / |r|`. A control bound
//! is linear. So with multipliers `l >= 0`:
//!
//! * stationarity: `|y - sum l_k grad g_k| / max(1, |y|)`;
//! * complementarity: `max_k l_k |g_k| / (1 + J)`;
//! * second order: the Hessian of the Lagrangian is `I - S`, `S = sum l_k J^T (I - nn^T) J / |r|`
//!   (positive semidefinite, rank <= 2 per active check), never formed. On the null space of
//!   the active rows (projector `P = I - A^T G^-1 A`, G the Gram matrix, factored by the QP) the
//!   smallest eigenvalue is `1 - lambda_max(P S P)`. Because the keep-out is semi-infinite, an
//!   active check sits at a minimum of `|r(t)|` in time, and the constraint's Hessian gains the
//!   envelope term `-f_yt f_yt^T / f_tt` (see `Envelope`), which makes `S` smaller; without it
//!   the paper's optimum shows a spurious flat direction (eigenvalue 9e-6 instead of 0.117). The
//!   eigenvalue is found by the Lanczos method (`lanczos`: at most `LANCZOS_STEPS` products,
//!   a few where `S` has low rank) from a fixed start vector (deterministic). When that shows
//!   the reduced Hessian positive definite (at least `CURVATURE_TOL`) it is the answer;
//!   otherwise `POWER_ITERATIONS` steps of the power method from the same start give the
//!   eigenvalue and its eigenvector, the negative-curvature direction the saddle escape and the
//!   flat-direction probe step along. Both approach `lambda_max` from below, so the reported
//!   eigenvalue is an estimate from above; Lanczos's is the closer (measured on the M7
//!   fixtures: the paper's case at N = 10 0.11553 against the power method's 0.11744, the
//!   8-spacecraft crossing 0.3046 against 0.4943, which had not converged in 120 steps).
//!
//! The multipliers are the last QP's: at a fixed point of the convex-concave map the QP's rows
//! are the constraint gradients at the iterate, so they are the Lagrange multipliers; the
//! stationarity residual measures how far from that fixed point the iterate is.

use super::curvature::{check_lengths, Curvature, Envelope, MAX_ENVELOPES};
use super::kernel::{dot, scale, Coefficients, MAX_BLOCKS};
use super::lanczos::{self, LANCZOS_STEPS};
use super::qp_state::{Mode, QpState};
use super::symmetry::Symmetries;
use super::transcription::{row_axpy, row_dot, RowId, Transcription};
use crate::capacity::{MAX_ACTIVE, MAX_FREE_PER_AXIS};
use crate::indexed::IndexedExt as _;
use serde::{Deserialize, Serialize};

/// `Solved` needs the scaled stationarity residual at or below this. The convex-concave
/// iteration stops on a relative cost change of `sqp_tol_cost` (1e-8), which leaves a gradient
/// of about its square root (4e-5 on the paper's case, 1.8e-4 on the 8-spacecraft crossing).
/// With the reduced curvature at least `mu`, the cost is within about `|grad|^2 / (2 mu)` of the
/// local optimum: at this tolerance `5e-7 |y|^2 / mu`, far below the 0.5 % the issue counts.
pub const STATIONARITY_TOL: f64 = 1e-3;
/// `Solved` needs the scaled complementarity at or below this.
pub const COMPLEMENTARITY_TOL: f64 = 1e-7;
/// `Solved` needs the smallest reduced-Hessian eigenvalue at or above this (positive definite
/// with a margin; the identity part is 1).
pub const CURVATURE_TOL: f64 = 1e-6;
/// The flat-direction probe (`Certificate::flat_direction_probed`) counts a probe's answer as
/// lower only when it is below the probed cost by more than this, relative to `1 + J` (the
/// iteration stops on a relative cost change of 1e-8, so equal-cost answers agree to ~1e-8).
pub const FLAT_PROBE_TOL_REL: f64 = 1e-6;
/// Power-method steps for the reduced Hessian's smallest eigenvalue.
pub const POWER_ITERATIONS: usize = 120;

/// An active constraint of the returned iterate.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub enum ActiveConstraint {
    /// Keep-out of the pair `(i, j)` checked at `time_tu`.
    KeepOut {
        /// The spacecraft pair, `i < j`.
        pair: (u8, u8),
        /// Check time in TU.
        time_tu: f64,
    },
    /// Control bound of one spacecraft, axis (0 = x) and node; `upper` is `u <= Umax`.
    Control {
        /// Spacecraft index.
        spacecraft: u8,
        /// Axis (0 = x, 1 = y, 2 = z).
        axis: u8,
        /// Node index.
        node: u8,
        /// Upper (`u <= Umax`) or lower (`u >= -Umax`) bound.
        upper: bool,
    },
}

/// One Lagrange multiplier (in the constraint's own units: per LU for keep-out, per FU for
/// control bounds, times FU^2 TU of cost).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct Multiplier {
    /// Which constraint.
    pub constraint: ActiveConstraint,
    /// Its multiplier, `>= 0`.
    pub value: f64,
}

/// First- and second-order optimality measures of the returned iterate (see the module docs).
/// All fields are finite; a measure that could not be taken says so in its flag.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct Certificate {
    /// The first-order measures were taken: the answer passed its checks (feasible) and the
    /// last QP's state is its own (`solver::finish`). Otherwise nothing but `max_violation` is
    /// measured, and the other measures are zero.
    pub first_order_evaluated: bool,
    /// `|grad L| / max(1, |y|)` in the cost metric.
    pub stationarity: f64,
    /// Largest violation: `d - min continuous separation` (LU) or node control beyond Umax
    /// (FU), 0 when none.
    pub max_violation: f64,
    /// `max_k l_k |g_k| / (1 + J)`.
    pub complementarity: f64,
    /// The reduced Hessian was evaluated (needs the QP's Gram factor).
    pub second_order_evaluated: bool,
    /// Smallest eigenvalue of the Hessian of the Lagrangian on the active rows' null space
    /// (1 when only the identity part acts there).
    pub min_reduced_eigenvalue: f64,
    /// Every active constraint fits in `multipliers` (the measures above always use all of
    /// them; past `MAX_ACTIVE` the list is cut, in row order).
    pub multipliers_complete: bool,
    /// Multipliers of the active keep-out checks and control bounds.
    pub multipliers: heapless::Vec<Multiplier, MAX_ACTIVE>,
    /// The reduced Hessian is singular within `CURVATURE_TOL` (a flat direction, as a
    /// continuous symmetry of the problem gives: two spacecraft swapping through the centre
    /// may pass on any side at the same cost) and the solver probed it: stepping along the
    /// flat direction both ways and iterating again found no lower cost (by more than
    /// `FLAT_PROBE_TOL_REL`) and came back to a flat point. Then the second-order necessary
    /// condition (eigenvalue `>= -CURVATURE_TOL`) certifies, with this flag saying so.
    pub flat_direction_probed: bool,
    /// Exact continuous symmetries deflated in the second-order test: turns of a group of
    /// spacecraft about the line its boundary states lie on (`symmetry.rs`; a collinear
    /// reversal, a head-on pair). Every point of such a turn has the same cost and meets the
    /// same constraints, so `min_reduced_eigenvalue` is a lower bound of the curvature on the
    /// complement of their generators (the sufficient condition for a manifold of minima).
    pub symmetry_directions: u8,
}

impl Certificate {
    /// An empty certificate (nothing evaluated).
    pub const fn new() -> Self {
        Self {
            first_order_evaluated: false,
            stationarity: 0.0,
            max_violation: 0.0,
            complementarity: 0.0,
            second_order_evaluated: false,
            min_reduced_eigenvalue: 0.0,
            multipliers_complete: false,
            multipliers: heapless::Vec::new(),
            flat_direction_probed: false,
            symmetry_directions: 0,
        }
    }

    /// Not taken for this answer (`solver::finish`): the flags say so and every measure is
    /// `new()`'s (not a previous answer's), but `max_violation`, an answer check's, is kept.
    pub(crate) fn not_evaluated(&mut self) {
        self.first_order_evaluated = false;
        self.stationarity = 0.0;
        self.complementarity = 0.0;
        self.second_order_evaluated = false;
        self.min_reduced_eigenvalue = 0.0;
        self.multipliers_complete = false;
        self.multipliers.clear();
        self.flat_direction_probed = false;
        self.symmetry_directions = 0;
    }

    /// First- and second-order conditions hold within the tolerances above.
    pub fn certifies_local_optimum(&self) -> bool {
        self.first_order_evaluated
            && self.second_order_evaluated
            && self.stationarity <= STATIONARITY_TOL
            && self.complementarity <= COMPLEMENTARITY_TOL
            && (self.min_reduced_eigenvalue >= CURVATURE_TOL
                || (self.flat_direction_probed && self.min_reduced_eigenvalue >= -CURVATURE_TOL))
    }

    /// First-order conditions and feasibility-independent measures met, and the reduced
    /// Hessian singular within `CURVATURE_TOL` (neither positive definite nor a saddle): the
    /// point the flat-direction probe examines.
    pub(crate) fn is_flat(&self) -> bool {
        self.first_order_evaluated
            && self.second_order_evaluated
            && self.stationarity <= STATIONARITY_TOL
            && self.complementarity <= COMPLEMENTARITY_TOL
            && self.min_reduced_eigenvalue >= -CURVATURE_TOL
            && self.min_reduced_eigenvalue < CURVATURE_TOL
    }
}

/// The public description of a row; `None` for a keep-out row the transcription does not hold
/// (never for a row of the QP's active set: the certificate then says its list is incomplete).
pub(super) fn describe(tr: &Transcription, id: RowId) -> Option<ActiveConstraint> {
    match id {
        RowId::Control { block, node, upper } => Some(ActiveConstraint::Control {
            spacecraft: block / 3,
            axis: block % 3,
            node,
            upper,
        }),
        RowId::KeepOut { pair, check } => {
            let p = usize::from(pair);
            let check = tr.check(p, usize::from(check))?;
            Some(ActiveConstraint::KeepOut {
                pair: tr.pair(p)?.spacecraft,
                time_tu: tr.time_of(check.tau),
            })
        }
    }
}

/// Evaluate the certificate at `y` (the transcription linearised at `y`, the QP state of the
/// QP that produced `y`). Writes the negative-curvature direction (unit, in the null space)
/// into `direction` when the reduced Hessian is not positive definite (zero otherwise).
/// `max_violation` is left to the caller. Returns the Lanczos products taken beyond the power
/// steps `work_units::finish` charges (nonzero only when the power method ran as well).
pub(crate) fn evaluate(
    tr: &Transcription,
    qp: &mut QpState,
    y: &Coefficients,
    cost: f64,
    direction: &mut Coefficients,
    w: &mut Coefficients,
    out: &mut Certificate,
) -> usize {
    let free = tr.basis.free;
    let size = (tr.blocks(), free);
    out.first_order_evaluated = true;
    out.flat_direction_probed = false;
    out.symmetry_directions = 0;
    out.multipliers.clear();
    out.multipliers_complete = true;
    // Stationarity and complementarity.
    *direction = *y;
    let mut complementarity = 0.0f64;
    qp.for_each_multiplier(tr, |id, value| {
        // A row the transcription does not hold (never: rows enter from its own scans) leaves
        // the first-order measures untaken.
        let Some(view) = tr.view(id) else {
            out.first_order_evaluated = false;
            out.multipliers_complete = false;
            return;
        };
        row_axpy(&view, -value, direction, free);
        let slack = row_dot(&view, y, free) - view.rhs;
        complementarity = complementarity.max(value * libm::fabs(slack));
        let listed = describe(tr, id).is_some_and(|constraint| {
            out.multipliers
                .push(Multiplier { constraint, value })
                .is_ok()
        });
        if !listed {
            out.multipliers_complete = false;
        }
    });
    let y_norm = libm::sqrt(dot(y, y, size));
    out.stationarity = libm::sqrt(dot(direction, direction, size)) / y_norm.max(1.0);
    out.complementarity = complementarity / (1.0 + libm::fabs(cost));
    // Second order: needs the Gram factor of the active rows as linearised at y.
    out.second_order_evaluated = false;
    out.min_reduced_eigenvalue = 0.0;
    *direction = [[0.0; MAX_FREE_PER_AXIS]; MAX_BLOCKS];
    let mut curved = false;
    qp.for_each_multiplier(tr, |id, value| {
        curved |= matches!(id, RowId::KeepOut { .. }) && value > 0.0;
    });
    if !curved {
        // Only linear constraints are active: the Hessian of the Lagrangian is the identity.
        out.min_reduced_eigenvalue = 1.0;
        out.second_order_evaluated = true;
        return 0;
    }
    if qp.mode != Mode::Factor || !qp.merge_close_checks(tr) {
        return 0;
    }
    let blocks = tr.blocks();
    let mut corrections: heapless::Vec<Envelope, MAX_ENVELOPES> = heapless::Vec::new();
    let mut sigma = envelope_corrections(tr, qp, y, &mut corrections);
    // Factor mode (checked above): the multipliers are the active rows' own.
    let mut lengths = [0.0; MAX_ACTIVE];
    if !check_lengths(tr, qp, y, &mut lengths) {
        return 0;
    }
    // The exact turn symmetries deflate the operator (`symmetry.rs`); `w` is free until the
    // eigenvalue methods below take it.
    let symmetries = Symmetries::find(tr, qp, y, w);
    out.symmetry_directions = u8::try_from(symmetries.count()).unwrap_or(u8::MAX);
    let op = Curvature {
        tr,
        qp,
        lengths: &lengths,
        corrections: &corrections,
        y,
        symmetries: &symmetries,
    };
    // Lanczos first (a few products where the power method took up to 120). A positive
    // definite answer is final; the direction is then unused (no saddle to leave, nothing flat
    // to probe) and left zero. Otherwise the power method below finds the eigenvector the
    // saddle escape and the flat-direction probe step along, from the same start as always.
    // A Gram factor that cannot be solved with (never: see `QpState::gram_solve`) leaves the
    // second-order measure untaken.
    if !start_vector(&op, direction) {
        *direction = [[0.0; MAX_FREE_PER_AXIS]; MAX_BLOCKS];
        return 0;
    }
    let lanczos = lanczos::largest(&op, direction, w, size);
    if let Some(estimate) = lanczos {
        if 1.0 - estimate.largest >= CURVATURE_TOL {
            *direction = [[0.0; MAX_FREE_PER_AXIS]; MAX_BLOCKS];
            out.min_reduced_eigenvalue = 1.0 - estimate.largest;
            out.second_order_evaluated = true;
            return 0;
        }
        // Where Lanczos spanned the start's whole Krylov space its smallest Ritz value is the
        // least eigenvalue any power iterate from that start meets: shifting by it instead of
        // the envelopes' bound keeps the iteration positive and converging at the spectrum's
        // own rate (issue 28: an envelope bound of 197 against a top eigenvalue of 3 left the
        // power method at 4e-4 after its settle test, and the saddle was reported certified).
        // Never below zero: rounding leaves components outside that space, whose eigenvalues
        // include PSP's zeros; a negative shift would let them outgrow the top one.
        if let Some(smallest) = estimate.smallest_exhausted {
            sigma = (-smallest).max(0.0);
        }
    }
    let extra = lanczos.map_or(LANCZOS_STEPS, |estimate| estimate.steps);
    if !start_vector(&op, direction) {
        *direction = [[0.0; MAX_FREE_PER_AXIS]; MAX_BLOCKS];
        return extra;
    }
    let mut largest = 0.0f64;
    for _ in 0..POWER_ITERATIONS {
        let norm = libm::sqrt(dot(direction, direction, size));
        if norm <= 1e-12 {
            largest = 0.0;
            break;
        }
        scale(direction, 1.0 / norm, size);
        *w = [[0.0; MAX_FREE_PER_AXIS]; MAX_BLOCKS];
        op.accumulate(direction, w);
        for (wr, dr) in w.iter_mut().zip(direction.iter()).take(blocks) {
            for (a, b) in wr.iter_mut().zip(dr.iter()).take(free) {
                *a += sigma * b;
            }
        }
        if !op.project(w) {
            *direction = [[0.0; MAX_FREE_PER_AXIS]; MAX_BLOCKS];
            return extra;
        }
        op.deflate(direction, w);
        let previous = largest;
        largest = dot(direction, w, size) - sigma;
        *direction = *w;
        // Converged far below the curvature tolerance (1e-6) at a positive curvature: stop
        // (deterministic either way). At a negative one the eigenvector is the saddle escape's
        // direction and converges more slowly than the eigenvalue: all steps are taken.
        let positive = largest < 1.0;
        if positive && libm::fabs(largest - previous) <= 1e-9 * (1.0 + libm::fabs(largest)) {
            break;
        }
    }
    let norm = libm::sqrt(dot(direction, direction, size));
    if norm > 0.0 {
        scale(direction, 1.0 / norm, size);
    }
    // Both methods estimate the largest eigenvalue from below (a Ritz value, a Rayleigh
    // quotient): the larger is the closer, and the certificate reports that one. The power
    // method's vector stays the direction the escape and the probe step along.
    if let Some(estimate) = lanczos {
        largest = largest.max(estimate.largest);
    }
    out.min_reduced_eigenvalue = 1.0 - largest;
    out.second_order_evaluated = true;
    extra
}

/// Envelope corrections of the active keep-out checks with a positive multiplier, into
/// `corrections` (at most `MAX_ENVELOPES`; past it a correction is left out, which only lowers
/// the estimate); returns the shift `sigma` that keeps `P (S + sigma I) P` positive
/// semidefinite for the power method where Lanczos cannot give a tighter one. Filled in place
/// and inlined: the list is 6.4 KB at capacity and must not be copied on the M7's stack.
#[inline(always)]
pub(super) fn envelope_corrections(
    tr: &Transcription,
    qp: &QpState,
    y: &Coefficients,
    corrections: &mut heapless::Vec<Envelope, MAX_ENVELOPES>,
) -> f64 {
    corrections.clear();
    let mut sigma = 0.0;
    qp.for_each_multiplier(tr, |id, value| {
        let RowId::KeepOut { pair, check } = id else {
            return;
        };
        let p = usize::from(pair);
        let (Some(c), Some(pair)) = (tr.check(p, usize::from(check)), tr.pair(p)) else {
            return;
        };
        if value <= 0.0 {
            return;
        }
        if let Some(envelope) = Envelope::new(tr, y, &pair, c.tau, value) {
            sigma += envelope.power_shift(&pair);
            let _ = corrections.push(envelope);
        }
    });
    sigma
}

/// The fixed start of both eigenvalue methods, projected on the null space: every sign
/// pattern present (deterministic, bit-identical host / M7). False when the projection cannot
/// be taken (`project`).
#[must_use]
fn start_vector(op: &Curvature<'_>, direction: &mut Coefficients) -> bool {
    let tr = op.tr;
    let free = tr.basis.free;
    *direction = [[0.0; MAX_FREE_PER_AXIS]; MAX_BLOCKS];
    for (b, row) in direction.iter_mut().indexed().take(tr.blocks()) {
        for (f, slot) in row.iter_mut().indexed().take(free) {
            let k = b.saturating_mul(free).saturating_add(f);
            *slot = libm::sin(0.7 * (k as f64) + 0.3);
        }
    }
    op.project(direction)
}
