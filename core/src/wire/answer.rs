//! The one request path: every front end (the flight service's workers, the Cortex-M7
//! firmware, `reconfig solve`, `reconfig feed`'s local check, the C interface) answers a
//! [`Request`] here: the limits check first, then the planner's solve into the caller's
//! buffers. Nothing else dispatches on the request kind.
//!
//! The caller owns every buffer ([`Buffers`]): a front end that carries only some planners (a
//! one-planner flight image) answers the others [`OutcomeRef::Unsupported`], and the planners
//! it does not carry are not linked in (the trait's methods for them are the default `None`,
//! which the optimiser folds away).

use super::{OutcomeRef, Planner, Request};
use crate::contract::Planner as _;
use crate::limits::Limits;
use crate::{geo_tour, impulsive, leo_tour, pseudospectral};

/// A planner's workspace and the solution it writes.
#[derive(Debug)]
pub struct Slot<W, S> {
    /// The planner's scratch buffers.
    pub workspace: W,
    /// The answer's buffer.
    pub solution: S,
}

/// The buffers a front end lends the request path, one slot per planner it carries. Each
/// method returns the planner's workspace and solution, or `None` when the front end does not
/// carry that planner (the default).
pub trait Buffers {
    /// Planner A's.
    fn pseudospectral(
        &mut self,
    ) -> Option<(
        &mut pseudospectral::Workspace,
        &mut pseudospectral::Solution,
    )> {
        None
    }
    /// Planner B's (also for requests in its input forms).
    fn impulsive(&mut self) -> Option<(&mut impulsive::Workspace, &mut impulsive::Solution)> {
        None
    }
    /// The GEO tour's.
    fn geo_tour(&mut self) -> Option<(&mut geo_tour::Workspace, &mut geo_tour::Solution)> {
        None
    }
    /// The LEO arc's.
    fn leo_arc(&mut self) -> Option<&mut leo_tour::ArcSolution> {
        None
    }
    /// The LEO sequencing's.
    fn leo_sequence(&mut self) -> Option<&mut leo_tour::sequence::Sequence> {
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
    pub leo_arc: leo_tour::ArcSolution,
    /// The LEO sequencing.
    pub leo_sequence: leo_tour::sequence::Sequence,
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
            leo_arc: leo_tour::ArcSolution::new(),
            leo_sequence: leo_tour::sequence::Sequence::new(),
        }
    }
}

impl Default for AllPlanners {
    fn default() -> Self {
        Self::new()
    }
}

impl Buffers for AllPlanners {
    fn pseudospectral(
        &mut self,
    ) -> Option<(
        &mut pseudospectral::Workspace,
        &mut pseudospectral::Solution,
    )> {
        let s = &mut self.pseudospectral;
        Some((&mut s.workspace, &mut s.solution))
    }
    fn impulsive(&mut self) -> Option<(&mut impulsive::Workspace, &mut impulsive::Solution)> {
        let s = &mut self.impulsive;
        Some((&mut s.workspace, &mut s.solution))
    }
    fn geo_tour(&mut self) -> Option<(&mut geo_tour::Workspace, &mut geo_tour::Solution)> {
        let s = &mut self.geo_tour;
        Some((&mut s.workspace, &mut s.solution))
    }
    fn leo_arc(&mut self) -> Option<&mut leo_tour::ArcSolution> {
        Some(&mut self.leo_arc)
    }
    fn leo_sequence(&mut self) -> Option<&mut leo_tour::sequence::Sequence> {
        Some(&mut self.leo_sequence)
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
    // Each planner's arm runs in a frame of its own (`apart`): a front end's stack while it
    // answers one planner's request holds no other planner's locals (a two-planner flight
    // image measures each planner's stack as its one-planner image does).
    match request {
        Request::Pseudospectral { problem, settings } => match buffers.pseudospectral() {
            None => OutcomeRef::Unsupported(Planner::Pseudospectral),
            Some((workspace, out)) => apart(|| {
                match run::<pseudospectral::Pseudospectral>(problem, settings, workspace, out) {
                    Ok(solution) => OutcomeRef::Pseudospectral(solution),
                    Err(e) => OutcomeRef::PseudospectralRejected(e),
                }
            }),
        },
        Request::Impulsive { problem, settings } => match buffers.impulsive() {
            None => OutcomeRef::Unsupported(Planner::Impulsive),
            Some((workspace, out)) => {
                apart(
                    || match run::<impulsive::Impulsive>(problem, settings, workspace, out) {
                        Ok(solution) => OutcomeRef::Impulsive(solution),
                        Err(e) => OutcomeRef::ImpulsiveRejected(e),
                    },
                )
            }
        },
        Request::ImpulsiveForm { problem, settings } => match buffers.impulsive() {
            None => OutcomeRef::Unsupported(Planner::Impulsive),
            Some((workspace, out)) => apart(|| {
                impulsive::Impulsive::reset(out);
                match impulsive::solve_form(problem, settings, workspace, out) {
                    Ok(end_state) => OutcomeRef::ImpulsiveForm {
                        solution: out,
                        end_state,
                    },
                    Err(e) => OutcomeRef::ImpulsiveRejected(e),
                }
            }),
        },
        Request::GeoTour { problem, settings } => match buffers.geo_tour() {
            None => OutcomeRef::Unsupported(Planner::GeoTour),
            Some((workspace, out)) => apart(|| {
                *out = geo_tour::Solution::new();
                match geo_tour::solve(problem, settings, workspace, out) {
                    Ok(()) => OutcomeRef::GeoTour(out),
                    Err(e) => OutcomeRef::GeoTourRejected(e),
                }
            }),
        },
        Request::LeoArc { problem, settings } => match buffers.leo_arc() {
            None => OutcomeRef::Unsupported(Planner::LeoArc),
            Some(out) => apart(|| match leo_tour::solve_arc(problem, settings) {
                Ok(solution) => {
                    *out = solution;
                    OutcomeRef::LeoArc(out)
                }
                Err(e) => OutcomeRef::LeoArcRejected(e),
            }),
        },
        Request::LeoSequence {
            problem,
            settings,
            arc_settings,
        } => match buffers.leo_sequence() {
            None => OutcomeRef::Unsupported(Planner::LeoSequence),
            Some(out) => apart(|| {
                match leo_tour::tour_order::choose_order(problem, settings, arc_settings) {
                    Ok(sequence) => {
                        *out = sequence;
                        OutcomeRef::LeoSequence(out)
                    }
                    Err(e) => OutcomeRef::LeoSequenceRejected(e),
                }
            }),
        },
    }
}

/// `f` in a frame of its own, never inlined into the caller (see [`answer`]).
#[inline(never)]
fn apart<R>(f: impl FnOnce() -> R) -> R {
    f()
}

/// One planner's solve into its slot, the slot reset first.
fn run<'a, P: crate::contract::Planner>(
    problem: &P::Problem,
    settings: &P::Settings,
    workspace: &mut P::Workspace,
    out: &'a mut P::Solution,
) -> Result<&'a P::Solution, P::Error> {
    P::reset(out);
    P::solve(problem, settings, workspace, out)?;
    Ok(out)
}
