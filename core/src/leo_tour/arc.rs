//! The per-arc search: a coarse grid of the first impulse epoch (two-impulse J2-corrected
//! Lambert transfers, [`super::arc_grid`]), then a bounded compass search over
//! the free impulse epochs and the free impulse vectors from the best grid candidates, with the
//! last leg's J2 correction re-shot each time the compass step halves.
//!
//! Variables, `M` impulses: the epochs `t_1 < ... < t_{M-1}` (the last impulse is pinned to the
//! arrival) and the vectors of the impulses `1..M-2`; impulse `M-1` is the departure of the
//! last leg (a J2-corrected Lambert leg to the client's arrival position) and impulse `M`
//! matches the client's velocity.
//!
//! Worst case: `grid_points x (2 max_revolutions + 1)` Lambert solves and `grid_points` client
//! states; then `candidates x search_max_evals` evaluations, each at most one client state,
//! `M - 2` propagations and one Lambert solve; each re-shooting (at most one per halving,
//! `log2(search_step_s / search_min_step_s) + 1` of them) `shoot_max_iter` propagations; all of
//! it charged to the work budget, which stops the search first when smaller.

use super::altitude;
use super::flight::{Flight, Model};
use super::j2::{join, pos, vel, State};
use super::mean_j2::MeanOrbit;
use super::shoot::{corrected_lambert_from, shoot, Family, Offset, Secant, Shot};
use super::track::Track;
use super::types::{Burn, Settings, MAX_IMPULSES, MAX_VARS};
use super::work_units;
use crate::astro::Gravity;
use crate::indexed::IndexedExt as _;
use crate::lambert::Branch;
use crate::vec3::{add, cross, dot, norm, scale, sub, Vec3};
use crate::work::Meter;

/// Everything one arc's search reads.
pub(crate) struct Ctx<'a> {
    pub settings: &'a Settings,
    pub g: Gravity,
    pub impulses: usize,
    pub tf: f64,
    /// The clients' checkpoints in the planning model, in the caller's workspace (`None` for
    /// an estimate, which never flies in the planning model).
    pub a: Option<&'a Track>,
    pub b: Option<&'a Track>,
    pub b_end: State,
    /// The model of the flights now (the search's, or the planning model's for the polish
    /// and the final check).
    pub flight: Flight,
    /// The clients' mean orbits at the arc start (the search model's client states); `None`
    /// where the conversion failed (the search model then has no client states).
    pub mean_a: Option<MeanOrbit>,
    pub mean_b: Option<MeanOrbit>,
    pub meter: Meter,
    pub evals: u32,
    /// The shootings' quasi-Newton matrix, carried from one shooting to the next of a
    /// refinement (reset at each candidate).
    pub secant: Secant,
    /// The last leg's last Lambert solution (family, Izzo's x): the warm start of the next
    /// solve of that family (the compass search moves a little at a time).
    pub lambert_guess: Option<(Family, f64)>,
    /// Client A's last state asked for (model, epoch bits): the compass search asks for the
    /// same first epoch in most of its evaluations. The flights' constants never change
    /// within an arc (the J2 continuation flies a scaled copy), so model and epoch decide.
    pub start_cache: StartCache,
    /// Each coast of the last plan flown to its last leg ([`Ctx::fly_to_last_leg`]): the
    /// compass search moves one variable at a time, so a move of a later epoch or burn flies
    /// the same earlier coasts again (bit for bit the same inputs, so the same state).
    pub coasts: [Option<Coast>; MAX_IMPULSES],
    /// The search's plans are polished in the planning model after it (a solve, not an
    /// estimate): its compass search in the search model stops at
    /// [`SEARCH_MODEL_MIN_STEP_FACTOR`] `x search_min_step_s`.
    pub polish_follows: bool,
}

/// Client A's last state asked for: ((model, epoch bits), state).
pub(crate) type StartCache = Option<((Model, u64), State)>;

/// One coast flown: its inputs (model, state after the burn, duration) and where it ended.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Coast {
    model: Model,
    start_bits: [u64; 6],
    dt_bits: u64,
    end: State,
}

