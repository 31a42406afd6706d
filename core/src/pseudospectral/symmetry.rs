//! Exact continuous symmetries of a returned iterate, which the certificate's second-order test
//! deflates (issue 28).
//!
//! Where a group of spacecraft that touch only each other (joined by active keep-out checks)
//! starts and ends on one line with its velocities along it — a collinear reversal, a head-on
//! pair — turning the whole group's trajectory about that line changes nothing: the cost
//! (`|y|^2`, the control's length), every distance within the group at every time, and the
//! boundary states (the base cubics lie on the line). So every point of that turn is optimal
//! when one is, and the Hessian of the Lagrangian is exactly singular along the turn's
//! generator `g = e x y` (coefficient-wise: each spacecraft's three axis blocks turned as a
//! vector). A second-order test that keeps `g` in its space sees a zero eigenvalue, and at an
//! iterate converged to the iteration's tolerance (stationarity ~1e-4) rounding moves it to
//! about -1e-6 either way: measured on the tuning set, budget lifted, 30 collinear reversals
//! and head-on sets ended `Feasible` at eigenvalues between -2e-5 and 1e-15.
//!
//! The sufficient condition that holds there is the one for a manifold of minima: the reduced
//! Hessian positive definite on the complement of the group orbit's tangent. The certificate
//! measures the largest eigenvalue of `P S P - sum g g^T / |g|^2` (Hotelling's deflation) in
//! place of `P S P`'s: at an exact stationary point `g` is an eigenvector of `P S P` with
//! eigenvalue 1, which the deflation sends to 0, and for any `x` in the null space and
//! orthogonal to every `g`, `x^T (P S P - g g^T) x = x^T S x`, so the reported eigenvalue is
//! never above the one on the complement (conservative, whether or not the point is exact).
//! Why not project `g` out with the rows: with nearly parallel active rows (two checks of a
//! pair 1e-4 apart in time) the Gram solve makes `P g` differ from `g` by more than rounding,
//! the projection with `g` removed is then not symmetric, and Lanczos met a Ritz value 2.2e-5
//! above the spectrum (measured on issue 28's collinear exchange). A generator is used only
//! when it is exactly a null direction of the linearised constraints (`|a . g| <= 1e-9 |a| |g|`
//! for every active row): a control bound active on an axis the turn moves breaks the
//! symmetry, and then the turn is not left out.
//!
//! No generator is stored (a `Coefficients` is 4 KB): each is rebuilt from `y` and the axis
//! where it is applied.

use super::kernel::{dot, Coefficients, MAX_BLOCKS};
use super::qp_state::QpState;
use super::transcription::{row_dot, RowId, Transcription};
use crate::capacity::{MAX_FREE_PER_AXIS, MAX_NODES, MAX_SPACECRAFT};
use crate::indexed::IndexedExt as _;
use crate::vec3::{self, Vec3};

/// Relative tolerance of "on the line" (a base cubic's node positions) and "a null direction of
/// the active rows" (`|a . g| / (|a| |g|)`): far above rounding (the generated problems' lines
/// are rotated at random: ~1e-15), far below any real misalignment.
const EXACT_TOL_REL: f64 = 1e-9;

/// The turns about a line that are exact symmetries of the iterate, one per group of spacecraft.
#[derive(Clone, Copy, Debug)]
pub(super) struct Symmetries {
    /// Unit direction of each group's line.
    axes: [Vec3; MAX_SPACECRAFT],
    /// Each group's spacecraft, one bit each.
    members: [u8; MAX_SPACECRAFT],
    /// `|g|^2` of each group's generator at the iterate.
    norm2: [f64; MAX_SPACECRAFT],
    count: usize,
}

impl Symmetries {
    /// No symmetry to deflate.
    pub(super) const NONE: Self = Self {
        axes: [[0.0; 3]; MAX_SPACECRAFT],
        members: [0; MAX_SPACECRAFT],
        norm2: [0.0; MAX_SPACECRAFT],
        count: 0,
    };

    /// How many turns are deflated.
    pub(super) const fn count(&self) -> usize {
        self.count
    }

