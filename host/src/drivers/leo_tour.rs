//! The LEO tour's driver: a tour fixture's requests answered in turn through the core's one
//! request path (`wire::answer`, with the caller's limits): the order (the sequencing request
//! of a `[sequence]` fixture), then the arcs' durations (a `[schedule]` fixture: the core's
//! schedule, a planning step on the host, not a request), then one request per arc of the
//! tour (`Fixture::requests` builds every one).

use super::answer::{answer, no_plan, refused};
use crate::fixture::leo_tour::LeoTourFixture;
use anyhow::{anyhow, Result};
use reconfig_core::leo_tour::schedule::{Schedule, ScheduleStatus};
use reconfig_core::leo_tour::sequence::Sequence;
use reconfig_core::leo_tour::tour_order::{self, SequenceWorkspace};
use reconfig_core::leo_tour::{ArcProblem, ArcSolution, Workspace};
use reconfig_core::limits::Limits;
use reconfig_core::wire::{Buffers, OutcomeRef, Request};
use std::time::Instant;

/// The LEO planners' buffers: the driver answers only LEO requests. The sequencing's
/// workspace holds an arc search's workspace, which the arc requests use too (as on board).
#[derive(Debug)]
pub struct LeoBuffers {
    workspace: Box<SequenceWorkspace>,
    arc: ArcSolution,
    sequence: Sequence,
}

impl LeoBuffers {
    /// Empty buffers (the workspace boxed: about 30 KB).
    pub fn new() -> Self {
        Self {
            workspace: Box::new(SequenceWorkspace::new()),
            arc: ArcSolution::new(),
            sequence: Sequence::new(),
        }
    }
}

impl Default for LeoBuffers {
    fn default() -> Self {
        Self::new()
    }
}

impl Buffers for LeoBuffers {
    fn leo_arc(&mut self) -> Option<(&mut Workspace, &mut ArcSolution)> {
        Some((&mut self.workspace.arc, &mut self.arc))
    }
    fn leo_sequence(&mut self) -> Option<(&mut SequenceWorkspace, &mut Sequence)> {
        Some((&mut self.workspace, &mut self.sequence))
    }
}

/// One planned arc of the tour.
#[derive(Debug, Clone)]
pub struct PlannedArc {
    /// Client index (0-based) the arc leaves.
    pub from: usize,
    /// Client index (0-based) the arc reaches.
    pub to: usize,
    /// The tour epoch (the fixture's `epoch`), Julian date, UTC: where the truth model's clock
    /// starts when it flies the arc (`start_s` later).
    pub tour_epoch_jd: f64,
    /// Arc start from the tour epoch, s.
    pub start_s: f64,
    /// Arc end from the tour epoch, s.
    pub end_s: f64,
    /// The core's answer (epochs from the arc start): its burns, or with no plan
    /// (`impulses == 0`) only its status.
    pub solution: ArcSolution,
    /// The arc's problem (states at the arc start).
    pub problem: ArcProblem,
    /// Planning time (the answer through the request path), s.
    pub solve_time_s: f64,
}

/// Plan every arc of the fixture's order: each arc's request ([`LeoTourFixture::requests`])
/// answered through the request path under `limits`.
///
/// # Errors
/// A fixture whose order is still to be chosen (a `[sequence]` table), a client that cannot
/// be propagated to an arc start, or an arc request refused by the limits or rejected by the
/// planner ([`super::answer::NoPlan`], naming the arc).
pub fn plan(f: &LeoTourFixture, limits: &Limits) -> Result<Vec<PlannedArc>> {
    if f.sequence.is_some() {
        return Err(anyhow!("{}: choose the order first (prepare)", f.name));
    }
    let mut buffers = LeoBuffers::default();
    let mut arcs = Vec::new();
    for ((from, to, start_s, duration_s), r) in f.legs().into_iter().zip(f.requests()?) {
        let Request::LeoArc { problem, .. } = r.request else {
            return Err(anyhow!("{}: not an arc request", r.label));
        };
        let answered = answer(&r.request, limits, &mut buffers);
        let OutcomeRef::LeoArc(solution) = answered.outcome else {
            return Err(no_plan(&r.label, &answered));
        };
        arcs.push(PlannedArc {
            from,
            to,
            tour_epoch_jd: f.epoch_jd,
            start_s,
            end_s: start_s + duration_s,
            solution: *solution,
            problem,
            solve_time_s: answered.time_s,
        });
    }
    Ok(arcs)
}

/// The order chosen by the core's sequencing for a fixture with a `[sequence]` table.
#[derive(Debug, Clone, Copy)]
pub struct ChosenOrder {
    /// The core's outcome (order, per-arc starts and durations, pruning counts).
    pub sequence: Sequence,
    /// Wall time of the answer to the sequencing request (every arc it planned), s.
    pub time_s: f64,
    /// The orders were ranked by full plans (`[sequence] full_plans`), not by estimates.
    pub full_plans: bool,
}

/// Choose the order of `f`'s tour: its sequencing request ([`LeoTourFixture::requests`])
/// answered through the request path under `limits` (`leo_tour::tour_order::choose_order`:
/// branch-and-bound, each arc's cost the per-arc search's estimate with the `[sequence]`
/// settings, or its full plan with `full_plans`), and return the fixture with that order and its intervals; `None` for a fixture
/// without a `[sequence]` table.
///
/// # Errors
/// The sequencing request refused by the limits or rejected (too few or many clients, a
/// client without an elliptic plane, intervals out of range).
pub fn choose_order(
    f: &LeoTourFixture,
    limits: &Limits,
) -> Result<Option<(LeoTourFixture, ChosenOrder)>> {
    if f.sequence.is_none() {
        return Ok(None);
    }
    let mut buffers = LeoBuffers::default();
    let requests = f.requests()?;
    let [r] = &requests[..] else {
        return Err(anyhow!("{}: one sequencing request expected", f.name));
    };
    let answered = answer(&r.request, limits, &mut buffers);
    let OutcomeRef::LeoSequence(sequence) = answered.outcome else {
        return Err(no_plan(&r.label, &answered));
    };
    let chosen = ChosenOrder {
        sequence: *sequence,
        time_s: answered.time_s,
        full_plans: f.sequence.is_some_and(|s| s.settings.full_plans),
    };
    Ok(Some((f.with_order(sequence), chosen)))
}

