//! Anderson acceleration of the convex-concave fixed-point map `y -> QP(linearised at y)`.
//!
//! The convex-concave sequence converges linearly, slowly where the solution slides along the
//! keep-out surface (rate 0.78 per subproblem measured on the paper's case with moving checks).
//! Anderson mixing with a short memory extrapolates the linearisation point from the last few
//! residuals `f = QP(y) - y`. Whatever point the QP is linearised at, its solution satisfies
//! every checked keep-out (`n . dr >= d` implies `|dr| >= d`), so acceleration never costs
//! feasibility at the checks; the solver resets the memory if an extrapolated point gives an
//! infeasible QP.

use super::kernel::{dot, Coefficients, MAX_BLOCKS};
use super::linalg::{cholesky_in_place, solve_lower, solve_lower_transposed};
use crate::capacity::MAX_FREE_PER_AXIS;
use crate::indexed::IndexedExt as _;

/// Most residual differences kept.
pub(crate) const MAX_MEMORY: usize = 1;

const ZERO: Coefficients = [[0.0; MAX_FREE_PER_AXIS]; MAX_BLOCKS];

/// The mixing history.
#[derive(Clone, Debug)]
pub(crate) struct Anderson {
    delta_f: [Coefficients; MAX_MEMORY],
    delta_g: [Coefficients; MAX_MEMORY],
    last_f: Coefficients,
    last_g: Coefficients,
    count: usize,
    next: usize,
    has_last: bool,
}

impl Anderson {
    pub const fn new() -> Self {
        Self {
            delta_f: [ZERO; MAX_MEMORY],
            delta_g: [ZERO; MAX_MEMORY],
            last_f: ZERO,
            last_g: ZERO,
            count: 0,
            next: 0,
            has_last: false,
        }
    }

    pub fn reset(&mut self) {
        self.count = 0;
        self.next = 0;
        self.has_last = false;
    }

    /// Forget the history and lend a square work array for the basis construction at setup
    /// (`Basis::build`), which runs before any mixing; `None` cannot happen (24 blocks >= 21
    /// coefficients) but is reported as a basis failure, never a panic.
    pub(super) fn setup_scratch(
        &mut self,
    ) -> Option<&mut [[f64; MAX_FREE_PER_AXIS]; MAX_FREE_PER_AXIS]> {
        self.reset();
        self.last_g.first_chunk_mut::<MAX_FREE_PER_AXIS>()
    }

    /// Forget the history and lend three of its buffers as scratch (the second-order step's
    /// CG vectors: after a Newton step the mixing history no longer describes the map).
    pub(super) fn lend(&mut self) -> [&mut Coefficients; 3] {
        self.reset();
        let [first] = &mut self.delta_f;
        let [second] = &mut self.delta_g;
        [first, second, &mut self.last_f]
    }

    /// Given the linearisation point `point` and the QP's solution `g`, overwrite `point` with
    /// the next linearisation point (in place: `point` is read only for the residual, and the
    /// caller needs no second dense vector on its stack). `memory` = 0 gives plain iteration
    /// (`point = g`).
    pub fn step(
        &mut self,
        point: &mut Coefficients,
        g: &Coefficients,
        memory: usize,
        blocks: usize,
        free: usize,
    ) {
        let memory = memory.min(MAX_MEMORY);
        let mut f = ZERO;
        for ((fb, gb), xb) in f.iter_mut().zip(g.iter()).zip(point.iter()).take(blocks) {
            for ((slot, gv), xv) in fb.iter_mut().zip(gb.iter()).zip(xb.iter()).take(free) {
                *slot = gv - xv;
            }
        }
        // Zero memory is plain iteration; otherwise the ring's length, non-zero by type (the
        // slot's wrap below cannot divide by zero).
        let Some(ring) = core::num::NonZeroUsize::new(memory) else {
            *point = *g;
            return;
        };
        if self.has_last {
            let slot = self.next;
            if let (Some(df), Some(dg)) = (self.delta_f.get_mut(slot), self.delta_g.get_mut(slot)) {
                // The differences of this step and the last, block by block and coefficient by
                // coefficient within the live sizes (every array holds MAX_BLOCKS blocks of
                // MAX_FREE_PER_AXIS coefficients).
                let deltas = df.iter_mut().zip(dg.iter_mut());
                let now = f.iter().zip(g.iter());
                let last = self.last_f.iter().zip(self.last_g.iter());
                for ((dfb, dgb), ((fb, gb), (lfb, lgb))) in deltas.zip(now.zip(last)).take(blocks) {
                    let slots = dfb.iter_mut().zip(dgb.iter_mut());
                    let values = fb.iter().zip(gb.iter()).zip(lfb.iter().zip(lgb.iter()));
                    for ((a, bb), ((fc, gc), (lfc, lgc))) in slots.zip(values).take(free) {
                        *a = fc - lfc;
                        *bb = gc - lgc;
                    }
                }
            }
            self.next = slot.saturating_add(1) % ring;
            self.count = self.count.saturating_add(1).min(memory);
        }
        self.last_f = f;
        self.last_g = *g;
        self.has_last = true;
        *point = *g;
        let k = self.count;
        if k == 0 {
            return;
        }
        // gamma = argmin |f - dF gamma|: normal equations with a small Tikhonov term (their
        // lower triangle: the factorisation and the solves read no other).
        let live = (blocks, free);
        let mut normal = [[0.0; MAX_MEMORY]; MAX_MEMORY];
        let mut rhs = [0.0; MAX_MEMORY];
        let mut trace = 0.0;
        let rows = self
            .delta_f
            .iter()
            .zip(rhs.iter_mut())
            .zip(normal.iter_mut());
        for (i, ((fi, slot), normal_row)) in rows.take(k).indexed() {
            *slot = dot(fi, &f, live);
            let entries = self.delta_f.iter().zip(normal_row.iter_mut());
            for (j, (fj, entry)) in entries.take(i.saturating_add(1)).indexed() {
                let value = dot(fi, fj, live);
                *entry = value;
                if i == j {
                    trace += value;
                }
            }
        }
        if trace <= 0.0 {
            return;
        }
        // The diagonal (a row has its diagonal entry: `k` is at most MAX_MEMORY). Not a
        // `step_by` walk: `StepBy::nth` divides, a panic path the C library must not link.
        for (i, row) in normal.iter_mut().enumerate().take(k) {
            if let Some(diagonal) = row.get_mut(i) {
                *diagonal += 1e-10 * trace;
            }
        }
        if cholesky_in_place(&mut normal, k).is_some()
            || !solve_lower(&normal, k, &mut rhs)
            || !solve_lower_transposed(&normal, k, &mut rhs)
        {
            self.reset();
            return;
        }
        for (gamma, dg) in rhs.iter().zip(self.delta_g.iter()).take(k) {
            for (nb, db) in point.iter_mut().zip(dg.iter()).take(blocks) {
                for (slot, d) in nb.iter_mut().zip(db.iter()).take(free) {
                    *slot -= gamma * d;
                }
            }
        }
    }
}
