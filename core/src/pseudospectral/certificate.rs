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

use super::lanczos::{self, Curvature, LANCZOS_STEPS};
use super::qp::{Mode, QpState};
use super::transcription::{
    block_dot, node_value, row_axpy, row_dot, Check, Coefficients, RowId, Transcription, MAX_BLOCKS,
};
use crate::capacity::{MAX_ACTIVE, MAX_FREE_PER_AXIS, MAX_NODES};
use crate::indexed::IndexedExt as _;
use crate::vec3;
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
/// Active keep-out checks whose envelope correction the second-order test holds at once
/// (about 400 bytes of stack each). Corrections past it are left out, which only lowers the
/// reported eigenvalue (the correction is positive semidefinite): conservative.
pub const MAX_ENVELOPES: usize = 16;

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
    /// The first-order measures were taken (the last QP ended at its optimum).
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
        }
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

/// `a . b` over the first `blocks` blocks and `free` coefficients (the rest are unused).
pub(super) fn dot(a: &Coefficients, b: &Coefficients, (blocks, free): (usize, usize)) -> f64 {
    let mut sum = 0.0;
    for (x, y) in a.iter().zip(b.iter()).take(blocks) {
        for (p, q) in x.iter().zip(y.iter()).take(free) {
            sum += p * q;
        }
    }
    sum
}

pub(super) fn scale(a: &mut Coefficients, factor: f64, (blocks, free): (usize, usize)) {
    for row in a.iter_mut().take(blocks) {
        for v in row.iter_mut().take(free) {
            *v *= factor;
        }
    }
}

/// Every multiplier of the last QP as (row, value >= 0).
fn for_each_multiplier(tr: &Transcription, qp: &QpState, mut f: impl FnMut(RowId, f64)) {
    match qp.mode {
        Mode::Factor => {
            for (&id, &value) in qp.active.iter().zip(qp.multiplier.iter()).take(qp.count) {
                f(id, value);
            }
        }
        Mode::Dual => super::qp_dual::for_each_multiplier(qp, tr, f),
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
            let check = tr
                .checks
                .get(p)
                .and_then(|row| row.get(usize::from(check)))?;
            let &pair = tr.pairs.get(p)?;
            Some(ActiveConstraint::KeepOut {
                pair,
                time_tu: tr.time_of(check.tau),
            })
        }
    }
}

/// `|r_i - r_j|` at each active row's check on `y` (0 for control rows), in the QP's row order:
/// the lengths `add_curvature` needs, computed once per point instead of once per product (a
/// CG or power-method product otherwise recomputed six dot products per check for them).
pub(super) fn check_lengths(
    tr: &Transcription,
    qp: &QpState,
    y: &Coefficients,
    out: &mut [f64; MAX_ACTIVE],
) {
    *out = [0.0; MAX_ACTIVE];
    for (slot, &id) in out.iter_mut().zip(qp.active.iter()).take(qp.count) {
        if let RowId::KeepOut { pair, check } = id {
            let p = usize::from(pair);
            if let Some(c) = tr.checks.get(p).and_then(|row| row.get(usize::from(check))) {
                let relative = tr.relative(p, c.source, y);
                *slot = libm::sqrt(
                    relative[0] * relative[0]
                        + relative[1] * relative[1]
                        + relative[2] * relative[2],
                );
            }
        }
    }
}