    /// The exact turn symmetries of `y` with the QP's active rows (see the module docs).
    /// `scratch` is overwritten.
    pub(super) fn find(
        tr: &Transcription,
        qp: &QpState,
        y: &Coefficients,
        scratch: &mut Coefficients,
    ) -> Self {
        let mut found = Self::NONE;
        let groups = groups(tr, qp);
        for (s, &group) in groups.iter().indexed().take(tr.spacecraft) {
            // Each group once, from its lowest-numbered spacecraft.
            if group == 0 || group.trailing_zeros() as usize != s {
                continue;
            }
            let Some(axis) = common_line(tr, group) else {
                continue;
            };
            let norm2 = generator_dot(tr, y, axis, group, y, true);
            if norm2 <= 1e-24 * (1.0 + dot_all(tr, y)) {
                continue; // The group flies its cubics: nothing to turn.
            }
            if !null_for_active_rows(tr, qp, y, axis, group, norm2, scratch) {
                continue;
            }
            if let (Some(a), Some(m), Some(n)) = (
                found.axes.get_mut(found.count),
                found.members.get_mut(found.count),
                found.norm2.get_mut(found.count),
            ) {
                *a = axis;
                *m = group;
                *n = norm2;
                found.count = found.count.saturating_add(1);
            }
        }
        found
    }

    /// `out -= sum (g . v) g / |g|^2` over the turns' generators at `y`: the deflation that
    /// takes each generator's eigenvalue out of `P S P` (see the module docs).
    pub(super) fn deflate(
        &self,
        tr: &Transcription,
        y: &Coefficients,
        v: &Coefficients,
        out: &mut Coefficients,
    ) {
        for ((&axis, &group), &norm2) in self
            .axes
            .iter()
            .zip(self.members.iter())
            .zip(self.norm2.iter())
            .take(self.count)
        {
            let along = generator_dot(tr, y, axis, group, v, false) / norm2;
            add_generator(tr, y, axis, group, -along, out);
        }
    }
}

/// Each spacecraft's group (a bit mask of the spacecraft joined to it by active keep-out
/// checks, itself included).
fn groups(tr: &Transcription, qp: &QpState) -> [u8; MAX_SPACECRAFT] {
    let mut group = [0u8; MAX_SPACECRAFT];
    for (g, &bit) in group
        .iter_mut()
        .zip(SPACECRAFT_BITS.iter())
        .take(tr.spacecraft)
    {
        *g = bit;
    }
    // Merging along each active pair until nothing changes: at most one pass per spacecraft.
    for _ in 0..MAX_SPACECRAFT {
        let mut changed = false;
        for &id in qp.active.iter().take(qp.count) {
            let RowId::KeepOut { pair, .. } = id else {
                continue;
            };
            let Some(p) = tr.pair(usize::from(pair)) else {
                continue;
            };
            let (i, j) = (usize::from(p.spacecraft.0), usize::from(p.spacecraft.1));
            let (Some(&gi), Some(&gj)) = (group.get(i), group.get(j)) else {
                continue;
            };
            let joined = gi | gj;
            if joined != gi || joined != gj {
                changed = true;
                for g in group.iter_mut().take(tr.spacecraft) {
                    if *g & joined != 0 {
                        *g = joined;
                    }
                }
            }
        }
        if !changed {
            break;
        }
    }
    group
}

/// The unit direction of the line every base cubic of `group` lies on (all nodes), or `None`.
/// A spacecraft at rest at one point lies on any line through it; a group of such alone has
/// no line of its own and is left alone.
fn common_line(tr: &Transcription, group: u8) -> Option<Vec3> {
    let nodes = tr.grid.degree.saturating_add(1).min(MAX_NODES);
    let mut scale = 1.0f64;
    let mut line: Option<(Vec3, Vec3)> = None;
    for s in members(tr, group) {
        for k in 0..nodes {
            let p = position(tr, s, k)?;
            scale = scale.max(vec3::norm(&p));
        }
        if line.is_none() {
            let first = position(tr, s, 0)?;
            // The node farthest from the first one gives the direction.
            let mut far = first;
            let mut far_distance = 0.0;
            for k in 1..nodes {
                let p = position(tr, s, k)?;
                let d = vec3::norm(&vec3::sub(&p, &first));
                if d > far_distance {
                    far_distance = d;
                    far = p;
                }
            }
            if far_distance > 0.0 {
                let direction = vec3::scale(&vec3::sub(&far, &first), 1.0 / far_distance);
                line = Some((first, direction));
            }
        }
    }
    let (origin, direction) = line?;
    let tol = EXACT_TOL_REL * scale;
    for s in members(tr, group) {
        for k in 0..nodes {
            let off = vec3::sub(&position(tr, s, k)?, &origin);
            if vec3::norm(&vec3::cross(&direction, &off)) > tol {
                return None;
            }
        }
    }
    Some(direction)
}

