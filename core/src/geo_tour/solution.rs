//! The planned tour: legs with their burns, totals, status.

use super::maneuver::{Burn, Direction, Method, MAX_BURNS};
use super::types::MAX_TARGETS;
use serde::{Deserialize, Serialize};

/// How the solve ended. Only `Solved` carries a usable plan; it is returned only after the
/// plan was checked: every burn within the cap, the legs' durations summing to at most the
/// mission time, every number finite.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
pub enum SolveStatus {
    /// No solve has written this solution.
    #[default]
    Unsolved,
    /// The plan meets the mission time and the cap; its total is the least the allocation
    /// found (see the docs for what is exact).
    Solved,
    /// Even the fastest admissible method of every leg overruns the mission time; `leg` is the
    /// leg that needs the most time (index in the sweep's order). `info.fastest_tour_s` says
    /// how long the fastest tour takes.
    MissionTooShort {
        /// Leg index (0 = from the servicer's slot).
        leg: u8,
    },
    /// The tour would fit in the mission time without the cap, but not with it: `leg` is the
    /// leg the cap slows most (or that has no admissible method at all).
    CapTooLow {
        /// Leg index.
        leg: u8,
    },
    /// `MethodPolicy::PaperRule`: the rule's method for `leg` is not admissible (its burns
    /// exceed the cap, or its orbit dips below `min_radius_km`).
    RuleMethodInadmissible {
        /// Leg index.
        leg: u8,
    },
    /// The final check of the plan failed (a burn over the cap, a non-finite number, the
    /// mission time exceeded by rounding); the plan is returned for inspection only.
    CheckFailed {
        /// First leg that failed.
        leg: u8,
    },
}

/// One leg of the tour.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct Leg {
    /// Index of the client in `Problem::targets_lon_rad`.
    pub target_index: u8,
    /// Longitude of the slot the leg leaves, rad in [0, 2 pi).
    pub from_lon_rad: f64,
    /// Longitude of the client, rad in [0, 2 pi).
    pub to_lon_rad: f64,
    /// Phase offset covered, rad, >= 0, in the sweep's direction.
    pub phase_rad: f64,
    /// The method.
    pub method: Method,
    /// Start of the leg after the mission epoch, s.
    pub start_s: f64,
    /// Time allotted to the leg, s: the transfer, then waiting co-located with the client.
    pub duration_s: f64,
    /// From the leg's start to the arrival (last burn), s.
    pub transfer_s: f64,
    /// Waiting after the arrival, co-located with the client, s.
    pub wait_s: f64,
    /// Sum of the leg's burn sizes, m/s.
    pub dv_mps: f64,
    /// Largest burn of the leg, m/s.
    pub max_burn_mps: f64,
    /// Semi-major axis of the intermediate orbit, km (drift orbit, phasing orbit, radial
    /// ellipse, Lambert transfer orbit); 0 for `Method::None`.
    pub orbit_sma_km: f64,
    /// Lambert revolutions (0 otherwise).
    pub revolutions: u16,
    /// Burns; `offset_s` measured from the leg's start.
    pub burns: heapless::Vec<Burn, MAX_BURNS>,
}

/// Counters.
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct SolveInfo {
    /// How it ended.
    pub status: SolveStatus,
    /// Sweep of the returned plan.
    pub direction: Option<Direction>,
    /// Time price at the returned allocation: marginal Δv of one more second, m/s per s
    /// (0 when time does not bind).
    pub price_mps_per_s: f64,
    /// Duration of the fastest admissible tour of this sweep, s.
    pub fastest_tour_s: f64,
    /// Price-search steps used (both sweeps).
    pub price_iterations: u32,
    /// Assignments tried by the duality-gap enumeration.
    pub gap_assignments: u32,
    /// Legs moved by the local Lambert-well refinement.
    pub refined_legs: u8,
}

/// A tour plan (or, with a status other than `Solved`, what could be shown).
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct Solution {
    /// Legs in visiting order.
    pub legs: heapless::Vec<Leg, MAX_TARGETS>,
    /// Sum of all burns, m/s.
    pub total_dv_mps: f64,
    /// Sum of the legs' durations (<= the mission time), s.
    pub mission_time_s: f64,
    /// Largest single burn, m/s.
    pub max_burn_mps: f64,
    /// Counters and status.
    pub info: SolveInfo,
}

impl Solution {
    /// An empty solution (`Unsolved`), for use as an output buffer.
    pub const fn new() -> Self {
        Self {
            legs: heapless::Vec::new(),
            total_dv_mps: 0.0,
            mission_time_s: 0.0,
            max_burn_mps: 0.0,
            info: SolveInfo {
                status: SolveStatus::Unsolved,
                direction: None,
                price_mps_per_s: 0.0,
                fastest_tour_s: 0.0,
                price_iterations: 0,
                gap_assignments: 0,
                refined_legs: 0,
            },
        }
    }
}
