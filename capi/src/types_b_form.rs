//! Planner B's other input forms as plain C structs (`reconfig_impulsive_solve_form`): the chief
//! as classical or equinoctial mean elements or an osculating ECI state; the relative state as
//! element differences, quasi-nonsingular ROE in metres, or the deputy's own orbits; the plan's
//! end state written back in the form the target was given in. A form is a code and one member
//! per form (no unions: every byte is defined); only the member the code names is read.

use crate::types_b::{
    ReconfigBEquinoctialElements, ReconfigBImpulsePoint, ReconfigBMeanElements,
    ReconfigBRelativeElements, ReconfigBSolution, RECONFIG_B_MAX_IMPULSES,
};

/// Orbit form code: classical mean elements (`classical`).
pub const RECONFIG_B_ORBIT_CLASSICAL: u8 = 0;
/// Orbit form code: equinoctial mean elements (`equinoctial`).
pub const RECONFIG_B_ORBIT_EQUINOCTIAL: u8 = 1;
/// Orbit form code: an osculating ECI state (`state`), converted on board by first-order J2
/// averaging.
pub const RECONFIG_B_ORBIT_STATE: u8 = 2;

/// Relative form code: deputy-minus-chief classical mean elements (`*_elements`).
pub const RECONFIG_B_RELATIVE_ELEMENTS: u8 = 0;
/// Relative form code: quasi-nonsingular ROE in metres (`*_roe`).
pub const RECONFIG_B_RELATIVE_ROE: u8 = 1;
/// Relative form code: the deputy's own orbits (`*_orbit`).
pub const RECONFIG_B_RELATIVE_DEPUTY: u8 = 2;

/// End-state form code: relative classical elements (`elements`).
pub const RECONFIG_B_END_ELEMENTS: u8 = 0;
/// End-state form code: ROE, m (`roe`).
pub const RECONFIG_B_END_ROE: u8 = 1;
/// End-state form code: the deputy's orbit, classical mean elements (`classical`).
pub const RECONFIG_B_END_DEPUTY_CLASSICAL: u8 = 2;
/// End-state form code: the deputy's orbit, equinoctial mean elements (`equinoctial`).
pub const RECONFIG_B_END_DEPUTY_EQUINOCTIAL: u8 = 3;
/// End-state form code: the deputy's orbit, osculating ECI state (`state`).
pub const RECONFIG_B_END_DEPUTY_STATE: u8 = 4;
/// End-state form code: the end state could not be written in the form (`unavailable_reason`
/// says why; the plan itself is unaffected, its status says whether it is usable).
pub const RECONFIG_B_END_UNAVAILABLE: u8 = 5;
/// No end state: the plan's nonlinear check could not be flown (a numerical failure).
pub const RECONFIG_B_END_NOT_FLOWN: u8 = 6;

/// Why a form could not be converted (`error.detail` of `RECONFIG_B_ERR_INPUT_FORM`, and
/// `unavailable_reason`): a number is not finite.
pub const RECONFIG_B_FORM_NOT_FINITE: i32 = 0;
/// The state or elements are not an ellipse the equinoctial set covers.
pub const RECONFIG_B_FORM_NOT_AN_ELLIPSE: i32 = 1;
/// Kepler's equation did not converge.
pub const RECONFIG_B_FORM_KEPLER: i32 = 2;
/// The osculating-to-mean inverse did not converge in its bounded steps.
pub const RECONFIG_B_FORM_MEAN_NOT_CONVERGED: i32 = 3;
/// ROE on a chief whose `|sin i|` (`value`) is below `min_sin_inclination` (`limit`).
pub const RECONFIG_B_FORM_ROE_EQUATORIAL_CHIEF: i32 = 4;

/// An ECI state (position km, velocity km/s).
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct ReconfigBCartesianState {
    /// Position, km.
    pub pos_km: [f64; 3],
    /// Velocity, km/s.
    pub vel_km_s: [f64; 3],
}

