//! Settings, problem, solution and errors of the per-arc rendezvous.

use super::flight::{Flight, Model};
use super::j2::State;
use crate::astro::{Gravity, EARTH_J2, EARTH_MU_KM3_S2, EARTH_RADIUS_KM};
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

/// Settings of the per-arc rendezvous; every loop is bounded by one of them.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct Settings {
    /// Gravitational parameter, km^3/s^2.
    pub mu_km3_s2: f64,
    /// Equatorial radius, km.
    pub re_km: f64,
    /// J2 (unnormalised).
    pub j2: f64,
    /// Largest RK4 step, s.
    pub step_s: f64,
    /// Most RK4 steps of one propagation.
    pub max_steps: u32,
    /// Householder steps of one Lambert solve.
    pub lambert_max_iter: u16,
    /// Lambert tolerance on Izzo's x.
    pub lambert_tol: f64,
    /// Most whole revolutions of a Lambert leg considered.
    pub max_revolutions: u16,
    /// Aim-point iterations of one J2 shooting.
    pub shoot_max_iter: u16,
    /// Arrival miss accepted by the shooting and by the final check, km.
    pub arrival_tol_km: f64,
    /// Points of the coarse grid of the first impulse epoch.
    pub grid_points: u16,
    /// Grid candidates refined locally (at most [`MAX_CANDIDATES`]).
    pub candidates: u8,
    /// Rounds of hops from the best refined plan (its intermediate impulse epochs moved by
    /// half revolutions, refined again); a round that finds nothing better ends them.
    pub hop_rounds: u8,
    /// Cost evaluations of one local refinement.
    pub search_max_evals: u32,
    /// First compass step of an impulse epoch, s.
    pub search_step_s: f64,
    /// First compass step of an impulse component, km/s.
    pub search_step_km_s: f64,
    /// The refinement stops when the epoch step is below this, s.
    pub search_min_step_s: f64,
    /// Least time between two impulses (and before the arrival), s.
    pub min_gap_s: f64,
    /// Work budget (units: one RK4 step = 1 unit, one Lambert solve = 8 units, one flight
    /// of the search model 9 units, one client state of the search model 4 units).
    pub work_budget: u64,
    /// The model of the grid, the local searches and the hops: `MeanElements` (the
    /// first-order J2 theory in closed form, then a polish in the planning model) or
    /// `Planning` (everything in the planning model, the slow reference).
    pub search_model: Model,
    /// Cost evaluations of the planning-model polish of the best search-model plan (and of
    /// a warm start's plan), with `search_model = MeanElements`.
    pub polish_max_evals: u32,
}

