//! Settings, problem, solution and errors of the per-arc rendezvous.

use super::flight::{Flight, Model};
use super::j2::State;
use crate::astro::{Gravity, EARTH_J2, EARTH_MU_KM3_S2, EARTH_RADIUS_KM};
use crate::contract::{Range, SettingError};
use crate::vec3::Vec3;
use serde::{Deserialize, Serialize};

/// Most impulses per arc (the paper uses three).
pub const MAX_IMPULSES: usize = 4;
/// Free variables of an arc: `M - 1` free impulse epochs and `M - 2` free impulse vectors.
pub const MAX_VARS: usize = (MAX_IMPULSES - 1) + 3 * (MAX_IMPULSES - 2);
/// Candidates kept from the coarse epoch grid for the local refinement.
pub const MAX_CANDIDATES: usize = 8;
/// Hops tried from the best plan per round: each free epoch alone and all together, both ways.
pub const MAX_HOPS: usize = 2 * MAX_IMPULSES;
/// Checkpoints of each client's trajectory (states stored at equal spacing over the arc).
pub const CHECKPOINTS: usize = 64;

crate::settings_table! {
    /// Settings of the per-arc rendezvous; every loop is bounded by one of them. The physical
    /// constants, the first compass steps, the least gap between impulses and the search
    /// model choose the problem or the method (no service limit); the work budget bounds
    /// their cost.
    pub struct Settings;
    /// The LEO arc's settings, by name (stable codes on the wire and in the C interface).
    pub enum SettingId for LeoArc;
    {
        /// Gravitational parameter, km^3/s^2.
        mu_km3_s2, MuKm3S2 = 0: f64 = EARTH_MU_KM3_S2,
        unit "km^3/s^2", range Range::closed(1.0, 1e7), limit Free;
        /// Equatorial radius, km.
        re_km, ReKm = 1: f64 = EARTH_RADIUS_KM,
        unit "km", range Range::closed(0.0, 1e5), limit Free;
        /// J2 (unnormalised).
        j2, J2 = 2: f64 = EARTH_J2,
        unit "", range Range::closed(0.0, 1e-2), limit Free;
        /// Largest RK4 step, s.
        step_s, StepS = 3: f64 = 20.0,
        unit "s", range Range::closed(0.1, 600.0), limit AtMost;
        /// Most RK4 steps of one propagation.
        max_steps, MaxSteps = 4: u32 = 50_000,
        unit "", range Range::closed(1.0, 1e6), limit AtMost;
        /// Householder steps of one Lambert solve.
        lambert_max_iter, LambertMaxIter = 5: u16 = 40,
        unit "", range Range::closed(1.0, 200.0), limit AtMost;
        /// Lambert tolerance on Izzo's x.
        lambert_tol, LambertTol = 6: f64 = 1e-13,
        unit "", range Range::closed(1e-15, 1e-6), limit AtMost;
        /// Most whole revolutions of a Lambert leg considered.
        max_revolutions, MaxRevolutions = 7: u16 = 40,
        unit "", range Range::closed(0.0, 200.0), limit AtMost;
        /// Aim-point iterations of one J2 shooting.
        shoot_max_iter, ShootMaxIter = 8: u16 = 30,
        unit "", range Range::closed(1.0, 100.0), limit AtMost;
        /// Arrival miss accepted by the shooting and by the final check, km.
        arrival_tol_km, ArrivalTolKm = 9: f64 = 1e-6,
        unit "km", range Range::closed(1e-9, 100.0), limit AtMost;
        /// Points of the coarse grid of the first impulse epoch.
        grid_points, GridPoints = 10: u16 = 96,
        unit "", range Range::closed(1.0, 4096.0), limit AtMost;
        /// Grid candidates refined locally (at most [`MAX_CANDIDATES`]).
        candidates, Candidates = 11: u8 = 8,
        unit "", range Range::closed(1.0, MAX_CANDIDATES as f64), limit AtMost;
        /// Rounds of hops from the best refined plan (its intermediate impulse epochs moved by
        /// half revolutions, refined again); a round that finds nothing better ends them.
        hop_rounds, HopRounds = 12: u8 = 6,
        unit "", range Range::closed(0.0, 16.0), limit AtMost;
        /// Cost evaluations of one local refinement.
        search_max_evals, SearchMaxEvals = 13: u32 = 4000,
        unit "", range Range::closed(0.0, 1e6), limit AtMost;
        /// First compass step of an impulse epoch, s.
        search_step_s, SearchStepS = 14: f64 = 600.0,
        unit "s", range Range::closed(0.0, 1e5), limit Free;
        /// First compass step of an impulse component, km/s.
        search_step_km_s, SearchStepKmS = 15: f64 = 0.02,
        unit "km/s", range Range::closed(0.0, 1.0), limit Free;
        /// The refinement stops when the epoch step is below this, s (in a solve, the search
        /// model's at 16 times this: the planning model's polish takes the plan down to it).
        search_min_step_s, SearchMinStepS = 16: f64 = 0.5,
        unit "s", range Range::closed(1e-6, 1e5), limit AtLeast;
        /// Least time between two impulses (and before the arrival), s; at most an eighth of
        /// the arc.
        min_gap_s, MinGapS = 17: f64 = 60.0,
        unit "s", range Range::closed(0.0, 3e6), limit Free;
        /// Work budget, in units of at most `work_units::MAX_INSTRUCTIONS_PER_UNIT` (100)
        /// Cortex-M7 instructions each (`work_units.rs`: every step charged by its dearest
        /// path, proven per kernel on the M7).
        work_budget, WorkBudget = 18: u64 = super::work_units::DEFAULT_WORK_BUDGET,
        unit "units", range Range::closed(1.0, 1e10), limit AtMost;
        /// The model of the grid, the local searches and the hops: `MeanElements` (the
        /// first-order J2 theory in closed form, then a polish in the planning model) or
        /// `Planning` (everything in the planning model, the slow reference).
        search_model, SearchModel = 19: Model = Model::MeanElements,
        unit "", range Range::any(), limit Free;
        /// Cost evaluations of the planning-model polish of the best search-model plan (and of
        /// a warm start's plan), with `search_model = MeanElements`.
        polish_max_evals, PolishMaxEvals = 20: u32 = 600,
        unit "", range Range::closed(0.0, 1e6), limit AtMost;
        /// Lowest altitude a transfer may reach above the equatorial radius, km: each coast
        /// between the first and the last burn at its osculating two-body perigee when it
        /// passes one, else at its lower end (J2 moves a LEO perigee by a few kilometres: keep
        /// a margin). A plan below it is not usable (`SolveStatus::BelowMinAltitude`).
        min_transfer_altitude_km, MinTransferAltitudeKm = 21: f64 = 100.0,
        unit "km", range Range::closed(0.0, 10_000.0), limit AtLeast;
    }
}