/// Each spacecraft's bit in a group mask: one per spacecraft, by construction.
const SPACECRAFT_BITS: [u8; MAX_SPACECRAFT] = [1, 2, 4, 8, 16, 32, 64, 128];

/// The spacecraft of `group`.
fn members(tr: &Transcription, group: u8) -> impl Iterator<Item = usize> {
    SPACECRAFT_BITS
        .iter()
        .indexed()
        .take(tr.spacecraft)
        .filter(move |&(_, &bit)| group & bit != 0)
        .map(|(s, _)| s)
}

/// Spacecraft `s`'s base cubic position at node `k`.
fn position(tr: &Transcription, s: usize, k: usize) -> Option<Vec3> {
    let b = s.checked_mul(3)?;
    let mut p = [0.0; 3];
    for (axis, slot) in p.iter_mut().indexed() {
        *slot = *tr.base_position.get(b.checked_add(axis)?)?.get(k)?;
    }
    Some(p)
}

/// Spacecraft block `block0`'s coefficient `f` as a vector over the three axes.
fn triple(y: &Coefficients, block0: usize, f: usize) -> Vec3 {
    let mut v = [0.0; 3];
    for (axis, slot) in v.iter_mut().indexed() {
        if let Some(&value) = block0
            .checked_add(axis)
            .and_then(|b| y.get(b))
            .and_then(|row| row.get(f))
        {
            *slot = value;
        }
    }
    v
}

/// Calls `visit(first block, coefficient)` for every free coefficient of `group`'s spacecraft.
fn for_each_coefficient(tr: &Transcription, group: u8, mut visit: impl FnMut(usize, usize)) {
    let free = tr.basis.free.min(MAX_FREE_PER_AXIS);
    for s in members(tr, group) {
        let block0 = s.saturating_mul(3);
        if block0.saturating_add(2) >= MAX_BLOCKS {
            continue;
        }
        for f in 0..free {
            visit(block0, f);
        }
    }
}

/// `g . x` with `g = axis x y` over `group` (`x` is `y` itself when `same`, then `|g|^2`).
fn generator_dot(
    tr: &Transcription,
    y: &Coefficients,
    axis: Vec3,
    group: u8,
    x: &Coefficients,
    same: bool,
) -> f64 {
    let mut sum = 0.0;
    for_each_coefficient(tr, group, |block0, f| {
        let g = vec3::cross(&axis, &triple(y, block0, f));
        let other = if same { g } else { triple(x, block0, f) };
        sum += vec3::dot(&g, &other);
    });
    sum
}

/// `out += scale g` with `g = axis x y` over `group` (each spacecraft's coefficient triples
/// turned as vectors).
fn add_generator(
    tr: &Transcription,
    y: &Coefficients,
    axis: Vec3,
    group: u8,
    scale: f64,
    out: &mut Coefficients,
) {
    for_each_coefficient(tr, group, |block0, f| {
        let g = vec3::cross(&axis, &triple(y, block0, f));
        for (axis_index, component) in g.iter().indexed() {
            if let Some(slot) = out
                .get_mut(block0.saturating_add(axis_index))
                .and_then(|row| row.get_mut(f))
            {
                *slot += scale * component;
            }
        }
    });
}

/// `|y|^2` over the live part.
fn dot_all(tr: &Transcription, y: &Coefficients) -> f64 {
    dot(y, y, (tr.blocks(), tr.basis.free))
}

/// Every active row is blind to the turn: `|a . g| <= EXACT_TOL_REL |a| |g|`.
fn null_for_active_rows(
    tr: &Transcription,
    qp: &QpState,
    y: &Coefficients,
    axis: Vec3,
    group: u8,
    norm2: f64,
    g: &mut Coefficients,
) -> bool {
    *g = [[0.0; MAX_FREE_PER_AXIS]; MAX_BLOCKS];
    add_generator(tr, y, axis, group, 1.0, g);
    let g_norm = libm::sqrt(norm2);
    let free = tr.basis.free;
    let blind = qp.active.iter().take(qp.count).all(|&id| {
        tr.view(id).is_some_and(|view| {
            libm::fabs(row_dot(&view, g, free)) <= EXACT_TOL_REL * view.norm * g_norm
        })
    });
    blind
}
