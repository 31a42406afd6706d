//! Planner B's other input forms: the one place where their C structs become core types and
//! back (the mean-element form is [`crate::convert_b`]'s).

use crate::convert_b::{
    equinoctial_to_c, form_error_to_c, mean_from_c, plan_from_c, relative_from_c, relative_to_c,
};
use crate::status::*;
use crate::types_b::{ReconfigBEquinoctialElements, ReconfigBMeanElements};
use crate::types_b_form::*;
use reconfig_core::impulsive::{
    CartesianState, EndState, EquinoctialElements, FormProblem, MeanElements, OrbitForm,
    RelativeForm, Roe,
};

/// Field code of `relative.form` in `RECONFIG_ERR_INVALID_CODE` refusals.
pub const RECONFIG_FIELD_RELATIVE_FORM: i32 = 30;

fn equinoctial_from_c(c: &ReconfigBEquinoctialElements) -> EquinoctialElements {
    EquinoctialElements {
        sma_km: c.sma_km,
        mean_longitude_rad: c.mean_longitude_rad,
        ex: c.ex,
        ey: c.ey,
        hx: c.hx,
        hy: c.hy,
    }
}

fn state_from_c(c: &ReconfigBCartesianState) -> CartesianState {
    CartesianState {
        pos_km: c.pos_km,
        vel_km_s: c.vel_km_s,
    }
}

fn state_to_c(s: &CartesianState) -> ReconfigBCartesianState {
    ReconfigBCartesianState {
        pos_km: s.pos_km,
        vel_km_s: s.vel_km_s,
    }
}

fn roe_from_c(c: &ReconfigBRoe) -> Roe {
    Roe {
        da_m: c.da_m,
        dlambda_m: c.dlambda_m,
        dex_m: c.dex_m,
        dey_m: c.dey_m,
        dix_m: c.dix_m,
        diy_m: c.diy_m,
    }
}

fn roe_to_c(r: &Roe) -> ReconfigBRoe {
    ReconfigBRoe {
        da_m: r.da_m,
        dlambda_m: r.dlambda_m,
        dex_m: r.dex_m,
        dey_m: r.dey_m,
        dix_m: r.dix_m,
        diy_m: r.diy_m,
    }
}

fn mean_to_c(m: &MeanElements) -> ReconfigBMeanElements {
    ReconfigBMeanElements {
        sma_km: m.sma_km,
        ecc: m.ecc,
        inc_rad: m.inc_rad,
        raan_rad: m.raan_rad,
        argp_rad: m.argp_rad,
        mean_anomaly_rad: m.mean_anomaly_rad,
    }
}

/// The orbit its form code names, or the refusal naming `field` (`RECONFIG_FIELD_CHIEF`,
/// `_DEPUTY_INITIAL` or `_DEPUTY_TARGET`) and the code.
fn orbit_from_c(c: &ReconfigBOrbitForm, field: i32) -> Result<OrbitForm, ReconfigError> {
    match c.form {
        RECONFIG_B_ORBIT_CLASSICAL => Ok(OrbitForm::Classical(mean_from_c(&c.classical))),
        RECONFIG_B_ORBIT_EQUINOCTIAL => {
            Ok(OrbitForm::Equinoctial(equinoctial_from_c(&c.equinoctial)))
        }
        RECONFIG_B_ORBIT_STATE => Ok(OrbitForm::State(state_from_c(&c.state))),
        other => Err(ReconfigError::new(
            RECONFIG_ERR_INVALID_CODE,
            field,
            f64::from(other),
            f64::from(RECONFIG_B_ORBIT_STATE),
        )),
    }
}

/// The core's request from the C struct.
///
/// # Errors
/// A form code outside its set (`RECONFIG_ERR_INVALID_CODE`, the field that holds it), or the
/// plan's refusals as for the mean-element form.
pub fn form_problem_from_c(c: &ReconfigBFormProblem) -> Result<FormProblem, ReconfigError> {
    let r = &c.relative;
    let relative = match r.form {
        RECONFIG_B_RELATIVE_ELEMENTS => RelativeForm::Elements {
            initial: relative_from_c(&r.initial_elements),
            target: relative_from_c(&r.target_elements),
        },
        RECONFIG_B_RELATIVE_ROE => RelativeForm::Roe {
            initial: roe_from_c(&r.initial_roe),
            target: roe_from_c(&r.target_roe),
        },
        RECONFIG_B_RELATIVE_DEPUTY => RelativeForm::Deputy {
            initial: orbit_from_c(&r.initial_orbit, RECONFIG_FIELD_DEPUTY_INITIAL)?,
            target: orbit_from_c(&r.target_orbit, RECONFIG_FIELD_DEPUTY_TARGET)?,
        },
        other => {
            return Err(ReconfigError::new(
                RECONFIG_ERR_INVALID_CODE,
                RECONFIG_FIELD_RELATIVE_FORM,
                f64::from(other),
                f64::from(RECONFIG_B_RELATIVE_DEPUTY),
            ))
        }
    };
    Ok(FormProblem {
        chief: orbit_from_c(&c.chief, RECONFIG_FIELD_CHIEF)?,
        relative,
        plan: plan_from_c(c.search, c.impulse_count, c.max_revolutions, &c.points)?,
    })
}

/// The C end state of the core's.
pub fn end_state_to_c(e: &EndState) -> ReconfigBEndState {
    let empty = ReconfigBEndState::default();
    match e {
        EndState::Elements(r) => ReconfigBEndState {
            form: RECONFIG_B_END_ELEMENTS,
            elements: relative_to_c(r),
            ..empty
        },
        EndState::Roe(r) => ReconfigBEndState {
            form: RECONFIG_B_END_ROE,
            roe: roe_to_c(r),
            ..empty
        },
        EndState::DeputyClassical(m) => ReconfigBEndState {
            form: RECONFIG_B_END_DEPUTY_CLASSICAL,
            classical: mean_to_c(m),
            ..empty
        },
        EndState::DeputyEquinoctial(q) => ReconfigBEndState {
            form: RECONFIG_B_END_DEPUTY_EQUINOCTIAL,
            equinoctial: equinoctial_to_c(q),
            ..empty
        },
        EndState::DeputyState(s) => ReconfigBEndState {
            form: RECONFIG_B_END_DEPUTY_STATE,
            state: state_to_c(s),
            ..empty
        },
        EndState::Unavailable(error) => ReconfigBEndState {
            form: RECONFIG_B_END_UNAVAILABLE,
            unavailable_reason: form_error_to_c(*error).0,
            ..empty
        },
        EndState::NotFlown => ReconfigBEndState {
            form: RECONFIG_B_END_NOT_FLOWN,
            ..empty
        },
    }
}
