//! The tour's order for a fixture with a `[sequence]` table: the core's on-board sequencing
//! (`reconfig_core::leo_tour::tour_order`: the branch-and-bound of `leo_tour::sequence`, each
//! arc's cost the core's estimate `leo_tour::estimate_arc_mps`, the per-arc search in the
//! search model with the table's faster settings).

use crate::fixture::leo_tour::LeoTourFixture;
use anyhow::{anyhow, Result};
use reconfig_core::leo_tour::schedule::{Schedule, ScheduleStatus};
use reconfig_core::leo_tour::sequence::{Sequence, SequenceStatus};
use reconfig_core::leo_tour::tour_order::{self, OnboardProblem};
use serde_json::json;
use std::time::Instant;

/// The order chosen by the core's sequencing for a fixture with a `[sequence]` table.
#[derive(Debug, Clone, Copy)]
pub struct ChosenOrder {
    /// The core's outcome (order, per-arc starts and durations, pruning counts).
    pub sequence: Sequence,
    /// Wall time of the sequencing (every arc it planned), s.
    pub time_s: f64,
}

/// Choose the order of `f`'s tour with the core's on-board sequencing
/// (`leo_tour::tour_order::choose_order`: branch-and-bound, each arc's cost the per-arc
/// search's estimate with the `[sequence]` settings), and return the fixture with that order
/// and its intervals.
///
/// # Errors
/// A sequencing request the core refuses (too few or many clients, a client without an
/// elliptic plane, intervals out of range).
pub fn choose_order(f: &LeoTourFixture) -> Result<Option<(LeoTourFixture, ChosenOrder)>> {
    let Some(spec) = f.sequence else {
        return Ok(None);
    };
    let started = Instant::now();
    let sequence =
        tour_order::choose_order(&f.sequence_problem()?, &spec.settings, &spec.arc_settings)
            .map_err(|e| anyhow!("sequencing refused: {e}"))?;
    let time_s = started.elapsed().as_secs_f64();
    Ok(Some((
        with_order(f, &sequence),
        ChosenOrder { sequence, time_s },
    )))
}

/// The on-board part of a `[sequence]` fixture as one core request
/// (`leo_tour::tour_order::plan_onboard`: the order, then every arc of it).
///
/// # Errors
/// A fixture without a `[sequence]` table, or with more clients than a request carries.
pub fn onboard_problem(f: &LeoTourFixture) -> Result<OnboardProblem> {
    let spec = f
        .sequence
        .ok_or_else(|| anyhow!("{} has no [sequence] table", f.name))?;
    Ok(OnboardProblem {
        tour: f.sequence_problem()?,
        sequence: spec.settings,
        estimates: spec.arc_settings,
        arcs: f.settings,
    })
}

/// `f` with the order and the arc durations of `sequence` (still with its `[sequence]`
/// table).
pub fn with_order(f: &LeoTourFixture, sequence: &Sequence) -> LeoTourFixture {
    let n = usize::from(sequence.len);
    let mut chosen = f.clone();
    chosen.order = sequence
        .order
        .iter()
        .take(n)
        .map(|&k| usize::from(k))
        .collect();
    chosen.intervals_s = sequence
        .durations_s
        .iter()
        .take(n.saturating_sub(1))
        .copied()
        .collect();
    chosen
}

pub fn sequence_json(c: &ChosenOrder) -> serde_json::Value {
    let q = &c.sequence;
    let n = usize::from(q.len);
    json!({
        "status": format!("{:?}", q.status),
        "order": q.order[..n].iter().map(|&k| usize::from(k) + 1).collect::<Vec<_>>(),
        "total_dv_mps": q.total_dv_mps,
        "durations_s": q.durations_s[..n.saturating_sub(1)].to_vec(),
        "arcs_planned": q.arcs_planned,
        "arcs_in_tree": q.arcs_in_tree,
        "orders_completed": q.orders_completed,
        "orders_total": q.orders_total,
        "bound_violations": q.bound_violations,
        "time_s": c.time_s,
    })
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
/// (`leo_tour::tour_order::choose_schedule`) and return the fixture with them; `None` for a
/// fixture without a `[schedule]` table.
///
/// # Errors
/// A schedule the core refuses (settings out of range) or one with no complete schedule.
pub fn choose_schedule(f: &LeoTourFixture) -> Result<Option<(LeoTourFixture, ChosenSchedule)>> {
    let Some(spec) = f.schedule else {
        return Ok(None);
    };
    let order: Vec<u8> = f
        .order
        .iter()
        .map(|&k| u8::try_from(k))
        .collect::<Result<_, _>>()?;
    let started = Instant::now();
    let schedule = tour_order::choose_schedule(
        &f.clients,
        &order,
        f.impulses,
        &spec.settings,
        &spec.arc_settings,
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

pub fn schedule_json(c: &ChosenSchedule) -> serde_json::Value {
    let q = &c.schedule;
    let n = usize::from(q.arcs);
    json!({
        "status": format!("{:?}", q.status),
        "durations_s": q.durations_s[..n].to_vec(),
        "duration_units": q.duration_units[..n].to_vec(),
        "unit_s": q.unit_s,
        "horizon_s": c.horizon_s,
        "total_dv_mps": q.total_dv_mps,
        "arcs_planned": q.arcs_planned,
        "time_s": c.time_s,
    })
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
/// A sequencing or schedule the core refuses, or one that found no order or schedule.
pub fn prepare(f: &LeoTourFixture) -> Result<Prepared> {
    let chosen = choose_order(f)?;
    if let Some((_, c)) = &chosen {
        if c.sequence.status == SequenceStatus::NoOrder {
            return Err(anyhow!(
                "sequencing: no order could be planned ({} arcs tried)",
                c.sequence.arcs_planned
            ));
        }
    }
    let (ordered, order) = match chosen {
        Some((g, c)) => (g, Some(c)),
        None => (f.clone(), None),
    };
    let (fixture, schedule) = match choose_schedule(&ordered)? {
        Some((g, c)) => (g, Some(c)),
        None => (ordered, None),
    };
    Ok(Prepared {
        fixture,
        order,
        schedule,
    })
}
