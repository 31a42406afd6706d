//! The visiting order of a tour: exhaustive depth-first enumeration with branch-and-bound.
//!
//! A node is a partial order; its cost is the sum of its arcs' planned Δv, and its bound adds,
//! for every client not yet visited, the cheapest bound of any arc that can enter it (each is
//! entered exactly once, from the current client or another unvisited one) with the node
//! drift allowed over the whole tour ([`bound::arc_bound_any_mps`]). Before an arc is planned
//! its own bound at its known start and duration ([`bound::arc_bound_mps`]) is checked
//! against the incumbent, so a pruned arc is never planned. Children are tried cheapest bound
//! first, ties by client number: deterministic.
//!
//! The arc cost depends on the start epoch (the nodes drift apart under J2), so the arc
//! planner is a callback given the start and the duration; the bound follows the drift with
//! the epoch and allows the chaser's own drift over the arc (see [`bound`]). Every planned arc
//! is compared with its bound: a plan cheaper than its bound would make the pruning unsafe,
//! and the outcome then says [`SequenceStatus::BoundViolated`].
//!
//! Worst case: every order of the clients, `N!` leaves (`(N-1)!` with the first fixed) and
//! at most `N! (1 + 1/1! + 1/2! + ...) < e N!` arcs planned; `max_arcs` stops it first, and
//! the work budget (`work_budget`) bounds its time: every node of the enumeration
//! ([`work_units::SEQUENCE_NODE`]) and every planned arc ([`work_units::SEQUENCE_ARC`]) is
//! charged before it runs, and the callback charges its own work (the clients' flights and the
//! arc estimate, each given what is left of the budget) to the same meter.

use super::bound::{self, BoundSettings, Plane};
use super::j2::State;
use crate::astro::Gravity;
use crate::contract::{Range, SettingError};
use crate::indexed::IndexedExt as _;
use crate::leo_tour::work_units;
use crate::work::Meter;
use serde::{Deserialize, Serialize};

/// Most clients of a tour.
pub const MAX_CLIENTS: usize = 8;

/// How each arc's duration is chosen.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub enum Intervals {
    /// By position in the tour (arc 1, arc 2, ...), whatever the clients: the printed
    /// intervals of the paper's tours.
    ByPosition([f64; MAX_CLIENTS - 1]),
    /// The paper's rule (eq. 9-11): `Δt_max = revolutions` periods of the tour's first client;
    /// where the node gap closes (`ΔΩ ΔΩ̇ <= 0`) the time for J2 to close it if shorter than
    /// `Δt_max`, else `Δt_max`; where it opens, `Δt_max / 2`. An arc is never shorter than
    /// `min_duration_s` (the rule can give a closing time near zero).
    PaperRule {
        /// X, target revolutions per `Δt_max`.
        revolutions: f64,
        /// Shortest arc, s.
        min_duration_s: f64,
    },
}

/// A sequencing request: the clients, the impulses of every arc, the first client and how the
/// arcs' durations are chosen.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct SequenceProblem {
    /// The clients' inertial states at the tour epoch, km and km/s.
    pub clients: heapless::Vec<State, MAX_CLIENTS>,
    /// Impulses per arc.
    pub impulses: u8,
    /// The first client (0-based), or `None` for a free first client.
    pub first: Option<u8>,
    /// Arc durations.
    pub intervals: Intervals,
}

