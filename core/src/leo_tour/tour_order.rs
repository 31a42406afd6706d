//! The tour's order from the clients' states, on board ([`solve_sequence`], the planners'
//! contract as [`LeoSequence`]): [`super::sequence::best_order`] with each arc's cost the per-arc
//! search's estimate ([`super::estimate_arc_mps`]), the clients flown to each arc start in the
//! estimates' search model (`search_model`: the closed-form first-order J2 theory by
//! default, whatever the span; RK4 steps in the planning model), all within the sequencing's
//! work budget. With `full_plans` (a ground design) each arc's cost is its full plan
//! ([`super::planned_arc_mps`]), the clients flown in the planning model.
//!
//! The enumeration meets the same arc (same clients, start and duration) under different
//! prefixes, and the same client state at an arc start many times: both are kept in
//! fixed-size caches in the caller's [`SequenceWorkspace`], so each is computed once while
//! the caches have room (and computed again, with the same result, once they are full).
//!
//! Worst case: `settings.work_budget` units in all (each unit at most
//! [`super::work_units::MAX_INSTRUCTIONS_PER_UNIT`] M7 instructions): the enumeration's nodes and
//! arcs, the clients' flights and the estimates are charged to one meter, and each estimate
//! may spend the least of its own `arc_settings.work_budget` and what is left. An estimate cut
//! by what is left makes the outcome `BudgetExhausted` (the enumeration stops there).

use super::bound::{plane_of, Plane};
use super::flight::{Flight, Model};
use super::j2::State;
use super::schedule::{best_schedule, Schedule, ScheduleError, ScheduleSettings, MAX_STEPS};
use super::sequence::{
    best_order, dt_max_s, Sequence, SequenceError, SequenceProblem, SequenceSettings,
    SequenceStatus, MAX_CLIENTS,
};
use super::{
    estimate_arc_mps, planned_arc_mps, propagate, solve_arc, ArcEstimate, ArcProblem, ArcSolution,
    PlanError, Settings, SolveStatus, Workspace,
};
use crate::work::Meter;
use serde::{Deserialize, Serialize};

/// An arc's cost for the sequencing: [`estimate_arc_mps`] or [`planned_arc_mps`].
type ArcCost = fn(&ArcProblem, &Settings, &mut Workspace) -> Result<ArcEstimate, PlanError>;

/// Client states at arc starts kept: every client at every start of a tour of
/// [`MAX_CLIENTS`] with durations by position.
const STATE_CACHE: usize = MAX_CLIENTS * (MAX_CLIENTS - 1);

/// Grid starts of a schedule: every unit of the longest horizon, 0 included.
const SCHEDULE_STARTS: usize = (MAX_CLIENTS - 1) * MAX_STEPS as usize + 1;

/// Arc costs kept: every (from, to) pair at every position of such a tour.
const ARC_CACHE: usize = MAX_CLIENTS * (MAX_CLIENTS - 1) * (MAX_CLIENTS - 1);

/// A fixed-capacity memo of `K -> V` searched linearly (hundreds of entries, each lookup far
/// cheaper than what it saves: an RK4 propagation or an arc estimate).
#[derive(Clone, Debug)]
struct Memo<K, V, const N: usize> {
    entries: [Option<(K, V)>; N],
    len: usize,
}

impl<K: Copy + PartialEq, V: Copy, const N: usize> Memo<K, V, N> {
    const fn new() -> Self {
        Self {
            entries: [None; N],
            len: 0,
        }
    }

    /// Forget every entry (the next sequencing starts empty).
    fn clear(&mut self) {
        self.len = 0;
    }

    fn get(&self, key: &K) -> Option<V> {
        self.entries
            .iter()
            .take(self.len)
            .flatten()
            .find(|(k, _)| k == key)
            .map(|(_, v)| *v)
    }

    /// Keep `value` under `key` while there is room (a full memo keeps what it has).
    fn put(&mut self, key: K, value: V) {
        if let Some(slot) = self.entries.get_mut(self.len) {
            *slot = Some((key, value));
            self.len = self.len.saturating_add(1);
        }
    }
}

