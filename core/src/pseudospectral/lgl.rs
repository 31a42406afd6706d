//! Legendre–Gauss–Lobatto nodes, quadrature weights, differentiation matrix and barycentric
//! interpolation (Huang 2012, eq. 8-15). Computed once per degree N into fixed arrays.

use crate::capacity::MAX_NODES;
use crate::indexed::IndexedExt as _;

/// The LGL grid of one degree N: nodes on [-1, 1], weights, differentiation matrix and
/// barycentric weights. Only the first `N + 1` entries of each array are meaningful.
#[derive(Clone, Debug)]
pub(crate) struct LglGrid {
    /// Degree N (N + 1 nodes).
    pub degree: usize,
    /// Nodes `tau_0 = -1 < ... < tau_N = 1`.
    pub tau: [f64; MAX_NODES],
    /// Quadrature weights `w_h = 2 / (N (N + 1) L_N(tau_h)^2)`.
    pub weight: [f64; MAX_NODES],
    /// `L_N(tau_h)`.
    pub legendre_at_node: [f64; MAX_NODES],
    /// Differentiation matrix `D[h][k]` (eq. 12, with `tau_h - tau_k`).
    pub diff: [[f64; MAX_NODES]; MAX_NODES],
    /// Barycentric weights, scaled to unit largest magnitude.
    pub bary: [f64; MAX_NODES],
}

/// Legendre polynomials `(L_{n-1}(x), L_n(x))` by the three-term recurrence.
pub(crate) fn legendre_pair(n: usize, x: f64) -> (f64, f64) {
    let mut previous = 1.0; // L_0
    let mut current = x; // L_1
    if n == 0 {
        return (0.0, 1.0);
    }
    let mut k = 1usize;
    while k < n {
        let kf = k as f64;
        let next = ((2.0 * kf + 1.0) * x * current - kf * previous) / (kf + 1.0);
        previous = current;
        current = next;
        k = k.saturating_add(1);
    }
    (previous, current)
}

impl LglGrid {
    /// An empty grid.
    pub const fn new() -> Self {
        Self {
            degree: 0,
            tau: [0.0; MAX_NODES],
            weight: [0.0; MAX_NODES],
            legendre_at_node: [0.0; MAX_NODES],
            diff: [[0.0; MAX_NODES]; MAX_NODES],
            bary: [0.0; MAX_NODES],
        }
    }

    /// Number of nodes, N + 1.
    pub fn nodes(&self) -> usize {
        self.degree.saturating_add(1)
    }

