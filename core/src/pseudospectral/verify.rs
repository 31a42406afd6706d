//! Continuous verification of the keep-out, and the dynamics check of eq. 29.
//!
//! Each axis of `r_i - r_j` is a polynomial of degree N, so the squared separation is a
//! polynomial of degree 2N. In the Bernstein basis on an interval, a polynomial lies between
//! the least and the greatest of its coefficients, and subdividing (de Casteljau) tightens those
//! bounds quadratically. A branch-and-bound over subintervals therefore finds the *global*
//! minimum of the separation over the whole horizon to a stated tolerance, with no sample grid
//! that a fast crossing could slip through. An interval whose coefficients form a convex
//! polygon holds a convex piece of the polynomial, which Newton's method finishes in a few
//! steps instead of subdividing on (`convex_minimum.rs`).

use super::convex_minimum::{convex_minimum, is_convex};
use super::lgl::LglGrid;
use crate::capacity::{MAX_DEGREE, MAX_NODES};
use crate::indexed::IndexedExt as _;

/// Coefficients of a degree-2N polynomial.
pub(crate) const MAX_PRODUCT: usize = 2 * MAX_DEGREE + 1;
/// Depth of the branch-and-bound stack (depth first, so it holds at most depth + 1 intervals).
/// 26 levels split [0, 1] to 1.5e-8; isolating a minimum to the search tolerance (0.02 d
/// verify_tol on the squared separation) needs about 20 on the fixtures (each level halves the
/// Bernstein bound's gap quadratically). A full stack marks the minimum uncertified, never
/// wrong. Was 32: the six levels cost 2,448 bytes of planner A's M7 RAM budget.
const STACK: usize = 26;

/// Converts nodal values to Bernstein coefficients on s = (tau + 1) / 2 in [0, 1]. Built at
/// set-up for the degree N; read by every search.
#[derive(Clone, Debug)]
pub(crate) struct Bernstein {
    degree: usize,
    to_bernstein: [[f64; MAX_NODES]; MAX_NODES],
    /// `C(N, i) C(N, j) / C(2N, i + j)` factors via binomials.
    binomial_n: [f64; MAX_NODES],
    binomial_2n: [f64; MAX_PRODUCT],
}

/// The branch-and-bound search's intervals (`Bernstein::minimum`): each interval's ends and its
/// coefficients, depth first. Scratch of one search; its contents mean nothing between searches.
#[derive(Clone, Debug)]
pub(crate) struct SearchStack {
    intervals: [(f64, f64, [f64; MAX_PRODUCT]); STACK],
}

impl SearchStack {
    pub const fn new() -> Self {
        Self {
            intervals: [(0.0, 0.0, [0.0; MAX_PRODUCT]); STACK],
        }
    }
}

fn binomials<const C: usize>(n: usize, out: &mut [f64; C]) {
    *out = [0.0; C];
    let mut value = 1.0;
    for k in 0..=n {
        if let Some(slot) = out.get_mut(k) {
            *slot = value;
        }
        value = value * ((n as f64) - (k as f64)) / ((k as f64) + 1.0);
    }
}

/// The global minimum of a separation polynomial.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub(crate) struct Minimum {
    /// Least squared separation found (an upper bound within tolerance of the true minimum).
    pub value_squared: f64,
    /// Where, in s in [0, 1].
    pub at_s: f64,
    /// The search finished (tolerance met everywhere) within its budget.
    pub certified: bool,
}

impl Bernstein {
    pub const fn new() -> Self {
        Self {
            degree: 0,
            to_bernstein: [[0.0; MAX_NODES]; MAX_NODES],
            binomial_n: [0.0; MAX_NODES],
            binomial_2n: [0.0; MAX_PRODUCT],
        }
    }

