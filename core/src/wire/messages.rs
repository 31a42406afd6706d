//! What a frame carries: the requests a feeder sends and the outcomes the service answers.

use super::FrameError;
use crate::contract::PlannerKind;
use crate::{geo_tour, hybrid, impulsive, leo_tour, pseudospectral};
use serde::{Deserialize, Serialize};

/// A planning request for either planner.
// No heap in the core: the variants stay inline, sized by the capacities.
#[allow(clippy::large_enum_variant)]
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub enum Request {
    /// PlannerKind A.
    Pseudospectral {
        /// The problem.
        problem: pseudospectral::Problem,
        /// Loop bounds and tolerances.
        settings: pseudospectral::Settings,
    },
    /// PlannerKind B.
    Impulsive {
        /// The problem.
        problem: impulsive::Problem,
        /// Loop bounds and tolerances.
        settings: impulsive::Settings,
    },
    /// The GEO servicing tour.
    GeoTour {
        /// The problem.
        problem: geo_tour::Problem,
        /// Loop bounds, tolerances and the paper's rule.
        settings: geo_tour::Settings,
    },
    /// PlannerKind B with its orbits in the forms the user gave (equinoctial elements, osculating
    /// ECI states, ROE, the deputy's own orbits), converted in the service by the core's
    /// `impulsive::forms`.
    ImpulsiveForm {
        /// The problem, in the user's forms.
        problem: impulsive::FormProblem,
        /// Loop bounds and tolerances.
        settings: impulsive::Settings,
    },
    /// One arc of the LEO tour (the per-arc rendezvous under J2).
    LeoArc {
        /// The arc: the clients' states at its start, its duration and impulse count.
        problem: leo_tour::ArcProblem,
        /// Loop bounds, tolerances and the work budget.
        settings: leo_tour::Settings,
    },
    /// The LEO tour's order (`leo_tour::tour_order::solve_sequence`).
    LeoSequence {
        /// The clients at the tour epoch, impulses per arc, first client, arc durations.
        problem: leo_tour::sequence::SequenceProblem,
        /// The bound's margins, the arc limit.
        settings: leo_tour::sequence::SequenceSettings,
        /// The per-arc search's settings for the arc estimates.
        arc_settings: leo_tour::Settings,
    },
    /// The hybrid chemical + electric transfer to a libration-point orbit: its shooting
    /// re-converged from the request's costates.
    Hybrid {
        /// The transfer and the costates to start from.
        problem: hybrid::Problem,
        /// Loop bounds, tolerances and the work budget.
        settings: hybrid::Settings,
    },
}

impl Request {
    /// Which planner the request is for.
    pub fn planner(&self) -> PlannerKind {
        match self {
            Self::Pseudospectral { .. } => PlannerKind::Pseudospectral,
            Self::Impulsive { .. } | Self::ImpulsiveForm { .. } => PlannerKind::Impulsive,
            Self::GeoTour { .. } => PlannerKind::GeoTour,
            Self::LeoArc { .. } => PlannerKind::LeoArc,
            Self::LeoSequence { .. } => PlannerKind::LeoSequence,
            Self::Hybrid { .. } => PlannerKind::Hybrid,
        }
    }
}