    /// Build the grid for degree `n` (`2 <= n < MAX_NODES`), with at most `max_newton` Newton
    /// steps per interior node. Returns false if `n` is out of range or Newton did not converge.
    ///
    /// Interior nodes are the zeros of `L_N'`; Newton's iteration on `(1 - x^2) L_N'(x)` in the
    /// form `x <- x - (x L_N - L_{N-1}) / ((N + 1) L_N)` from the Chebyshev–Gauss–Lobatto points
    /// (which interlace the LGL nodes) converges quadratically; nodes are then symmetrised.
    pub fn build(&mut self, n: usize, max_newton: u16) -> bool {
        if !(2..MAX_NODES).contains(&n) {
            return false;
        }
        // Reset in place: a `Self::new()` temporary would cost its size in stack.
        self.tau.fill(0.0);
        self.weight.fill(0.0);
        self.legendre_at_node.fill(0.0);
        for row in self.diff.iter_mut() {
            row.fill(0.0);
        }
        self.bary.fill(0.0);
        self.degree = n;
        let nf = n as f64;
        let nodes = n.saturating_add(1);
        let mut converged = true;
        for (h, slot) in self.tau.iter_mut().indexed().take(nodes) {
            let mut x = -libm::cos(core::f64::consts::PI * (h as f64) / nf);
            if h > 0 && h < n {
                let mut done = false;
                for _ in 0..max_newton {
                    let (lm1, l) = legendre_pair(n, x);
                    let step = (x * l - lm1) / ((nf + 1.0) * l);
                    x -= step;
                    if libm::fabs(step) <= 4.0 * f64::EPSILON {
                        done = true;
                        break;
                    }
                }
                converged &= done;
            } else if h == 0 {
                x = -1.0;
            } else {
                x = 1.0;
            }
            *slot = x;
        }
        // Symmetrise: tau_{N-h} = -tau_h exactly, walking the nodes from both ends at once (the
        // middle node of even N, left between them, is exactly 0).
        let Some((front, back)) = self.tau.split_at_mut_checked(nodes / 2) else {
            return false;
        };
        let live_back = nodes.saturating_sub(nodes / 2);
        for (low, high) in front.iter_mut().zip(back.iter_mut().take(live_back).rev()) {
            let symmetric = 0.5 * (*low - *high);
            *low = symmetric;
            *high = -symmetric;
        }
        if n % 2 == 0 {
            if let Some(middle) = back.first_mut() {
                *middle = 0.0;
            }
        }
        let scale = 2.0 / (nf * (nf + 1.0));
        let node_values = self.legendre_at_node.iter_mut().zip(self.weight.iter_mut());
        for (&tau, (legendre, weight)) in self.tau.iter().zip(node_values).take(nodes) {
            let (_, l) = legendre_pair(n, tau);
            *legendre = l;
            *weight = scale / (l * l);
        }
        let at_nodes = self.tau.iter().zip(self.legendre_at_node.iter());
        for (h, (row, (&tau_h, &lh))) in self
            .diff
            .iter_mut()
            .zip(at_nodes.clone())
            .take(nodes)
            .indexed()
        {
            for (k, (slot, (&tau_k, &lk))) in
                row.iter_mut().zip(at_nodes.clone()).take(nodes).indexed()
            {
                *slot = if h == k {
                    if h == 0 {
                        -nf * (nf + 1.0) / 4.0
                    } else if h == n {
                        nf * (nf + 1.0) / 4.0
                    } else {
                        0.0
                    }
                } else {
                    lh / (lk * (tau_h - tau_k))
                };
            }
        }
        let mut largest = 0.0f64;
        for (k, (slot, &tau_k)) in self
            .bary
            .iter_mut()
            .zip(self.tau.iter())
            .take(nodes)
            .indexed()
        {
            let mut product = 1.0;
            for (j, &tau_j) in self.tau.iter().take(nodes).indexed() {
                if j != k {
                    product *= tau_k - tau_j;
                }
            }
            let value = 1.0 / product;
            largest = largest.max(libm::fabs(value));
            *slot = value;
        }
        if largest > 0.0 {
            for slot in self.bary.iter_mut().take(nodes) {
                *slot /= largest;
            }
        }
        converged
    }

    /// The nodes `tau_0 < ... < tau_N`, in order.
    pub fn taus(&self) -> impl Iterator<Item = f64> + Clone + '_ {
        self.tau.iter().take(self.nodes()).copied()
    }

    /// The nodes with their quadrature weights, `(tau_h, w_h)` in node order.
    pub fn nodes_and_weights(&self) -> impl Iterator<Item = (f64, f64)> + Clone + '_ {
        self.tau
            .iter()
            .zip(self.weight.iter())
            .take(self.nodes())
            .map(|(&tau, &weight)| (tau, weight))
    }

    /// Lagrange basis values `l_k(tau)` for k = 0..=N, by the barycentric formula.
    /// Exact (a unit vector) when `tau` coincides with a node.
    pub fn lagrange_row(&self, tau: f64, out: &mut [f64; MAX_NODES]) {
        *out = [0.0; MAX_NODES];
        let n = self.degree;
        for (slot, &node) in out
            .iter_mut()
            .zip(self.tau.iter())
            .take(n.saturating_add(1))
        {
            if tau - node == 0.0 {
                *slot = 1.0;
                return;
            }
        }
        let mut denominator = 0.0;
        // Nodes 0..=n with their barycentric weights (n < MAX_NODES, the grid's capacity).
        let nodes = self.bary.iter().zip(self.tau.iter()).zip(out.iter_mut());
        for ((&weight, &node), slot) in nodes.take(n.saturating_add(1)) {
            let term = weight / (tau - node);
            *slot = term;
            denominator += term;
        }
        for slot in out.iter_mut().take(n.saturating_add(1)) {
            *slot /= denominator;
        }
    }

    /// Interpolate nodal values at `tau` (the solver builds the row once per point and uses
    /// `interpolate_with`; this one-shot form serves the tests).
    #[cfg(test)]
    pub fn interpolate(&self, values: &[f64; MAX_NODES], tau: f64) -> f64 {
        let mut row = [0.0; MAX_NODES];
        self.lagrange_row(tau, &mut row);
        dot(&row, values, self.nodes())
    }

    /// Interpolate nodal values with a row `lagrange_row` built for the point: the same sum as
    /// `interpolate`, so several values at one point need only one row (its divisions are most
    /// of an interpolation's cost).
    pub fn interpolate_with(&self, row: &[f64; MAX_NODES], values: &[f64; MAX_NODES]) -> f64 {
        dot(row, values, self.nodes())
    }

    /// Nodal values of the derivative (in tau) of the interpolant of `values`: `D values`.
    pub fn differentiate(&self, values: &[f64; MAX_NODES], out: &mut [f64; MAX_NODES]) {
        *out = [0.0; MAX_NODES];
        let count = self.nodes();
        for (slot, row) in out.iter_mut().zip(self.diff.iter()).take(count) {
            *slot = dot(row, values, count);
        }
    }
}