/// In a solve, the compass search in the search model stops at this multiple of
/// `search_min_step_s` (8 s at the defaults), the planning model's at `search_min_step_s`: the
/// search model is a few m/s from the planning model, whose polish starts from a sixteenth of
/// the first steps (37.5 s), so the search model's finer levels decide nothing the polish
/// keeps. An estimate (no polish after) searches to `search_min_step_s`. Chosen on the
/// tuning seeds of `host/examples/leo_arc_campaign.rs` (8 and 16 against 1; docs/leo-tour.md,
/// "Work budget").
const SEARCH_MODEL_MIN_STEP_FACTOR: f64 = 16.0;

/// Doublings of the step after a compass move that pays (docs/leo-tour.md, "Work budget").
const EXPANSIONS: u8 = 4;

/// One of the arc's two clients.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Client {
    /// Client A: the chaser's start.
    A,
    /// Client B: the rendezvous target.
    B,
}

/// A grid candidate or a refined point.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Point {
    pub x: [f64; MAX_VARS],
    pub fam: Family,
    pub off: Offset,
    pub cost: f64,
    /// Whether `off` is a converged shooting at `x` (so `cost` is the cost of a plan that
    /// arrives, in the model it was shot in).
    pub shot: bool,
    /// The quasi-Newton matrix of the shooting that converged at `x` (the identity when not
    /// shot): the polish's shootings start from it (the two models' Jacobians of the miss
    /// are close), as does the final check.
    pub secant: Secant,
}

impl Point {
    /// The ranking of refined points: shot ones first, then the cheaper.
    pub fn better_than(&self, other: &Self) -> bool {
        (!self.shot, self.cost) < (!other.shot, other.cost)
    }
}

/// A plan flown from scratch in the planning model with an exact shooting of its last leg
/// ([`Ctx::finish`]): what the caller gets, and whether it arrives.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Flown {
    /// The burns, `impulses` of them.
    pub burns: [Burn; MAX_IMPULSES],
    pub impulses: u8,
    /// Sum of the burn sizes, m/s (finite).
    pub total_dv_mps: f64,
    /// Arrival miss, m (finite).
    pub miss_m: f64,
    /// The last leg's family.
    pub fam: Family,
    /// The miss is within `arrival_tol_km`.
    pub arrives: bool,
    /// The transfer's lowest altitude, km (NaN when a coast's state is not finite).
    pub lowest_altitude_km: f64,
    /// The transfer stays at or above `min_transfer_altitude_km` (false for a NaN).
    pub clear: bool,
}

impl Flown {
    /// Usable: it arrives and stays above the least altitude.
    pub fn admissible(&self) -> bool {
        self.arrives && self.clear
    }
}

pub(super) fn families(max_revs: u16) -> impl Iterator<Item = Family> {
    core::iter::once(Family {
        revs: 0,
        branch: Branch::Left,
    })
    .chain((1..=max_revs).flat_map(|revs| {
        [Branch::Left, Branch::Right]
            .into_iter()
            .map(move |branch| Family { revs, branch })
    }))
}

/// The two-body period of `s`, s (0 off an ellipse).
pub(crate) fn period_s(mu: f64, s: &State) -> f64 {
    semi_major_km(mu, s).map_or(0.0, |a| {
        2.0 * core::f64::consts::PI * libm::sqrt(a * a * a / mu)
    })
}

/// The two-body semi-major axis of `s`, km (`None` off an ellipse).
pub(crate) fn semi_major_km(mu: f64, s: &State) -> Option<f64> {
    let v = vel(s);
    let a = 1.0 / (2.0 / norm(&pos(s)) - dot(&v, &v) / mu);
    (a > 0.0 && a.is_finite()).then_some(a)
}