    /// Build the nodal-to-Bernstein matrix for the grid (Gauss–Jordan with partial pivoting on
    /// the Bernstein collocation matrix). Returns false if it is singular.
    pub fn build(&mut self, grid: &LglGrid) -> bool {
        let n = grid.degree;
        // At most MAX_NODES by the problem's validation; the clamp lets the compiler see every
        // row swap below in bounds (no panic path in the flight library).
        let size = grid.nodes().min(MAX_NODES);
        self.degree = n;
        binomials(n, &mut self.binomial_n);
        binomials(n.saturating_mul(2), &mut self.binomial_2n);
        let mut a = [[0.0; MAX_NODES]; MAX_NODES];
        // The inverse is built in place in `to_bernstein` (no second matrix on the stack).
        let inv = &mut self.to_bernstein;
        for row in inv.iter_mut() {
            row.fill(0.0);
        }
        for (a_row, tau) in a.iter_mut().zip(grid.taus()).take(size) {
            let s = 0.5 * (tau + 1.0);
            let entries = a_row.iter_mut().zip(self.binomial_n.iter());
            for (k, (slot, &c)) in entries.take(size).indexed() {
                *slot = c * libm::pow(s, k as f64) * libm::pow(1.0 - s, n.saturating_sub(k) as f64);
            }
        }
        // The identity (a row has its diagonal entry: `size` is at most MAX_NODES).
        for (i, row) in inv.iter_mut().enumerate().take(size) {
            if let Some(diagonal) = row.get_mut(i) {
                *diagonal = 1.0;
            }
        }
        for col in 0..size {
            // The first largest entry of column `col` from the diagonal down.
            let mut pivot = col;
            let mut p = 0.0;
            // Each row's entry `col` (`col < size <= MAX_NODES`: every row has it).
            let column = a.iter().filter_map(|row| row.get(col)).indexed();
            for (row, &value) in column.skip(col).take(size.saturating_sub(col)) {
                if row == col || libm::fabs(value) > libm::fabs(p) {
                    pivot = row;
                    p = value;
                }
            }
            if libm::fabs(p) < 1e-300 {
                return false;
            }
            a.swap(col, pivot.min(MAX_NODES.saturating_sub(1)));
            inv.swap(col, pivot.min(MAX_NODES.saturating_sub(1)));
            // The pivot row, and the others in row order.
            let (Some((above, rest)), Some((inv_above, inv_rest))) =
                (a.split_at_mut_checked(col), inv.split_at_mut_checked(col))
            else {
                return false;
            };
            let (Some((pivot_row, below)), Some((inv_pivot_row, inv_below))) =
                (rest.split_first_mut(), inv_rest.split_first_mut())
            else {
                return false;
            };
            for (va, vi) in pivot_row
                .iter_mut()
                .zip(inv_pivot_row.iter_mut())
                .take(size)
            {
                *va /= p;
                *vi /= p;
            }
            let live_below = size.saturating_sub(col.saturating_add(1));
            let others = above
                .iter_mut()
                .zip(inv_above.iter_mut())
                .chain(below.iter_mut().zip(inv_below.iter_mut()).take(live_below));
            for (row, inv_row) in others {
                let Some(&factor) = row.get(col) else {
                    return false;
                };
                if factor != 0.0 {
                    let entries = row.iter_mut().zip(inv_row.iter_mut());
                    let pivots = pivot_row.iter().zip(inv_pivot_row.iter());
                    for ((va, vi), (pa, pi)) in entries.zip(pivots).take(size) {
                        *va -= factor * pa;
                        *vi -= factor * pi;
                    }
                }
            }
        }
        // a * coeffs = nodal  =>  coeffs = inv * nodal.
        true
    }

    /// Bernstein coefficients of the interpolant of `nodal`.
    pub fn coefficients(&self, nodal: &[f64; MAX_NODES], out: &mut [f64; MAX_NODES]) {
        let size = self.degree.saturating_add(1);
        *out = [0.0; MAX_NODES];
        for (slot, row) in out.iter_mut().zip(self.to_bernstein.iter()).take(size) {
            let mut sum = 0.0;
            for (entry, value) in row.iter().zip(nodal.iter()).take(size) {
                sum += entry * value;
            }
            *slot = sum;
        }
    }

