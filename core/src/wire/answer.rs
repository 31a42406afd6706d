//! The one request path: every front end (the flight service's workers, the Cortex-M7
//! firmware, `reconfig solve`, `reconfig feed`'s local check, the C interface) answers a
//! [`Request`] here: the limits check first, then the planner's solve into the caller's
//! buffers. Nothing else dispatches on the request kind.
//!
//! The caller owns every buffer ([`Buffers`]): a front end that carries only some planners (a
//! one-planner flight image) answers the others [`OutcomeRef::Unsupported`], and the planners
//! it does not carry are not linked in (the trait's methods for them are the default `None`,
//! which the optimiser folds away).

use super::{OutcomeRef, Request};
use crate::contract::Planner as _;
use crate::contract::PlannerKind;
use crate::leo_tour::sequence::Sequence;
use crate::leo_tour::tour_order::{LeoSequence, SequencePlanSettings, SequenceWorkspace};
use crate::limits::Limits;
use crate::{geo_tour, hybrid, impulsive, leo_tour, pseudospectral};

/// A planner's workspace and the solution it writes.
#[derive(Debug)]
pub struct Slot<W, S> {
    /// The planner's scratch buffers.
    pub workspace: W,
    /// The answer's buffer.
    pub solution: S,
}

/// A planner's workspace and solution lent to the request path, or `None` when the front end
/// does not carry the planner.
pub type Lent<'a, W, S> = Option<(&'a mut W, &'a mut S)>;

impl<W, S> Slot<W, S> {
    /// The slot's workspace and solution, lent.
    pub fn lend(&mut self) -> Lent<'_, W, S> {
        Some((&mut self.workspace, &mut self.solution))
    }
}

/// The buffers a front end lends the request path, one slot per planner it carries. Each
/// method returns the planner's workspace and solution, or `None` when the front end does not
/// carry that planner (the default).
pub trait Buffers {
    /// Planner A's.
    fn pseudospectral(&mut self) -> Lent<'_, pseudospectral::Workspace, pseudospectral::Solution> {
        None
    }
    /// Planner B's (also for requests in its input forms).
    fn impulsive(&mut self) -> Lent<'_, impulsive::Workspace, impulsive::Solution> {
        None
    }
    /// The GEO tour's.
    fn geo_tour(&mut self) -> Lent<'_, geo_tour::Workspace, geo_tour::Solution> {
        None
    }
    /// The LEO arc's.
    fn leo_arc(&mut self) -> Lent<'_, leo_tour::Workspace, leo_tour::ArcSolution> {
        None
    }
    /// The LEO sequencing's.
    fn leo_sequence(&mut self) -> Lent<'_, SequenceWorkspace, Sequence> {
        None
    }
    /// The hybrid transfer's.
    fn hybrid(&mut self) -> Lent<'_, hybrid::Workspace, hybrid::Solution> {
        None
    }
}

/// Every planner's buffers (the flight service's workers and `reconfig solve` carry them all).
/// About 240 KB: build it boxed, once.
#[derive(Debug)]
pub struct AllPlanners {
    /// Planner A.
    pub pseudospectral: Slot<pseudospectral::Workspace, pseudospectral::Solution>,
    /// Planner B.
    pub impulsive: Slot<impulsive::Workspace, impulsive::Solution>,
    /// The GEO tour.
    pub geo_tour: Slot<geo_tour::Workspace, geo_tour::Solution>,
    /// The LEO arc.
    pub leo_arc: Slot<leo_tour::Workspace, leo_tour::ArcSolution>,
    /// The LEO sequencing.
    pub leo_sequence: Slot<SequenceWorkspace, Sequence>,
    /// The hybrid transfer.
    pub hybrid: Slot<hybrid::Workspace, hybrid::Solution>,
}

impl AllPlanners {
    /// Empty buffers.
    pub const fn new() -> Self {
        Self {
            pseudospectral: Slot {
                workspace: pseudospectral::Workspace::new(),
                solution: pseudospectral::Solution::new(),
            },
            impulsive: Slot {
                workspace: impulsive::Workspace::new(),
                solution: impulsive::Solution::new(),
            },
            geo_tour: Slot {
                workspace: geo_tour::Workspace::new(),
                solution: geo_tour::Solution::new(),
            },
            leo_arc: Slot {
                workspace: leo_tour::Workspace::new(),
                solution: leo_tour::ArcSolution::new(),
            },
            leo_sequence: Slot {
                workspace: SequenceWorkspace::new(),
                solution: Sequence::new(),
            },
            hybrid: Slot {
                workspace: hybrid::Workspace::new(),
                solution: hybrid::Solution::new(),
            },
        }
    }
}

impl Default for AllPlanners {
    fn default() -> Self {
        Self::new()
    }
}