/// The sequencing's caller-owned buffers: the memo of the client states at arc starts, the
/// memo of the arc estimates, and the arc search's [`Workspace`] the estimates run in (which
/// [`plan_onboard`] also plans the chosen order's arcs in). Built once (`new()` is a `const
/// fn`: it can sit in a `static`); every sequencing empties the memos first.
#[derive(Clone, Debug)]
pub struct SequenceWorkspace {
    /// Client `k`'s state at a start epoch (bits): `None` when it could not be flown.
    states: Memo<(usize, u64), Option<State>, STATE_CACHE>,
    /// The arc (from, to, start bits, duration bits)'s estimate, m/s, or `None`.
    arcs: Memo<(usize, usize, u64, u64), Option<f64>, ARC_CACHE>,
    /// The arc search's buffers.
    pub arc: Workspace,
}

impl SequenceWorkspace {
    /// Empty buffers.
    pub const fn new() -> Self {
        Self {
            states: Memo::new(),
            arcs: Memo::new(),
            arc: Workspace::new(),
        }
    }
}

impl Default for SequenceWorkspace {
    fn default() -> Self {
        Self::new()
    }
}

/// The cheapest visiting order of the clients (`problem.clients`: inertial states at the tour
/// epoch, km and km/s, at most [`MAX_CLIENTS`]), with `problem.impulses` per arc, each arc's
/// cost the estimate of the per-arc search with `arc_settings` (which also give the planning
/// model the clients are flown in), or with `settings.full_plans` its full plan, written into
/// `out`. An arc whose estimate has no Δv (no
/// transfer, the budget spent, a refusal of that arc) is not taken.
///
/// Worst case: see the module docs.
///
/// # Errors
/// [`SequenceError`] when the request is refused before planning: a client count outside
/// `2..=MAX_CLIENTS`, a client state with no elliptic plane, a first client or an interval out
/// of range, sequencing or arc settings out of range; `out` is then untouched. A sequencing
/// that finds no order is [`SequenceStatus::NoOrder`] in `out`.
pub fn solve_sequence(
    problem: &SequenceProblem,
    settings: &SequenceSettings,
    arc_settings: &Settings,
    workspace: &mut SequenceWorkspace,
    out: &mut Sequence,
) -> Result<(), SequenceError> {
    let clients = problem.clients.as_slice();
    let impulses = problem.impulses;
    let g = arc_settings.gravity();
    let count = SequenceError::Clients {
        count: clients.len(),
    };
    if clients.len() > MAX_CLIENTS || clients.len() < 2 {
        return Err(count);
    }
    // Filled with the first client's plane, the others set below; only the first
    // `clients.len()` are read.
    let first =
        plane_of(&g, clients.first().ok_or(count)?).ok_or(SequenceError::Client { index: 0 })?;
    let mut planes: [Plane; MAX_CLIENTS] = [first; MAX_CLIENTS];
    for (index, (slot, s)) in planes.iter_mut().zip(clients).enumerate().skip(1) {
        *slot = plane_of(&g, s).ok_or(SequenceError::Client { index })?;
    }
    let planes = planes.get(..clients.len()).ok_or(count)?;
    // The arcs' settings are every estimate's: out of range, each would be refused.
    arc_settings
        .check_ranges()
        .map_err(SequenceError::InvalidArcSetting)?;
    // Every arc estimate would refuse such a client (`validate::check`): refuse the request,
    // naming it, rather than find no order.
    let low = super::validate::first_low_client(clients.iter().enumerate(), g.mu_km3_s2, g.re_km);
    if let Some(low) = low {
        return Err(SequenceError::ClientPerigee(low));
    }
    let SequenceWorkspace { states, arcs, arc } = workspace;
    states.clear();
    arcs.clear();
    let tour = (problem.first, &problem.intervals);
    // Full plans fly their clients in the planning model (as the tour's arcs are planned);
    // estimates in the estimates' search model.
    let (model, arc_cost): (Model, ArcCost) = if settings.full_plans {
        (Model::Planning, planned_arc_mps)
    } else {
        (arc_settings.search_model, estimate_arc_mps)
    };
    let flight = Flight {
        g,
        model,
        step_s: arc_settings.step_s,
        max_steps: arc_settings.max_steps,
    };
    best_order(
        &g,
        planes,
        tour,
        settings,
        |meter, i, j, t0, dt| {
            let key = (i, j, t0.to_bits(), dt.to_bits());
            if let Some(cost) = arcs.get(&key) {
                return cost;
            }
            let mut at = |k: usize, meter: &mut Meter| -> Option<State> {
                let key = (k, t0.to_bits());
                if let Some(s) = states.get(&key) {
                    return s;
                }
                let s = flight.fly(clients.get(k)?, t0, meter);
                // A flight the meter refused is not kept: the enumeration stops there.
                if !meter.exhausted() {
                    states.put(key, s);
                }
                s
            };
            let (from, to) = (at(i, meter)?, at(j, meter)?);
            // The estimate spends at most its own budget and what is left of the sequencing's;
            // with less left than it charges before it can stop, it is not started.
            let left = meter.remaining();
            if left < super::estimate_floor_units(dt, arc_settings, model) {
                let _ = meter.spend(u64::MAX);
                return None;
            }
            let capped = Settings {
                work_budget: arc_settings.work_budget.min(left),
                ..*arc_settings
            };
            let estimate = arc_cost(
                &ArcProblem {
                    from,
                    to,
                    duration_s: dt,
                    impulses,
                },
                &capped,
                arc,
            );
            let cost = match estimate {
                Ok(e) => {
                    meter.charge(e.work_units);
                    let cut = matches!(e.status, SolveStatus::BudgetExhausted { .. });
                    if cut && capped.work_budget < arc_settings.work_budget {
                        // Cut by the sequencing's budget, not its own: not the estimate the
                        // arc's settings ask for, so the enumeration stops (and says so).
                        let _ = meter.spend(u64::MAX);
                        return e.dv_mps;
                    }
                    e.dv_mps
                }
                // Refused at its checks (charged as a solve's fixed part).
                Err(_) => {
                    meter.charge(super::work_units::SOLVE);
                    None
                }
            };
            arcs.put(key, cost);
            cost
        },
        out,
    )
}