/// The on-board part of a `[sequence]` fixture as its requests, in the order a flight computer
/// answers them: the sequencing request, then each arc's request of the order it answers (the
/// answer computed here, through the request path under `limits`).
///
/// # Errors
/// As [`choose_order`]; a fixture without a `[sequence]` table.
pub fn onboard_requests(
    f: &LeoTourFixture,
    limits: &Limits,
) -> Result<Vec<crate::fixture::FixtureRequest>> {
    let Some((ordered, _)) = choose_order(f, limits)? else {
        return Err(anyhow!("{} has no [sequence] table", f.name));
    };
    let mut requests = f.requests()?;
    requests.extend(ordered.requests()?);
    Ok(requests)
}

/// The arcs' durations chosen by the core's schedule for a fixture with a `[schedule]` table.
#[derive(Debug, Clone, Copy)]
pub struct ChosenSchedule {
    /// The core's outcome (durations, the estimates' total, arcs planned).
    pub schedule: Schedule,
    /// The horizon the schedule had, s.
    pub horizon_s: f64,
    /// Wall time of the schedule (every arc it estimated), s.
    pub time_s: f64,
}

/// Choose the durations of `f`'s arcs, for its order, with the core's schedule
/// (`leo_tour::tour_order::choose_schedule`, a planning step on the host: no request kind)
/// and return the fixture with them; `None` for a fixture without a `[schedule]` table. Its
/// arc estimates are arc searches: their settings are held to the limits of an arc request.
///
/// # Errors
/// Estimate settings outside the limits ([`super::answer::NoPlan`], a refusal), a schedule
/// the core refuses (settings out of range) or one with no complete schedule.
pub fn choose_schedule(
    f: &LeoTourFixture,
    limits: &Limits,
) -> Result<Option<(LeoTourFixture, ChosenSchedule)>> {
    let Some(spec) = f.schedule else {
        return Ok(None);
    };
    if let Err(v) = limits.leo_tour.check_settings(&spec.arc_settings) {
        return Err(refused(&format!("{} schedule", f.name), v));
    }
    let order: Vec<u8> = f
        .order
        .iter()
        .map(|&k| u8::try_from(k))
        .collect::<Result<_, _>>()?;
    let mut workspace = Box::new(Workspace::new());
    let started = Instant::now();
    let schedule = tour_order::choose_schedule(
        &f.clients,
        &order,
        f.impulses,
        &spec.settings,
        &spec.arc_settings,
        &mut workspace,
    )
    .map_err(|e| anyhow!("schedule refused: {e}"))?;
    let time_s = started.elapsed().as_secs_f64();
    if !schedule.total_dv_mps.is_finite() {
        let why = if schedule.status == ScheduleStatus::ArcLimit {
            "max_arcs stopped it"
        } else {
            "every one has an arc the planner refused"
        };
        return Err(anyhow!(
            "schedule: no complete schedule ({why}; {} arcs tried)",
            schedule.arcs_planned
        ));
    }
    let mut scheduled = f.clone();
    scheduled.intervals_s = schedule
        .durations_s
        .iter()
        .take(usize::from(schedule.arcs))
        .copied()
        .collect();
    Ok(Some((
        scheduled,
        ChosenSchedule {
            schedule,
            horizon_s: spec.settings.horizon_s,
            time_s,
        },
    )))
}

/// A LEO tour fixture ready to plan: its order chosen when it has a `[sequence]` table, then
/// its arcs' durations when it has a `[schedule]` table.
#[derive(Debug, Clone)]
pub struct Prepared {
    /// The fixture with its order and durations.
    pub fixture: LeoTourFixture,
    /// The sequencing's outcome, for a `[sequence]` fixture.
    pub order: Option<ChosenOrder>,
    /// The schedule's outcome, for a `[schedule]` fixture.
    pub schedule: Option<ChosenSchedule>,
}

/// Choose `f`'s order (a `[sequence]` fixture), then its arcs' durations (a `[schedule]`
/// fixture): what `reconfig solve`, `reconfig plot` and the feeder plan.
///
/// # Errors
/// A sequencing or schedule refused or rejected, or one that found no order or schedule.
pub fn prepare(f: &LeoTourFixture, limits: &Limits) -> Result<Prepared> {
    let chosen = choose_order(f, limits)?;
    if let Some((_, c)) = &chosen {
        if !c.sequence.info.status.is_usable() {
            return Err(anyhow!(
                "sequencing: no order could be planned ({:?}, {} arcs tried)",
                c.sequence.info.status,
                c.sequence.info.arcs_planned
            ));
        }
    }
    let (ordered, order) = match chosen {
        Some((g, c)) => (g, Some(c)),
        None => (f.clone(), None),
    };
    let (fixture, schedule) = match choose_schedule(&ordered, limits)? {
        Some((g, c)) => (g, Some(c)),
        None => (ordered, None),
    };
    Ok(Prepared {
        fixture,
        order,
        schedule,
    })
}
