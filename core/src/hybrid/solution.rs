//! The hybrid planner's settings, its status and its answer.

use super::problem::Objective;
use super::trace::MAX_SWITCH_TIMES;
use crate::contract::Range;
use serde::{Deserialize, Serialize};

/// The default work budget, in step trials of the integrator (with or without the
/// state-transition matrix): docs/hybrid.md, "Work budget".
pub const DEFAULT_WORK_BUDGET: u64 = 100_000;

crate::settings_table! {
    /// Loop bounds, tolerances and the work budget of a hybrid solve. Every loop is bounded by
    /// these: at most `max_iterations` Newton iterations, each of one propagation with the
    /// state-transition matrix and at most `max_halvings + 1` without, and all integrations
    /// together at most `work_budget` step trials (docs/hybrid.md, "Work budget").
    pub struct Settings;
    /// The hybrid planner's settings, by name (stable codes on the wire and in the C interface).
    pub enum SettingId for Hybrid;
    {
        /// Newton iterations at most.
        max_iterations, MaxIterations = 0: u16 = 30,
        unit "", range Range::closed(1.0, 500.0), limit AtMost;
        /// Halvings of a Newton step at most, when the full step does not lower the residual.
        max_halvings, MaxHalvings = 1: u16 = 12,
        unit "", range Range::closed(0.0, 60.0), limit AtMost;
        /// Converged when the shooting residual's largest component is at most this (LU, LU/TU
        /// and the costate rows alike).
        tolerance, Tolerance = 2: f64 = 1e-10,
        unit "", range Range::closed(1e-14, 1e-3), limit AtMost;
        /// `Solved` needs the Hamiltonian constant along the flown plan to this.
        hamiltonian_tol, HamiltonianTol = 3: f64 = 1e-10,
        unit "", range Range::closed(1e-14, 1e-3), limit AtMost;
        /// The integrator's relative tolerance per component.
        relative_tol, RelativeTol = 4: f64 = 1e-13,
        unit "", range Range::closed(1e-15, 1e-6), limit AtMost;
        /// The integrator's absolute tolerance per component.
        absolute_tol, AbsoluteTol = 5: f64 = 1e-15,
        unit "", range Range::closed(1e-18, 1e-6), limit AtMost;
        /// The arrival point must return to itself after the halo period to this (largest
        /// component, LU or LU/TU).
        halo_closure_tol, HaloClosureTol = 6: f64 = 1e-6,
        unit "", range Range::closed(1e-12, 1e-2), limit AtMost;
        /// Pieces of the check flight (the Hamiltonian is compared at their ends and at every
        /// switch).
        check_segments, CheckSegments = 7: u16 = 64,
        unit "", range Range::closed(1.0, 4096.0), limit AtMost;
        /// `Solved` needs the check flight (the plan flown again in pieces, so with another
        /// step sequence) to reach the arrival to this: it bounds the integration's own error
        /// at the arrival, which the shooting's residual cannot see.
        flight_tol, FlightTol = 9: f64 = 1e-9,
        unit "", range Range::closed(1e-14, 1e-3), limit AtMost;
        /// Shootings of the walk from the start's design to the request at most, where the
        /// request's own shooting does not converge (0: no walk).
        continuation_steps, ContinuationSteps = 10: u16 = 32,
        unit "", range Range::closed(0.0, 200.0), limit AtMost;
        /// Step trials of the integrator the whole solve may use (the halo check a sixteenth,
        /// the shooting three quarters, the check flight the rest); when they run out the
        /// solve ends `BudgetExhausted`.
        work_budget, WorkBudget = 8: u64 = DEFAULT_WORK_BUDGET,
        unit "units", range Range::closed(100.0, 1e9), limit AtMost;
    }
}

/// Why an integration stopped early (other than the work budget).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[repr(u8)]
pub enum Stopped {
    /// The step fell below the resolution of the time (a primary hit).
    StepTooSmall = 0,
    /// A derivative was not finite.
    NotFinite = 1,
    /// The bang-bang law switched more often than a propagation allows.
    SwitchLimit = 2,
}