/// The arc estimates' default settings while sequencing: a coarse search (8 grid epochs, one
/// candidate, 100 evaluations, the compass search stopped at 128 s, no hops) whose whole tree
/// of five clients fits the sequencing's default budget. Chosen on generated tours (tuning
/// seeds 0..20 of `host/examples/leo_sequence_campaign.rs`): a complete enumeration with
/// coarse estimates chose better orders than a partial one with the published fixture's
/// finer estimates (64 epochs, two candidates, 1,000 evaluations, 8 s), which the budget
/// cuts after a dozen arcs. The figures on held-out tours: docs/leo-tour.md, "Sequencing".
pub const ESTIMATE_SETTINGS: Settings = Settings {
    grid_points: 8,
    candidates: 1,
    hop_rounds: 0,
    search_max_evals: 100,
    search_min_step_s: 128.0,
    ..Settings::DEFAULT
};

/// The sequencing's settings in the planners' contract: its own and its arc estimates'
/// (the wire's `Request::LeoSequence { settings, arc_settings }`). By default the estimates'
/// are [`ESTIMATE_SETTINGS`].
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct SequencePlanSettings {
    /// The sequencing's settings.
    pub order: SequenceSettings,
    /// The arc estimates' settings.
    pub arc: Settings,
}

impl Default for SequencePlanSettings {
    fn default() -> Self {
        Self {
            order: SequenceSettings::DEFAULT,
            arc: ESTIMATE_SETTINGS,
        }
    }
}

/// The sequencing in the planners' contract ([`crate::contract::Planner`]):
/// [`solve_sequence`].
#[derive(Clone, Copy, Debug)]
pub struct LeoSequence;

crate::impl_planner!(
    LeoSequence: SequenceProblem, SequencePlanSettings, SequenceWorkspace, Sequence,
    SequenceError, SequenceStatus, LeoSequence, solve_with,
    reset |out| out.reset()
);

/// [`solve_sequence`] with both settings in one value (the contract's shape).
fn solve_with(
    problem: &SequenceProblem,
    settings: &SequencePlanSettings,
    workspace: &mut SequenceWorkspace,
    out: &mut Sequence,
) -> Result<(), SequenceError> {
    solve_sequence(problem, &settings.order, &settings.arc, workspace, out)
}

