//! The planner-B result: impulses, totals, terminal errors and counters.

use super::status::{SolveInfo, SolveStatus};
use super::types::{EquinoctialElements, RelativeElements};
use crate::capacity::MAX_IMPULSES;
use serde::{Deserialize, Serialize};

/// One planned impulse.
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct Impulse {
    /// Time from the initial epoch, s.
    pub time_s: f64,
    /// The deputy's mean argument of latitude `u = omega + M` at the impulse, rad in `[0, 2 pi)`
    /// (its mean longitude when [`super::point_phase`] says so, for an equatorial chief).
    pub arg_latitude_rad: f64,
    /// The deputy's true argument of latitude `omega + f` at the impulse, rad in `[0, 2 pi)`
    /// (its true longitude for an equatorial chief).
    pub true_arg_latitude_rad: f64,
    /// Whole revolutions since the previous impulse (Wang 2018, eq. 7).
    pub revolutions: i32,
    /// Velocity change in the deputy's local frame: radial (away from Earth), along-track
    /// (in-plane, perpendicular to radial, positive with the motion), normal (along the orbit
    /// angular momentum); m/s.
    pub dv_rtn_mps: [f64; 3],
}

/// The nonlinear check of a plan (exact impulses, J2 secular drift) at its last impulse:
/// achieved minus wanted.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct TerminalError {
    /// Deputy position error along the target's along-track direction, m.
    pub along_track_m: f64,
    /// Norm of the deputy position error, m.
    pub position_m: f64,
    /// Relative elements (angles wrapped to `[-pi, pi]`). In a solve in the equinoctial set
    /// these are the differences of the two orbits' classical elements, whose node and perigee
    /// angles are not defined at i = 0 and e = 0 (they are then 0 on each side): read
    /// `equinoctial` there.
    pub elements: RelativeElements,
    /// Equinoctial elements (mean longitude wrapped to `[-pi, pi]`); regular at e = 0 and
    /// i = 0.
    pub equinoctial: EquinoctialElements,
}

/// A plan (or the best so far, with a status saying why), written into caller-owned memory.
/// Every number is finite whatever the status; a value that does not exist is absent
/// (`None`). A plan whose own numbers came out non-finite is not returned: the status is then
/// `NumericalFailure(NonFinite)` with no impulses (totals and final time 0).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Solution {
    /// The impulses in time order.
    pub impulses: heapless::Vec<Impulse, MAX_IMPULSES>,
    /// `sum_k |dv_k|` of `impulses`, m/s.
    pub total_dv_mps: f64,
    /// Total of the minimum-norm fixed point `F^+ dY` (eq. 14) at the same impulse points, m/s
    /// (absent when it came out non-finite).
    pub min_norm_total_dv_mps: Option<f64>,
    /// Total of the linear-model fixed point before the nonlinear correction (the min-fuel one
    /// when `info.min_fuel_used`, else equal to `min_norm_total_dv_mps`), m/s (absent when it
    /// came out non-finite).
    pub linear_total_dv_mps: Option<f64>,
    /// Time of the last impulse, s.
    pub final_time_s: f64,
    /// The nonlinear check of the returned impulses at the last impulse; absent when the check
    /// could not be flown (a numerical failure: Kepler, a singular state) or gave non-finite
    /// numbers.
    pub terminal_error: Option<TerminalError>,
    /// Counters and status.
    pub info: SolveInfo,
}

impl Solution {
    /// An empty solution (status `Unsolved`), for use as an output buffer.
    pub const fn new() -> Self {
        Self {
            impulses: heapless::Vec::new(),
            total_dv_mps: 0.0,
            min_norm_total_dv_mps: None,
            linear_total_dv_mps: None,
            final_time_s: 0.0,
            terminal_error: None,
            info: SolveInfo {
                status: SolveStatus::Unsolved,
                iterations: 0,
                min_fuel_iterations: 0,
                correction_iterations: 0,
                rank: 0,
                condition_number: None,
                min_fuel_used: false,
                correction_used: false,
                evaluations: 0,
                min_fuel_gap_mps: 0.0,
                work_units: 0,
            },
        }
    }
}

impl Default for Solution {
    fn default() -> Self {
        Self::new()
    }
}