/// What the service answers to one request.
// No heap in the core: the solution stays inline (about 16 KB at capacity).
#[allow(clippy::large_enum_variant)]
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub enum Outcome {
    /// PlannerKind A iterated; the solution's `info.status` says how it ended.
    Pseudospectral(pseudospectral::Solution),
    /// PlannerKind A rejected the request before iterating.
    PseudospectralRejected(pseudospectral::PlanError),
    /// PlannerKind B iterated; the solution's `info.status` says how it ended.
    Impulsive(impulsive::Solution),
    /// PlannerKind B rejected the request before iterating.
    ImpulsiveRejected(impulsive::PlanError),
    /// The request frame could not be decoded; says what was wrong.
    BadRequest(FrameError),
    /// The request asks for more work or less safety than the service's limits allow; nothing
    /// was solved (see [`crate::limits`]).
    LimitExceeded(crate::limits::LimitViolation),
    /// The request waited in the service's queue past its deadline; nothing was solved.
    Expired(Expiry),
    /// The GEO tour planned; the solution's `info.status` says how it ended.
    GeoTour(geo_tour::Solution),
    /// The GEO tour rejected the request.
    GeoTourRejected(geo_tour::PlanError),
    /// PlannerKind B iterated on a [`Request::ImpulsiveForm`]; the solution's `info.status` says how
    /// it ended, the end state is in the form the request gave its target in. (A rejection is
    /// [`Outcome::ImpulsiveRejected`].)
    ImpulsiveForm {
        /// The plan.
        solution: impulsive::Solution,
        /// The plan's end state in the user's form.
        end_state: impulsive::EndState,
    },
    /// The LEO arc planned; the solution's `status` says how it ended.
    LeoArc(leo_tour::ArcSolution),
    /// The LEO arc planner rejected the request.
    LeoArcRejected(leo_tour::PlanError),
    /// The LEO tour's order; its `status` says what the order is.
    LeoSequence(leo_tour::sequence::Sequence),
    /// The LEO tour's sequencing rejected the request.
    LeoSequenceRejected(leo_tour::sequence::SequenceError),
    /// The front end that answered does not carry the request's planner (a one-planner flight
    /// image); nothing was solved.
    Unsupported(PlannerKind),
    /// The hybrid transfer planned; the solution's `info.status` says how it ended.
    Hybrid(hybrid::Solution),
    /// The hybrid planner rejected the request.
    HybridRejected(hybrid::PlanError),
}

/// How long an expired request waited and the deadline it had, in microseconds.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub struct Expiry {
    /// Time from the service's receipt of the request to its answer, us.
    pub queued_us: u64,
    /// The request's deadline, counted from its receipt, us.
    pub deadline_us: u64,
}