crate::status_enum! {
    /// How the solve ended: `#[repr(u8)]` with stable codes. Only `Solved` may be flown: the
    /// shooting converged (residual at most `tolerance`) and the plan flown once more reaches
    /// the arrival to `flight_tol` with the Hamiltonian constant to `hamiltonian_tol`, every
    /// number finite.
    #[derive(Eq)]
    pub enum SolveStatus {
        /// Converged and checked.
        Solved = 1,
        /// The work budget ran out before the shooting converged (or before the check flight
        /// ended); the returned costates are the best iterate. `verified` is false: a plan
        /// that was not shown to reach the arrival is never offered.
        BudgetExhausted {
            /// The returned plan passed the checks of `Solved` (never, today).
            verified: bool,
        } = 2,
        /// `max_iterations` Newton iterations did not converge.
        IterationLimit = 3,
        /// No step along the last Newton direction lowered the residual.
        NoDescent = 4,
        /// The shooting's Jacobian was singular.
        Singular = 5,
        /// A propagation stopped early.
        IntegrationStopped(Stopped) = 6,
        /// The shooting converged but the check flight did not reach the arrival to
        /// `flight_tol`, or the Hamiltonian drifted beyond `hamiltonian_tol`.
        CheckFailed = 7,
    }
    usable: [Self::Solved | Self::BudgetExhausted { verified: true }];
    budget: BudgetExhausted;
}

/// The walk from the start's design to the request (docs/hybrid.md, "On board").
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct Walked {
    /// Shootings of the walk (0: the request's own shooting converged, or no walk was tried).
    pub shootings: u16,
    /// The fraction of the way from the design to the request whose shooting converged last
    /// (1: the request's).
    pub reached: f64,
}

/// Counters.
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct SolveInfo {
    /// How it ended.
    pub status: SolveStatus,
    /// Newton iterations.
    pub iterations: u32,
    /// Step trials of every integration (the halo check, the shooting, the check flight):
    /// the work units, at most `Settings::work_budget`.
    pub work_units: u64,
    /// Evaluations of the derivative (with or without the state-transition matrix).
    pub evaluations: u64,
    /// The walk from the design.
    pub walked: Walked,
}

/// The plan flown once more from the returned costates.
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct FlownPlan {
    /// Mass at the arrival, MU (fraction of the mass before the impulse).
    pub final_mass: f64,
    /// Largest component of `[r(t_f) − r_f, v(t_f) − v_f, λm(t_f)]` on this flight (at most
    /// `Settings::flight_tol` for `Solved`).
    pub end_miss: f64,
    /// Largest `|H(t) − H(0)|` over the check flight's pieces and switches.
    pub hamiltonian_drift: f64,
    /// Arcs of full thrust.
    pub thrust_arcs: u32,
    /// Switches of the bang-bang law.
    pub switches: u32,
    /// The first switch times, TU from the departure (`switches` of them at most; the rest 0).
    pub switch_times_tu: [f64; MAX_SWITCH_TIMES],
}

/// A hybrid transfer (or, with a status that is not usable, what could be shown). Every
/// number is finite whatever the status; what could not be computed is absent.
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct Solution {
    /// Status and counters.
    pub info: SolveInfo,
    /// What was minimised.
    pub objective: Objective,
    /// Impulse ratio κ.
    pub kappa: f64,
    /// Phase of the impulse, rad.
    pub theta_rad: f64,
    /// Time of flight, TU.
    pub duration_tu: f64,
    /// Initial costates `[λr, λv, λm]` (the converged ones, or the best iterate).
    pub costates: [f64; 7],
    /// λ0 of minimum time (1 for the fixed-time objectives, whose costates are scaled by it).
    pub cost_multiplier: f64,
    /// Mass after the chemical impulse, MU.
    pub mass_after_impulse: f64,
    /// Largest component of the shooting residual at the returned costates (absent when they
    /// could not be flown).
    pub residual: Option<f64>,
    /// The check flight (absent when it could not be flown to the end).
    pub flown: Option<FlownPlan>,
}

impl Settings {
    /// The integrator's tolerances of these settings with a bound of `max_steps` step trials
    /// (beyond `u32::MAX`, `u32::MAX`: the integrator counts in `u32`).
    pub fn tolerance(&self, max_steps: u64) -> super::integrate::Tolerance {
        super::integrate::Tolerance {
            relative: self.relative_tol,
            absolute: self.absolute_tol,
            max_steps: u32::try_from(max_steps).unwrap_or(u32::MAX),
        }
    }
}

impl Solution {
    /// The empty `Unsolved` answer.
    pub const fn new() -> Self {
        Self {
            info: SolveInfo {
                status: SolveStatus::Unsolved,
                iterations: 0,
                work_units: 0,
                evaluations: 0,
                walked: Walked {
                    shootings: 0,
                    reached: 0.0,
                },
            },
            objective: Objective::MinFuel,
            kappa: 0.0,
            theta_rad: 0.0,
            duration_tu: 0.0,
            costates: [0.0; 7],
            cost_multiplier: 0.0,
            mass_after_impulse: 0.0,
            residual: None,
            flown: None,
        }
    }
}
