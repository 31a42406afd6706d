//! The free coefficients of one axis's position polynomial.
//!
//! With collocation at all N + 1 LGL nodes, each axis of each spacecraft is one polynomial of
//! degree N; velocity and control at the nodes are its exact derivatives, and the LGL quadrature
//! of the squared control (degree 2N - 4) is exact. Node positions are written
//! `x = x_cubic + Zt z`: `x_cubic` is the unconstrained minimum-energy cubic (it meets all four
//! boundary conditions), and the N - 3 columns of `Zt` span the polynomials `(1 - tau^2)^2 q(tau)`
//! that vanish with their first derivative at both ends, orthonormalised in the cost metric.
//! The cubic is optimal on the affine set, so the cross term vanishes and for mass m
//! `J_axis = m^2 J_cubic + 1/2 |y|^2` with `y = m z`: the QP Hessian is the identity.

use super::lgl::LglGrid;
use super::linalg::{cholesky_in_place, solve_lower};
use crate::capacity::{MAX_FREE_PER_AXIS, MAX_NODES};
use crate::indexed::IndexedExt as _;

/// Per (N, T): the basis and its derivative rows.
#[derive(Clone, Debug)]
pub(crate) struct Basis {
    /// Free coefficients per axis, N - 3.
    pub free: usize,
    /// `Zt[h][c]`: node h's position per unit coefficient c (unit mass).
    pub position: [[f64; MAX_FREE_PER_AXIS]; MAX_NODES],
    /// `(2/T)^2 (D^2 Zt)[h][c]`: node h's acceleration (LU/TU^2) per unit coefficient.
    pub accel: [[f64; MAX_FREE_PER_AXIS]; MAX_NODES],
    /// Euclidean norm of each `accel` row.
    pub accel_norm: [f64; MAX_NODES],
}

impl Basis {
    /// An empty basis.
    pub const fn new() -> Self {
        Self {
            free: 0,
            position: [[0.0; MAX_FREE_PER_AXIS]; MAX_NODES],
            accel: [[0.0; MAX_FREE_PER_AXIS]; MAX_NODES],
            accel_norm: [0.0; MAX_NODES],
        }
    }

    /// Build the basis for `grid` and horizon `horizon_tu`. `scratch` is a square work array.
    /// Returns false when the cost metric is not numerically positive definite.
    pub fn build(
        &mut self,
        grid: &LglGrid,
        horizon_tu: f64,
        scratch: &mut [[f64; MAX_FREE_PER_AXIS]; MAX_FREE_PER_AXIS],
    ) -> bool {
        self.free = 0;
        for row in self.position.iter_mut().chain(self.accel.iter_mut()) {
            row.fill(0.0);
        }
        self.accel_norm.fill(0.0);
        let n = grid.degree;
        let nodes = grid.nodes();
        let Some(free) = n.checked_sub(3) else {
            return false;
        };
        if free == 0 || free > MAX_FREE_PER_AXIS {
            return false;
        }
        self.free = free;
        // Raw basis: (1 - tau^2)^2 P_c(tau), Legendre P_c keeps the Gram matrix well scaled.
        let mut raw = [[0.0; MAX_FREE_PER_AXIS]; MAX_NODES];
        for (row, tau) in raw.iter_mut().zip(grid.taus()) {
            let bubble = (1.0 - tau * tau) * (1.0 - tau * tau);
            // Legendre P_c(tau) by the three-term recurrence.
            let (mut previous, mut current) = (0.0, 1.0);
            for (c, slot) in row.iter_mut().take(free).indexed() {
                *slot = bubble * current;
                let k = c as f64;
                let next = ((2.0 * k + 1.0) * tau * current - k * previous) / (k + 1.0);
                previous = current;
                current = next;
            }
        }
        // Accelerations per unit raw coefficient: (2/T)^2 D (D raw), each node's row of D
        // applied to every column at once (per entry the same sum, in the same node order, as
        // differentiating one column at a time). `self.accel` holds D raw meanwhile (it is
        // written last, below).
        let scale = 4.0 / (horizon_tu * horizon_tu);
        let mut raw_accel = [[0.0; MAX_FREE_PER_AXIS]; MAX_NODES];
        apply_rows(grid, &raw, &mut self.accel, free);
        apply_rows(grid, &self.accel, &mut raw_accel, free);
        for row in raw_accel.iter_mut().take(nodes) {
            for value in row.iter_mut().take(free) {
                *value *= scale;
            }
        }
        // Cost metric: J = T/4 sum_h w_h a_h^2 = 1/2 z^T M z with M = T/2 A^T W A (its lower
        // triangle: the factorisation reads no other).
        *scratch = [[0.0; MAX_FREE_PER_AXIS]; MAX_FREE_PER_AXIS];
        for ((_, w), row) in grid.nodes_and_weights().zip(raw_accel.iter()) {
            for (a, (metric_row, &ra)) in scratch.iter_mut().zip(row.iter()).take(free).indexed() {
                for (slot, &rb) in metric_row
                    .iter_mut()
                    .zip(row.iter())
                    .take(a.saturating_add(1))
                {
                    *slot += w * ra * rb;
                }
            }
        }
        for (a, metric_row) in scratch.iter_mut().take(free).indexed() {
            for slot in metric_row.iter_mut().take(a.saturating_add(1)) {
                *slot *= 0.5 * horizon_tu;
            }
        }
        if cholesky_in_place(scratch, free).is_some() {
            return false;
        }
        // Orthonormalise: Zt = Z L^{-T}, i.e. each row r of Z gives row L^{-1} r^T.
        let rows = raw.iter().zip(raw_accel.iter());
        let outputs = self.position.iter_mut().zip(self.accel.iter_mut());
        for ((raw_row, raw_accel_row), ((position, accel), accel_norm)) in rows
            .zip(outputs.zip(self.accel_norm.iter_mut()))
            .take(nodes)
        {
            let mut row = *raw_row;
            let mut accel_row = *raw_accel_row;
            if !solve_lower(scratch, free, &mut row) || !solve_lower(scratch, free, &mut accel_row)
            {
                return false;
            }
            let mut norm2 = 0.0;
            for v in accel_row.iter().take(free) {
                norm2 += v * v;
            }
            *position = row;
            *accel = accel_row;
            *accel_norm = libm::sqrt(norm2);
        }
        true
    }