crate::settings_table! {
    /// Settings of the sequencing: the bound's conservatism, the arc limit and the work budget.
    /// The per-arc estimates' settings travel beside them ([`super::Settings`]).
    pub struct SequenceSettings;
    /// The sequencing's settings, by name (stable codes on the wire and in the C interface).
    pub enum SettingId for LeoSequence;
    {
        /// Most arcs planned (the callback's calls); the enumeration stops there.
        max_arcs, MaxArcs = 0: u32 = DEFAULT_MAX_ARCS,
        unit "", range Range::any(), limit AtMost;
        /// The bound's semi-major-axis band margin on each side of the two clients', km (a
        /// smaller margin prunes more).
        band_margin_km, BandMarginKm = 1: f64 = 100.0,
        unit "km", range Range::at_least(0.0), limit AtLeast;
        /// The bound's inclination band margin on each side, rad.
        band_margin_rad, BandMarginRad = 2: f64 = 1.0_f64 * (core::f64::consts::PI / 180.0),
        unit "rad", range Range::at_least(0.0), limit AtLeast;
        /// The bound is multiplied by `1 - bound_margin`.
        bound_margin, BoundMargin = 3: f64 = 0.05,
        unit "", range Range::closed_open(0.0, 1.0), limit AtLeast;
        /// Work budget of the whole sequencing (its enumeration, the clients' flights and every
        /// arc estimate), in the arc's units of at most
        /// `work_units::MAX_INSTRUCTIONS_PER_UNIT` (100) Cortex-M7 instructions each; each
        /// estimate may spend at most its own `work_budget` and what is left of this one.
        work_budget, WorkBudget = 4: u64 = work_units::DEFAULT_WORK_BUDGET,
        unit "units", range Range::closed(1.0, 1e10), limit AtMost;
        /// Each arc's cost is its full plan ([`super::planned_arc_mps`]: the per-arc search,
        /// the planning model's polish and the final check, the clients flown in the planning
        /// model), not the search's estimate: the order is then the cheapest by the plans the
        /// tour would fly. A ground design: a full plan costs up to the arc's `work_budget`
        /// (4 M units by default), so the built-in limits keep it off.
        full_plans, FullPlans = 5: bool = false,
        unit "", range Range::any(), limit MustBeOff;
    }
}

/// The arcs a sequencing may estimate by default: the whole tree of five clients (320) with
/// room, about 0.4 s on the development machine at 1.7 ms an arc.
pub const DEFAULT_MAX_ARCS: u32 = 400;

impl SequenceSettings {
    /// The bound's margins.
    pub fn bound(&self) -> BoundSettings {
        BoundSettings {
            band_margin_km: self.band_margin_km,
            band_margin_rad: self.band_margin_rad,
            margin: self.bound_margin,
        }
    }
}

crate::status_enum! {
    /// What the returned order is (the contract's vocabulary, [`crate::contract::Status`]).
    #[derive(Eq)]
    pub enum SequenceStatus {
        /// Every order was either planned or pruned by the bound, and no planned arc was cheaper
        /// than its bound: the order is the cheapest for the arc costs given (the contract's
        /// `Solved`).
        Optimal = 1,
        /// The enumeration finished but some planned arc was cheaper than its bound: the order is
        /// the cheapest of those planned, and a pruned order might have been cheaper.
        BoundViolated = 2,
        /// `max_arcs` stopped the enumeration: the best order planned so far.
        ArcLimit = 3,
        /// No order was found: no `order`, no `total_dv_mps`. With `arc_limit`, `max_arcs` stopped
        /// the enumeration before any complete order; without it, every order has an arc the
        /// planner refused.
        NoOrder {
            /// `max_arcs` stopped the enumeration.
            arc_limit: bool,
        } = 4,
        /// The work budget (`work_budget`) stopped the enumeration. With `verified`, the
        /// cheapest order planned so far (every arc of it estimated, the order complete; a
        /// cheaper one may be among those not reached); without it, no complete order was
        /// reached: no `order`, no `total_dv_mps`.
        BudgetExhausted {
            /// An order was reached before the budget ran out.
            verified: bool,
        } = 5,
    }
    usable: [
        Self::Optimal
            | Self::BoundViolated
            | Self::ArcLimit
            | Self::BudgetExhausted { verified: true }
    ];
    budget: BudgetExhausted;
}

