//! The curvature of the keep-out constraints in the Hessian of the Lagrangian, `S` (see
//! `certificate`): each active keep-out check's term `l J^T (I - n n^T) J / |r|`, the time-envelope
//! correction of a semi-infinite check at its minimum in time (`Envelope`), the projection on
//! the active rows' null space, and the operator `P S P` as the certificate's eigenvalue
//! methods apply it (`Curvature`). The second-order step (`newton.rs`) and the certificate
//! (`certificate.rs`, `lanczos.rs`) both use these, so neither takes them from the other.

use super::kernel::Coefficients;
use super::qp_state::QpState;
use super::symmetry::Symmetries;
use super::transcription::{
    block_dot, row_axpy, row_dot, spacecraft_blocks, Check, Pair, RowId, Transcription,
};
use crate::capacity::{MAX_ACTIVE, MAX_FREE_PER_AXIS, MAX_NODES};
use crate::indexed::IndexedExt as _;
use crate::vec3;

/// Active keep-out checks whose envelope correction the second-order test holds at once
/// (about 400 bytes of stack each). Corrections past it are left out, which only lowers the
/// reported eigenvalue (the correction is positive semidefinite): conservative.
pub const MAX_ENVELOPES: usize = 16;

/// `|r_i - r_j|` at each active row's check on `y` (0 for control rows), in the QP's row order:
/// the lengths `add_curvature` needs, computed once per point instead of once per product (a
/// CG or power-method product otherwise recomputed six dot products per check for them).
/// Returns false when an active row is not the transcription's (never: rows enter the working
/// set from its own scans); the caller then takes no curvature products (`project`,
/// `Curvature::accumulate` and `newton::curvature` pass over such a row).
#[must_use]
pub(super) fn check_lengths(
    tr: &Transcription,
    qp: &QpState,
    y: &Coefficients,
    out: &mut [f64; MAX_ACTIVE],
) -> bool {
    *out = [0.0; MAX_ACTIVE];
    for (slot, &id) in out.iter_mut().zip(qp.active.iter()).take(qp.count) {
        if tr.view(id).is_none() {
            return false;
        }
        if let RowId::KeepOut { pair, check } = id {
            let p = usize::from(pair);
            let Some(relative) = tr
                .check(p, usize::from(check))
                .zip(tr.pair(p))
                .and_then(|(c, pair)| tr.relative(&pair, c.source, y))
            else {
                return false;
            };
            *slot = libm::sqrt(
                relative[0] * relative[0] + relative[1] * relative[1] + relative[2] * relative[2],
            );
        }
    }
    true
}

/// An active keep-out row's check and pair (`None` for a control row, or a row that names no
/// check of the transcription: `check_lengths` has refused those).
pub(super) fn keep_out_term(tr: &Transcription, id: RowId) -> Option<(Pair, Check)> {
    let RowId::KeepOut { pair, check } = id else {
        return None;
    };
    let p = usize::from(pair);
    Some((tr.pair(p)?, tr.check(p, usize::from(check))?))
}