impl Settings {
    /// The planning model's constants.
    pub fn gravity(&self) -> Gravity {
        Gravity {
            mu_km3_s2: self.mu_km3_s2,
            re_km: self.re_km,
            j2: self.j2,
        }
    }

    /// Flights in `model` with these settings' constants and step bounds.
    pub fn flight(&self, model: Model) -> Flight {
        Flight {
            g: self.gravity(),
            model,
            step_s: self.step_s,
            max_steps: self.max_steps,
        }
    }
}

/// One arc: the chaser starts on client A's state at the arc start (t = 0) and must be on
/// client B's position and velocity at `duration_s`.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct ArcProblem {
    /// Client A's (the chaser's) inertial state at the arc start, km and km/s.
    pub from: State,
    /// Client B's inertial state at the arc start, km and km/s.
    pub to: State,
    /// Arc duration, s: the last impulse is at this epoch.
    pub duration_s: f64,
    /// Impulses M, 2..=[`MAX_IMPULSES`].
    pub impulses: u8,
}

/// One impulse.
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct Burn {
    /// Epoch from the arc start, s.
    pub epoch_s: f64,
    /// Inertial Δv, km/s.
    pub dv_km_s: Vec3,
    /// Δv in the chaser's RTN frame just before the burn (radial, along-track, normal), m/s.
    pub rtn_mps: Vec3,
}

crate::status_enum! {
    /// How an arc's solve ended (the contract's vocabulary, [`crate::contract::Status`]). The
    /// plan in the solution, when there is one, was flown from scratch in the planning model with
    /// an exact shooting of its last leg; that flight decides the status.
    #[derive(Eq)]
    pub enum SolveStatus {
        /// The plan, flown from scratch in the planning model, arrives within `arrival_tol_km` of
        /// the client with its velocity, its transfer above `min_transfer_altitude_km`.
        Solved = 1,
        /// The best plan found misses by more than `arrival_tol_km` (its miss is returned). Not
        /// usable.
        ArrivalMissed = 2,
        /// The work budget (`work_budget`) stopped the search. With `verified` the returned plan
        /// arrives and stays above `min_transfer_altitude_km` as for `Solved` (usable; a longer
        /// search might find less Δv); without it, the plan returned misses or dips below (its
        /// burns, miss and lowest altitude are returned), or the budget was spent before any
        /// plan (no burns: `impulses == 0`, `miss_m` absent).
        BudgetExhausted {
            /// The returned plan arrives within `arrival_tol_km`.
            verified: bool,
        } = 3,
        /// No transfer of the search reached the client (no Lambert leg converged): no burns.
        NoTransfer = 4,
        /// The best plan found arrives but its transfer dips below `min_transfer_altitude_km`
        /// (its lowest altitude is returned). Not usable.
        BelowMinAltitude = 5,
    }
    usable: [Self::Solved | Self::BudgetExhausted { verified: true }];
    budget: BudgetExhausted;
}

/// How an arc's solve ended and what it cost.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
pub struct SolveInfo {
    /// The status.
    pub status: SolveStatus,
    /// Cost evaluations made.
    pub evaluations: u32,
    /// Work units used (`work_budget`).
    pub work_units: u64,
}