/// How a sequencing ended and what it took.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
pub struct SequenceInfo {
    /// What the order is.
    pub status: SequenceStatus,
    /// Arcs planned (callback calls).
    pub arcs_planned: u32,
    /// Arcs in the whole enumeration tree (what planning every order would take with each
    /// arc of a shared prefix planned once).
    pub arcs_in_tree: u32,
    /// Complete orders reached (each planned to the end).
    pub orders_completed: u32,
    /// Orders in the enumeration.
    pub orders_total: u32,
    /// Planned arcs cheaper than their bound.
    pub bound_violations: u32,
    /// Work units used (`work_budget`).
    pub work_units: u64,
}

/// The outcome of a sequencing. Every number is finite whatever the status; with no order
/// (`len == 0`) the order, starts and durations are zero and `total_dv_mps` is absent.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct Sequence {
    /// The order, 0-based client indices; `len` of them.
    pub order: [u8; MAX_CLIENTS],
    /// Clients in the order (0 when there is none).
    pub len: u8,
    /// The planned Δv of the order, m/s; absent when there is no order.
    pub total_dv_mps: Option<f64>,
    /// The arcs' start epochs (from the tour epoch), s; `len - 1` of them.
    pub starts_s: [f64; MAX_CLIENTS - 1],
    /// The arcs' durations, s.
    pub durations_s: [f64; MAX_CLIENTS - 1],
    /// The status and the counters.
    pub info: SequenceInfo,
}

impl Sequence {
    /// The empty `Unsolved` outcome (no order), for use as an output buffer (a `const fn`: it
    /// can sit in a `static`).
    pub const fn new() -> Self {
        Self {
            order: [0; MAX_CLIENTS],
            len: 0,
            total_dv_mps: None,
            starts_s: [0.0; MAX_CLIENTS - 1],
            durations_s: [0.0; MAX_CLIENTS - 1],
            info: SequenceInfo {
                status: SequenceStatus::Unsolved,
                arcs_planned: 0,
                arcs_in_tree: 0,
                orders_completed: 0,
                orders_total: 0,
                bound_violations: 0,
                work_units: 0,
            },
        }
    }

    /// Make this the empty `Unsolved` outcome, in place.
    pub fn reset(&mut self) {
        *self = Self::new();
    }
}

impl Default for Sequence {
    fn default() -> Self {
        Self::new()
    }
}

/// Why a sequencing was refused.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub enum SequenceError {
    /// Fewer than two or more than [`MAX_CLIENTS`] clients.
    Clients {
        /// Clients given.
        count: usize,
    },
    /// The first client is not one of the clients.
    First {
        /// The index given.
        index: u8,
    },
    /// A client's state has no elliptic plane.
    Client {
        /// Which client (0-based).
        index: usize,
    },
    /// An interval is not finite and positive (position, value); or an unused interval (past
    /// the last arc) is not finite.
    Interval {
        /// Arc position (0-based).
        position: usize,
        /// The value given, s.
        value_s: f64,
    },
    /// A setting is out of its range: the setting, the value and the range.
    InvalidSetting(SettingError<SettingId>),
    /// A setting of the arcs (every estimate's) is out of its range.
    InvalidArcSetting(SettingError<crate::leo_tour::SettingId>),
    /// A client's osculating perigee is below the least altitude
    /// ([`crate::leo_tour::validate::MIN_PERIGEE_ALTITUDE_KM`]), or inside the Earth.
    ClientPerigee(crate::leo_tour::validate::LowPerigee),
}

impl core::fmt::Display for SequenceError {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        match *self {
            Self::Clients { count } => {
                write!(f, "{count} clients: a tour takes 2..={MAX_CLIENTS}")
            }
            Self::First { index } => write!(f, "first client {index} is not one of the clients"),
            Self::Client { index } => write!(f, "client {index} has no elliptic orbit plane"),
            Self::Interval { position, value_s } => write!(
                f,
                "interval {position} = {value_s} s is not finite and positive"
            ),
            Self::InvalidSetting(e) => write!(f, "{e}"),
            Self::InvalidArcSetting(e) => write!(f, "arc {e}"),
            Self::ClientPerigee(low) => write!(f, "{low}"),
        }
    }
}

