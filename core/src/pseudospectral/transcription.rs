//! The transcribed problem in free coefficients: base (cubic) trajectories, keep-out check
//! points per pair, and the linear constraint rows the QP works with.
//!
//! Variables `y[b]`, block `b = 3 sc + axis`, hold `mass * z` for that axis (see [`super::basis`]).
//! Every constraint is a row `a^T y >= rhs` that touches at most six blocks, all with the same
//! coefficient vector up to a scalar, so rows are stored as descriptors, never as dense vectors.

use super::basis::Basis;
use super::kernel::{Coefficients, MAX_BLOCKS};
use super::lgl::LglGrid;
use crate::capacity::{
    MAX_CHECKS_PER_PAIR, MAX_FREE_PER_AXIS, MAX_NODES, MAX_PAIRS, MAX_SPACECRAFT,
    MAX_VERIFY_POINTS_PER_PAIR, TEST_POINTS_PER_PAIR,
};
use crate::indexed::IndexedExt as _;

/// Off-node check points (test and verification points) at capacity.
pub(crate) const MAX_POINTS: usize =
    MAX_PAIRS * (TEST_POINTS_PER_PAIR + MAX_VERIFY_POINTS_PER_PAIR);

/// Two checks of one pair closer than this in normalised time (tau in [-1, 1]) are one
/// constraint for the second-order measures (see `QpState::merge_close_checks`).
pub(crate) const CLOSE_CHECKS_TAU: f64 = 1e-4;

/// Per block and node, the position row's dot product with a coefficient vector
/// (`Transcription::node_dots`).
pub(crate) type NodeDots = [[f64; MAX_NODES]; MAX_BLOCKS];

/// Where a keep-out check's position row comes from.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Source {
    /// An LGL node.
    Node(u8),
    /// An off-node point (index into the point table).
    Point(u16),
}

/// One keep-out check of one pair at one time, with its current linearisation.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Check {
    pub tau: f64,
    pub source: Source,
    /// Outside the pruning window (eq. 23): no constraint.
    pub pruned: bool,
    /// Unit direction of the linearisation, pointing from spacecraft j to i.
    pub normal: [f64; 3],
}

impl Check {
    // All zero bits, so a workspace built from it can live in `.bss`.
    const EMPTY: Self = Self {
        tau: 0.0,
        source: Source::Node(0),
        pruned: false,
        normal: [0.0, 0.0, 0.0],
    };
}

/// Position row and base relative position of an off-node point.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Point {
    pub row: [f64; MAX_FREE_PER_AXIS],
    pub row_norm: f64,
    /// `r_i - r_j` of the base cubics at this time.
    pub base_relative: [f64; 3],
}

impl Point {
    const EMPTY: Self = Self {
        row: [0.0; MAX_FREE_PER_AXIS],
        row_norm: 0.0,
        base_relative: [0.0; 3],
    };
}

/// A constraint of the QP.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum RowId {
    /// Control bound at a node: `upper` is `u <= Umax`, else `u >= -Umax`.
    Control { block: u8, node: u8, upper: bool },
    /// Keep-out at check `check` of pair `pair`.
    KeepOut { pair: u8, check: u8 },
}

/// A row's coefficients: up to six blocks, each `coef * vector`.
#[derive(Clone, Copy, Debug)]
pub(crate) struct RowView<'a> {
    pub vector: &'a [f64; MAX_FREE_PER_AXIS],
    pub blocks: [(usize, f64); 6],
    pub count: usize,
    pub rhs: f64,
    pub norm: f64,
}

