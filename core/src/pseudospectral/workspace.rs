//! Planner-A workspace: every scratch buffer of a solve, sized by the capacities.

use super::anderson::Anderson;
use super::guess::AxisLaw;
use super::kernel::{Coefficients, MAX_BLOCKS};
use super::qp_state::QpState;
use super::transcription::Transcription;
use super::verify::Bernstein;
use crate::capacity::{MAX_FREE_PER_AXIS, MAX_PAIRS, MAX_SPACECRAFT};

const NO_LAW: AxisLaw = AxisLaw {
    alpha: 0.0,
    beta: 0.0,
    boundary: super::guess::AxisBoundary {
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

/// Scratch memory for planner A. Build once (it can live in a `static`: `new` is `const` and
/// all zero bits, so a static workspace lands in `.bss` and costs no flash),
/// reuse for every solve; a solve overwrites all of it. Its size is fixed by
/// [`crate::capacity`]; see the README for `size_of::<Workspace>()`.
#[derive(Clone, Debug)]
pub struct Workspace {
    pub(crate) transcription: Transcription,
    pub(crate) qp: QpState,
    pub(crate) bernstein: Bernstein,
    pub(crate) laws: [[AxisLaw; 3]; MAX_SPACECRAFT],
    /// The current iterate (and linearisation point).
    pub(crate) iterate: Coefficients,
    /// The QP's output.
    pub(crate) trial: Coefficients,
    pub(crate) anderson: Anderson,
    /// The last QP solution (the feasible iterate).
    pub(crate) accepted: Coefficients,
    /// Direction used for a pair's linearisation where the spacecraft coincide.
    pub(crate) fallback_normal: [[f64; 3]; MAX_PAIRS],
    /// The saddle's iterate while an escape from it is tried.
    pub(crate) saved: Coefficients,
    /// The solve's work meter.
    pub(crate) work: crate::work::Meter,
    /// Pairs (bit `pair`) whose continuous minimum at `iterate` the SQP's convergence test
    /// searched and found at least `d - verify_tol` (`iteration::sqp`, set with
    /// `SqpEnd::Converged`): the verification round after it need not search them again.
    pub(crate) searched_clean: u32,
}

impl Workspace {
    /// A fresh workspace.
    pub const fn new() -> Self {
        Self {
            transcription: Transcription::new(),
            qp: QpState::new(),
            bernstein: Bernstein::new(),
            laws: [[NO_LAW; 3]; MAX_SPACECRAFT],
            iterate: [[0.0; MAX_FREE_PER_AXIS]; MAX_BLOCKS],
            trial: [[0.0; MAX_FREE_PER_AXIS]; MAX_BLOCKS],
            anderson: Anderson::new(),
            accepted: [[0.0; MAX_FREE_PER_AXIS]; MAX_BLOCKS],
            fallback_normal: [[0.0; 3]; MAX_PAIRS],
            saved: [[0.0; MAX_FREE_PER_AXIS]; MAX_BLOCKS],
            work: crate::work::Meter::new(0),
            searched_clean: 0,
        }
    }
}

impl Default for Workspace {
    fn default() -> Self {
        Self::new()
    }
}