    /// `e(tau) = Zt^T l(tau)`: position at `tau` per unit coefficient.
    pub fn position_row(&self, grid: &LglGrid, tau: f64, out: &mut [f64; MAX_FREE_PER_AXIS]) {
        let mut lagrange = [0.0; MAX_NODES];
        grid.lagrange_row(tau, &mut lagrange);
        *out = [0.0; MAX_FREE_PER_AXIS];
        for (weight, row) in lagrange.iter().zip(self.position.iter()).take(grid.nodes()) {
            for (slot, value) in out.iter_mut().zip(row.iter()).take(self.free) {
                *slot += weight * value;
            }
        }
    }
}

/// `out = D values` on the first `free` columns, `D` the grid's differentiation matrix: per
/// entry `sum_k D[h][k] values[k][c]` over the nodes in order (`out` starts at zero).
fn apply_rows(
    grid: &LglGrid,
    values: &[[f64; MAX_FREE_PER_AXIS]; MAX_NODES],
    out: &mut [[f64; MAX_FREE_PER_AXIS]; MAX_NODES],
    free: usize,
) {
    let nodes = grid.nodes();
    for (out_row, d_row) in out.iter_mut().zip(grid.diff.iter()).take(nodes) {
        for (&d, row) in d_row.iter().zip(values.iter()).take(nodes) {
            for (slot, &v) in out_row.iter_mut().zip(row.iter()).take(free) {
                *slot += d * v;
            }
        }
    }
}

#[cfg(test)]
#[allow(clippy::needless_range_loop)]
mod tests {
    use super::*;

    fn build(n: usize, t: f64) -> (LglGrid, Basis) {
        let mut g = LglGrid::new();
        assert!(g.build(n, 60));
        let mut b = Basis::new();
        let mut s = [[0.0; MAX_FREE_PER_AXIS]; MAX_FREE_PER_AXIS];
        assert!(b.build(&g, t, &mut s));
        (g, b)
    }

    #[test]
    fn basis_is_cost_orthonormal_and_meets_homogeneous_boundaries() {
        for n in [4usize, 9, 10, 16, 24] {
            let (g, b) = build(n, 10.0);
            // Orthonormal: T/4 sum w a_i a_j = delta_ij / 2.
            for i in 0..b.free {
                for j in 0..b.free {
                    let s: f64 = (0..=n)
                        .map(|h| g.weight[h] * b.accel[h][i] * b.accel[h][j])
                        .sum();
                    let expected = if i == j { 1.0 } else { 0.0 };
                    assert!((0.5 * 10.0 * s - expected).abs() < 1e-9, "n={n} {i} {j}");
                }
            }
            // Zero position and velocity at both ends.
            for c in 0..b.free {
                let mut col = [0.0; MAX_NODES];
                for h in 0..=n {
                    col[h] = b.position[h][c];
                }
                let mut d = [0.0; MAX_NODES];
                g.differentiate(&col, &mut d);
                assert!(col[0].abs() < 1e-14 && col[n].abs() < 1e-14);
                assert!(d[0].abs() < 1e-9 && d[n].abs() < 1e-9, "n={n} c={c}");
            }
        }
    }
}