/// The transcription of one problem.
#[derive(Clone, Debug)]
pub(crate) struct Transcription {
    pub grid: LglGrid,
    pub basis: Basis,
    pub horizon_tu: f64,
    pub max_control_fu: f64,
    pub keep_out_lu: f64,
    /// Keep-out used in the constraints: d plus the margin.
    pub keep_out_active_lu: f64,
    pub spacecraft: usize,
    pub mass: [f64; MAX_SPACECRAFT],
    /// Base (cubic) node positions per block.
    pub base_position: [[f64; MAX_NODES]; MAX_BLOCKS],
    /// Base (cubic) node control forces per block.
    pub base_control: [[f64; MAX_NODES]; MAX_BLOCKS],
    /// Euclidean norm of each node position row of the basis.
    pub node_row_norm: [f64; MAX_NODES],
    pub pairs: [(u8, u8); MAX_PAIRS],
    pub pair_count: usize,
    pub checks: [[Check; MAX_CHECKS_PER_PAIR]; MAX_PAIRS],
    pub check_count: [usize; MAX_PAIRS],
    pub points: [Point; MAX_POINTS],
    pub point_count: usize,
    /// Extra keep-out per pair (LU), raised by verification where a dip below d persists after
    /// the pair already received a verification point.
    pub margin: [f64; MAX_PAIRS],
    /// Index (into the pair's checks) of the pair's moving check, which follows the continuous
    /// separation minimum from one convex subproblem to the next.
    pub moving_check: [Option<u8>; MAX_PAIRS],
    /// Where each pair's moving check was before its last jump to another minimum (tau), to
    /// tell a check that cycles between two minima (`linearise::freeze_if_cycling`).
    pub moving_from: [Option<f64>; MAX_PAIRS],
    /// Cost of the base cubics, `T/4 sum w U_cubic^2`.
    pub base_cost: f64,
    /// Pruning window per pair in TU: checks outside `[start, end]` are not constrained.
    pub window: [(f64, f64); MAX_PAIRS],
}

const ZERO_ROW: [f64; MAX_FREE_PER_AXIS] = [0.0; MAX_FREE_PER_AXIS];

impl Transcription {
    /// An empty transcription.
    pub const fn new() -> Self {
        Self {
            grid: LglGrid::new(),
            basis: Basis::new(),
            horizon_tu: 0.0,
            max_control_fu: 0.0,
            keep_out_lu: 0.0,
            keep_out_active_lu: 0.0,
            spacecraft: 0,
            mass: [0.0; MAX_SPACECRAFT],
            base_position: [[0.0; MAX_NODES]; MAX_BLOCKS],
            base_control: [[0.0; MAX_NODES]; MAX_BLOCKS],
            node_row_norm: [0.0; MAX_NODES],
            pairs: [(0, 0); MAX_PAIRS],
            pair_count: 0,
            checks: [[Check::EMPTY; MAX_CHECKS_PER_PAIR]; MAX_PAIRS],
            check_count: [0; MAX_PAIRS],
            points: [Point::EMPTY; MAX_POINTS],
            point_count: 0,
            margin: [0.0; MAX_PAIRS],
            moving_check: [None; MAX_PAIRS],
            moving_from: [None; MAX_PAIRS],
            base_cost: 0.0,
            window: [(0.0, 0.0); MAX_PAIRS],
        }
    }

    /// Number of variable blocks, 3 M.
    pub fn blocks(&self) -> usize {
        self.spacecraft.saturating_mul(3)
    }

    /// Time (TU) of a normalised time.
    pub fn time_of(&self, tau: f64) -> f64 {
        0.5 * self.horizon_tu * (tau + 1.0)
    }

    /// Normalised time of a time in TU.
    pub fn tau_of(&self, t: f64) -> f64 {
        2.0 * t / self.horizon_tu - 1.0
    }

    /// Keep-out enforced at the checks of `pair`: d, the settings' margin and the pair's own.
    pub fn keep_out_for(&self, pair: usize) -> f64 {
        self.keep_out_active_lu + self.margin.get(pair).copied().unwrap_or(0.0)
    }

    pub fn mass_of(&self, sc: usize) -> f64 {
        self.mass.get(sc).copied().unwrap_or(1.0)
    }

    /// Add a keep-out check for `pair` at `tau`; node times reuse the node rows. Returns false
    /// when the pair's checks or the point table are full.
    pub fn add_check(&mut self, pair: usize, tau: f64) -> bool {
        let count = self
            .check_count
            .get(pair)
            .copied()
            .unwrap_or(MAX_CHECKS_PER_PAIR);
        if count >= MAX_CHECKS_PER_PAIR {
            return false;
        }
        let Some(&(i, j)) = self.pairs.get(pair) else {
            return false;
        };
        let mut node = None;
        for h in 0..self.grid.nodes() {
            if self.grid.at(h) - tau == 0.0 {
                node = u8::try_from(h).ok();
            }
        }
        let source = if let Some(h) = node {
            Source::Node(h)
        } else {
            if self.point_count >= MAX_POINTS {
                return false;
            }
            let point = self.point_at(i, j, tau);
            let index = self.point_count;
            if let Some(slot) = self.points.get_mut(index) {
                *slot = point;
            }
            self.point_count = index.saturating_add(1);
            Source::Point(u16::try_from(index).unwrap_or(u16::MAX))
        };
        let t = self.time_of(tau);
        let (start, end) = self.window.get(pair).copied().unwrap_or((0.0, 0.0));
        let check = Check {
            tau,
            source,
            pruned: t < start || t > end,
            normal: [1.0, 0.0, 0.0],
        };
        if let Some(slot) = self.checks.get_mut(pair).and_then(|row| row.get_mut(count)) {
            *slot = check;
        }
        if let Some(slot) = self.check_count.get_mut(pair) {
            *slot = count.saturating_add(1);
        }
        true
    }