    /// Bernstein coefficients (degree 2N) of `sum_axis p_axis^2` from the three axes'
    /// degree-N coefficients.
    pub fn squared_norm(&self, axes: &[[f64; MAX_NODES]; 3], out: &mut [f64; MAX_PRODUCT]) {
        let size = self.degree.saturating_add(1);
        *out = [0.0; MAX_PRODUCT];
        let [x, y, z] = axes;
        // Term (i, j) adds to coefficient i + j: walk the products of row i from coefficient i
        // on (the same terms, in the same order, as indexing each one; no index to check).
        for (i, (&ci, ((xi, yi), zi))) in self
            .binomial_n
            .iter()
            .zip(x.iter().zip(y.iter()).zip(z.iter()))
            .indexed()
            .take(size)
        {
            let (Some(targets), Some(c2s)) = (out.get_mut(i..), self.binomial_2n.get(i..)) else {
                continue;
            };
            for ((slot, &c2), (&cj, ((xj, yj), zj))) in targets.iter_mut().zip(c2s.iter()).zip(
                self.binomial_n
                    .iter()
                    .zip(x.iter().zip(y.iter()).zip(z.iter()))
                    .take(size),
            ) {
                let mut product = 0.0;
                product += xi * xj;
                product += yi * yj;
                product += zi * zj;
                *slot += ci * cj / c2 * product;
            }
        }
    }

    /// Global minimum over s in [0, 1] of the degree-2N polynomial with Bernstein coefficients
    /// `coeffs`, to absolute tolerance `tol`, with at most `budget` subdivisions, its intervals
    /// kept on `stack`.
    pub fn minimum(
        &self,
        stack: &mut SearchStack,
        coeffs: &[f64; MAX_PRODUCT],
        tol: f64,
        budget: u32,
    ) -> Minimum {
        let degree = self.degree.saturating_mul(2);
        let &[first, ..] = coeffs;
        // A degree beyond the coefficients (never: the grid's degree is validated) has no end
        // value to start from: searched nothing, certified nothing.
        let Some(&last) = coeffs.get(degree) else {
            return Minimum {
                value_squared: first,
                at_s: 0.0,
                certified: false,
            };
        };
        let mut best = if first <= last {
            Minimum {
                value_squared: first,
                at_s: 0.0,
                certified: true,
            }
        } else {
            Minimum {
                value_squared: last,
                at_s: 1.0,
                certified: true,
            }
        };
        let mut top = 0usize;
        if let Some(slot) = stack.intervals.get_mut(0) {
            *slot = (0.0, 1.0, *coeffs);
            top = 1;
        }
        let mut spent = 0u32;
        while top > 0 {
            let index = top.saturating_sub(1);
            let Some((lo, hi, c)) = stack.intervals.get_mut(index) else {
                break;
            };
            let (lo, hi) = (*lo, *hi);
            let mut lower = f64::INFINITY;
            for v in c.iter().take(degree.saturating_add(1)) {
                lower = lower.min(*v);
            }
            if lower >= best.value_squared - tol {
                top = index;
                continue;
            }
            if spent >= budget {
                best.certified = false;
                top = index;
                continue;
            }
            // Where the interval's control polygon is convex, so is the polynomial: Newton on
            // its derivative finishes the interval in a few O(degree) steps, where subdivision
            // would need a level per halving (`convex_minimum.rs`).
            let Some(coefficients) = c.get(..=degree) else {
                best.certified = false;
                top = index;
                continue;
            };
            if is_convex(coefficients) {
                let convex = convex_minimum(coefficients, tol, best.value_squared);
                spent = spent.saturating_add(convex.steps);
                if convex.value < best.value_squared {
                    best.value_squared = convex.value;
                    best.at_s = lo + convex.at_u * (hi - lo);
                }
                if convex.certified {
                    top = index;
                    continue;
                }
            }
            if spent >= budget || index.saturating_add(2) > STACK || hi - lo < 1e-12 {
                best.certified = false;
                top = index;
                continue;
            }
            spent = spent.saturating_add(1);
            // de Casteljau at the midpoint, in place: level r averages the first degree - r
            // coefficients and leaves coefficient degree - r alone from then on, so the array
            // ends as the right half's coefficients; the left half's are each level's first.
            // (No copies of the interval: the subdivision is most of a verification's work.)
            let mut left = [0.0; MAX_PRODUCT];
            for r in 0..=degree {
                let &mut [c_first, ..] = c;
                if let Some(slot) = left.get_mut(r) {
                    *slot = c_first;
                }
                // c[k] <- (c[k] + c[k + 1]) / 2 for k < degree - r, in increasing k (each reads
                // its right neighbour before that one is replaced): the same sums, walked by
                // an iterator with no index to check (the subdivision's inner loop).
                let count = degree.saturating_sub(r);
                if let Some(level) = c.get_mut(..=count) {
                    let mut entries = level.iter_mut();
                    if let Some(mut left_entry) = entries.next() {
                        for right_entry in entries {
                            *left_entry = 0.5 * (*left_entry + *right_entry);
                            left_entry = right_entry;
                        }
                    }
                }
            }
            let mid = 0.5 * (lo + hi);
            let &mut [value_mid, ..] = c;
            if value_mid < best.value_squared {
                best.value_squared = value_mid;
                best.at_s = mid;
            }
            // Depth first, left half on top (the right half already sits in this slot).
            if let Some(slot) = stack.intervals.get_mut(index) {
                slot.0 = mid;
            }
            if let Some(slot) = stack.intervals.get_mut(index.saturating_add(1)) {
                *slot = (lo, mid, left);
            }
            top = index.saturating_add(2);
        }
        best
    }
}

