//! Planner B (impulsive, Wang 2018) as plain C structs: the mean-element problem form. Lengths
//! km, times s, angles rad, impulses m/s.

use crate::status::ReconfigError;
use reconfig_core::capacity::MAX_IMPULSES;

/// Most impulses planner B plans (`capacity::MAX_IMPULSES`).
pub const RECONFIG_B_MAX_IMPULSES: usize = 6;

// A literal so that the header can spell it; the core's capacity decides (see types_a).
const _: () = assert!(RECONFIG_B_MAX_IMPULSES == MAX_IMPULSES);

/// Mean classical orbital elements.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct ReconfigBMeanElements {
    /// Semi-major axis, km.
    pub sma_km: f64,
    /// Eccentricity.
    pub ecc: f64,
    /// Inclination, rad.
    pub inc_rad: f64,
    /// Right ascension of the ascending node, rad.
    pub raan_rad: f64,
    /// Argument of perigee, rad.
    pub argp_rad: f64,
    /// Mean anomaly, rad.
    pub mean_anomaly_rad: f64,
}

/// Deputy-minus-chief mean elements, same order and units.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct ReconfigBRelativeElements {
    /// Delta a, km.
    pub dsma_km: f64,
    /// Delta e.
    pub decc: f64,
    /// Delta i, rad.
    pub dinc_rad: f64,
    /// Delta RAAN, rad.
    pub draan_rad: f64,
    /// Delta argument of perigee, rad.
    pub dargp_rad: f64,
    /// Delta mean anomaly, rad.
    pub dmean_anomaly_rad: f64,
}

/// Mean equinoctial elements (or their difference).
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct ReconfigBEquinoctialElements {
    /// Semi-major axis, km.
    pub sma_km: f64,
    /// Mean longitude, rad.
    pub mean_longitude_rad: f64,
    /// e cos(omega + Omega).
    pub ex: f64,
    /// e sin(omega + Omega).
    pub ey: f64,
    /// tan(i/2) cos Omega.
    pub hx: f64,
    /// tan(i/2) sin Omega.
    pub hy: f64,
}

/// Where one impulse is applied (Wang 2018, eq. 7).
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct ReconfigBImpulsePoint {
    /// Mean argument of latitude at the impulse, rad (mean longitude for an equatorial chief).
    pub arg_latitude_rad: f64,
    /// Whole revolutions since the previous impulse.
    pub revolutions: i32,
}

/// A reconfiguration request in mean elements.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct ReconfigBProblem {
    /// The chief's mean elements at the initial epoch.
    pub chief: ReconfigBMeanElements,
    /// Deputy minus chief at the initial epoch.
    pub initial: ReconfigBRelativeElements,
    /// Deputy minus chief wanted after the last impulse.
    pub target: ReconfigBRelativeElements,
    /// 0: impulses at `points`; 1: search the points for the least total dv.
    pub search: u8,
    /// Impulses: the first `impulse_count` of `points`, or the search's impulse count.
    pub impulse_count: u8,
    /// Search only: limit on the sum of revolution counts.
    pub max_revolutions: i32,
    /// Fixed impulse points (search: unused).
    pub points: [ReconfigBImpulsePoint; RECONFIG_B_MAX_IMPULSES],
}

/// Loop bounds, tolerances and thresholds (`reconfig_core::impulsive::Settings`, same names).
/// Flags are 0 or 1.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct ReconfigBSettings {
    /// Work budget of a solve, work units.
    pub work_budget: u64,
    /// Seed of the search's generator.
    pub search_seed: u64,
    /// Fixed-point convergence tolerance, m/s.
    pub fixed_point_tol_mps: f64,
    /// Joint min-fuel fixed-point tolerance, m/s.
    pub min_fuel_step_tol_mps: f64,
    /// Least-fuel cone program gap tolerance, m/s.
    pub min_fuel_tol_mps: f64,
    /// Accepted terminal error of the nonlinear correction.
    pub correction_tol: f64,
    /// Relative singular-value threshold.
    pub rank_rcond: f64,
    /// Classical set: least eccentricity accepted.
    pub min_eccentricity: f64,
    /// Least |sin i| accepted.
    pub min_sin_inclination: f64,
    /// Lowest perigee altitude accepted, km.
    pub min_perigee_altitude_km: f64,
    /// First pattern step of a local search, rad.
    pub search_step_rad: f64,
    /// Least pattern step of a local search, rad.
    pub search_min_step_rad: f64,
    /// Screening cone-program tolerance, m/s.
    pub search_screen_tol_mps: f64,
    /// Local-search cone-program tolerance, m/s.
    pub search_tol_mps: f64,
    /// Largest sum of revolution counts accepted.
    pub max_total_revolutions: i32,
    /// Random samples of a search.
    pub search_samples: u32,
    /// Most evaluations of a search.
    pub search_max_evaluations: u32,
    /// Most fixed-point iterations per phase.
    pub fixed_point_max_iter: u16,
    /// Most interior-point iterations of one cone program.
    pub min_fuel_max_iter: u16,
    /// Most nonlinear-correction steps.
    pub correction_max_iter: u16,
    /// Most Newton steps for Kepler's equation.
    pub kepler_max_iter: u16,
    /// Most QR steps of one SVD.
    pub svd_max_iter: u16,
    /// Linearisations per local-search evaluation.
    pub search_fixed_point_max_iter: u16,
    /// Local searches of a search.
    pub search_starts: u8,
    /// 1: least-fuel refinement; 0: minimum-norm impulses.
    pub min_fuel: u8,
    /// 1: nonlinear defect correction; 0: the linear model's fixed point.
    pub nonlinear_correction: u8,
    /// 0: classical elements (the paper's set); 1: equinoctial (default).
    pub element_set: u8,
}