    /// Position row and base relative position of pair (i, j) at `tau`.
    fn point_at(&self, i: u8, j: u8, tau: f64) -> Point {
        let mut lagrange = [0.0; MAX_NODES];
        self.grid.lagrange_row(tau, &mut lagrange);
        let mut point = Point::EMPTY;
        self.basis.position_row(&self.grid, tau, &mut point.row);
        point.row_norm = norm(&point.row, self.basis.free);
        for axis in 0..3 {
            let bi = usize::from(i).saturating_mul(3).saturating_add(axis);
            let bj = usize::from(j).saturating_mul(3).saturating_add(axis);
            let pi = dot_nodes(&lagrange, self.base_position.get(bi), self.grid.nodes());
            let pj = dot_nodes(&lagrange, self.base_position.get(bj), self.grid.nodes());
            if let Some(slot) = point.base_relative.get_mut(axis) {
                *slot = pi - pj;
            }
        }
        point
    }

    /// The pair's moving check, when it has one.
    pub fn moving_check_of(&self, pair: usize) -> Option<Check> {
        let index = self.moving_check.get(pair).copied().flatten()?;
        self.checks
            .get(pair)
            .and_then(|row| row.get(usize::from(index)))
            .copied()
    }

    /// Put the pair's moving check at `tau` (creating it on first use). Returns false when no
    /// check or point slot is left. A node time is nudged off the node: the moving check always
    /// owns an off-node point slot.
    pub fn place_moving_check(&mut self, pair: usize, tau: f64) -> bool {
        let Some(&(i, j)) = self.pairs.get(pair) else {
            return false;
        };
        let existing = self.moving_check.get(pair).copied().flatten();
        let index = match existing {
            Some(index) => usize::from(index),
            None => {
                let count = self
                    .check_count
                    .get(pair)
                    .copied()
                    .unwrap_or(MAX_CHECKS_PER_PAIR);
                if count >= MAX_CHECKS_PER_PAIR || self.point_count >= MAX_POINTS {
                    return false;
                }
                let point = self.point_count;
                self.point_count = point.saturating_add(1);
                if let Some(slot) = self.checks.get_mut(pair).and_then(|row| row.get_mut(count)) {
                    *slot = Check {
                        source: Source::Point(u16::try_from(point).unwrap_or(u16::MAX)),
                        ..Check::EMPTY
                    };
                }
                if let Some(slot) = self.check_count.get_mut(pair) {
                    *slot = count.saturating_add(1);
                }
                if let Some(slot) = self.moving_check.get_mut(pair) {
                    *slot = u8::try_from(count).ok();
                }
                count
            }
        };
        let Some(check) = self
            .checks
            .get(pair)
            .and_then(|row| row.get(index))
            .copied()
        else {
            return false;
        };
        let Source::Point(point_index) = check.source else {
            return false;
        };
        let value = self.point_at(i, j, tau);
        if let Some(slot) = self.points.get_mut(usize::from(point_index)) {
            *slot = value;
        }
        let t = self.time_of(tau);
        let (start, end) = self.window.get(pair).copied().unwrap_or((0.0, 0.0));
        if let Some(slot) = self.checks.get_mut(pair).and_then(|row| row.get_mut(index)) {
            slot.tau = tau;
            slot.pruned = t < start || t > end;
        }
        true
    }

    /// The position row of a check and its norm.
    pub fn check_row(&self, source: Source) -> (&[f64; MAX_FREE_PER_AXIS], f64) {
        match source {
            Source::Node(h) => (
                self.basis.position.get(usize::from(h)).unwrap_or(&ZERO_ROW),
                self.node_row_norm
                    .get(usize::from(h))
                    .copied()
                    .unwrap_or(0.0),
            ),
            Source::Point(p) => match self.points.get(usize::from(p)) {
                Some(point) => (&point.row, point.row_norm),
                None => (&ZERO_ROW, 0.0),
            },
        }
    }

