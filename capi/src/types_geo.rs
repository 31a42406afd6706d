//! The GEO servicing tour (issue 12) as plain C structs: longitudes rad (Earth-fixed, east
//! positive), times s, burns m/s.

use reconfig_core::geo_tour::{MAX_BURNS, MAX_TARGETS};

use crate::status::ReconfigError;

/// Most clients of one tour (`geo_tour::MAX_TARGETS`).
pub const RECONFIG_GEO_MAX_TARGETS: usize = 16;
/// Most burns of one leg (`geo_tour::MAX_BURNS`).
pub const RECONFIG_GEO_MAX_BURNS: usize = 4;

// Literals so that the header can spell them; the core's capacities decide.
const _: () = assert!(RECONFIG_GEO_MAX_TARGETS == MAX_TARGETS);
const _: () = assert!(RECONFIG_GEO_MAX_BURNS == MAX_BURNS);

/// Sweep code: plan both sweeps and keep the cheaper (east on a tie).
pub const RECONFIG_GEO_SWEEP_CHEAPER: u8 = 0;
/// Sweep code: eastward only.
pub const RECONFIG_GEO_SWEEP_EAST: u8 = 1;
/// Sweep code: westward only.
pub const RECONFIG_GEO_SWEEP_WEST: u8 = 2;

/// Policy code: every method of every leg competes on delta-v under the time price.
pub const RECONFIG_GEO_POLICY_BY_COST: u8 = 0;
/// Policy code: the paper's threshold rule on each leg's phase offset.
pub const RECONFIG_GEO_POLICY_PAPER_RULE: u8 = 1;
/// Policy code: the paper's threshold rule, a Lambert leg's transfer time free (its wells, with
/// the time price) instead of the rule's fixed time.
pub const RECONFIG_GEO_POLICY_PAPER_RULE_FREE_LAMBERT: u8 = 2;

/// Leg method code: the client is in the same slot (no burn).
pub const RECONFIG_GEO_METHOD_NONE: u8 = 0;
/// Leg method code: drift phasing (4 burns).
pub const RECONFIG_GEO_METHOD_DRIFT: u8 = 1;
/// Leg method code: one-revolution Hohmann-type phasing (2 burns).
pub const RECONFIG_GEO_METHOD_HOHMANN: u8 = 2;
/// Leg method code: radial-impulse phasing (2 burns).
pub const RECONFIG_GEO_METHOD_RADIAL: u8 = 3;
/// Leg method code: Lambert transfer (2 burns).
pub const RECONFIG_GEO_METHOD_LAMBERT: u8 = 4;

/// Direction code of the returned sweep: east.
pub const RECONFIG_GEO_DIRECTION_EAST: u8 = 0;
/// Direction code of the returned sweep: west.
pub const RECONFIG_GEO_DIRECTION_WEST: u8 = 1;
/// Direction code: no sweep was returned.
pub const RECONFIG_GEO_DIRECTION_NONE: u8 = 2;

/// A servicing tour request.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct ReconfigGeoProblem {
    /// The servicer's slot: Earth-fixed longitude, rad (east positive).
    pub start_lon_rad: f64,
    /// Time for the whole tour, s.
    pub mission_time_s: f64,
    /// Largest single burn allowed, m/s.
    pub max_burn_mps: f64,
    /// Clients in `targets_lon_rad`.
    pub target_count: u8,
    /// `RECONFIG_GEO_SWEEP_*`.
    pub sweep: u8,
    /// `RECONFIG_GEO_POLICY_*`.
    pub policy: u8,
    /// The clients' slots, rad, in any order; the first `target_count` are used.
    pub targets_lon_rad: [f64; RECONFIG_GEO_MAX_TARGETS],
}

/// Loop bounds, tolerances, the paper's rule and the work budget
/// (`reconfig_core::geo_tour::Settings`, same names).
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct ReconfigGeoSettings {
    /// Lambert tolerance on Izzo's x.
    pub lambert_tol: f64,
    /// The price search stops this close to the mission time, s.
    pub time_tol_s: f64,
    /// Exchange search: first-order effect below which a well is refined, m/s.
    pub exchange_margin_mps: f64,
    /// No intermediate orbit closer to Earth's centre than this, km.
    pub min_radius_km: f64,
    /// Paper's rule: drift above this phase offset, rad.
    pub rule_drift_above_rad: f64,
    /// Paper's rule: one-revolution Hohmann above this, rad.
    pub rule_hohmann_above_rad: f64,
    /// Paper's rule: radial above this, rad; Lambert at or below.
    pub rule_radial_above_rad: f64,
    /// Transfer time of a direct Lambert leg (and of the paper's rule), s.
    pub lambert_direct_time_s: f64,
    /// Work units a solve may use; the best plan so far is returned, checked, when they run
    /// out (`RECONFIG_GEO_BUDGET_EXHAUSTED_*`).
    pub work_budget: u64,
    /// Most whole revolutions of a Lambert transfer.
    pub lambert_max_revolutions: u16,
    /// Householder steps per Lambert solve.
    pub lambert_max_iter: u16,
    /// Golden-section steps per Lambert well.
    pub well_iterations: u16,
    /// Steps of every 1-D root.
    pub root_max_iter: u16,
    /// Steps of the time-price search.
    pub price_max_iter: u16,
    /// Rounds of the exchange search.
    pub exchange_rounds: u16,
    /// Legs switching at the critical price tried both ways.
    pub gap_max_legs: u8,
}