/// Quasi-nonsingular relative orbital elements, each times the chief's a, in metres.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct ReconfigBRoe {
    /// `a da / a`, m.
    pub da_m: f64,
    /// `a dlambda`, m.
    pub dlambda_m: f64,
    /// `a de_x`, m.
    pub dex_m: f64,
    /// `a de_y`, m.
    pub dey_m: f64,
    /// `a di_x`, m.
    pub dix_m: f64,
    /// `a di_y`, m.
    pub diy_m: f64,
}

/// One orbit in any of the three forms; `form` (`RECONFIG_B_ORBIT_*`) names the member read.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct ReconfigBOrbitForm {
    /// Which member holds the orbit (`RECONFIG_B_ORBIT_*`).
    pub form: u8,
    /// Classical mean elements.
    pub classical: ReconfigBMeanElements,
    /// Equinoctial mean elements.
    pub equinoctial: ReconfigBEquinoctialElements,
    /// Osculating ECI state.
    pub state: ReconfigBCartesianState,
}

/// The relative state in any of its forms; `form` (`RECONFIG_B_RELATIVE_*`) names the pair
/// read.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct ReconfigBRelativeForm {
    /// Which pair holds the state (`RECONFIG_B_RELATIVE_*`).
    pub form: u8,
    /// Element differences at the epoch.
    pub initial_elements: ReconfigBRelativeElements,
    /// Element differences wanted after the last impulse.
    pub target_elements: ReconfigBRelativeElements,
    /// ROE at the epoch, m.
    pub initial_roe: ReconfigBRoe,
    /// ROE wanted after the last impulse, m.
    pub target_roe: ReconfigBRoe,
    /// The deputy's orbit at the epoch.
    pub initial_orbit: ReconfigBOrbitForm,
    /// The deputy's target orbit, referred to the epoch.
    pub target_orbit: ReconfigBOrbitForm,
}

/// A planner-B request with its orbits in the forms the user gave.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct ReconfigBFormProblem {
    /// The chief at the epoch.
    pub chief: ReconfigBOrbitForm,
    /// The deputy relative to the chief (or its own orbits).
    pub relative: ReconfigBRelativeForm,
    /// 0: impulses at `points`; 1: search the points for the least total dv.
    pub search: u8,
    /// Impulses: the first `impulse_count` of `points`, or the search's impulse count.
    pub impulse_count: u8,
    /// Search only: limit on the sum of revolution counts.
    pub max_revolutions: i32,
    /// Fixed impulse points (search: unused).
    pub points: [ReconfigBImpulsePoint; RECONFIG_B_MAX_IMPULSES],
}

/// The plan's end state (the deputy after the last impulse, as flown in the nonlinear check) in
/// the form the target was given in, referred to the chief at the epoch like the target.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct ReconfigBEndState {
    /// Which member holds it (`RECONFIG_B_END_*`).
    pub form: u8,
    /// With `RECONFIG_B_END_UNAVAILABLE`: why (`RECONFIG_B_FORM_*`); else 0.
    pub unavailable_reason: i32,
    /// Achieved relative classical elements.
    pub elements: ReconfigBRelativeElements,
    /// Achieved ROE, m.
    pub roe: ReconfigBRoe,
    /// The deputy's achieved orbit, classical mean elements.
    pub classical: ReconfigBMeanElements,
    /// The deputy's achieved orbit, equinoctial mean elements.
    pub equinoctial: ReconfigBEquinoctialElements,
    /// The deputy's achieved orbit, osculating ECI state.
    pub state: ReconfigBCartesianState,
}

/// A planner-B result for a request in other forms: the plan, and its end state in the
/// request's form (written when `plan.status >= 0`).
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct ReconfigBFormSolution {
    /// The plan, as `reconfig_impulsive_solve` writes it (status, refusal, impulses, figures).
    pub plan: ReconfigBSolution,
    /// The end state in the request's form.
    pub end: ReconfigBEndState,
}
