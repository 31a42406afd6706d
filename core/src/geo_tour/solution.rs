//! The planned tour: legs with their burns, totals, status.

use super::maneuver::{Burn, Direction, Method, MAX_BURNS};
use super::types::MAX_TARGETS;
use serde::{Deserialize, Serialize};

crate::status_enum! {
    /// How the solve ended: `#[repr(u8)]` with stable codes (the C interface's status is 200 plus
    /// the code, and 207 for an unverified budget stop). A plan may be flown when
    /// [`SolveStatus::is_usable`]: `Solved`, or `BudgetExhausted { verified: true }`; either is
    /// returned only after the plan was checked: every burn within the cap, the legs' durations
    /// summing to at most the mission time, every number finite.
    #[derive(Eq)]
    pub enum SolveStatus {
        /// The plan meets the mission time and the cap; its total is the least the allocation
        /// found (see the docs for what is exact).
        Solved = 1,
        /// Even the fastest admissible method of every leg overruns the mission time; `leg` is the
        /// leg that needs the most time (index in the sweep's order). `info.fastest_tour_s` says
        /// how long the fastest tour takes (absent when no tour is admissible at all).
        MissionTooShort {
            /// Leg index (0 = from the servicer's slot).
            leg: u8,
        } = 2,
        /// The tour would fit in the mission time without the cap, but not with it: `leg` is the
        /// leg the cap slows most (or that has no admissible method at all).
        CapTooLow {
            /// Leg index.
            leg: u8,
        } = 3,
        /// `MethodPolicy::PaperRule`: the rule's method for `leg` is not admissible (its burns
        /// exceed the cap, or its orbit dips below `min_radius_km`).
        RuleMethodInadmissible {
            /// Leg index.
            leg: u8,
        } = 4,
        /// The final check of the plan failed (a burn over the cap, a non-finite number, the
        /// mission time exceeded by rounding); the plan is returned for inspection only (a number
        /// that came out NaN or infinite is written as 0).
        CheckFailed {
            /// First leg that failed.
            leg: u8,
        } = 5,
        /// The work budget (`Settings::work_budget`) ran out before the method's own end (tables,
        /// price search, gap enumeration, exchange search or the other sweep cut short). The
        /// returned plan is the best one found so far (none when the budget ran out before the
        /// allocation had one), checked like any other with the part of the budget kept for it:
        /// `verified` says whether it met every condition of `Solved` (then it may be flown; a
        /// longer solve might find less Δv).
        BudgetExhausted {
            /// The returned plan passed the checks of `Solved`.
            verified: bool,
        } = 6,
    }
    usable: [Self::Solved | Self::BudgetExhausted { verified: true }];
    budget: BudgetExhausted;
}

impl SolveStatus {
    /// The leg the status names, if any.
    pub const fn leg(&self) -> Option<u8> {
        match *self {
            Self::MissionTooShort { leg }
            | Self::CapTooLow { leg }
            | Self::RuleMethodInadmissible { leg }
            | Self::CheckFailed { leg } => Some(leg),
            Self::Unsolved | Self::Solved | Self::BudgetExhausted { .. } => None,
        }
    }
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
    /// (0 when time does not bind, or when no allocation was made).
    pub price_mps_per_s: f64,
    /// Duration of the fastest admissible tour of this sweep, s; absent when no tour is
    /// admissible (some leg has no method within the cap) or when the solve stopped before
    /// every leg's options were known (a budget stop, a sweep cut short by its bounds).
    pub fastest_tour_s: Option<f64>,
    /// Price-search steps used (both sweeps).
    pub price_iterations: u32,
    /// Assignments tried by the duality-gap enumeration.
    pub gap_assignments: u32,
    /// Legs moved by the local Lambert-well refinement.
    pub refined_legs: u8,
    /// Work units used (`Settings::work_budget`, both sweeps), the final checks included.
    pub work_units: u64,
}

/// A tour plan (or, with a status that is not usable, what could be shown). Every number is
/// finite whatever the status; a value that does not exist is absent (`Option`).
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
                fastest_tour_s: None,
                price_iterations: 0,
                gap_assignments: 0,
                refined_legs: 0,
                work_units: 0,
            },
        }
    }
}

/// Every number of `leg` is finite.
pub(crate) fn leg_is_finite(leg: &Leg) -> bool {
    let numbers = [
        leg.from_lon_rad,
        leg.to_lon_rad,
        leg.phase_rad,
        leg.start_s,
        leg.duration_s,
        leg.transfer_s,
        leg.wait_s,
        leg.dv_mps,
        leg.max_burn_mps,
        leg.orbit_sma_km,
    ];
    numbers.iter().all(|x| x.is_finite())
        && leg
            .burns
            .iter()
            .all(|b| b.offset_s.is_finite() && b.dv_rtn_mps.iter().all(|x| x.is_finite()))
}

/// Write every non-finite number of `out` as 0 (`fastest_tour_s` as absent): a usable plan
/// has none (its checks say so); a plan returned for inspection may.
pub(crate) fn make_finite(out: &mut Solution) {
    fn zero(x: &mut f64) {
        if !x.is_finite() {
            *x = 0.0;
        }
    }
    for leg in &mut out.legs {
        for x in [
            &mut leg.from_lon_rad,
            &mut leg.to_lon_rad,
            &mut leg.phase_rad,
            &mut leg.start_s,
            &mut leg.duration_s,
            &mut leg.transfer_s,
            &mut leg.wait_s,
            &mut leg.dv_mps,
            &mut leg.max_burn_mps,
            &mut leg.orbit_sma_km,
        ] {
            zero(x);
        }
        for b in &mut leg.burns {
            zero(&mut b.offset_s);
            b.dv_rtn_mps.iter_mut().for_each(zero);
        }
    }
    zero(&mut out.total_dv_mps);
    zero(&mut out.mission_time_s);
    zero(&mut out.max_burn_mps);
    zero(&mut out.info.price_mps_per_s);
    out.info.fastest_tour_s = out.info.fastest_tour_s.filter(|x| x.is_finite());
}