/// The arcs' durations for the visiting `order` (0-based client indices into `clients`,
/// inertial states at the tour epoch): [`super::schedule::best_schedule`] on the grid of `Δt_max /
/// settings.steps` (`Δt_max` from the order's first client), each arc's cost the estimate of
/// the per-arc search with `arc_settings` in `workspace`, the clients flown to each arc start
/// in the planning model.
///
/// Each client is needed at the grid's starts of the arc that reaches it and of the arc that
/// leaves it; both rows of states are kept (a client state is flown once per start).
///
/// Worst case: [`super::schedule::best_schedule`]'s arcs, each one estimate within
/// `arc_settings.work_budget`, and at most `2 × (horizon units + 1)` propagations per arc of
/// at most `arc_settings.max_steps` RK4 steps.
///
/// # Errors
/// [`ScheduleError`]: an order of fewer than 2 or more than [`MAX_CLIENTS`] clients or naming
/// a client not given (as `Arcs`), a first client without an elliptic plane (as
/// `Revolutions`), a client of the order below the least perigee altitude (`ClientPerigee`),
/// or settings out of range.
pub fn choose_schedule(
    clients: &[State],
    order: &[u8],
    impulses: u8,
    settings: &ScheduleSettings,
    arc_settings: &Settings,
    workspace: &mut Workspace,
) -> Result<Schedule, ScheduleError> {
    let g = arc_settings.gravity();
    let arcs = order.len().saturating_sub(1);
    let named = |k: &u8| clients.get(usize::from(*k)).is_some();
    if order.len() > MAX_CLIENTS || !order.iter().all(named) {
        return Err(ScheduleError::Arcs { count: arcs });
    }
    let bad_revolutions = ScheduleError::Revolutions {
        value: settings.revolutions,
    };
    let first = order
        .first()
        .and_then(|&k| clients.get(usize::from(k)))
        .and_then(|s| plane_of(&g, s))
        .ok_or(bad_revolutions)?;
    // Every arc estimate would refuse a client of the order below the least perigee: refuse
    // the request, naming it, rather than find no schedule.
    let in_order = order.iter().filter_map(|&k| {
        let index = usize::from(k);
        clients.get(index).map(|s| (index, s))
    });
    if let Some(low) = super::validate::first_low_client(in_order, g.mu_km3_s2, g.re_km) {
        return Err(ScheduleError::ClientPerigee(low));
    }
    let dt_max_s = dt_max_s(&g, &first, settings.revolutions);
    // The states of the arc's two clients at each start on the grid, for the arc in hand.
    let mut rows = StateRows::new();
    best_schedule(arcs, dt_max_s, settings, |arc| {
        let k = arc.arc;
        let (&a, &b) = (order.get(k)?, order.get(k.saturating_add(1))?);
        rows.arc(k);
        let at = |c: u8| {
            clients
                .get(usize::from(c))
                .and_then(|s| propagate(arc_settings, s, arc.start_s))
        };
        let from = rows.from.get_or_fly(arc.start_units, || at(a))?;
        let to = rows.to.get_or_fly(arc.start_units, || at(b))?;
        estimate_arc_mps(
            &ArcProblem {
                from,
                to,
                duration_s: arc.duration_s,
                impulses,
            },
            arc_settings,
            workspace,
        )
        .ok()
        .and_then(|e| e.dv_mps)
    })
}

/// One client's states at the grid's starts (`None`: not flown yet; `Some(None)`: could not
/// be flown).
struct StateRow([Option<Option<State>>; SCHEDULE_STARTS]);

impl StateRow {
    fn get_or_fly(&mut self, start: u8, fly: impl FnOnce() -> Option<State>) -> Option<State> {
        let slot = self.0.get_mut(usize::from(start))?;
        *slot.get_or_insert_with(fly)
    }
}

/// The states of the arc in hand's two clients; the client an arc reaches is the one the
/// next arc leaves, so its row moves over.
struct StateRows {
    arc: usize,
    from: StateRow,
    to: StateRow,
}

impl StateRows {
    fn new() -> Self {
        Self {
            arc: 0,
            from: StateRow([None; SCHEDULE_STARTS]),
            to: StateRow([None; SCHEDULE_STARTS]),
        }
    }

    /// Make the rows those of arc `k` (arcs come in increasing order).
    fn arc(&mut self, k: usize) {
        if k != self.arc {
            self.from = core::mem::replace(&mut self.to, StateRow([None; SCHEDULE_STARTS]));
            self.arc = k;
        }
    }
}

