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

/// A plan (or the best so far, with a status saying why), written into caller-owned memory.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Solution {
    /// The impulses in time order.
    pub impulses: heapless::Vec<Impulse, MAX_IMPULSES>,
    /// `sum_k |dv_k|` of `impulses`, m/s.
    pub total_dv_mps: f64,
    /// Total of the minimum-norm fixed point `F^+ dY` (eq. 14) at the same impulse points, m/s.
    pub min_norm_total_dv_mps: f64,
    /// Total of the linear-model fixed point before the nonlinear correction (the min-fuel one
    /// when `info.min_fuel_used`, else equal to `min_norm_total_dv_mps`), m/s.
    pub linear_total_dv_mps: f64,
    /// Time of the last impulse, s.
    pub final_time_s: f64,
    /// Nonlinear check (exact impulses, J2 secular drift): deputy position error at the last
    /// impulse along the target's along-track direction, m.
    pub terminal_error_m: f64,
    /// Nonlinear check: norm of the deputy position error at the last impulse, m.
    pub terminal_position_error_m: f64,
    /// Nonlinear check: achieved minus wanted relative elements at the last impulse (angles
    /// wrapped to `[-pi, pi]`).
    /// In a solve in the equinoctial set these are the differences of the two orbits' classical
    /// elements, whose node and perigee angles are not defined at i = 0 and e = 0 (they are
    /// then 0 on each side): read `terminal_error_equinoctial` there.
    pub terminal_error_elements: RelativeElements,
    /// Nonlinear check: achieved minus wanted equinoctial elements at the last impulse (mean
    /// longitude wrapped to `[-pi, pi]`); regular at e = 0 and i = 0.
    pub terminal_error_equinoctial: EquinoctialElements,
    /// Counters and status.
    pub info: SolveInfo,
}

impl Solution {
    /// An empty solution (status `Unsolved`), for use as an output buffer.
    pub const fn new() -> Self {
        Self {
            impulses: heapless::Vec::new(),
            total_dv_mps: 0.0,
            min_norm_total_dv_mps: 0.0,
            linear_total_dv_mps: 0.0,
            final_time_s: 0.0,
            terminal_error_m: 0.0,
            terminal_position_error_m: 0.0,
            terminal_error_elements: RelativeElements {
                dsma_km: 0.0,
                decc: 0.0,
                dinc_rad: 0.0,
                draan_rad: 0.0,
                dargp_rad: 0.0,
                dmean_anomaly_rad: 0.0,
            },
            terminal_error_equinoctial: EquinoctialElements {
                sma_km: 0.0,
                mean_longitude_rad: 0.0,
                ex: 0.0,
                ey: 0.0,
                hx: 0.0,
                hy: 0.0,
            },
            info: SolveInfo {
                status: SolveStatus::Unsolved,
                iterations: 0,
                min_fuel_iterations: 0,
                correction_iterations: 0,
                rank: 0,
                condition_number: 0.0,
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