/// `out += sign * S v` restricted to one active keep-out check `c` of `pair` with multiplier
/// `l`, at a point `y` where the check's separation has length `length` (`check_lengths`) and
/// its normal is the unit separation (`unit_normals_at(tr, y)` sets it with the same arithmetic).
pub(super) fn add_curvature(
    tr: &Transcription,
    (pair, c): (&Pair, &Check),
    length: f64,
    l: f64,
    v: &Coefficients,
    out: &mut Coefficients,
) {
    if length <= 0.0 {
        return;
    }
    let (i, j) = pair.spacecraft;
    let (mi, mj) = pair.masses;
    let (Some((row, _)), Some(vi), Some(vj)) = (
        tr.check_row(c.source),
        spacecraft_blocks(v, i),
        spacecraft_blocks(v, j),
    ) else {
        return;
    };
    let n = c.normal;
    let free = tr.basis.free;
    let mut jv = [0.0; 3];
    for (slot, (bi, bj)) in jv.iter_mut().zip(vi.iter().zip(vj.iter())) {
        *slot = block_dot(row, bi, free) / mi - block_dot(row, bj, free) / mj;
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
    /// The pair's index (`Transcription::pair`).
    pair: u8,
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
        pair: &Pair,
        tau: f64,
        l: f64,
    ) -> Option<Self> {
        let (i, j) = pair.spacecraft;
        let (mi, mj) = pair.masses;
        let free = tr.basis.free;
        let nodes = tr.grid.nodes();
        let rate = 2.0 / tr.horizon_tu;
        let mut r = [0.0; 3];
        let mut rd = [0.0; 3];
        let mut rdd = [0.0; 3];
        // One interpolation row at `tau` serves every value below.
        let mut lagrange = [0.0; MAX_NODES];
        tr.grid.lagrange_row(tau, &mut lagrange);
        let base = spacecraft_blocks(&tr.base_position, i)?
            .iter()
            .zip(spacecraft_blocks(&tr.base_position, j)?);
        let blocks = spacecraft_blocks(y, i)?
            .iter()
            .zip(spacecraft_blocks(y, j)?);
        let states = r.iter_mut().zip(rd.iter_mut()).zip(rdd.iter_mut());
        for (((r_axis, rd_axis), rdd_axis), ((base_i, base_j), (yi, yj))) in
            states.zip(base.zip(blocks))
        {
            let mut values = [0.0; MAX_NODES];
            let nodal = base_i
                .iter()
                .zip(base_j.iter())
                .zip(tr.basis.position.iter());
            for (slot, ((&pi, &pj), row)) in values.iter_mut().zip(nodal).take(nodes) {
                *slot = pi - pj + block_dot(row, yi, free) / mi - block_dot(row, yj, free) / mj;
            }
            let mut first = [0.0; MAX_NODES];
            let mut second = [0.0; MAX_NODES];
            tr.grid.differentiate(&values, &mut first);
            tr.grid.differentiate(&first, &mut second);
            *r_axis = tr.grid.interpolate_with(&lagrange, &values);
            *rd_axis = rate * tr.grid.interpolate_with(&lagrange, &first);
            *rdd_axis = rate * rate * tr.grid.interpolate_with(&lagrange, &second);
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
            pair: u8::try_from(pair.index).ok()?,
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
            for (value, row) in column.iter_mut().zip(tr.basis.position.iter()).take(nodes) {
                *value = *row.get(f)?;
            }
            let mut derivative = [0.0; MAX_NODES];
            tr.grid.differentiate(&column, &mut derivative);
            *slot = rate * tr.grid.interpolate_with(&lagrange, &derivative);
        }
        let weights = envelope
            .along_position
            .iter_mut()
            .zip(envelope.along_velocity.iter_mut());
        for ((position_weight, velocity_weight), (&ra, &rda)) in
            weights.zip(r.iter().zip(rd.iter()))
        {
            *position_weight = rda / length - radial * ra / cube;
            *velocity_weight = ra / length;
        }
        Some(envelope)
    }

    /// The pair this correction belongs to (its index: `Transcription::pair`).
    pub(super) fn pair(&self) -> usize {
        usize::from(self.pair)
    }

    /// This correction's part of the shift `sigma` that keeps `P (S + sigma I) P` positive
    /// semidefinite for the certificate's power method: `w |f_yt|^2` with the rows' entries
    /// squared per spacecraft mass (a bound on the correction's largest eigenvalue).
    pub(super) fn power_shift(&self, pair: &Pair) -> f64 {
        let mut norm2 = 0.0;
        let along = self.along_position.iter().zip(self.along_velocity.iter());
        for (&a, &b) in along {
            for (pv, qv) in self.position_row.iter().zip(self.velocity_row.iter()) {
                let e = a * pv + b * qv;
                norm2 += e * e;
            }
        }
        let (mi, mj) = pair.masses;
        self.weight * norm2 * (1.0 / (mi * mi) + 1.0 / (mj * mj))
    }

    /// `f_yt . v`, `pair` the correction's pair (`Envelope::pair`).
    pub(super) fn dot(&self, tr: &Transcription, pair: &Pair, v: &Coefficients) -> f64 {
        let free = tr.basis.free;
        let (i, j) = pair.spacecraft;
        let (mi, mj) = pair.masses;
        let (Some(vi), Some(vj)) = (spacecraft_blocks(v, i), spacecraft_blocks(v, j)) else {
            return 0.0;
        };
        let mut sum = 0.0;
        let along = self.along_position.iter().zip(self.along_velocity.iter());
        for ((&a, &b), (bi, bj)) in along.zip(vi.iter().zip(vj.iter())) {
            let p = block_dot(&self.position_row, bi, free) / mi
                - block_dot(&self.position_row, bj, free) / mj;
            let q = block_dot(&self.velocity_row, bi, free) / mi
                - block_dot(&self.velocity_row, bj, free) / mj;
            sum += a * p + b * q;
        }
        sum
    }

    /// `out += alpha f_yt`, `pair` the correction's pair (`Envelope::pair`).
    pub(super) fn axpy(&self, tr: &Transcription, pair: &Pair, alpha: f64, out: &mut Coefficients) {
        let free = tr.basis.free;
        let (i, j) = pair.spacecraft;
        let (mi, mj) = pair.masses;
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

/// `x <- P x`: remove the part of `x` in the span of the active rows (rows the transcription
/// does not hold have no part: `check_lengths` refuses a working set with one). Returns false,
/// with `x` not projected, when the Gram factor cannot be solved with (`QpState::gram_solve`).
#[must_use]
pub(super) fn project(tr: &Transcription, qp: &QpState, x: &mut Coefficients) -> bool {
    let free = tr.basis.free;
    let mut b = [0.0; MAX_ACTIVE];
    for (slot, &id) in b.iter_mut().zip(qp.active.iter()).take(qp.count) {
        if let Some(view) = tr.view(id) {
            *slot = row_dot(&view, x, free);
        }
    }
    if !qp.gram_solve(&mut b) {
        return false;
    }
    for (value, &id) in b.iter().zip(qp.active.iter()).take(qp.count) {
        if let Some(view) = tr.view(id) {
            row_axpy(&view, -value, x, free);
        }
    }
    true
}

/// `S` less the envelope terms (the curvature of the active keep-out checks at the iterate), for
/// the projected products.
pub(super) struct Curvature<'a> {
    pub tr: &'a Transcription,
    pub qp: &'a QpState,
    /// `|r|` at each active row's check (`check_lengths`).
    pub lengths: &'a [f64; MAX_ACTIVE],
    pub corrections: &'a [Envelope],
    /// The iterate, whose exact turn symmetries (`symmetries`) deflate the operator.
    pub y: &'a Coefficients,
    /// The turns about a line that are exact symmetries of the iterate (`symmetry.rs`).
    pub symmetries: &'a Symmetries,
}

impl Curvature<'_> {
    /// `x <- P x` (see `project`).
    #[must_use]
    pub(super) fn project(&self, x: &mut Coefficients) -> bool {
        project(self.tr, self.qp, x)
    }

    /// `out -= sum (g . v) g / |g|^2` over the turn symmetries' generators: applied after the
    /// projection, the operator is `P S P` deflated by them (`symmetry.rs`).
    pub(super) fn deflate(&self, v: &Coefficients, out: &mut Coefficients) {
        self.symmetries.deflate(self.tr, self.y, v, out);
    }

    /// The dimension of any Krylov space of `P S P`, at most: `S` has rank at most two per
    /// active keep-out check (`J^T (I - n n^T) J`) plus one per envelope correction, so a
    /// Krylov space spans at most that rank plus its start. Past it a Lanczos step meets only
    /// rounding (`lanczos`).
    pub(super) fn krylov_dimension(&self) -> usize {
        let checks = self
            .qp
            .active
            .iter()
            .take(self.qp.count)
            .filter(|&&id| keep_out_term(self.tr, id).is_some())
            // Not `count()`: its sum keeps an overflow check (a panic path) the abort-proof
            // C library must not link.
            .fold(0usize, |n, _| n.saturating_add(1));
        // The deflation adds a term of rank one per turn symmetry.
        checks
            .saturating_mul(2)
            .saturating_add(self.corrections.len())
            .saturating_add(self.symmetries.count())
            .saturating_add(1)
    }

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
            if let Some((pair, c)) = keep_out_term(tr, id) {
                add_curvature(tr, (&pair, &c), length, value, v, out);
            }
        }
        for envelope in self.corrections {
            // Built for a pair of this transcription, so found; a correction left out would
            // only lower the estimate.
            if let Some(pair) = tr.pair(envelope.pair()) {
                let along = envelope.weight * envelope.dot(tr, &pair, v);
                envelope.axpy(tr, &pair, -along, out);
            }
        }
    }
}