impl core::error::Error for SequenceError {}

/// The paper's longest arc (eq. 9): `revolutions` periods of the tour's `first` client, s.
pub fn dt_max_s(g: &Gravity, first: &Plane, revolutions: f64) -> f64 {
    let period = 2.0
        * core::f64::consts::PI
        * libm::sqrt(first.a_km * first.a_km * first.a_km / g.mu_km3_s2);
    revolutions * period
}

/// The paper's interval rule (eq. 9-11) for an arc from `chaser` to `target` starting at
/// `start_s` (nodes drifted there at their secular rates): `Δt_max = revolutions` periods of
/// the tour's `first` client; where the node gap closes (`ΔΩ ΔΩ̇ <= 0`) the time for J2 to close
/// it (`|ΔΩ / ΔΩ̇|`, the printed ratio's magnitude) if shorter than `Δt_max`, else `Δt_max`;
/// where it opens, `Δt_max / 2`; never below `min_duration_s`.
pub fn paper_rule_duration_s(
    g: &Gravity,
    first: &Plane,
    (chaser, target): (&Plane, &Plane),
    start_s: f64,
    (revolutions, min_duration_s): (f64, f64),
) -> f64 {
    let two_pi = 2.0 * core::f64::consts::PI;
    let dt_max = dt_max_s(g, first, revolutions);
    let raan = |p: &Plane| p.raan_rad + p.raan_rate_rad_s * start_s;
    let mut d_raan = raan(target) - raan(chaser);
    d_raan -= two_pi * libm::round(d_raan / two_pi);
    let d_rate = target.raan_rate_rad_s - chaser.raan_rate_rad_s;
    let dt = if d_raan * d_rate <= 0.0 {
        let elim = if d_rate == 0.0 {
            f64::INFINITY
        } else {
            (d_raan / d_rate).abs()
        };
        elim.min(dt_max)
    } else {
        0.5 * dt_max
    };
    dt.max(min_duration_s)
}

/// The cheapest complete order found so far.
#[derive(Clone, Copy)]
struct Best {
    order: [u8; MAX_CLIENTS],
    total_dv_mps: f64,
    starts_s: [f64; MAX_CLIENTS - 1],
    durations_s: [f64; MAX_CLIENTS - 1],
}

struct Search<'a, F> {
    g: &'a Gravity,
    planes: &'a [Plane],
    /// `planes.len()`, checked to be at most [`MAX_CLIENTS`]: client numbers are `u8`.
    count: u8,
    intervals: &'a Intervals,
    bound: BoundSettings,
    max_arcs: u32,
    /// Each client's cheapest entry bound from a given client: `any[j][i]`.
    any: [[f64; MAX_CLIENTS]; MAX_CLIENTS],
    plan_arc: F,
    best: Option<Best>,
    path: [u8; MAX_CLIENTS],
    starts: [f64; MAX_CLIENTS - 1],
    durations: [f64; MAX_CLIENTS - 1],
    arcs_planned: u32,
    orders_completed: u32,
    violations: u32,
    /// Why the enumeration stopped short of its end, if it did.
    stopped: Option<Stop>,
    meter: Meter,
}

/// What stopped an enumeration short of its end.
#[derive(Clone, Copy, PartialEq, Eq)]
enum Stop {
    /// `max_arcs` arcs were planned.
    ArcLimit,
    /// The work budget ran out.
    Budget,
}

fn factorial(n: u8) -> u32 {
    (1..=u32::from(n)).fold(1_u32, u32::saturating_mul)
}

/// The arcs of the enumeration tree below a node with `remaining` clients to visit.
fn tree_arcs(remaining: u8) -> u32 {
    // T(r) = r (1 + T(r - 1)): r children, each one arc plus its own subtree.
    (1..=u32::from(remaining)).fold(0_u32, |acc, k| acc.saturating_add(1).saturating_mul(k))
}