/// One planned impulse.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct ReconfigBImpulse {
    /// Time from the initial epoch, s.
    pub time_s: f64,
    /// Mean argument of latitude at the impulse, rad.
    pub arg_latitude_rad: f64,
    /// True argument of latitude at the impulse, rad.
    pub true_arg_latitude_rad: f64,
    /// Velocity change: radial, along-track, normal, m/s.
    pub dv_rtn_mps: [f64; 3],
    /// Whole revolutions since the previous impulse.
    pub revolutions: i32,
}

/// A planner-B result.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct ReconfigBSolution {
    /// The status code the solve returned (`RECONFIG_B_*`, or a refusal).
    pub status: i32,
    /// With `RECONFIG_B_NUMERICAL_FAILURE`: 0 Kepler, 1 SVD, 2 singular state, 3 non-finite.
    pub numerical_stage: i32,
    /// Why the request was refused (all zero when it was not).
    pub error: ReconfigError,
    /// With `RECONFIG_B_UNSAFE_PERIGEE`: the arc (1..N); else 0.
    pub unsafe_arc: i32,
    /// With `RECONFIG_B_UNSAFE_PERIGEE`: its perigee altitude, km; else 0.
    pub unsafe_perigee_altitude_km: f64,
    /// With `RECONFIG_B_LINEARISED`: the position miss of the nonlinear check, m; else 0.
    pub linearised_miss_m: f64,
    /// 1 when the plan may be flown (SOLVED, BUDGET_EXHAUSTED_VERIFIED).
    pub usable: u8,
    /// Impulses in `impulses`.
    pub impulse_count: u8,
    /// Numerical rank of F at the returned plan.
    pub rank: u8,
    /// 1: the min-fuel refinement lowered the total.
    pub min_fuel_used: u8,
    /// 1: the nonlinear correction was applied.
    pub correction_used: u8,
    /// 1: `condition_number` holds a value; 0: absent (F rank-deficient, or not computed).
    pub has_condition_number: u8,
    /// 1: `min_norm_total_dv_mps` holds a value; 0: absent (it came out non-finite).
    pub has_min_norm_total_dv_mps: u8,
    /// 1: `linear_total_dv_mps` holds a value; 0: absent (it came out non-finite).
    pub has_linear_total_dv_mps: u8,
    /// 1: the `terminal_*` fields hold the nonlinear check; 0: absent (the check could not be
    /// flown: a numerical failure), and they are 0.
    pub has_terminal_error: u8,
    /// Fixed-point iterations of the returned plan.
    pub iterations: u16,
    /// Interior-point iterations, all told.
    pub min_fuel_iterations: u16,
    /// Nonlinear-correction steps.
    pub correction_iterations: u16,
    /// Fixed-point solves evaluated.
    pub evaluations: u32,
    /// Work units used.
    pub work_units: u64,
    /// Condition number of F at the returned plan (when `has_condition_number`, else 0).
    pub condition_number: f64,
    /// Certified least-fuel gap, m/s.
    pub min_fuel_gap_mps: f64,
    /// sum |dv_k|, m/s.
    pub total_dv_mps: f64,
    /// Total of the minimum-norm fixed point, m/s (when `has_min_norm_total_dv_mps`, else 0).
    pub min_norm_total_dv_mps: f64,
    /// Total of the linear-model fixed point, m/s (when `has_linear_total_dv_mps`, else 0).
    pub linear_total_dv_mps: f64,
    /// Time of the last impulse, s.
    pub final_time_s: f64,
    /// Nonlinear check: along-track position error at the last impulse, m.
    pub terminal_error_m: f64,
    /// Nonlinear check: position error norm at the last impulse, m.
    pub terminal_position_error_m: f64,
    /// Nonlinear check: achieved minus wanted relative elements.
    pub terminal_error_elements: ReconfigBRelativeElements,
    /// Nonlinear check: achieved minus wanted equinoctial elements.
    pub terminal_error_equinoctial: ReconfigBEquinoctialElements,
    /// The impulses in time order; the first `impulse_count` are used.
    pub impulses: [ReconfigBImpulse; RECONFIG_B_MAX_IMPULSES],
}