/// A borrowed [`Outcome`]: encodes to the same bytes without copying a solution.
#[derive(Clone, Copy, Debug, Serialize)]
pub enum OutcomeRef<'a> {
    /// See [`Outcome::Pseudospectral`].
    Pseudospectral(&'a pseudospectral::Solution),
    /// See [`Outcome::PseudospectralRejected`].
    PseudospectralRejected(pseudospectral::PlanError),
    /// See [`Outcome::Impulsive`].
    Impulsive(&'a impulsive::Solution),
    /// See [`Outcome::ImpulsiveRejected`].
    ImpulsiveRejected(impulsive::PlanError),
    /// See [`Outcome::BadRequest`].
    BadRequest(FrameError),
    /// See [`Outcome::LimitExceeded`].
    LimitExceeded(crate::limits::LimitViolation),
    /// See [`Outcome::Expired`].
    Expired(Expiry),
    /// See [`Outcome::GeoTour`].
    GeoTour(&'a geo_tour::Solution),
    /// See [`Outcome::GeoTourRejected`].
    GeoTourRejected(geo_tour::PlanError),
    /// See [`Outcome::ImpulsiveForm`].
    ImpulsiveForm {
        /// The plan.
        solution: &'a impulsive::Solution,
        /// The plan's end state in the user's form.
        end_state: impulsive::EndState,
    },
    /// See [`Outcome::LeoArc`].
    LeoArc(&'a leo_tour::ArcSolution),
    /// See [`Outcome::LeoArcRejected`].
    LeoArcRejected(leo_tour::PlanError),
    /// See [`Outcome::LeoSequence`].
    LeoSequence(&'a leo_tour::sequence::Sequence),
    /// See [`Outcome::LeoSequenceRejected`].
    LeoSequenceRejected(leo_tour::sequence::SequenceError),
    /// See [`Outcome::Unsupported`].
    Unsupported(PlannerKind),
    /// See [`Outcome::Hybrid`].
    Hybrid(&'a hybrid::Solution),
    /// See [`Outcome::HybridRejected`].
    HybridRejected(hybrid::PlanError),
}

/// A planner's refusal of a request before planning (its `PlanError`), as a report shows it.
pub trait Rejection: core::fmt::Debug + core::fmt::Display {}

impl<T: core::fmt::Debug + core::fmt::Display> Rejection for T {}

impl OutcomeRef<'_> {
    /// Whether the answer's plan may be flown: `Some` when the planner planned (its status's
    /// verdict: `contract::Status::is_usable`), `None` when nothing was planned
    /// (refused, rejected, unsupported, expired or a bad frame).
    pub fn usable(&self) -> Option<bool> {
        match self {
            Self::Pseudospectral(s) => Some(s.info.status.is_usable()),
            Self::Impulsive(s) | Self::ImpulsiveForm { solution: s, .. } => {
                Some(s.info.status.is_usable())
            }
            Self::GeoTour(s) => Some(s.info.status.is_usable()),
            Self::LeoArc(s) => Some(s.info.status.is_usable()),
            Self::LeoSequence(q) => Some(q.info.status.is_usable()),
            Self::Hybrid(s) => Some(s.info.status.is_usable()),
            _ => None,
        }
    }

    /// The planner's refusal of the request before planning (a `*Rejected` outcome).
    pub fn rejection(&self) -> Option<&dyn Rejection> {
        match self {
            Self::PseudospectralRejected(e) => Some(e),
            Self::ImpulsiveRejected(e) => Some(e),
            Self::GeoTourRejected(e) => Some(e),
            Self::LeoArcRejected(e) => Some(e),
            Self::LeoSequenceRejected(e) => Some(e),
            Self::HybridRejected(e) => Some(e),
            _ => None,
        }
    }

    /// The work units the planner used, for a planner that planned.
    pub fn work_units(&self) -> Option<u64> {
        match self {
            Self::LeoSequence(s) => Some(s.info.work_units),
            Self::Pseudospectral(s) => Some(s.info.work_units),
            Self::Impulsive(s) | Self::ImpulsiveForm { solution: s, .. } => Some(s.info.work_units),
            Self::LeoArc(s) => Some(s.info.work_units),
            Self::GeoTour(s) => Some(s.info.work_units),
            Self::Hybrid(s) => Some(s.info.work_units),
            _ => None,
        }
    }
}

impl Outcome {
    /// Borrow as an [`OutcomeRef`] (same encoding).
    pub fn as_ref(&self) -> OutcomeRef<'_> {
        match self {
            Self::Pseudospectral(s) => OutcomeRef::Pseudospectral(s),
            Self::PseudospectralRejected(e) => OutcomeRef::PseudospectralRejected(*e),
            Self::Impulsive(s) => OutcomeRef::Impulsive(s),
            Self::ImpulsiveRejected(e) => OutcomeRef::ImpulsiveRejected(*e),
            Self::BadRequest(e) => OutcomeRef::BadRequest(*e),
            Self::LimitExceeded(v) => OutcomeRef::LimitExceeded(*v),
            Self::Expired(x) => OutcomeRef::Expired(*x),
            Self::GeoTour(s) => OutcomeRef::GeoTour(s),
            Self::GeoTourRejected(e) => OutcomeRef::GeoTourRejected(*e),
            Self::ImpulsiveForm {
                solution,
                end_state,
            } => OutcomeRef::ImpulsiveForm {
                solution,
                end_state: *end_state,
            },
            Self::LeoArc(s) => OutcomeRef::LeoArc(s),
            Self::LeoArcRejected(e) => OutcomeRef::LeoArcRejected(*e),
            Self::LeoSequence(q) => OutcomeRef::LeoSequence(q),
            Self::LeoSequenceRejected(e) => OutcomeRef::LeoSequenceRejected(*e),
            Self::Unsupported(p) => OutcomeRef::Unsupported(*p),
            Self::Hybrid(s) => OutcomeRef::Hybrid(s),
            Self::HybridRejected(e) => OutcomeRef::HybridRejected(*e),
        }
    }
}