impl<F: FnMut(&mut Meter, usize, usize, f64, f64) -> Option<f64>> Search<'_, F> {
    fn duration(&self, position: usize, from: usize, to: usize, start_s: f64) -> Option<f64> {
        match *self.intervals {
            Intervals::ByPosition(list) => list.get(position).copied(),
            Intervals::PaperRule {
                revolutions,
                min_duration_s,
            } => {
                let first = self.planes.get(usize::from(*self.path.first()?))?;
                let (c, t) = (self.planes.get(from)?, self.planes.get(to)?);
                Some(paper_rule_duration_s(
                    self.g,
                    first,
                    (c, t),
                    start_s,
                    (revolutions, min_duration_s),
                ))
            }
        }
    }

    /// The bound of the clients still to visit from `current`.
    fn rest_bound(&self, current: usize, visited: u16) -> f64 {
        let n = self.planes.len();
        let unvisited = |k: usize| visited & (1_u16 << k) == 0;
        (0..n)
            .filter(|&j| unvisited(j))
            .map(|j| {
                let row = self.any.get(j);
                (0..n)
                    .filter(|&i| i != j && (i == current || unvisited(i)))
                    .filter_map(|i| row.and_then(|r| r.get(i)).copied())
                    .fold(f64::INFINITY, f64::min)
            })
            .map(|b| if b.is_finite() { b } else { 0.0 })
            .sum()
    }

    fn incumbent(&self) -> f64 {
        self.best.map_or(f64::INFINITY, |b| b.total_dv_mps)
    }

    /// Extend the partial order of `depth` clients (the last `current`), at `time_s`, cost
    /// `cost`, visited set `visited`.
    fn extend(&mut self, depth: usize, current: usize, time_s: f64, cost: f64, visited: u16) {
        if depth == usize::from(self.count) {
            self.orders_completed = self.orders_completed.saturating_add(1);
            if cost < self.incumbent() {
                self.best = Some(Best {
                    order: self.path,
                    total_dv_mps: cost,
                    starts_s: self.starts,
                    durations_s: self.durations,
                });
            }
            return;
        }
        let Some(position) = depth.checked_sub(1) else {
            return;
        };
        // The node's children, their bounds and their pruning tests (a planned child's arc is
        // charged on its own).
        if !self.meter.spend(work_units::SEQUENCE_NODE) {
            self.stopped = Some(Stop::Budget);
            return;
        }
        // Children with their arc bounds, cheapest first (ties by client number).
        let mut kids = [(f64::INFINITY, 0_u8, 0.0_f64); MAX_CLIENTS];
        let mut count = 0_usize;
        for j in (0..self.count).filter(|&j| visited & (1_u16 << j) == 0) {
            let Some(dt) = self.duration(position, current, usize::from(j), time_s) else {
                continue;
            };
            let (Some(a), Some(b)) = (self.planes.get(current), self.planes.get(usize::from(j)))
            else {
                continue;
            };
            let lb = bound::arc_bound_mps(self.g, a, b, time_s, dt, &self.bound);
            if let Some(slot) = kids.get_mut(count) {
                *slot = (lb, j, dt);
                count = count.saturating_add(1);
            }
        }
        // At most one child per client: `count <= MAX_CLIENTS`.
        let Some(kids) = kids.get_mut(..count) else {
            return;
        };
        kids.sort_unstable_by(|x, y| x.0.total_cmp(&y.0).then(x.1.cmp(&y.1)));
        for &(lb, client, dt) in kids.iter() {
            let j = usize::from(client);
            if self.stopped.is_some() {
                return;
            }
            let next_visited = visited | (1_u16 << j);
            if cost + lb + self.rest_bound(j, next_visited) >= self.incumbent() {
                continue;
            }
            if self.arcs_planned >= self.max_arcs {
                self.stopped = Some(Stop::ArcLimit);
                return;
            }
            if !self.meter.spend(work_units::SEQUENCE_ARC) {
                self.stopped = Some(Stop::Budget);
                return;
            }
            self.arcs_planned = self.arcs_planned.saturating_add(1);
            // The callback charges its flights and estimate to the meter, within what is left.
            let Some(dv) = (self.plan_arc)(&mut self.meter, current, j, time_s, dt) else {
                continue;
            };
            if !dv.is_finite() {
                continue;
            }
            if dv < lb {
                self.violations = self.violations.saturating_add(1);
            }
            let next_cost = cost + dv;
            if next_cost + self.rest_bound(j, next_visited) >= self.incumbent() {
                continue;
            }
            let (Some(p), Some(s), Some(d)) = (
                self.path.get_mut(depth),
                self.starts.get_mut(position),
                self.durations.get_mut(position),
            ) else {
                continue;
            };
            *p = client;
            *s = time_s;
            *d = dt;
            self.extend(
                depth.saturating_add(1),
                j,
                time_s + dt,
                next_cost,
                next_visited,
            );
        }
    }
}