/// `out += sign * S v` restricted to one active keep-out check `c` of `pair` with multiplier
/// `l`, at a point `y` where the check's separation has length `length` (`check_lengths`) and
/// its normal is the unit separation (`unit_normals_at(tr, y)` sets it with the same arithmetic).
pub(super) fn add_curvature(
    tr: &Transcription,
    (pair, c): (usize, &Check),
    length: f64,
    l: f64,
    v: &Coefficients,
    out: &mut Coefficients,
) {
    let Some(&(i, j)) = tr.pairs.get(pair) else {
        return;
    };
    if length <= 0.0 {
        return;
    }
    let n = c.normal;
    let (row, _) = tr.check_row(c.source);
    let free = tr.basis.free;
    let (mi, mj) = (tr.mass_of(usize::from(i)), tr.mass_of(usize::from(j)));
    let block = |sc: u8, axis: usize| usize::from(sc).saturating_mul(3).saturating_add(axis);
    let mut jv = [0.0; 3];
    for (axis, slot) in jv.iter_mut().indexed() {
        *slot = block_dot(row, v, block(i, axis), free) / mi
            - block_dot(row, v, block(j, axis), free) / mj;
    }
    let along = n[0] * jv[0] + n[1] * jv[1] + n[2] * jv[2];
    for (axis, (value, normal)) in jv.iter().zip(n.iter()).indexed() {
        let t = (value - along * normal) * l / length;
        for (sc, mass, sign) in [(i, mi, 1.0), (j, mj, -1.0)] {
            if let Some(values) = out.get_mut(block(sc, axis)) {
                for (slot, r) in values.iter_mut().zip(row.iter()).take(free) {
                    *slot += sign * t * r / mass;
                }
            }
        }
    }
}

/// The time-envelope correction of an active keep-out check. The keep-out is semi-infinite:
/// what must hold is `phi(y) = min_t |r(t, y)| >= d`, and on a trajectory verified feasible on
/// the continuous trajectory an active check sits at a local minimum of `|r(t)|` in time. The
/// Hessian of `phi` is `f_yy - f_yt f_yt^T / f_tt` (f = |r|, at the minimising t);
/// `add_curvature` gives `f_yy`, this the rank-one term, so the Lagrangian gains
/// `+l f_yt f_yt^T / f_tt`. `f_yt` is kept compactly (the basis position and velocity rows at the
/// check time and the relative state), never as a dense vector.
#[derive(Clone, Copy, Debug)]
pub(super) struct Envelope {
    pair: (u8, u8),
    position_row: [f64; MAX_FREE_PER_AXIS],
    velocity_row: [f64; MAX_FREE_PER_AXIS],
    /// Per axis: the weights of the position row and of the velocity row in `f_yt`.
    along_position: [f64; 3],
    along_velocity: [f64; 3],
    /// `l / f_tt`.
    pub(super) weight: f64,
}

impl Envelope {
    /// Build for the check of `pair` at `tau` with multiplier `l`; `None` when the check is not
    /// a strict minimum in time (then the correction is left out, which only lowers the
    /// reported curvature: conservative).
    pub(super) fn new(
        tr: &Transcription,
        y: &Coefficients,
        pair: usize,
        tau: f64,
        l: f64,
    ) -> Option<Self> {
        let &(i, j) = tr.pairs.get(pair)?;
        let free = tr.basis.free;
        let nodes = tr.grid.nodes();
        let (mi, mj) = (tr.mass_of(usize::from(i)), tr.mass_of(usize::from(j)));
        let rate = 2.0 / tr.horizon_tu;
        let mut r = [0.0; 3];
        let mut rd = [0.0; 3];
        let mut rdd = [0.0; 3];
        // One interpolation row at `tau` serves every value below.
        let mut lagrange = [0.0; MAX_NODES];
        tr.grid.lagrange_row(tau, &mut lagrange);
        for axis in 0..3 {
            let mut values = [0.0; MAX_NODES];
            for (h, slot) in values.iter_mut().indexed().take(nodes) {
                let row = tr.basis.position.get(h)?;
                *slot = node_value(&tr.base_position, block(i, axis), h)
                    - node_value(&tr.base_position, block(j, axis), h)
                    + block_dot(row, y, block(i, axis), free) / mi
                    - block_dot(row, y, block(j, axis), free) / mj;
            }
            let mut first = [0.0; MAX_NODES];
            let mut second = [0.0; MAX_NODES];
            tr.grid.differentiate(&values, &mut first);
            tr.grid.differentiate(&first, &mut second);
            *r.get_mut(axis)? = tr.grid.interpolate_with(&lagrange, &values);
            *rd.get_mut(axis)? = rate * tr.grid.interpolate_with(&lagrange, &first);
            *rdd.get_mut(axis)? = rate * rate * tr.grid.interpolate_with(&lagrange, &second);
        }
        let length = libm::sqrt(vec3::dot(&r, &r));
        if length <= 0.0 {
            return None;
        }
        let cube = length * length * length;
        let radial = vec3::dot(&r, &rd);
        let f_tt = (vec3::dot(&rd, &rd) + vec3::dot(&r, &rdd)) / length - radial * radial / cube;
        if f_tt <= 1e-9 * (1.0 + vec3::dot(&rd, &rd) / length) {
            return None;
        }
        let mut envelope = Self {
            pair: (i, j),
            position_row: [0.0; MAX_FREE_PER_AXIS],
            velocity_row: [0.0; MAX_FREE_PER_AXIS],
            along_position: [0.0; 3],
            along_velocity: [0.0; 3],
            weight: l / f_tt,
        };
        tr.basis
            .position_row(&tr.grid, tau, &mut envelope.position_row);
        for (f, slot) in envelope.velocity_row.iter_mut().indexed().take(free) {
            let mut column = [0.0; MAX_NODES];
            for (h, value) in column.iter_mut().indexed().take(nodes) {
                *value = tr.basis.position.get(h)?.get(f).copied()?;
            }
            let mut derivative = [0.0; MAX_NODES];
            tr.grid.differentiate(&column, &mut derivative);
            *slot = rate * tr.grid.interpolate_with(&lagrange, &derivative);
        }
        for axis in 0..3 {
            let (ra, rda) = (*r.get(axis)?, *rd.get(axis)?);
            *envelope.along_position.get_mut(axis)? = rda / length - radial * ra / cube;
            *envelope.along_velocity.get_mut(axis)? = ra / length;
        }
        Some(envelope)
    }