/// The tour's on-board part as one request: the clients at the tour epoch, the impulses per
/// arc, the sequencing's settings, the settings of its arc estimates and those of the arcs
/// planned in full (what the LEO firmware image carries for a `[sequence]` fixture).
#[derive(Clone, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct OnboardProblem {
    /// The clients, the impulses per arc, the first client and the arcs' durations.
    pub tour: SequenceProblem,
    /// The sequencing's settings.
    pub sequence: SequenceSettings,
    /// The arc estimates' settings while sequencing.
    pub estimates: Settings,
    /// The settings of the chosen order's arcs.
    pub arcs: Settings,
}

/// The tour's on-board part: the order ([`solve_sequence`], arcs estimated with
/// `problem.estimates`) and each arc of it planned with [`solve_arc`] and `problem.arcs` (the
/// full search), the clients flown to each arc start in the planning model of `problem.arcs`.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct OnboardPlan {
    /// The sequencing's outcome.
    pub sequence: Sequence,
    /// Arc `k` of the order (`k < sequence.len - 1`): its plan (with its status), or why it
    /// was refused; `None` beyond the order's arcs (all of them when there is no order).
    pub arcs: [Option<Result<ArcSolution, PlanError>>; MAX_CLIENTS - 1],
}

impl OnboardPlan {
    /// No order and no arcs, for use as an output buffer (a `const fn`: it can sit in a
    /// `static`).
    pub const fn new() -> Self {
        Self {
            sequence: Sequence::new(),
            arcs: [None; MAX_CLIENTS - 1],
        }
    }
}

impl Default for OnboardPlan {
    fn default() -> Self {
        Self::new()
    }
}

/// Choose the order and plan its arcs into `out`, in `workspace` (its arc workspace serves the
/// sequencing's estimates, then the arcs): what a flight computer runs before the tour (and
/// what `reconfig solve` does for a `[sequence]` fixture, without the truth-model checks).
///
/// Worst case: [`solve_sequence`]'s, then `clients.len() - 1` arcs, each two propagations of
/// at most `problem.arcs.max_steps` RK4 steps and one [`solve_arc`] within
/// `problem.arcs.work_budget`.
///
/// # Errors
/// As [`solve_sequence`] (`out` is then untouched). An arc that is refused is in
/// [`OnboardPlan::arcs`].
pub fn plan_onboard(
    problem: &OnboardProblem,
    workspace: &mut SequenceWorkspace,
    out: &mut OnboardPlan,
) -> Result<(), SequenceError> {
    let clients = problem.tour.clients.as_slice();
    let settings = &problem.arcs;
    solve_sequence(
        &problem.tour,
        &problem.sequence,
        &problem.estimates,
        workspace,
        &mut out.sequence,
    )?;
    let sequence = &out.sequence;
    out.arcs = [None; MAX_CLIENTS - 1];
    let legs = sequence
        .order
        .windows(2)
        .zip(sequence.starts_s.iter().zip(sequence.durations_s.iter()))
        .take(usize::from(sequence.len).saturating_sub(1));
    for (slot, (pair, (&start_s, &duration_s))) in out.arcs.iter_mut().zip(legs) {
        let at = |k: u8| {
            clients
                .get(usize::from(k))
                .and_then(|c| propagate(settings, c, start_s))
        };
        let (Some(&a), Some(&b)) = (pair.first(), pair.get(1)) else {
            continue;
        };
        let (from, to) = match (at(a), at(b)) {
            (Some(from), Some(to)) => (from, to),
            (None, _) => {
                *slot = Some(Err(PlanError::Propagation {
                    field: super::Field::From,
                }));
                continue;
            }
            (_, None) => {
                *slot = Some(Err(PlanError::Propagation {
                    field: super::Field::To,
                }));
                continue;
            }
        };
        let problem = ArcProblem {
            from,
            to,
            duration_s,
            impulses: problem.tour.impulses,
        };
        // The plan is written in place, in its slot.
        let planned = slot.insert(Ok(ArcSolution::new()));
        if let Ok(solution) = planned {
            if let Err(e) = solve_arc(&problem, settings, &mut workspace.arc, solution) {
                *planned = Err(e);
            }
        }
    }
    Ok(())
}

#[cfg(test)]
#[path = "tour_order_tests.rs"]
mod tests;
