//! The hybrid chemical + electric transfer to a libration-point orbit (issue 30,
//! `hybrid::solve`) as plain C structs, in the paper's units (`hybrid::units`: LU the
//! Earth-Moon distance, TU, VU = LU/TU, MU the mass before the impulse) where the core uses
//! them, and days, N, s, km for the engines, the time of flight and the parking orbit.

use reconfig_core::hybrid::trace::MAX_SWITCH_TIMES;

use crate::status::ReconfigError;

/// Switch times a solution carries at most (`hybrid::trace::MAX_SWITCH_TIMES`).
pub const RECONFIG_HYBRID_MAX_SWITCH_TIMES: usize = 32;
/// Components of the state with its mass (`[r, v, m]`) and of its costates (`[lambda_r, lambda_v, lambda_m]`).
pub const RECONFIG_HYBRID_STATE_LEN: usize = 7;

// Literals so that the header can spell them; the core's sizes decide (the conversions assign
// the core's `[f64; 7]` arrays whole, so another length fails to compile there).
const _: () = assert!(RECONFIG_HYBRID_MAX_SWITCH_TIMES == MAX_SWITCH_TIMES);

/// Objective code (`objective`): least propellant at a fixed time of flight (the bang-bang
/// law; `hybrid::Objective::MinFuel`).
pub const RECONFIG_HYBRID_OBJECTIVE_MIN_FUEL: u8 = 0;
/// Objective code: least thrust energy at a fixed time of flight (`MinEnergy`).
pub const RECONFIG_HYBRID_OBJECTIVE_MIN_ENERGY: u8 = 1;
/// Objective code: least time of flight at full thrust (`MinTime`; `duration_days` is the first
/// guess, `cost_multiplier` the start's lambda0; no free kappa or theta).
pub const RECONFIG_HYBRID_OBJECTIVE_MIN_TIME: u8 = 2;

/// Why an integration stopped (`stopped`, with `RECONFIG_HYBRID_INTEGRATION_STOPPED`): the step
/// fell below the resolution of the time (a primary hit).
pub const RECONFIG_HYBRID_STOPPED_STEP_TOO_SMALL: i32 = 0;
/// Why an integration stopped: a derivative was not finite.
pub const RECONFIG_HYBRID_STOPPED_NOT_FINITE: i32 = 1;
/// Why an integration stopped: the bang-bang law switched more often than a propagation allows.
pub const RECONFIG_HYBRID_STOPPED_SWITCH_LIMIT: i32 = 2;

/// A transfer from the circular parking orbit through the chemical impulse to a point of the
/// halo orbit (`hybrid::Problem`, same names), with the costates designed on the ground to start
/// the shooting from.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct ReconfigHybridProblem {
    /// Impulse ratio kappa (speed after / before the impulse), in [1, sqrt(2)).
    pub kappa: f64,
    /// Phase of the impulse on the parking orbit, rad, in [-2 pi, 2 pi].
    pub theta_rad: f64,
    /// Time of flight, days, in [0.1, 100] (for minimum time its first guess).
    pub duration_days: f64,
    /// Largest thrust of the electric engine, N, in [1e-3, 1e3].
    pub thrust_n: f64,
    /// Specific impulse of the electric engine, s, in [100, 1e5].
    pub specific_impulse_s: f64,
    /// Specific impulse of the chemical engine, s, in [50, 1000].
    pub chemical_specific_impulse_s: f64,
    /// Radius of the circular parking orbit about the Earth, km, in [6478, 50000].
    pub parking_radius_km: f64,
    /// Added to the state after the impulse: a navigation update of the departure, position
    /// (LU, at most 0.01), velocity (LU/TU, at most 0.1), mass (MU, at most 0.1); zero for the
    /// planned departure.
    pub departure_offset: [f64; RECONFIG_HYBRID_STATE_LEN],
    /// Arrival position on the halo orbit, LU (rotating frame, barycentric).
    pub arrival_r_lu: [f64; 3],
    /// Arrival velocity, LU/TU.
    pub arrival_v_vu: [f64; 3],
    /// Period of the halo orbit through the arrival point, TU: the request is refused
    /// (`RECONFIG_HYBRID_ERR_NOT_ON_PERIODIC_ORBIT`) when the point does not return to itself
    /// after it to `halo_closure_tol`.
    pub halo_period_tu: f64,
    /// Initial costates to start the shooting from, `[lambda_r, lambda_v, lambda_m]` (the ground's design).
    pub costates: [f64; RECONFIG_HYBRID_STATE_LEN],
    /// The cost multiplier lambda0 of minimum time (at least 0 there); unused by the fixed-time
    /// objectives but must be finite.
    pub cost_multiplier: f64,
    /// The time of flight the start costates were designed for, days (the request's own when
    /// they were designed for it).
    pub design_duration_days: f64,
    /// The thrust the start costates were designed for, N.
    pub design_thrust_n: f64,
    /// `RECONFIG_HYBRID_OBJECTIVE_*`.
    pub objective: u8,
    /// 1: kappa free by its transversality condition (minimum fuel or energy only); 0: fixed.
    pub free_kappa: u8,
    /// 1: theta free by its transversality condition (minimum fuel or energy only); 0: fixed.
    pub free_theta: u8,
}