/// The cheapest visiting order of the clients (`planes`, from [`bound::plane_of`] of their
/// states at the tour epoch), each arc planned by `plan_arc(meter, from, to, start_s,
/// duration_s)` (its Δv in m/s, or `None` when it cannot be planned; it charges its work to
/// `meter`, which has already been charged `work_units::SEQUENCE_FIXED`, and may spend what
/// [`Meter::remaining`] says), written into `out`.
///
/// # Errors
/// [`SequenceError`] for a request outside the limits; `out` is then untouched.
pub fn best_order<F: FnMut(&mut Meter, usize, usize, f64, f64) -> Option<f64>>(
    g: &Gravity,
    planes: &[Plane],
    (first, intervals): (Option<u8>, &Intervals),
    settings: &SequenceSettings,
    plan_arc: F,
    out: &mut Sequence,
) -> Result<(), SequenceError> {
    let n = planes.len();
    let count = match u8::try_from(n) {
        Ok(count) if (2..=MAX_CLIENTS).contains(&n) => count,
        _ => return Err(SequenceError::Clients { count: n }),
    };
    if let Some(f) = first {
        if f >= count {
            return Err(SequenceError::First { index: f });
        }
    }
    if let Intervals::ByPosition(list) = *intervals {
        // The arcs' intervals are finite and positive; the slots past the last arc are unused
        // but travel in the request: finite too (a NaN or an infinity is refused wherever the
        // request carries it).
        let arcs = n.saturating_sub(1);
        for (position, &value_s) in list.iter().indexed() {
            let used = position < arcs;
            if !(value_s.is_finite() && (value_s > 0.0 || !used)) {
                return Err(SequenceError::Interval { position, value_s });
            }
        }
    }
    if let Intervals::PaperRule {
        revolutions,
        min_duration_s,
    } = *intervals
    {
        for (position, value_s) in [(0, revolutions), (1, min_duration_s)] {
            if !(value_s.is_finite() && value_s > 0.0) {
                return Err(SequenceError::Interval { position, value_s });
            }
        }
    }
    // A negative or NaN margin would make the bound prune orders it must not.
    settings
        .check_ranges()
        .map_err(SequenceError::InvalidSetting)?;
    let bound_settings = settings.bound();
    // The whole tour lasts at most (n - 1) of the longest interval.
    let longest = match *intervals {
        Intervals::ByPosition(list) => list
            .iter()
            .take(n.saturating_sub(1))
            .fold(0.0_f64, |m, &v| m.max(v)),
        Intervals::PaperRule {
            revolutions,
            min_duration_s,
        } => {
            let a_max = planes.iter().fold(0.0_f64, |m, p| m.max(p.a_km));
            let period =
                2.0 * core::f64::consts::PI * libm::sqrt(a_max * a_max * a_max / g.mu_km3_s2);
            (revolutions * period).max(min_duration_s)
        }
    };
    let horizon_s = longest * (n as f64);
    let mut any = [[f64::INFINITY; MAX_CLIENTS]; MAX_CLIENTS];
    for (row, b) in any.iter_mut().zip(planes.iter()) {
        for (cell, a) in row.iter_mut().zip(planes.iter()) {
            *cell = bound::arc_bound_any_mps(g, a, b, horizon_s, &bound_settings);
        }
    }
    let mut search = Search {
        g,
        planes,
        count,
        intervals,
        bound: bound_settings,
        max_arcs: settings.max_arcs,
        any,
        plan_arc,
        best: None,
        path: [0; MAX_CLIENTS],
        starts: [0.0; MAX_CLIENTS - 1],
        durations: [0.0; MAX_CLIENTS - 1],
        arcs_planned: 0,
        orders_completed: 0,
        violations: 0,
        stopped: None,
        meter: Meter::new(settings.work_budget),
    };
    // The request's checks, the clients' planes and the matrix of entry bounds.
    search.meter.charge(work_units::SEQUENCE_FIXED);
    // First clients cheapest bound of the whole tour first (ties by number), as children are
    // tried: a search the budget cuts short has then reached the likelier orders.
    let mut firsts = [(0.0_f64, 0_u8); MAX_CLIENTS];
    let mut first_count = 0_usize;
    for start in first.map_or(0..count, |f| f..f.saturating_add(1)) {
        let lb = search.rest_bound(usize::from(start), 1_u16 << start);
        if let Some(slot) = firsts.get_mut(first_count) {
            *slot = (lb, start);
            first_count = first_count.saturating_add(1);
        }
    }
    if let Some(filled) = firsts.get_mut(..first_count) {
        filled.sort_unstable_by(|x, y| x.0.total_cmp(&y.0).then(x.1.cmp(&y.1)));
    }
    for &(_, start) in firsts.iter().take(first_count) {
        if search.stopped.is_some() {
            break;
        }
        if let Some(p) = search.path.first_mut() {
            *p = start;
        }
        search.extend(1, usize::from(start), 0.0, 0.0, 1_u16 << start);
    }
    let first_choices = u32::from(if first.is_some() { 1 } else { count });
    let per_first = factorial(count.saturating_sub(1));
    let orders_total = per_first.saturating_mul(first_choices);
    let arcs_in_tree = tree_arcs(count.saturating_sub(1)).saturating_mul(first_choices);
    out.reset();
    // A refused step (a node or an arc the budget had no room for), or an estimate the
    // callback reports cut by the sequencing's budget (it then exhausts the meter).
    let budget_cut = search.meter.exhausted();
    let status = match search.best {
        Some(b) => {
            out.order = b.order;
            out.len = count;
            out.total_dv_mps = Some(b.total_dv_mps);
            out.starts_s = b.starts_s;
            out.durations_s = b.durations_s;
            if budget_cut {
                SequenceStatus::BudgetExhausted { verified: true }
            } else if search.stopped == Some(Stop::ArcLimit) {
                SequenceStatus::ArcLimit
            } else if search.violations > 0 {
                SequenceStatus::BoundViolated
            } else {
                SequenceStatus::Optimal
            }
        }
        None if budget_cut => SequenceStatus::BudgetExhausted { verified: false },
        None => SequenceStatus::NoOrder {
            arc_limit: search.stopped == Some(Stop::ArcLimit),
        },
    };
    out.info = SequenceInfo {
        status,
        arcs_planned: search.arcs_planned,
        arcs_in_tree,
        orders_completed: search.orders_completed,
        orders_total,
        bound_violations: search.violations,
        work_units: search.meter.used(),
    };
    Ok(())
}

#[cfg(test)]
#[path = "sequence_tests.rs"]
mod tests;