    /// `r_i - r_j` of the base cubics at a check.
    pub fn base_relative(&self, pair: usize, source: Source) -> [f64; 3] {
        match source {
            Source::Node(h) => {
                let mut out = [0.0; 3];
                if let Some(&(i, j)) = self.pairs.get(pair) {
                    for (axis, slot) in out.iter_mut().indexed() {
                        let bi = usize::from(i).saturating_mul(3).saturating_add(axis);
                        let bj = usize::from(j).saturating_mul(3).saturating_add(axis);
                        *slot = node_value(&self.base_position, bi, usize::from(h))
                            - node_value(&self.base_position, bj, usize::from(h));
                    }
                }
                out
            }
            Source::Point(p) => self
                .points
                .get(usize::from(p))
                .map(|point| point.base_relative)
                .unwrap_or([0.0; 3]),
        }
    }

    /// `r_i - r_j` at a check for the coefficients `y`.
    pub fn relative(&self, pair: usize, source: Source, y: &Coefficients) -> [f64; 3] {
        let mut out = self.base_relative(pair, source);
        let (row, _) = self.check_row(source);
        if let Some(&(i, j)) = self.pairs.get(pair) {
            let (mi, mj) = (self.mass_of(usize::from(i)), self.mass_of(usize::from(j)));
            for (axis, slot) in out.iter_mut().indexed() {
                let bi = usize::from(i).saturating_mul(3).saturating_add(axis);
                let bj = usize::from(j).saturating_mul(3).saturating_add(axis);
                *slot += block_dot(row, y, bi, self.basis.free) / mi
                    - block_dot(row, y, bj, self.basis.free) / mj;
            }
        }
        out
    }

    /// `block_dot(position row of node h, y, b)` for every block and node: each block's node
    /// offsets (times its mass). A block appears in M - 1 pairs, so a scan over every pair's
    /// node checks reads these instead of recomputing six dot products per check (measured on
    /// the 8-spacecraft crossing: 408 dot products per QP scan instead of about 2,900).
    pub fn node_dots(&self, y: &Coefficients, out: &mut NodeDots) {
        let free = self.basis.free;
        for (block, row) in out.iter_mut().indexed().take(self.blocks()) {
            for (slot, position) in row
                .iter_mut()
                .zip(self.basis.position.iter())
                .take(self.grid.nodes())
            {
                *slot = block_dot(position, y, block, free);
            }
        }
    }

    /// `relative(pair, source, y)` with the node checks' dot products read from `dots`
    /// (`node_dots` of the same `y`): the same operations in the same order, so the same bits.
    pub fn relative_with(
        &self,
        pair: usize,
        source: Source,
        y: &Coefficients,
        dots: &NodeDots,
    ) -> [f64; 3] {
        let Source::Node(h) = source else {
            return self.relative(pair, source, y);
        };
        let mut out = self.base_relative(pair, source);
        if let Some(&(i, j)) = self.pairs.get(pair) {
            let (mi, mj) = (self.mass_of(usize::from(i)), self.mass_of(usize::from(j)));
            let h = usize::from(h);
            for (axis, slot) in out.iter_mut().indexed() {
                let bi = usize::from(i).saturating_mul(3).saturating_add(axis);
                let bj = usize::from(j).saturating_mul(3).saturating_add(axis);
                *slot += node_value(dots, bi, h) / mi - node_value(dots, bj, h) / mj;
            }
        }
        out
    }