/// The hybrid planner's settings (`reconfig_core::hybrid::Settings`, same names).
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct ReconfigHybridSettings {
    /// Converged when the shooting residual's largest component is at most this.
    pub tolerance: f64,
    /// `SOLVED` needs the Hamiltonian constant along the flown plan to this.
    pub hamiltonian_tol: f64,
    /// The integrator's relative tolerance per component.
    pub relative_tol: f64,
    /// The integrator's absolute tolerance per component.
    pub absolute_tol: f64,
    /// The arrival point must return to itself after the halo period to this (LU or LU/TU).
    pub halo_closure_tol: f64,
    /// `SOLVED` needs the check flight to reach the arrival to this.
    pub flight_tol: f64,
    /// Step trials of the integrator the whole solve may use; when they run out the solve ends
    /// `RECONFIG_HYBRID_BUDGET_EXHAUSTED_*`.
    pub work_budget: u64,
    /// Newton iterations at most.
    pub max_iterations: u16,
    /// Halvings of a Newton step at most.
    pub max_halvings: u16,
    /// Pieces of the check flight.
    pub check_segments: u16,
    /// Shootings of the walk from the start's design to the request at most (0: no walk).
    pub continuation_steps: u16,
}

/// The plan flown once more from the returned costates (`hybrid::FlownPlan`).
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct ReconfigHybridFlown {
    /// Mass at the arrival, MU (fraction of the mass before the impulse).
    pub final_mass: f64,
    /// Largest component of `[r(t_f) - r_f, v(t_f) - v_f, lambda_m(t_f)]` on this flight.
    pub end_miss: f64,
    /// Largest `|H(t) - H(0)|` over the check flight's pieces and switches.
    pub hamiltonian_drift: f64,
    /// Arcs of full thrust.
    pub thrust_arcs: u32,
    /// Switches of the bang-bang law.
    pub switches: u32,
    /// The first switch times, TU from the departure (`switches` of them at most, the rest 0).
    pub switch_times_tu: [f64; RECONFIG_HYBRID_MAX_SWITCH_TIMES],
}

/// A hybrid transfer (`hybrid::Solution`), or with a status other than SOLVED what could be
/// shown. Every number is finite; an absent value is 0 with its `has_` flag 0.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct ReconfigHybridSolution {
    /// The status code the solve returned (`RECONFIG_HYBRID_*`, or a refusal).
    pub status: i32,
    /// With `RECONFIG_HYBRID_INTEGRATION_STOPPED`: `RECONFIG_HYBRID_STOPPED_*`; else 0.
    pub stopped: i32,
    /// Why the request was refused (all zero when it was not).
    pub error: ReconfigError,
    /// 1 when the plan may be flown (SOLVED, BUDGET_EXHAUSTED_VERIFIED).
    pub usable: u8,
    /// What was minimised (`RECONFIG_HYBRID_OBJECTIVE_*`).
    pub objective: u8,
    /// 1 when `residual` holds a value (the returned costates could be flown).
    pub has_residual: u8,
    /// 1 when `flown` holds the check flight (it was flown to the end).
    pub has_flown: u8,
    /// Shootings of the walk from the design (0: the request's own shooting converged, or no
    /// walk was tried).
    pub walked_shootings: u16,
    /// Newton iterations.
    pub iterations: u32,
    /// Work units used: step trials of every integration, at most `work_budget`.
    pub work_units: u64,
    /// Evaluations of the derivative (with or without the state-transition matrix).
    pub evaluations: u64,
    /// The fraction of the way from the design to the request whose shooting converged last
    /// (1: the request's).
    pub walked_reached: f64,
    /// Impulse ratio kappa.
    pub kappa: f64,
    /// Phase of the impulse, rad.
    pub theta_rad: f64,
    /// Time of flight, TU.
    pub duration_tu: f64,
    /// Initial costates `[lambda_r, lambda_v, lambda_m]` (the converged ones, or the best iterate).
    pub costates: [f64; RECONFIG_HYBRID_STATE_LEN],
    /// lambda0 of minimum time (1 for the fixed-time objectives).
    pub cost_multiplier: f64,
    /// Mass after the chemical impulse, MU.
    pub mass_after_impulse: f64,
    /// Largest component of the shooting residual at the returned costates when
    /// `has_residual`; else 0.
    pub residual: f64,
    /// The check flight when `has_flown`; else all zero.
    pub flown: ReconfigHybridFlown,
}