/// Dot product of the first `count` entries.
pub(crate) fn dot(a: &[f64], b: &[f64], count: usize) -> f64 {
    let mut sum = 0.0;
    for (x, y) in a.iter().zip(b.iter()).take(count) {
        sum += x * y;
    }
    sum
}

#[cfg(test)]
#[allow(clippy::needless_range_loop)]
mod tests {
    use super::*;

    fn grid(n: usize) -> LglGrid {
        let mut g = LglGrid::new();
        assert!(g.build(n, 60));
        g
    }

    #[test]
    fn known_nodes_and_weights_n4() {
        // N = 4: nodes 0, +-sqrt(3/7), +-1; weights 32/45, 49/90, 1/10.
        let g = grid(4);
        let s = libm::sqrt(3.0 / 7.0);
        let expected = [-1.0, -s, 0.0, s, 1.0];
        for h in 0..5 {
            assert!((g.tau[h] - expected[h]).abs() < 1e-15, "node {h}");
        }
        assert!((g.weight[2] - 32.0 / 45.0).abs() < 1e-14);
        assert!((g.weight[1] - 49.0 / 90.0).abs() < 1e-14);
        assert!((g.weight[0] - 0.1).abs() < 1e-14);
    }

    #[test]
    fn quadrature_exact_to_degree_2n_minus_1() {
        for n in [4usize, 9, 10, 16, 24] {
            let g = grid(n);
            for p in 0..(2 * n) {
                let q: f64 = (0..=n).map(|h| g.weight[h] * g.tau[h].powi(p as i32)).sum();
                let exact = if p % 2 == 1 {
                    0.0
                } else {
                    2.0 / (p as f64 + 1.0)
                };
                assert!((q - exact).abs() < 1e-13, "n={n} p={p}: {q} vs {exact}");
            }
        }
    }

    #[test]
    fn differentiation_exact_for_degree_n() {
        for n in [4usize, 10, 24] {
            let g = grid(n);
            let mut v = [0.0; MAX_NODES];
            for h in 0..=n {
                v[h] = g.tau[h].powi(n as i32) - 2.0 * g.tau[h];
            }
            let mut d = [0.0; MAX_NODES];
            g.differentiate(&v, &mut d);
            for h in 0..=n {
                let exact = n as f64 * g.tau[h].powi(n as i32 - 1) - 2.0;
                assert!((d[h] - exact).abs() < 1e-10 * (n * n) as f64, "n={n} h={h}");
            }
        }
    }

    #[test]
    fn barycentric_interpolation_exact_for_polynomials() {
        let g = grid(12);
        let mut v = [0.0; MAX_NODES];
        let f = |x: f64| 3.0 * x.powi(12) - x.powi(5) + 0.5;
        for h in 0..=12 {
            v[h] = f(g.tau[h]);
        }
        for x in [-0.99, -0.3, 0.0, 0.123, 0.77, 1.0] {
            assert!((g.interpolate(&v, x) - f(x)).abs() < 1e-13, "x={x}");
        }
    }

    #[test]
    fn out_of_range_degree_is_refused() {
        let mut g = LglGrid::new();
        assert!(!g.build(1, 60));
        assert!(!g.build(MAX_NODES, 60));
    }
}