    /// `f_yt . v`.
    pub(super) fn dot(&self, tr: &Transcription, v: &Coefficients) -> f64 {
        let free = tr.basis.free;
        let (i, j) = self.pair;
        let (mi, mj) = (tr.mass_of(usize::from(i)), tr.mass_of(usize::from(j)));
        let mut sum = 0.0;
        let along = self.along_position.iter().zip(self.along_velocity.iter());
        for (axis, (&a, &b)) in along.indexed() {
            let (bi, bj) = (block(i, axis), block(j, axis));
            let p = block_dot(&self.position_row, v, bi, free) / mi
                - block_dot(&self.position_row, v, bj, free) / mj;
            let q = block_dot(&self.velocity_row, v, bi, free) / mi
                - block_dot(&self.velocity_row, v, bj, free) / mj;
            sum += a * p + b * q;
        }
        sum
    }

    /// `out += alpha f_yt`.
    pub(super) fn axpy(&self, tr: &Transcription, alpha: f64, out: &mut Coefficients) {
        let free = tr.basis.free;
        let (i, j) = self.pair;
        let (mi, mj) = (tr.mass_of(usize::from(i)), tr.mass_of(usize::from(j)));
        let along = self.along_position.iter().zip(self.along_velocity.iter());
        for (axis, (&a, &b)) in along.indexed() {
            for (sc, mass, sign) in [(i, mi, 1.0), (j, mj, -1.0)] {
                if let Some(values) = out.get_mut(block(sc, axis)) {
                    let scale = alpha * sign / mass;
                    for ((slot, p), q) in values
                        .iter_mut()
                        .zip(self.position_row.iter())
                        .zip(self.velocity_row.iter())
                        .take(free)
                    {
                        *slot += scale * (a * p + b * q);
                    }
                }
            }
        }
    }
}

fn block(sc: u8, axis: usize) -> usize {
    usize::from(sc).saturating_mul(3).saturating_add(axis)
}