/// One burn of a leg.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct ReconfigGeoBurn {
    /// Time after the leg's start, s.
    pub offset_s: f64,
    /// Velocity change: radial, along-track (eastward), normal, m/s.
    pub dv_rtn_mps: [f64; 3],
}

/// One leg of the tour.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct ReconfigGeoLeg {
    /// Longitude of the slot the leg leaves, rad in [0, 2 pi).
    pub from_lon_rad: f64,
    /// Longitude of the client, rad in [0, 2 pi).
    pub to_lon_rad: f64,
    /// Phase offset covered in the sweep's direction, rad.
    pub phase_rad: f64,
    /// Start of the leg after the mission epoch, s.
    pub start_s: f64,
    /// Time allotted to the leg (transfer, then waiting at the client), s.
    pub duration_s: f64,
    /// From the leg's start to the arrival (last burn), s.
    pub transfer_s: f64,
    /// Waiting after the arrival, s.
    pub wait_s: f64,
    /// Sum of the leg's burn sizes, m/s.
    pub dv_mps: f64,
    /// Largest burn of the leg, m/s.
    pub max_burn_mps: f64,
    /// Semi-major axis of the intermediate orbit, km (0 for no method).
    pub orbit_sma_km: f64,
    /// Lambert revolutions (0 otherwise).
    pub revolutions: u16,
    /// Index of the client in the request's `targets_lon_rad`.
    pub target_index: u8,
    /// `RECONFIG_GEO_METHOD_*`.
    pub method: u8,
    /// Burns in `burns`.
    pub burn_count: u8,
    /// The burns in time order; the first `burn_count` are used.
    pub burns: [ReconfigGeoBurn; RECONFIG_GEO_MAX_BURNS],
}

/// A GEO tour result.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct ReconfigGeoSolution {
    /// The status code the solve returned (`RECONFIG_GEO_*`, or a refusal).
    pub status: i32,
    /// With `MISSION_TOO_SHORT`, `CAP_TOO_LOW`, `RULE_METHOD_INADMISSIBLE`, `CHECK_FAILED`: the
    /// leg the status names (0 = from the servicer's slot); else -1.
    pub status_leg: i32,
    /// Why the request was refused (all zero when it was not).
    pub error: ReconfigError,
    /// 1 when the plan may be flown (SOLVED, BUDGET_EXHAUSTED_VERIFIED).
    pub usable: u8,
    /// 1 when `fastest_tour_s` holds a value: no tour is admissible at all (a leg has no
    /// method within the cap), or the solve stopped before every leg's options were known,
    /// leaves it 0 (and `fastest_tour_s` 0).
    pub has_fastest_tour_s: u8,
    /// `RECONFIG_GEO_DIRECTION_*` of the returned sweep.
    pub direction: u8,
    /// Legs in `legs`.
    pub leg_count: u8,
    /// Legs moved by the local Lambert-well refinement.
    pub refined_legs: u8,
    /// Price-search steps used (both sweeps).
    pub price_iterations: u32,
    /// Assignments tried by the duality-gap enumeration.
    pub gap_assignments: u32,
    /// Sum of all burns, m/s.
    pub total_dv_mps: f64,
    /// Sum of the legs' durations, s.
    pub mission_time_s: f64,
    /// Largest single burn, m/s.
    pub max_burn_mps: f64,
    /// Time price at the returned allocation, m/s per s.
    pub price_mps_per_s: f64,
    /// Duration of the fastest admissible tour of this sweep, s, when `has_fastest_tour_s`;
    /// else 0.
    pub fastest_tour_s: f64,
    /// Work units used (`work_budget`), the final checks included.
    pub work_units: u64,
    /// Legs in visiting order; the first `leg_count` are used.
    pub legs: [ReconfigGeoLeg; RECONFIG_GEO_MAX_TARGETS],
}