impl Ctx<'_> {
    /// Client `which`'s state at `t_s` in the model of the flights now: from its checkpoints
    /// in the planning model, flown from the arc start in the search model.
    pub(crate) fn client_state(&mut self, which: Client, t_s: f64) -> Option<State> {
        let key = (self.flight.model, t_s.to_bits());
        if which == Client::A {
            if let Some((k, s)) = self.start_cache {
                if k == key {
                    return Some(s);
                }
            }
            let s = self.client_state_flown(which, t_s)?;
            self.start_cache = Some((key, s));
            return Some(s);
        }
        self.client_state_flown(which, t_s)
    }

    fn client_state_flown(&mut self, which: Client, t_s: f64) -> Option<State> {
        let (track, mean) = match which {
            Client::A => (self.a, self.mean_a),
            Client::B => (self.b, self.mean_b),
        };
        match self.flight.model {
            Model::Planning => track?.state_at(&self.flight, t_s, &mut self.meter),
            Model::MeanElements => {
                if !self.meter.spend(work_units::MEAN_STATE) {
                    return None;
                }
                mean?.state_at(&self.g, t_s)
            }
        }
    }

    /// `f` run with the flights in `model`, the model restored after.
    pub(crate) fn in_model<T>(&mut self, model: Model, f: impl FnOnce(&mut Self) -> T) -> T {
        let saved = self.flight.model;
        self.flight.model = model;
        let out = f(self);
        self.flight.model = saved;
        out
    }

    pub(crate) fn nvars(&self) -> usize {
        self.impulses
            .saturating_sub(1)
            .saturating_add(self.impulses.saturating_sub(2).saturating_mul(3))
    }

    /// The epochs of `x` if they are in order with the least gaps, else `None`.
    pub(crate) fn epochs(&self, x: &[f64; MAX_VARS]) -> Option<[f64; MAX_IMPULSES]> {
        let mut t = [self.tf; MAX_IMPULSES];
        let free = self.impulses.saturating_sub(1);
        let mut prev = -self.settings.min_gap_s;
        for (slot, &ti) in t.iter_mut().zip(x.iter()).take(free) {
            if !(ti.is_finite() && ti >= prev + self.settings.min_gap_s) {
                return None;
            }
            // The first impulse may sit at the arc start.
            *slot = ti;
            prev = ti;
        }
        (prev <= self.tf - self.settings.min_gap_s && t.first()? >= &0.0).then_some(t)
    }

    /// Fly `x` to the last leg's departure: (burn k's pre-burn state and Δv for k < M-1, the
    /// state before impulse M-1, the epochs).
    #[allow(clippy::type_complexity)]
    pub(crate) fn fly_to_last_leg(
        &mut self,
        x: &[f64; MAX_VARS],
    ) -> Option<([(State, Vec3); MAX_IMPULSES], State, [f64; MAX_IMPULSES])> {
        // Charged before the epochs are checked: an evaluation refused there still ran.
        if !self.meter.spend(work_units::EVALUATION) {
            return None;
        }
        let t = self.epochs(x)?;
        let t1 = *t.first()?;
        let mut s = self.client_state(Client::A, t1)?;
        let mut pre = [([0.0; 6], [0.0; 3]); MAX_IMPULSES];
        let free_vectors = self.impulses.saturating_sub(2);
        let dvs = x.get(self.impulses.saturating_sub(1)..)?.chunks_exact(3);
        let legs = pre
            .iter_mut()
            .zip(dvs)
            .zip(t.windows(2))
            .zip(self.coasts.iter_mut());
        for (((slot, dv), w), coast) in legs.take(free_vectors) {
            let dv: Vec3 = [*dv.first()?, *dv.get(1)?, *dv.get(2)?];
            *slot = (s, dv);
            let after = join(&pos(&s), &add(&vel(&s), &dv));
            let dt = *w.get(1)? - *w.first()?;
            if !self.meter.spend(work_units::COAST_LOOKUP) {
                return None;
            }
            let start_bits = after.map(f64::to_bits);
            let (model, dt_bits) = (self.flight.model, dt.to_bits());
            s = match coast {
                Some(c) if (c.model, c.start_bits, c.dt_bits) == (model, start_bits, dt_bits) => {
                    c.end
                }
                _ => {
                    let end = self.flight.fly(&after, dt, &mut self.meter)?;
                    *coast = Some(Coast {
                        model,
                        start_bits,
                        dt_bits,
                        end,
                    });
                    end
                }
            };
        }
        Some((pre, s, t))
    }

    /// Cost (km/s) of `x` with the last leg's offset frozen.
    pub(crate) fn cost(&mut self, x: &[f64; MAX_VARS], fam: Family, off: &Offset) -> Option<f64> {
        self.evals = self.evals.saturating_add(1);
        let flown = self.fly_to_last_leg(x)?;
        self.last_leg_cost(&flown, fam, off)
    }

    /// The cost of a plan flown to its last leg (`fly_to_last_leg`'s output) with the last
    /// leg in `fam`, offset frozen.
    #[allow(clippy::type_complexity)]
    fn last_leg_cost(
        &mut self,
        (pre, s, t): &([(State, Vec3); MAX_IMPULSES], State, [f64; MAX_IMPULSES]),
        fam: Family,
        off: &Offset,
    ) -> Option<f64> {
        if !self.meter.spend(work_units::LAST_LEG) {
            return None;
        }
        let t_last = *t.get(self.impulses.checked_sub(2)?)?;
        let guess = self
            .lambert_guess
            .and_then(|(f, x)| (f == fam).then_some(x));
        let (v_dep, v_arr, x) = corrected_lambert_from(
            self.settings,
            s,
            &pos(&self.b_end),
            self.tf - t_last,
            fam,
            off,
            guess,
            &mut self.meter,
        )?;
        self.lambert_guess = Some((fam, x));
        let free: f64 = pre
            .iter()
            .take(self.impulses.saturating_sub(2))
            .map(|(_, dv)| norm(dv))
            .sum();
        let c = free + norm(&sub(&v_dep, &vel(s))) + norm(&sub(&vel(&self.b_end), &v_arr));
        c.is_finite().then_some(c)
    }

    /// The cheapest family of the last leg at `x` (offset frozen): `x` flown once to its last
    /// leg, then one Lambert solve per family (one evaluation).
    pub(crate) fn best_family(
        &mut self,
        x: &[f64; MAX_VARS],
        off: &Offset,
    ) -> Option<(Family, f64)> {
        self.best_family_of(x, off, families(self.settings.max_revolutions))
    }

    /// [`Self::best_family`] among `candidates`.
    pub(crate) fn best_family_of(
        &mut self,
        x: &[f64; MAX_VARS],
        off: &Offset,
        candidates: impl Iterator<Item = Family>,
    ) -> Option<(Family, f64)> {
        self.evals = self.evals.saturating_add(1);
        let flown = self.fly_to_last_leg(x)?;
        let mut best: Option<(Family, f64)> = None;
        for fam in candidates {
            if let Some(c) = self.last_leg_cost(&flown, fam, off) {
                if best.is_none_or(|(_, b)| c < b) {
                    best = Some((fam, c));
                }
            }
            if self.meter.stage_refused() {
                break;
            }
        }
        best
    }

    /// Shoot the last leg from `s` at `t_last` to client B's end position, in `p`'s Lambert
    /// family from `p`'s offset, with the context's quasi-Newton matrix and meter.
    fn shoot_last_leg(&mut self, s: &State, t_last: f64, p: &Point) -> Option<Shot> {
        let target = pos(&self.b_end);
        shoot(
            &self.flight,
            self.settings,
            s,
            &target,
            self.tf - t_last,
            p.fam,
            &p.off,
            &mut self.secant,
            &mut self.meter,
        )
    }

    /// Re-shoot the last leg at `p` (exact J2): `p` with the new offset and its cost, or
    /// `None` when the shooting did not reach `arrival_tol_km`.
    pub(crate) fn reshoot(&mut self, p: &Point) -> Option<Point> {
        let flown = self.fly_to_last_leg(&p.x)?;
        let (_, s, t) = &flown;
        let t_last = *t.get(self.impulses.checked_sub(2)?)?;
        let shot = self.shoot_last_leg(s, t_last, p)?;
        if shot.miss_km > self.settings.arrival_tol_km {
            return None;
        }
        // The plan flown to its last leg once: the shooting and the cost share the flight.
        self.evals = self.evals.saturating_add(1);
        let cost = self.last_leg_cost(&flown, p.fam, &shot.offset)?;
        Some(Point {
            off: shot.offset,
            cost,
            shot: true,
            secant: self.secant,
            ..*p
        })
    }

    /// Bounded compass search from `p` (the search's first steps and budget; the last leg's
    /// family picked again at the start).
    pub fn refine(&mut self, p: Point) -> Point {
        let s = self.settings;
        self.refine_with(
            p,
            (s.search_step_s, s.search_step_km_s),
            s.search_max_evals,
            true,
        )
    }

    /// The polish of a search-model point in the model of the flights now: the compass
    /// search from a sixteenth of the search's first steps, `polish_max_evals` evaluations,
    /// the family kept.
    pub fn polish(&mut self, p: Point) -> Point {
        self.refine_with(
            p,
            self.polish_first_steps(),
            self.settings.polish_max_evals,
            false,
        )
    }

    /// The polish's first steps (an epoch's, s; a burn component's, km/s): a sixteenth of the
    /// search's. Also the descent's scales of its variables (`arc_descent.rs`).
    pub(crate) fn polish_first_steps(&self) -> (f64, f64) {
        let s = self.settings;
        (s.search_step_s / 16.0, s.search_step_km_s / 16.0)
    }

    /// Bounded compass search from `p` with first steps `(epoch s, component km/s)`, at most
    /// `budget` evaluations.
    fn refine_with(
        &mut self,
        p: Point,
        (first_step_s, first_step_km_s): (f64, f64),
        budget: u32,
        pick_family: bool,
    ) -> Point {
        let nv = self.nvars();
        let free = self.impulses.saturating_sub(1);
        // With three or more impulses the last leg's family may change once the intermediate
        // burns exist; pick it again at the start.
        let mut best = Point { shot: false, ..p };
        // A refinement starts its shootings from the identity (the search's results do not
        // depend on the order of its refinements); a polish from the point's own matrix:
        // measured, a third fewer planning-model shooting iterations on Example I's first arc.
        self.secant = if pick_family {
            Secant::default()
        } else {
            p.secant
        };
        if self.impulses > 2 && pick_family {
            if let Some((fam, c)) = self.best_family(&p.x, &p.off) {
                best.fam = fam;
                best.cost = c;
            }
        }
        if let Some(q) = self.reshoot(&best) {
            best = q;
        }
        // The last point whose J2 shooting converged: the search returns there when the
        // frozen offset has led it where no J2 transfer of the family exists.
        let mut anchor = best;
        let mut step_t = first_step_s;
        let mut step_v = first_step_km_s;
        let start_evals = self.evals;
        let min_step_s = match (self.flight.model, self.polish_follows) {
            (Model::MeanElements, true) => {
                self.settings.search_min_step_s * SEARCH_MODEL_MIN_STEP_FACTOR
            }
            _ => self.settings.search_min_step_s,
        };
        'levels: while step_t >= min_step_s {
            let mut improved = true;
            while improved {
                improved = false;
                for i in 0..nv {
                    for sign in [1.0, -1.0] {
                        if self.evals.saturating_sub(start_evals) >= budget
                            || self.meter.stage_refused()
                        {
                            break 'levels;
                        }
                        let mut y = best.x;
                        let h = if i < free { step_t } else { step_v };
                        if let Some(yi) = y.get_mut(i) {
                            *yi += sign * h;
                        }
                        if let Some(c) = self.cost(&y, best.fam, &best.off) {
                            if c < best.cost {
                                best.x = y;
                                best.cost = c;
                                improved = true;
                                // A move that pays is tried again at double the step, up to
                                // `EXPANSIONS` times: the search strides down a long slope
                                // instead of crawling it at the level's step.
                                let mut stride = h;
                                for _ in 0..EXPANSIONS {
                                    if self.evals.saturating_sub(start_evals) >= budget
                                        || self.meter.stage_refused()
                                    {
                                        break;
                                    }
                                    stride *= 2.0;
                                    let mut z = best.x;
                                    if let Some(zi) = z.get_mut(i) {
                                        *zi += sign * stride;
                                    }
                                    match self.cost(&z, best.fam, &best.off) {
                                        Some(c) if c < best.cost => {
                                            best.x = z;
                                            best.cost = c;
                                        }
                                        _ => break,
                                    }
                                }
                            }
                        }
                    }
                }
                // After each sweep that moved, the offset is re-shot at the new point; the move
                // stands only if its exact (J2-shot) cost is below the anchor's.
                if improved {
                    match self.reshoot(&best) {
                        Some(q) if q.better_than(&anchor) => {
                            best = q;
                            anchor = q;
                        }
                        _ => {
                            best = anchor;
                            improved = false;
                        }
                    }
                }
            }
            step_t *= 0.5;
            step_v *= 0.5;
        }
        anchor
    }

    /// Fly `p` in the planning model with an exact J2 shooting of the last leg, and check the
    /// arrival: the plan the caller gets.
    pub(crate) fn finish(&mut self, p: &Point) -> Option<Flown> {
        self.in_model(Model::Planning, |ctx| ctx.finish_in_planning_model(p))
    }

    fn finish_in_planning_model(&mut self, p: &Point) -> Option<Flown> {
        if !self.meter.spend(work_units::FINISH) {
            return None;
        }
        let (pre, s, t) = self.fly_to_last_leg(&p.x)?;
        let last = self.impulses.checked_sub(2)?;
        let t_last = *t.get(last)?;
        self.secant = p.secant;
        let shot = self.shoot_last_leg(&s, t_last, p)?;
        let mut burns = [Burn::default(); MAX_IMPULSES];
        let mut fill = |k: usize, state: &State, dv: Vec3, epoch_s: f64| {
            if let Some(b) = burns.get_mut(k) {
                *b = Burn {
                    epoch_s,
                    dv_km_s: dv,
                    rtn_mps: scale(&rtn(state, &dv), 1e3),
                };
            }
        };
        for (k, ((state, dv), &epoch)) in pre.iter().zip(t.iter()).take(last).indexed() {
            fill(k, state, *dv, epoch);
        }
        fill(last, &s, sub(&shot.v_dep_km_s, &vel(&s)), t_last);
        let v_match = sub(&vel(&self.b_end), &vel(&shot.arrival));
        fill(last.checked_add(1)?, &shot.arrival, v_match, self.tf);
        let total: f64 = burns.iter().map(|b| norm(&b.dv_km_s)).sum::<f64>() * 1e3;
        let miss_m = shot.miss_km * 1e3;
        // Finite below (or no plan): the old `miss > tol` test's complement.
        let arrives = miss_m <= self.settings.arrival_tol_km * 1e3;
        // The transfer's coasts: after each burn before the last leg to the next burn, then the
        // last leg from its departure to the arrival.
        let mu = self.g.mu_km3_s2;
        let coast_ends = pre
            .iter()
            .skip(1)
            .take(last.saturating_sub(1))
            .map(|(st, _)| *st);
        let coasts = pre
            .iter()
            .take(last)
            .zip(coast_ends.chain(core::iter::once(s)))
            .zip(t.windows(2));
        // A NaN anywhere makes the lowest NaN (`f64::min` alone would drop it).
        let lower = |acc: f64, low: f64| {
            if acc.is_nan() || low.is_nan() {
                f64::NAN
            } else {
                acc.min(low)
            }
        };
        let mut lowest_km = f64::INFINITY;
        for (((state, dv), end), w) in coasts {
            let start = join(&pos(state), &add(&vel(state), dv));
            let dt = match w {
                [a, b] => *b - *a,
                _ => f64::NAN,
            };
            lowest_km = lower(lowest_km, altitude::lowest_radius_km(mu, &start, &end, dt));
        }
        let departure = join(&pos(&s), &shot.v_dep_km_s);
        let last_low = altitude::lowest_radius_km(mu, &departure, &shot.arrival, self.tf - t_last);
        lowest_km = lower(lowest_km, last_low);
        let lowest_altitude_km = lowest_km - self.g.re_km;
        let clear = lowest_altitude_km >= self.settings.min_transfer_altitude_km;
        (total.is_finite() && miss_m.is_finite()).then_some(Flown {
            burns,
            impulses: u8::try_from(self.impulses).ok()?,
            total_dv_mps: total,
            miss_m,
            fam: p.fam,
            arrives,
            lowest_altitude_km,
            clear,
        })
    }
}

/// The radial, along-track and normal unit vectors of `state`; `None` for a degenerate state.
pub(crate) fn rtn_axes(state: &State) -> Option<[Vec3; 3]> {
    let r = pos(state);
    let h = cross(&r, &vel(state));
    let rn = norm(&r);
    let hn = norm(&h);
    if rn <= 0.0 || hn <= 0.0 {
        return None;
    }
    let ir = scale(&r, 1.0 / rn);
    let ih = scale(&h, 1.0 / hn);
    Some([ir, cross(&ih, &ir), ih])
}

/// `dv` in the RTN frame of `state`.
pub fn rtn(state: &State, dv: &Vec3) -> Vec3 {
    rtn_axes(state).map_or([0.0; 3], |[ir, it, ih]| {
        [dot(dv, &ir), dot(dv, &it), dot(dv, &ih)]
    })
}
