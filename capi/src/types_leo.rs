//! The LEO tour's per-arc rendezvous (issue 13, `leo_tour::solve_arc`) as plain C structs:
//! inertial states km and km/s, epochs s from the arc start, burns m/s (RTN) and km/s
//! (inertial), altitudes km, the arrival miss m.

use reconfig_core::leo_tour::MAX_IMPULSES;

use crate::status::ReconfigError;

/// Most impulses of one arc (`leo_tour::MAX_IMPULSES`).
pub const RECONFIG_LEO_MAX_IMPULSES: usize = 4;

// A literal so that the header can spell it; the core's capacity decides.
const _: () = assert!(RECONFIG_LEO_MAX_IMPULSES == MAX_IMPULSES);

/// Search-model code (`search_model`): everything in the planning model (two-body + J2 by
/// RK4), the slow reference.
pub const RECONFIG_LEO_MODEL_PLANNING: u8 = 0;
/// Search-model code (`search_model`): the first-order J2 theory in closed form, then a polish
/// in the planning model (the default).
pub const RECONFIG_LEO_MODEL_MEAN_ELEMENTS: u8 = 1;

/// Lambert branch code of the last leg: Izzo's "left" (low-path) solution.
pub const RECONFIG_LEO_BRANCH_LEFT: u8 = 0;
/// Lambert branch code of the last leg: Izzo's "right" solution.
pub const RECONFIG_LEO_BRANCH_RIGHT: u8 = 1;

/// One arc: the chaser starts on client A's state at the arc start (t = 0) and must be on
/// client B's position and velocity at `duration_s` (`leo_tour::ArcProblem`). States are
/// inertial (Earth-centred), at the arc start.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct ReconfigLeoArcProblem {
    /// Client A's (the chaser's) position at the arc start, km.
    pub from_position_km: [f64; 3],
    /// Client A's velocity at the arc start, km/s.
    pub from_velocity_km_s: [f64; 3],
    /// Client B's position at the arc start, km.
    pub to_position_km: [f64; 3],
    /// Client B's velocity at the arc start, km/s.
    pub to_velocity_km_s: [f64; 3],
    /// Arc duration, s: the last impulse is at this epoch.
    pub duration_s: f64,
    /// Impulses, 2 to `RECONFIG_LEO_MAX_IMPULSES`.
    pub impulses: u8,
}

/// The arc search's settings (`reconfig_core::leo_tour::Settings`, same names).
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct ReconfigLeoArcSettings {
    /// Gravitational parameter, km^3/s^2.
    pub mu_km3_s2: f64,
    /// Equatorial radius, km.
    pub re_km: f64,
    /// J2 (unnormalised).
    pub j2: f64,
    /// Largest RK4 step, s.
    pub step_s: f64,
    /// Lambert tolerance on Izzo's x.
    pub lambert_tol: f64,
    /// Arrival miss accepted by the shooting and by the final check, km.
    pub arrival_tol_km: f64,
    /// First compass step of an impulse epoch, s.
    pub search_step_s: f64,
    /// First compass step of an impulse component, km/s.
    pub search_step_km_s: f64,
    /// The refinement stops when the epoch step is below this, s.
    pub search_min_step_s: f64,
    /// Least time between two impulses (and before the arrival), s; at most an eighth of the
    /// arc.
    pub min_gap_s: f64,
    /// Lowest altitude a transfer may reach above the equatorial radius, km.
    pub min_transfer_altitude_km: f64,
    /// Work units a solve may use; the best plan so far is returned, checked, when they run
    /// out (`RECONFIG_LEO_BUDGET_EXHAUSTED_*`).
    pub work_budget: u64,
    /// Most RK4 steps of one propagation.
    pub max_steps: u32,
    /// Cost evaluations of one local refinement.
    pub search_max_evals: u32,
    /// Cost evaluations of the planning-model polish.
    pub polish_max_evals: u32,
    /// Householder steps of one Lambert solve.
    pub lambert_max_iter: u16,
    /// Most whole revolutions of a Lambert leg considered.
    pub max_revolutions: u16,
    /// Aim-point iterations of one J2 shooting.
    pub shoot_max_iter: u16,
    /// Points of the coarse grid of the first impulse epoch.
    pub grid_points: u16,
    /// Grid candidates refined locally.
    pub candidates: u8,
    /// Rounds of hops from the best refined plan.
    pub hop_rounds: u8,
    /// `RECONFIG_LEO_MODEL_*`: the model of the grid, the local searches and the hops.
    pub search_model: u8,
}

/// One impulse of an arc.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct ReconfigLeoBurn {
    /// Epoch from the arc start, s.
    pub epoch_s: f64,
    /// Velocity change in the chaser's RTN frame just before the burn (radial, along-track,
    /// normal), m/s.
    pub dv_rtn_mps: [f64; 3],
    /// Inertial velocity change, km/s.
    pub dv_km_s: [f64; 3],
}

/// A planned arc (`leo_tour::ArcSolution`), or with a status other than SOLVED what could be
/// shown. Every number is finite; an absent value is 0 with its `has_` flag 0.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct ReconfigLeoArcSolution {
    /// The status code the solve returned (`RECONFIG_LEO_*`, or a refusal).
    pub status: i32,
    /// Why the request was refused (all zero when it was not).
    pub error: ReconfigError,
    /// 1 when the plan may be flown (SOLVED, BUDGET_EXHAUSTED_VERIFIED).
    pub usable: u8,
    /// Burns in `burns` (0 when no plan was found).
    pub impulses: u8,
    /// 1 when `miss_m` holds a value (a plan was flown in the planning model).
    pub has_miss_m: u8,
    /// 1 when `lowest_altitude_km` holds a value.
    pub has_lowest_altitude_km: u8,
    /// `RECONFIG_LEO_BRANCH_*` of the last Lambert leg.
    pub last_leg_branch: u8,
    /// Revolutions of the last Lambert leg.
    pub last_leg_revolutions: u16,
    /// Cost evaluations made.
    pub evaluations: u32,
    /// Sum of the burn sizes, m/s (0 with no burns).
    pub total_dv_mps: f64,
    /// Position miss at arrival when the plan is flown in the planning model, m, when
    /// `has_miss_m`; else 0.
    pub miss_m: f64,
    /// The transfer's lowest altitude above the equatorial radius, km, when
    /// `has_lowest_altitude_km`; else 0.
    pub lowest_altitude_km: f64,
    /// Work units used (`work_budget`).
    pub work_units: u64,
    /// The burns in time order; the first `impulses` are used (the rest zero).
    pub burns: [ReconfigLeoBurn; RECONFIG_LEO_MAX_IMPULSES],
}