impl Default for Settings {
    fn default() -> Self {
        Self {
            mu_km3_s2: EARTH_MU_KM3_S2,
            re_km: EARTH_RADIUS_KM,
            j2: EARTH_J2,
            step_s: 20.0,
            max_steps: 50_000,
            lambert_max_iter: 40,
            lambert_tol: 1e-13,
            max_revolutions: 40,
            shoot_max_iter: 30,
            arrival_tol_km: 1e-6,
            grid_points: 96,
            candidates: 8,
            hop_rounds: 6,
            search_max_evals: 4000,
            search_step_s: 600.0,
            search_step_km_s: 0.02,
            search_min_step_s: 0.5,
            min_gap_s: 60.0,
            work_budget: 400_000_000,
            search_model: Model::MeanElements,
            polish_max_evals: 600,
        }
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

/// What the returned plan is.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[repr(u8)]
pub enum Status {
    /// The plan, flown from scratch in the planning model, arrives within `arrival_tol_km` of
    /// the client with its velocity.
    Solved = 0,
    /// The best plan found misses by more than `arrival_tol_km` (its miss is returned).
    ArrivalMissed = 1,
    /// The work budget stopped the search; the plan returned is checked as for `Solved`.
    BudgetExhaustedSolved = 2,
}

/// A planned arc.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct ArcSolution {
    /// What the plan is.
    pub status: Status,
    /// The burns, `impulses` of them in time order (the rest zero).
    pub burns: [Burn; MAX_IMPULSES],
    /// How many of `burns` are used.
    pub impulses: u8,
    /// Sum of the burn sizes, m/s.
    pub total_dv_mps: f64,
    /// Position miss at arrival when the plan is flown in the planning model, m.
    pub miss_m: f64,
    /// Revolutions of the last Lambert leg.
    pub last_leg_revolutions: u16,
    /// Lambert branch of the last leg (for a re-plan of the same family).
    pub last_leg_branch: crate::lambert::Branch,
    /// Cost evaluations made.
    pub evaluations: u32,
    /// Work units used.
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
    /// `Settings::mu_km3_s2`.
    Mu = 4,
    /// `Settings::re_km`.
    EquatorialRadius = 5,
    /// `Settings::j2`.
    J2 = 6,
    /// `Settings::step_s`.
    Step = 7,
    /// `Settings::max_steps`.
    MaxSteps = 8,
    /// `Settings::lambert_max_iter`.
    LambertMaxIter = 9,
    /// `Settings::lambert_tol`.
    LambertTol = 10,
    /// `Settings::max_revolutions`.
    MaxRevolutions = 11,
    /// `Settings::shoot_max_iter`.
    ShootMaxIter = 12,
    /// `Settings::arrival_tol_km`.
    ArrivalTol = 13,
    /// `Settings::grid_points`.
    GridPoints = 14,
    /// `Settings::candidates`.
    Candidates = 15,
    /// `Settings::search_max_evals`.
    SearchMaxEvals = 16,
    /// `Settings::search_step_s`.
    SearchStep = 17,
    /// `Settings::search_step_km_s`.
    SearchStepKmps = 18,
    /// `Settings::search_min_step_s`.
    SearchMinStep = 19,
    /// `Settings::min_gap_s`.
    MinGap = 20,
    /// `Settings::work_budget`.
    WorkBudget = 21,
    /// `Settings::hop_rounds`.
    HopRounds = 22,
    /// `Settings::polish_max_evals`.
    PolishMaxEvals = 23,
}

impl Field {
    /// The field's name in a request (and a fixture).
    pub const fn name(self) -> &'static str {
        match self {
            Self::From => "from",
            Self::To => "to",
            Self::Duration => "duration_s",
            Self::Impulses => "impulses",
            Self::Mu => "mu_km3_s2",
            Self::EquatorialRadius => "re_km",
            Self::J2 => "j2",
            Self::Step => "step_s",
            Self::MaxSteps => "max_steps",
            Self::LambertMaxIter => "lambert_max_iter",
            Self::LambertTol => "lambert_tol",
            Self::MaxRevolutions => "max_revolutions",
            Self::ShootMaxIter => "shoot_max_iter",
            Self::ArrivalTol => "arrival_tol_km",
            Self::GridPoints => "grid_points",
            Self::Candidates => "candidates",
            Self::SearchMaxEvals => "search_max_evals",
            Self::SearchStep => "search_step_s",
            Self::SearchStepKmps => "search_step_km_s",
            Self::SearchMinStep => "search_min_step_s",
            Self::MinGap => "min_gap_s",
            Self::WorkBudget => "work_budget",
            Self::HopRounds => "hop_rounds",
            Self::PolishMaxEvals => "polish_max_evals",
        }
    }
}

/// Why an arc was not planned.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub enum PlanError {
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
    /// No transfer of the grid reached the client (no Lambert leg converged).
    NoTransfer,
    /// The work budget was spent before any plan was found.
    BudgetExhausted {
        /// Units used.
        used: u64,
        /// The budget.
        budget: u64,
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
            Self::Propagation { field } => write!(
                f,
                "client state `{}` cannot be propagated over the arc",
                field.name()
            ),
            Self::NoTransfer => f.write_str("no transfer of the grid reached the client"),
            Self::BudgetExhausted { used, budget } => write!(
                f,
                "work budget spent before any plan ({used} of {budget} units)"
            ),
        }
    }
}

impl core::error::Error for PlanError {}
