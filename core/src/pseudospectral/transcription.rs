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

/// A pair of spacecraft of the transcription with its lookups done once
/// (`Transcription::pair`).
#[derive(Clone, Copy, Debug)]
pub(crate) struct Pair {
    /// Its index among the transcription's pairs.
    pub index: usize,
    /// The spacecraft `(i, j)`, `i < j`.
    pub spacecraft: (u8, u8),
    /// Their masses.
    pub masses: (f64, f64),
    /// The keep-out enforced at its checks: d, the settings' margin and the pair's own.
    pub keep_out: f64,
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

    /// The mass of spacecraft `sc` (`None` past the spacecraft array).
    pub fn mass_of(&self, sc: usize) -> Option<f64> {
        self.mass.get(sc).copied()
    }

    /// Pair `index` with its lookups done once: its spacecraft, their masses, its keep-out.
    /// `None` for an index that names no pair of this transcription.
    pub fn pair(&self, index: usize) -> Option<Pair> {
        if index >= self.pair_count {
            return None;
        }
        let (&(i, j), &margin) = (self.pairs.get(index)?, self.margin.get(index)?);
        Some(Pair {
            index,
            spacecraft: (i, j),
            masses: (self.mass_of(usize::from(i))?, self.mass_of(usize::from(j))?),
            keep_out: self.keep_out_active_lu + margin,
        })
    }