/// A planned arc, or with a status other than `Solved`, what could be shown. Every number is
/// finite whatever the status; a plan with no burns (`impulses == 0`: `NoTransfer`, a budget
/// spent before any plan, `Unsolved`) has zero burns, `total_dv_mps = 0`, no `miss_m` and
/// `last_leg_revolutions = 0` / `last_leg_branch = Left`.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct ArcSolution {
    /// The burns, `impulses` of them in time order (the rest zero).
    pub burns: [Burn; MAX_IMPULSES],
    /// How many of `burns` are used (0 when no plan was found).
    pub impulses: u8,
    /// Sum of the burn sizes, m/s (0 with no burns).
    pub total_dv_mps: f64,
    /// Position miss at arrival when the plan is flown in the planning model, m; absent when
    /// no plan was flown.
    pub miss_m: Option<f64>,
    /// Revolutions of the last Lambert leg.
    pub last_leg_revolutions: u16,
    /// Lambert branch of the last leg (for a re-plan of the same family).
    pub last_leg_branch: crate::lambert::Branch,
    /// The transfer's lowest altitude above the equatorial radius, km
    /// (`min_transfer_altitude_km`); absent when no plan was flown or it is not finite.
    pub lowest_altitude_km: Option<f64>,
    /// The status and the counters.
    pub info: SolveInfo,
}

impl ArcSolution {
    /// The empty `Unsolved` answer (no burns), for use as an output buffer (a `const fn`: it
    /// can sit in a `static`).
    pub const fn new() -> Self {
        const NO_BURN: Burn = Burn {
            epoch_s: 0.0,
            dv_km_s: [0.0; 3],
            rtn_mps: [0.0; 3],
        };
        Self {
            burns: [NO_BURN; MAX_IMPULSES],
            impulses: 0,
            total_dv_mps: 0.0,
            miss_m: None,
            last_leg_revolutions: 0,
            last_leg_branch: crate::lambert::Branch::Left,
            lowest_altitude_km: None,
            info: SolveInfo {
                status: SolveStatus::Unsolved,
                evaluations: 0,
                work_units: 0,
            },
        }
    }

    /// Make this the empty `Unsolved` answer, in place.
    pub fn reset(&mut self) {
        *self = Self::new();
    }
}

impl Default for ArcSolution {
    fn default() -> Self {
        Self::new()
    }
}

/// The sequencing's arc cost ([`super::estimate_arc_mps`]): the Δv of the best plan of the
/// search shot in the search model, or why there is none.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct ArcEstimate {
    /// The estimate, m/s; absent when the search shot no plan (`status` says why).
    pub dv_mps: Option<f64>,
    /// `Solved` (an estimate), `BudgetExhausted { verified }` (the budget stopped the search;
    /// `verified`: an estimate was shot before), `NoTransfer`; with `search_model =
    /// Planning` the planned arc's status (an estimate only when it is usable).
    pub status: SolveStatus,
    /// Work units used (`work_budget`).
    pub work_units: u64,
}

/// A field of the request.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[repr(u8)]
pub enum Field {
    /// `ArcProblem::from`.
    From = 0,
    /// `ArcProblem::to`.
    To = 1,
    /// `ArcProblem::duration_s`.
    Duration = 2,
    /// `ArcProblem::impulses`.
    Impulses = 3,
    /// The perigee altitude of `ArcProblem::from`'s osculating orbit, km.
    FromPerigeeAltitudeKm = 4,
    /// The perigee altitude of `ArcProblem::to`'s osculating orbit, km.
    ToPerigeeAltitudeKm = 5,
}

impl Field {
    /// The field's name in a request (and a fixture).
    pub const fn name(self) -> &'static str {
        match self {
            Self::From => "from",
            Self::To => "to",
            Self::Duration => "duration_s",
            Self::Impulses => "impulses",
            Self::FromPerigeeAltitudeKm => "from (perigee altitude, km)",
            Self::ToPerigeeAltitudeKm => "to (perigee altitude, km)",
        }
    }
}

/// Why an arc was refused before planning (a plan that ends without a transfer is a
/// [`SolveStatus`], not an error).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub enum PlanError {
    /// A setting is out of its range: the setting, the value and the range.
    InvalidSetting(SettingError<SettingId>),
    /// A value is NaN, infinite or outside `[min, max]`.
    OutOfRange {
        /// Which field.
        field: Field,
        /// The value given.
        value: f64,
        /// Least accepted value.
        min: f64,
        /// Largest accepted value.
        max: f64,
    },
    /// A client's trajectory over the arc needs more than `max_steps` RK4 steps per
    /// checkpoint interval or leaves the finite numbers.
    Propagation {
        /// Which client (`From` or `To`).
        field: Field,
    },
}

impl core::fmt::Display for PlanError {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        match *self {
            Self::OutOfRange {
                field,
                value,
                min,
                max,
            } => write!(f, "{} = {value} is outside [{min}, {max}]", field.name()),
            Self::InvalidSetting(e) => write!(f, "{e}"),
            Self::Propagation { field } => write!(
                f,
                "client state `{}` cannot be propagated over the arc",
                field.name()
            ),
        }
    }
}

impl core::error::Error for PlanError {}
