//! Planner-A workspace: every scratch buffer of a solve, sized by the capacities, in three parts
//! by when they are written: what set-up builds, the iteration's iterates, and the continuous
//! verification's state.

use super::anderson::Anderson;
use super::guess::{AxisBoundary, AxisLaw};
use super::kept::Kept;
use super::kernel::{Coefficients, MAX_BLOCKS};
use super::qp_state::QpState;
use super::transcription::Transcription;
use super::verify::{Bernstein, SearchStack};
use crate::capacity::{MAX_FREE_PER_AXIS, MAX_PAIRS, MAX_SPACECRAFT};

const NO_LAW: AxisLaw = AxisLaw {
    alpha: 0.0,
    beta: 0.0,
    boundary: AxisBoundary {
        p0: 0.0,
        v0: 0.0,
        p1: 0.0,
        v1: 0.0,
        horizon: 0.0,
        mass: 0.0,
        max_control: 0.0,
    },
    saturated: false,
};

const ZERO: Coefficients = [[0.0; MAX_FREE_PER_AXIS]; MAX_BLOCKS];

/// Scratch memory for planner A. Build once (it can live in a `static`: `new` is `const` and
/// all zero bits, so a static workspace lands in `.bss` and costs no flash),
/// reuse for every solve; a solve overwrites all of it. Its size is fixed by
/// [`crate::capacity`]; see the README for `size_of::<Workspace>()`.
#[derive(Clone, Debug)]
pub struct Workspace {
    /// Built by set-up (`setup.rs`) from the problem.
    pub(crate) setup: SetUp,
    /// The convex-concave iteration's state (`iteration.rs`, `solver.rs`).
    pub(crate) iterates: Iterates,
    /// The continuous verification's state (`solver.rs`, `linearise::pair_minimum`).
    pub(crate) verification: Verification,
    /// The solve's work meter.
    pub(crate) work: crate::work::Meter,
}

/// What set-up builds from the problem: the LGL grid, the basis and the Bernstein conversion
/// (they depend on N and T alone), the analytic guess's laws, and the transcription built on
/// them (base cubics, pairs, pruning windows, keep-out checks). After set-up only the
/// transcription's keep-out checks change: their linearised normals, the moving checks, the
/// checks and margins verification adds (`Transcription::add_check`, `place_moving_check`).
#[derive(Clone, Debug)]
pub(crate) struct SetUp {
    pub(crate) transcription: Transcription,
    pub(crate) bernstein: Bernstein,
    pub(crate) laws: [[AxisLaw; 3]; MAX_SPACECRAFT],
}

/// The convex-concave iteration's iterates: the linearisation point, the QP's answer and the
/// last accepted one, the QP's working set, the Anderson memory, and each pair's fallback
/// direction (the side it swerves to where it violates a check).
#[derive(Clone, Debug)]
pub(crate) struct Iterates {
    /// The current iterate (and linearisation point).
    pub(crate) iterate: Coefficients,
    /// The QP's output.
    pub(crate) trial: Coefficients,
    /// The last QP solution (the feasible iterate).
    pub(crate) accepted: Coefficients,
    /// The best verified answer of a solve's first run (`kept.rs`), then the saddle's or the
    /// flat point's iterate while an escape or a probe from it is tried.
    pub(crate) saved: Coefficients,
    /// What `saved` holds during the first run (`kept.rs`).
    pub(crate) kept: Kept,
    pub(crate) anderson: Anderson,
    pub(crate) qp: QpState,
    /// Direction used for a pair's linearisation where the spacecraft coincide.
    pub(crate) fallback_normal: [[f64; 3]; MAX_PAIRS],
}

/// The continuous verification's state: the separation search's intervals, the pairs the
/// SQP's convergence test found clean, and the verification points each pair received.
#[derive(Clone, Debug)]
pub(crate) struct Verification {
    pub(crate) search: SearchStack,
    /// Pairs (bit `pair`) whose continuous minimum at `iterate` the SQP's convergence test
    /// searched and found at least `d - verify_tol` (`iteration::sqp`, set with
    /// `SqpEnd::Converged`): the verification round after it need not search them again.
    pub(crate) searched_clean: u32,
    /// Verification points each pair received.
    pub(crate) verify_points: [u8; MAX_PAIRS],
}

impl Workspace {
    /// A fresh workspace.
    pub const fn new() -> Self {
        Self {
            setup: SetUp {
                transcription: Transcription::new(),
                bernstein: Bernstein::new(),
                laws: [[NO_LAW; 3]; MAX_SPACECRAFT],
            },
            iterates: Iterates {
                iterate: ZERO,
                trial: ZERO,
                accepted: ZERO,
                saved: ZERO,
                kept: Kept::OFF,
                anderson: Anderson::new(),
                qp: QpState::new(),
                fallback_normal: [[0.0; 3]; MAX_PAIRS],
            },
            verification: Verification {
                search: SearchStack::new(),
                searched_clean: 0,
                verify_points: [0; MAX_PAIRS],
            },
            work: crate::work::Meter::new(0),
        }
    }
}

impl Default for Workspace {
    fn default() -> Self {
        Self::new()
    }
}