/// `x <- P x`: remove the part of `x` in the span of the active rows.
pub(super) fn project(tr: &Transcription, qp: &QpState, x: &mut Coefficients) {
    let free = tr.basis.free;
    let mut b = [0.0; MAX_ACTIVE];
    for (slot, &id) in b.iter_mut().zip(qp.active.iter()).take(qp.count) {
        *slot = row_dot(&tr.view(id), x, free);
    }
    qp.gram_solve(&mut b);
    for (value, &id) in b.iter().zip(qp.active.iter()).take(qp.count) {
        row_axpy(&tr.view(id), -value, x, free);
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
    out.multipliers.clear();
    out.multipliers_complete = true;
    // Stationarity and complementarity.
    *direction = *y;
    let mut complementarity = 0.0f64;
    for_each_multiplier(tr, qp, |id, value| {
        let view = tr.view(id);
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
    for_each_multiplier(tr, qp, |id, value| {
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
    // Envelope corrections of the active moving checks (at most one per pair), and a shift
    // `sigma` that keeps `P (S + sigma I) P` positive semidefinite for the power method.
    let mut corrections: heapless::Vec<Envelope, MAX_ENVELOPES> = heapless::Vec::new();
    let mut sigma = 0.0;
    for_each_multiplier(tr, qp, |id, value| {
        let RowId::KeepOut { pair, check } = id else {
            return;
        };
        let p = usize::from(pair);
        let Some(c) = tr.checks.get(p).and_then(|row| row.get(usize::from(check))) else {
            return;
        };
        if value <= 0.0 {
            return;
        }
        if let Some(envelope) = Envelope::new(tr, y, p, c.tau, value) {
            let mut norm2 = 0.0;
            let along = envelope
                .along_position
                .iter()
                .zip(envelope.along_velocity.iter());
            for (&a, &b) in along {
                for (pv, qv) in envelope
                    .position_row
                    .iter()
                    .zip(envelope.velocity_row.iter())
                {
                    let e = a * pv + b * qv;
                    norm2 += e * e;
                }
            }
            let (mi, mj) = (
                tr.mass_of(usize::from(envelope.pair.0)),
                tr.mass_of(usize::from(envelope.pair.1)),
            );
            sigma += envelope.weight * norm2 * (1.0 / (mi * mi) + 1.0 / (mj * mj));
            // Past the capacity a correction is left out: that only lowers the estimate.
            let _ = corrections.push(envelope);
        }
    });
    // Factor mode (checked above): the multipliers are the active rows' own.
    let mut lengths = [0.0; MAX_ACTIVE];
    check_lengths(tr, qp, y, &mut lengths);
    let op = Curvature {
        tr,
        qp,
        lengths: &lengths,
        corrections: &corrections,
    };
    // Lanczos first (a few products where the power method took up to 120). A positive
    // definite answer is final; the direction is then unused (no saddle to leave, nothing flat
    // to probe) and left zero. Otherwise the power method below finds the eigenvector the
    // saddle escape and the flat-direction probe step along, from the same start as always.
    start_vector(tr, qp, direction);
    let lanczos = lanczos::largest(&op, direction, w, size);
    if let Some((largest, _)) = lanczos {
        if 1.0 - largest >= CURVATURE_TOL {
            *direction = [[0.0; MAX_FREE_PER_AXIS]; MAX_BLOCKS];
            out.min_reduced_eigenvalue = 1.0 - largest;
            out.second_order_evaluated = true;
            return 0;
        }
    }
    let extra = lanczos.map_or(LANCZOS_STEPS, |(_, steps)| steps);
    start_vector(tr, qp, direction);
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
        project(tr, qp, w);
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
    out.min_reduced_eigenvalue = 1.0 - largest;
    out.second_order_evaluated = true;
    extra
}

/// The fixed start of both eigenvalue methods, projected on the null space: every sign
/// pattern present (deterministic, bit-identical host / M7).
fn start_vector(tr: &Transcription, qp: &QpState, direction: &mut Coefficients) {
    let free = tr.basis.free;
    *direction = [[0.0; MAX_FREE_PER_AXIS]; MAX_BLOCKS];
    for (b, row) in direction.iter_mut().indexed().take(tr.blocks()) {
        for (f, slot) in row.iter_mut().indexed().take(free) {
            let k = b.saturating_mul(free).saturating_add(f);
            *slot = libm::sin(0.7 * (k as f64) + 0.3);
        }
    }
    project(tr, qp, direction);
}