#[cfg(test)]
#[allow(clippy::needless_range_loop)]
mod tests {
    use super::*;

    #[test]
    fn finds_a_narrow_dip_between_nodes() {
        let n = 10;
        let mut g = LglGrid::new();
        assert!(g.build(n, 60));
        let mut b = Bernstein::new();
        assert!(b.build(&g));
        // x(tau) = tau - 0.033 (a fast crossing), y = 0.001, z = 0: minimum 0.001 at tau = 0.033.
        let mut axes = [[0.0; MAX_NODES]; 3];
        let mut nodal = [[0.0; MAX_NODES]; 3];
        for h in 0..=n {
            nodal[0][h] = 5.0 * (g.tau[h] - 0.033);
            nodal[1][h] = 0.001;
        }
        for a in 0..3 {
            b.coefficients(&nodal[a], &mut axes[a]);
        }
        let mut f = [0.0; MAX_PRODUCT];
        b.squared_norm(&axes, &mut f);
        let m = b.minimum(&mut SearchStack::new(), &f, 1e-16, 10_000);
        assert!(m.certified);
        assert!(
            (m.value_squared.sqrt() - 0.001).abs() < 1e-7,
            "{}",
            m.value_squared.sqrt()
        );
        assert!((m.at_s - (1.033 / 2.0)).abs() < 1e-4, "{}", m.at_s);
    }

    #[test]
    fn coefficients_reproduce_the_polynomial_at_degree_24() {
        let n = 24;
        let mut g = LglGrid::new();
        assert!(g.build(n, 60));
        let mut b = Bernstein::new();
        assert!(b.build(&g));
        let mut nodal = [0.0; MAX_NODES];
        let f = |t: f64| t.powi(24) - 3.0 * t.powi(7) + 0.25;
        for h in 0..=n {
            nodal[h] = f(g.tau[h]);
        }
        let mut c = [0.0; MAX_NODES];
        b.coefficients(&nodal, &mut c);
        // Endpoint coefficients are the endpoint values.
        assert!((c[0] - f(-1.0)).abs() < 1e-9 && (c[n] - f(1.0)).abs() < 1e-9);
    }
}