    /// The coefficients of a constraint row.
    pub fn view(&self, id: RowId) -> RowView<'_> {
        match id {
            RowId::Control { block, node, upper } => {
                let h = usize::from(node);
                let b = usize::from(block);
                let base = node_value(&self.base_control, b, h);
                let (coef, rhs) = if upper {
                    (-1.0, base - self.max_control_fu)
                } else {
                    (1.0, -self.max_control_fu - base)
                };
                RowView {
                    vector: self.basis.accel.get(h).unwrap_or(&ZERO_ROW),
                    blocks: [(b, coef), (0, 0.0), (0, 0.0), (0, 0.0), (0, 0.0), (0, 0.0)],
                    count: 1,
                    rhs,
                    norm: self.basis.accel_norm.get(h).copied().unwrap_or(0.0),
                }
            }
            RowId::KeepOut { pair, check } => {
                let p = usize::from(pair);
                let c = self
                    .checks
                    .get(p)
                    .and_then(|row| row.get(usize::from(check)))
                    .copied()
                    .unwrap_or(Check::EMPTY);
                let (vector, row_norm) = self.check_row(c.source);
                let base = self.base_relative(p, c.source);
                let (i, j) = self.pairs.get(p).copied().unwrap_or((0, 0));
                let (mi, mj) = (self.mass_of(usize::from(i)), self.mass_of(usize::from(j)));
                let mut blocks = [(0usize, 0.0f64); 6];
                for axis in 0..3 {
                    let n = c.normal.get(axis).copied().unwrap_or(0.0);
                    let bi = usize::from(i).saturating_mul(3).saturating_add(axis);
                    let bj = usize::from(j).saturating_mul(3).saturating_add(axis);
                    if let Some(slot) = blocks.get_mut(axis) {
                        *slot = (bi, n / mi);
                    }
                    if let Some(slot) = blocks.get_mut(axis.saturating_add(3)) {
                        *slot = (bj, -n / mj);
                    }
                }
                let base_along = c.normal.iter().zip(base.iter()).map(|(a, b)| a * b);
                let mut along = 0.0;
                for v in base_along {
                    along += v;
                }
                RowView {
                    vector,
                    blocks,
                    count: 6,
                    rhs: self.keep_out_for(p) - along,
                    norm: row_norm * libm::sqrt(1.0 / (mi * mi) + 1.0 / (mj * mj)),
                }
            }
        }
    }
}

/// `row . y[block]` over the first `free` entries.
pub(crate) fn block_dot(
    row: &[f64; MAX_FREE_PER_AXIS],
    y: &Coefficients,
    block: usize,
    free: usize,
) -> f64 {
    match y.get(block) {
        Some(values) => {
            let mut sum = 0.0;
            for (a, b) in row.iter().zip(values.iter()).take(free) {
                sum += a * b;
            }
            sum
        }
        None => 0.0,
    }
}

/// `a^T y` for a row view.
pub(crate) fn row_dot(view: &RowView<'_>, y: &Coefficients, free: usize) -> f64 {
    let mut sum = 0.0;
    for &(block, coef) in view.blocks.iter().take(view.count) {
        if coef != 0.0 {
            sum += coef * block_dot(view.vector, y, block, free);
        }
    }
    sum
}

/// `y += alpha a`.
pub(crate) fn row_axpy(view: &RowView<'_>, alpha: f64, y: &mut Coefficients, free: usize) {
    for &(block, coef) in view.blocks.iter().take(view.count) {
        if let Some(values) = y.get_mut(block) {
            let scale = alpha * coef;
            for (slot, v) in values.iter_mut().zip(view.vector.iter()).take(free) {
                *slot += scale * v;
            }
        }
    }
}

/// `a1^T a2` for two row views.
pub(crate) fn rows_dot(a: &RowView<'_>, b: &RowView<'_>, free: usize) -> f64 {
    let mut weight = 0.0;
    for &(block_a, coef_a) in a.blocks.iter().take(a.count) {
        for &(block_b, coef_b) in b.blocks.iter().take(b.count) {
            if block_a == block_b {
                weight += coef_a * coef_b;
            }
        }
    }
    if weight == 0.0 {
        return 0.0;
    }
    let mut vector_dot = 0.0;
    for (x, y) in a.vector.iter().zip(b.vector.iter()).take(free) {
        vector_dot += x * y;
    }
    weight * vector_dot
}

pub(crate) fn norm(row: &[f64; MAX_FREE_PER_AXIS], free: usize) -> f64 {
    let mut sum = 0.0;
    for v in row.iter().take(free) {
        sum += v * v;
    }
    libm::sqrt(sum)
}

pub(crate) fn node_value(table: &[[f64; MAX_NODES]; MAX_BLOCKS], block: usize, node: usize) -> f64 {
    table
        .get(block)
        .and_then(|row| row.get(node))
        .copied()
        .unwrap_or(0.0)
}

fn dot_nodes(lagrange: &[f64; MAX_NODES], values: Option<&[f64; MAX_NODES]>, count: usize) -> f64 {
    match values {
        Some(values) => super::lgl::dot(lagrange, values, count),
        None => 0.0,
    }
}