    /// The checks of pair `index` in order, with their indices (none for an index that names no
    /// pair).
    pub fn checks_of(&self, index: usize) -> impl Iterator<Item = (usize, &Check)> + '_ {
        self.checks
            .iter()
            .zip(self.check_count.iter())
            .take(self.pair_count)
            .nth(index)
            .into_iter()
            .flat_map(|(checks, &count)| checks.iter().take(count).indexed())
    }

    /// Check `check` of pair `pair` (`None` when the pair has no such check).
    pub fn check(&self, pair: usize, check: usize) -> Option<Check> {
        if pair >= self.pair_count || check >= *self.check_count.get(pair)? {
            return None;
        }
        self.checks.get(pair)?.get(check).copied()
    }

    /// Add a keep-out check for `pair` at `tau`; node times reuse the node rows. Returns false
    /// when the pair's checks or the point table are full (or `pair` names no pair).
    pub fn add_check(&mut self, pair: usize, tau: f64) -> bool {
        let (Some(&count), Some(&(i, j)), Some(&(start, end))) = (
            self.check_count.get(pair),
            self.pairs.get(pair),
            self.window.get(pair),
        ) else {
            return false;
        };
        if count >= MAX_CHECKS_PER_PAIR {
            return false;
        }
        // The node at `tau`, if one is (the nodes are distinct: at most one).
        let mut node = None;
        for (h, node_tau) in self.grid.taus().indexed() {
            if node_tau - tau == 0.0 {
                node = u8::try_from(h).ok();
            }
        }
        let source = if let Some(h) = node {
            Source::Node(h)
        } else {
            if self.point_count >= MAX_POINTS {
                return false;
            }
            let Some(point) = self.point_at(i, j, tau) else {
                return false;
            };
            let index = self.point_count;
            if let Some(slot) = self.points.get_mut(index) {
                *slot = point;
            }
            self.point_count = index.saturating_add(1);
            Source::Point(u16::try_from(index).unwrap_or(u16::MAX))
        };
        let t = self.time_of(tau);
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

    /// Position row and base relative position of pair (i, j) at `tau` (`None` when a spacecraft
    /// index is past the base cubics).
    fn point_at(&self, i: u8, j: u8, tau: f64) -> Option<Point> {
        let (base_i, base_j) = (
            spacecraft_blocks(&self.base_position, i)?,
            spacecraft_blocks(&self.base_position, j)?,
        );
        let mut lagrange = [0.0; MAX_NODES];
        self.grid.lagrange_row(tau, &mut lagrange);
        let mut point = Point::EMPTY;
        self.basis.position_row(&self.grid, tau, &mut point.row);
        point.row_norm = norm(&point.row, self.basis.free);
        let nodes = self.grid.nodes();
        for ((slot, bi), bj) in point.base_relative.iter_mut().zip(base_i).zip(base_j) {
            let pi = super::lgl::dot(&lagrange, bi, nodes);
            let pj = super::lgl::dot(&lagrange, bj, nodes);
            *slot = pi - pj;
        }
        Some(point)
    }

    /// The pair's moving check, when it has one.
    pub fn moving_check_of(&self, pair: usize) -> Option<Check> {
        let index = self.moving_check.get(pair).copied().flatten()?;
        self.check(pair, usize::from(index))
    }

    /// Put the pair's moving check at `tau` (creating it on first use). Returns false when no
    /// check or point slot is left (or `pair` names no pair). A node time is nudged off the
    /// node: the moving check always owns an off-node point slot.
    pub fn place_moving_check(&mut self, pair: usize, tau: f64) -> bool {
        let (Some(&(i, j)), Some(&count), Some(&(start, end)), Some(&existing)) = (
            self.pairs.get(pair),
            self.check_count.get(pair),
            self.window.get(pair),
            self.moving_check.get(pair),
        ) else {
            return false;
        };
        let index = match existing {
            Some(index) => usize::from(index),
            None => {
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
        let Some(check) = self.check(pair, index) else {
            return false;
        };
        let Source::Point(point_index) = check.source else {
            return false;
        };
        let Some(value) = self.point_at(i, j, tau) else {
            return false;
        };
        if let Some(slot) = self.points.get_mut(usize::from(point_index)) {
            *slot = value;
        }
        let t = self.time_of(tau);
        if let Some(slot) = self.checks.get_mut(pair).and_then(|row| row.get_mut(index)) {
            slot.tau = tau;
            slot.pruned = t < start || t > end;
        }
        true
    }

    /// The position row of a check and its norm (`None` for a node or point the transcription
    /// does not hold).
    pub fn check_row(&self, source: Source) -> Option<(&[f64; MAX_FREE_PER_AXIS], f64)> {
        match source {
            Source::Node(h) => {
                let h = usize::from(h);
                Some((self.basis.position.get(h)?, *self.node_row_norm.get(h)?))
            }
            Source::Point(p) => {
                let point = self.points.get(usize::from(p))?;
                Some((&point.row, point.row_norm))
            }
        }
    }

    /// `r_i - r_j` of the base cubics at a check of `pair`.
    pub fn base_relative(&self, pair: &Pair, source: Source) -> Option<[f64; 3]> {
        match source {
            Source::Node(h) => {
                let (i, j) = pair.spacecraft;
                let h = usize::from(h);
                let blocks = spacecraft_blocks(&self.base_position, i)?
                    .iter()
                    .zip(spacecraft_blocks(&self.base_position, j)?);
                let mut out = [0.0; 3];
                for (slot, (bi, bj)) in out.iter_mut().zip(blocks) {
                    *slot = bi.get(h)? - bj.get(h)?;
                }
                Some(out)
            }
            Source::Point(p) => self
                .points
                .get(usize::from(p))
                .map(|point| point.base_relative),
        }
    }

    /// `r_i - r_j` at a check of `pair` for the coefficients `y`.
    pub fn relative(&self, pair: &Pair, source: Source, y: &Coefficients) -> Option<[f64; 3]> {
        let mut out = self.base_relative(pair, source)?;
        let (row, _) = self.check_row(source)?;
        let (i, j) = pair.spacecraft;
        let (mi, mj) = pair.masses;
        let free = self.basis.free;
        let blocks = spacecraft_blocks(y, i)?
            .iter()
            .zip(spacecraft_blocks(y, j)?);
        for (slot, (yi, yj)) in out.iter_mut().zip(blocks) {
            *slot += block_dot(row, yi, free) / mi - block_dot(row, yj, free) / mj;
        }
        Some(out)
    }

    /// `block_dot(position row of node h, y, b)` for every block and node: each block's node
    /// offsets (times its mass). A block appears in M - 1 pairs, so a scan over every pair's
    /// node checks reads these instead of recomputing six dot products per check (measured on
    /// the 8-spacecraft crossing: 408 dot products per QP scan instead of about 2,900).
    pub fn node_dots(&self, y: &Coefficients, out: &mut NodeDots) {
        let free = self.basis.free;
        for (row, values) in out.iter_mut().zip(y.iter()).take(self.blocks()) {
            for (slot, position) in row
                .iter_mut()
                .zip(self.basis.position.iter())
                .take(self.grid.nodes())
            {
                *slot = block_dot(position, values, free);
            }
        }
    }

    /// `relative(pair, source, y)` with the node checks' dot products read from `dots`
    /// (`node_dots` of the same `y`): the same operations in the same order, so the same bits.
    pub fn relative_with(
        &self,
        pair: &Pair,
        source: Source,
        y: &Coefficients,
        dots: &NodeDots,
    ) -> Option<[f64; 3]> {
        let Source::Node(h) = source else {
            return self.relative(pair, source, y);
        };
        let mut out = self.base_relative(pair, source)?;
        let (i, j) = pair.spacecraft;
        let (mi, mj) = pair.masses;
        let h = usize::from(h);
        let blocks = spacecraft_blocks(dots, i)?
            .iter()
            .zip(spacecraft_blocks(dots, j)?);
        for (slot, (di, dj)) in out.iter_mut().zip(blocks) {
            *slot += di.get(h)? / mi - dj.get(h)? / mj;
        }
        Some(out)
    }

    /// The coefficients of a constraint row (`None` for a row this transcription does not hold).
    pub fn view(&self, id: RowId) -> Option<RowView<'_>> {
        match id {
            RowId::Control { block, node, upper } => {
                let h = usize::from(node);
                let b = usize::from(block);
                let base = *self.base_control.get(b)?.get(h)?;
                let (coef, rhs) = if upper {
                    (-1.0, base - self.max_control_fu)
                } else {
                    (1.0, -self.max_control_fu - base)
                };
                Some(RowView {
                    vector: self.basis.accel.get(h)?,
                    blocks: [(b, coef), (0, 0.0), (0, 0.0), (0, 0.0), (0, 0.0), (0, 0.0)],
                    count: 1,
                    rhs,
                    norm: *self.basis.accel_norm.get(h)?,
                })
            }
            RowId::KeepOut { pair, check } => {
                let p = usize::from(pair);
                let c = self.check(p, usize::from(check))?;
                let pair = self.pair(p)?;
                let (vector, row_norm) = self.check_row(c.source)?;
                let base = self.base_relative(&pair, c.source)?;
                let (i, j) = pair.spacecraft;
                let (mi, mj) = pair.masses;
                let [n0, n1, n2] = c.normal;
                let bi = usize::from(i).saturating_mul(3);
                let bj = usize::from(j).saturating_mul(3);
                let blocks = [
                    (bi, n0 / mi),
                    (bi.saturating_add(1), n1 / mi),
                    (bi.saturating_add(2), n2 / mi),
                    (bj, -n0 / mj),
                    (bj.saturating_add(1), -n1 / mj),
                    (bj.saturating_add(2), -n2 / mj),
                ];
                let base_along = c.normal.iter().zip(base.iter()).map(|(a, b)| a * b);
                let mut along = 0.0;
                for v in base_along {
                    along += v;
                }
                Some(RowView {
                    vector,
                    blocks,
                    count: 6,
                    rhs: pair.keep_out - along,
                    norm: row_norm * libm::sqrt(1.0 / (mi * mi) + 1.0 / (mj * mj)),
                })
            }
        }
    }
}

/// The three blocks (x, y, z) of spacecraft `sc` in a per-block table (`None` past the table).
pub(crate) fn spacecraft_blocks<T>(table: &[T; MAX_BLOCKS], sc: u8) -> Option<&[T; 3]> {
    table.chunks_exact(3).nth(usize::from(sc))?.try_into().ok()
}

/// `row . values` over the first `free` entries (`values`: one block of a coefficient vector).
pub(crate) fn block_dot(
    row: &[f64; MAX_FREE_PER_AXIS],
    values: &[f64; MAX_FREE_PER_AXIS],
    free: usize,
) -> f64 {
    let mut sum = 0.0;
    for (a, b) in row.iter().zip(values.iter()).take(free) {
        sum += a * b;
    }
    sum
}

/// `a^T y` for a row view (its blocks are blocks of `y`: the view's pair or control node).
pub(crate) fn row_dot(view: &RowView<'_>, y: &Coefficients, free: usize) -> f64 {
    let mut sum = 0.0;
    for &(block, coef) in view.blocks.iter().take(view.count) {
        if coef != 0.0 {
            if let Some(values) = y.get(block) {
                sum += coef * block_dot(view.vector, values, free);
            }
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