impl Buffers for AllPlanners {
    fn pseudospectral(&mut self) -> Lent<'_, pseudospectral::Workspace, pseudospectral::Solution> {
        self.pseudospectral.lend()
    }
    fn impulsive(&mut self) -> Lent<'_, impulsive::Workspace, impulsive::Solution> {
        self.impulsive.lend()
    }
    fn geo_tour(&mut self) -> Lent<'_, geo_tour::Workspace, geo_tour::Solution> {
        self.geo_tour.lend()
    }
    fn leo_arc(&mut self) -> Lent<'_, leo_tour::Workspace, leo_tour::ArcSolution> {
        self.leo_arc.lend()
    }
    fn leo_sequence(&mut self) -> Lent<'_, SequenceWorkspace, Sequence> {
        self.leo_sequence.lend()
    }
    fn hybrid(&mut self) -> Lent<'_, hybrid::Workspace, hybrid::Solution> {
        self.hybrid.lend()
    }
}

/// Answer `request`: refused `LimitExceeded` (nothing solved) when it asks for more work or
/// less safety than `limits` allow, `Unsupported` when `buffers` do not carry its planner,
/// else the planner's answer written into its slot (reset first, so the answer never depends
/// on an earlier request) or its refusal.
///
/// Worst case: the limits check (a pass over the request's settings and sizes) and one solve,
/// bounded by the request's settings, which the limits bound.
pub fn answer<'a, B: Buffers + ?Sized>(
    request: &Request,
    limits: &Limits,
    buffers: &'a mut B,
) -> OutcomeRef<'a> {
    if let Err(violation) = limits.check(request) {
        return OutcomeRef::LimitExceeded(violation);
    }
    // Each planner's arm runs in a frame of its own (`run`, `run_form`, never inlined):
    // a front end's stack while it
    // answers one planner's request holds no other planner's locals (a two-planner flight
    // image measures each planner's stack as its one-planner image does).
    match request {
        Request::Pseudospectral { problem, settings } => run::<pseudospectral::Pseudospectral>(
            (problem, settings),
            buffers.pseudospectral(),
            (
                OutcomeRef::Pseudospectral,
                OutcomeRef::PseudospectralRejected,
            ),
        ),
        Request::Impulsive { problem, settings } => run::<impulsive::Impulsive>(
            (problem, settings),
            buffers.impulsive(),
            (OutcomeRef::Impulsive, OutcomeRef::ImpulsiveRejected),
        ),
        Request::ImpulsiveForm { problem, settings } => {
            run_form(problem, settings, buffers.impulsive())
        }
        Request::GeoTour { problem, settings } => run::<geo_tour::GeoTour>(
            (problem, settings),
            buffers.geo_tour(),
            (OutcomeRef::GeoTour, OutcomeRef::GeoTourRejected),
        ),
        Request::LeoArc { problem, settings } => run::<leo_tour::LeoArc>(
            (problem, settings),
            buffers.leo_arc(),
            (OutcomeRef::LeoArc, OutcomeRef::LeoArcRejected),
        ),
        Request::LeoSequence {
            problem,
            settings,
            arc_settings,
        } => run::<LeoSequence>(
            (
                problem,
                &SequencePlanSettings {
                    order: *settings,
                    arc: *arc_settings,
                },
            ),
            buffers.leo_sequence(),
            (OutcomeRef::LeoSequence, OutcomeRef::LeoSequenceRejected),
        ),
        Request::Hybrid { problem, settings } => run::<hybrid::Hybrid>(
            (problem, settings),
            buffers.hybrid(),
            (OutcomeRef::Hybrid, OutcomeRef::HybridRejected),
        ),
    }
}

/// Planner B on a request in the user's input forms. Out of line: the conversion's locals
/// would otherwise sit in `answer`'s frame under every planner-B solve (836 B of M7 stack,
/// measured by the C interface's per-call figures).
#[inline(never)]
fn run_form<'a>(
    problem: &impulsive::FormProblem,
    settings: &impulsive::Settings,
    slot: Lent<'a, impulsive::Workspace, impulsive::Solution>,
) -> OutcomeRef<'a> {
    let Some((workspace, out)) = slot else {
        return OutcomeRef::Unsupported(PlannerKind::Impulsive);
    };
    impulsive::Impulsive::reset(out);
    match impulsive::solve_form(problem, settings, workspace, out) {
        Ok(end_state) => OutcomeRef::ImpulsiveForm {
            solution: out,
            end_state,
        },
        Err(e) => OutcomeRef::ImpulsiveRejected(e),
    }
}

/// How a planner's answer and refusal become outcomes (its two `OutcomeRef` variants).
type Outcomes<'a, P> = (
    fn(&'a <P as crate::contract::Planner>::Solution) -> OutcomeRef<'a>,
    fn(<P as crate::contract::Planner>::Error) -> OutcomeRef<'a>,
);

/// One planner's answer: `Unsupported` without a slot, else its solve into the slot (reset
/// first) and the outcome `ok` of the solution or `rejected` of the refusal. Out of line, so
/// each planner's arm has a frame of its own (see [`answer`]).
#[inline(never)]
fn run<'a, P: crate::contract::Planner>(
    (problem, settings): (&P::Problem, &P::Settings),
    slot: Lent<'a, P::Workspace, P::Solution>,
    (ok, rejected): Outcomes<'a, P>,
) -> OutcomeRef<'a> {
    let Some((workspace, out)) = slot else {
        return OutcomeRef::Unsupported(P::KIND);
    };
    P::reset(out);
    match P::solve(problem, settings, workspace, out) {
        Ok(()) => ok(out),
        Err(e) => rejected(e),
    }
}
