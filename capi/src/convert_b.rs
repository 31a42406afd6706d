//! Planner B: the one place where C structs become core types and back.

use crate::convert_a::flag;
use crate::status::*;
use crate::types_b::*;
use crate::types_b_form::{
    RECONFIG_B_FORM_KEPLER, RECONFIG_B_FORM_MEAN_NOT_CONVERGED, RECONFIG_B_FORM_NOT_AN_ELLIPSE,
    RECONFIG_B_FORM_NOT_FINITE, RECONFIG_B_FORM_ROE_EQUATORIAL_CHIEF,
};
use reconfig_core::capacity::MAX_IMPULSES;
use reconfig_core::impulsive::{
    EquinoctialElements, FormError, FormPart, ImpulsePlan, ImpulsePoint, MeanElements, Orbit,
    PlanError, Problem, Quantity, RelativeElements, SettingId, Settings, Solution, SolveStatus,
    Stage,
};

crate::mirror_settings!(ReconfigBSettings => Settings, SettingId {
    work_budget,
    search_seed,
    fixed_point_tol_mps,
    min_fuel_step_tol_mps,
    min_fuel_tol_mps,
    correction_tol,
    rank_rcond,
    min_eccentricity,
    min_sin_inclination,
    min_perigee_altitude_km,
    search_step_rad,
    search_min_step_rad,
    search_screen_tol_mps,
    search_tol_mps,
    max_total_revolutions,
    search_samples,
    search_max_evaluations,
    fixed_point_max_iter,
    min_fuel_max_iter,
    correction_max_iter,
    kepler_max_iter,
    svd_max_iter,
    search_fixed_point_max_iter,
    search_starts,
    min_fuel,
    nonlinear_correction,
    element_set,
});

pub(crate) fn mean_from_c(c: &ReconfigBMeanElements) -> MeanElements {
    MeanElements {
        sma_km: c.sma_km,
        ecc: c.ecc,
        inc_rad: c.inc_rad,
        raan_rad: c.raan_rad,
        argp_rad: c.argp_rad,
        mean_anomaly_rad: c.mean_anomaly_rad,
    }
}

pub(crate) fn relative_from_c(c: &ReconfigBRelativeElements) -> RelativeElements {
    RelativeElements {
        dsma_km: c.dsma_km,
        decc: c.decc,
        dinc_rad: c.dinc_rad,
        draan_rad: c.draan_rad,
        dargp_rad: c.dargp_rad,
        dmean_anomaly_rad: c.dmean_anomaly_rad,
    }
}

pub(crate) fn relative_to_c(r: &RelativeElements) -> ReconfigBRelativeElements {
    ReconfigBRelativeElements {
        dsma_km: r.dsma_km,
        decc: r.decc,
        dinc_rad: r.dinc_rad,
        draan_rad: r.draan_rad,
        dargp_rad: r.dargp_rad,
        dmean_anomaly_rad: r.dmean_anomaly_rad,
    }
}

pub(crate) fn equinoctial_to_c(e: &EquinoctialElements) -> ReconfigBEquinoctialElements {
    ReconfigBEquinoctialElements {
        sma_km: e.sma_km,
        mean_longitude_rad: e.mean_longitude_rad,
        ex: e.ex,
        ey: e.ey,
        hx: e.hx,
        hy: e.hy,
    }
}

/// The core's problem from the C struct, written into `out` (kept in the caller's workspace).
///
/// # Errors
/// As [`plan_from_c`].
pub fn problem_from_c(c: &ReconfigBProblem, out: &mut Problem) -> Result<(), ReconfigError> {
    out.chief = mean_from_c(&c.chief);
    out.initial = relative_from_c(&c.initial);
    out.target = relative_from_c(&c.target);
    out.plan = plan_from_c(c.search, c.impulse_count, c.max_revolutions, &c.points)?;
    Ok(())
}

/// The core's impulse plan from the C fields every problem form shares: a search (`search` 1)
/// of `impulse_count` impulses, or the first `impulse_count` fixed `points`.
///
/// # Errors
/// Fixed points above the array (the core's capacity), or `search` other than 0 or 1.
pub fn plan_from_c(
    search: u8,
    impulse_count: u8,
    max_revolutions: i32,
    points: &[ReconfigBImpulsePoint; RECONFIG_B_MAX_IMPULSES],
) -> Result<ImpulsePlan, ReconfigError> {
    if flag(search, RECONFIG_FIELD_SEARCH, -1)? {
        return Ok(ImpulsePlan::Search {
            impulses: impulse_count,
            max_revolutions,
        });
    }
    let count = usize::from(impulse_count);
    let over = ReconfigError::new(
        RECONFIG_B_ERR_CAPACITY_EXCEEDED,
        RECONFIG_FIELD_IMPULSE_COUNT,
        f64::from(impulse_count),
        MAX_IMPULSES as f64,
    );
    if count > MAX_IMPULSES {
        return Err(over);
    }
    let mut fixed = heapless::Vec::new();
    for p in points.iter().take(count) {
        // Cannot fail: `count <= MAX_IMPULSES`, the vector's capacity; reported if it did.
        fixed
            .push(ImpulsePoint {
                arg_latitude_rad: p.arg_latitude_rad,
                revolutions: p.revolutions,
            })
            .map_err(|_| over)?;
    }
    Ok(ImpulsePlan::Fixed(fixed))
}

fn orbit_field(orbit: Orbit) -> i32 {
    match orbit {
        Orbit::Chief => RECONFIG_FIELD_CHIEF,
        Orbit::DeputyInitial => RECONFIG_FIELD_DEPUTY_INITIAL,
        Orbit::DeputyTarget => RECONFIG_FIELD_DEPUTY_TARGET,
    }
}

/// Element indices of [`ReconfigBMeanElements`] in refusals.
const ECC: i32 = 1;
const INC: i32 = 2;
const SMA: i32 = 0;

/// The value a `NotFinite { what, index }` or `AngleOutOfRange` refusal names, read back from
/// the core's problem (the request as planned: for another input form, after conversion). The
/// core's index is an element index 0..6 or an impulse index below the count it accepted (its
/// docs), so the `get` always finds it; were it ever outside, the refusal would still carry the
/// core's code, field and index, with value 0.
fn input_value(what: Quantity, index: u8, problem: &Problem) -> (i32, f64) {
    let i = usize::from(index);
    match what {
        Quantity::Chief => {
            let c = &problem.chief;
            let all = [
                c.sma_km,
                c.ecc,
                c.inc_rad,
                c.raan_rad,
                c.argp_rad,
                c.mean_anomaly_rad,
            ];
            (RECONFIG_FIELD_CHIEF, all.get(i).copied().unwrap_or(0.0))
        }
        Quantity::Initial | Quantity::Target => {
            let (field, r) = if what == Quantity::Initial {
                (RECONFIG_FIELD_INITIAL, &problem.initial)
            } else {
                (RECONFIG_FIELD_TARGET, &problem.target)
            };
            let all = [
                r.dsma_km,
                r.decc,
                r.dinc_rad,
                r.draan_rad,
                r.dargp_rad,
                r.dmean_anomaly_rad,
            ];
            (field, all.get(i).copied().unwrap_or(0.0))
        }
        Quantity::ImpulsePoint => (
            RECONFIG_FIELD_IMPULSE_POINT,
            match &problem.plan {
                ImpulsePlan::Fixed(points) => points.get(i).map_or(0.0, |p| p.arg_latitude_rad),
                ImpulsePlan::Search { .. } => 0.0,
            },
        ),
    }
}

/// The C refusal of a core refusal: field, element index, value and limit from the core's
/// variant (the value read back from the request where the core does not carry it: `problem`
/// is the core's problem as planned).
pub fn error_to_c(e: &PlanError, problem: &Problem) -> ReconfigError {
    match *e {
        PlanError::NotFinite { what, index } => {
            let (field, value) = input_value(what, index, problem);
            ReconfigError::new(RECONFIG_B_ERR_NOT_FINITE, field, value, 0.0).at(i32::from(index))
        }
        PlanError::EccentricityTooSmall { orbit, ecc, min } => ReconfigError::new(
            RECONFIG_B_ERR_ECCENTRICITY_TOO_SMALL,
            orbit_field(orbit),
            ecc,
            min,
        )
        .at(ECC),
        PlanError::NotElliptic { orbit, ecc } => {
            ReconfigError::new(RECONFIG_B_ERR_NOT_ELLIPTIC, orbit_field(orbit), ecc, 1.0).at(ECC)
        }
        PlanError::SemiMajorAxisOutOfRange {
            orbit,
            sma_km,
            min_km,
            max_km,
        } => ReconfigError::new(
            RECONFIG_B_ERR_SMA_OUT_OF_RANGE,
            orbit_field(orbit),
            sma_km,
            if sma_km > max_km { max_km } else { min_km },
        )
        .at(SMA),
        PlanError::InclinationSingular {
            orbit,
            sin_inc,
            min,
        } => ReconfigError::new(
            RECONFIG_B_ERR_INCLINATION_SINGULAR,
            orbit_field(orbit),
            sin_inc,
            min,
        )
        .at(INC),
        PlanError::NegativeRevolutions {
            impulse,
            revolutions,
        } => ReconfigError::new(
            RECONFIG_B_ERR_NEGATIVE_REVOLUTIONS,
            RECONFIG_FIELD_REVOLUTIONS,
            f64::from(revolutions),
            0.0,
        )
        .at(i32::from(impulse)),
        PlanError::RevolutionsOverLimit { requested, limit } => ReconfigError::new(
            RECONFIG_B_ERR_REVOLUTIONS_OVER_LIMIT,
            RECONFIG_FIELD_REVOLUTIONS,
            f64::from(requested),
            f64::from(limit),
        ),
        PlanError::CapacityExceeded {
            requested,
            capacity,
        } => ReconfigError::new(
            RECONFIG_B_ERR_CAPACITY_EXCEEDED,
            RECONFIG_FIELD_IMPULSE_COUNT,
            f64::from(requested),
            f64::from(capacity),
        ),
        PlanError::NoImpulses => ReconfigError::new(
            RECONFIG_B_ERR_NO_IMPULSES,
            RECONFIG_FIELD_IMPULSE_COUNT,
            0.0,
            1.0,
        ),
        PlanError::InvalidSetting(s) => setting_error_to_c(&s),
        PlanError::PerigeeTooLow {
            orbit,
            perigee_altitude_km,
            min_km,
        } => ReconfigError::new(
            RECONFIG_B_ERR_PERIGEE_TOO_LOW,
            orbit_field(orbit),
            perigee_altitude_km,
            min_km,
        ),
        PlanError::InclinationOutOfRange { orbit, inc_rad } => ReconfigError::new(
            RECONFIG_B_ERR_INCLINATION_OUT_OF_RANGE,
            orbit_field(orbit),
            inc_rad,
            if inc_rad > 0.0 {
                core::f64::consts::PI
            } else {
                0.0
            },
        )
        .at(INC),
        PlanError::AngleOutOfRange {
            what,
            index,
            value_rad,
            limit_rad,
        } => ReconfigError::new(
            RECONFIG_B_ERR_ANGLE_OUT_OF_RANGE,
            input_value(what, index, problem).0,
            value_rad,
            limit_rad,
        )
        .at(i32::from(index)),
        PlanError::InputForm { part, error } => input_form_error_to_c(part, error),
    }
}

/// The C code of a form error (`RECONFIG_B_FORM_*`) with the value and limit it names (`|sin i|`
/// and its minimum for an equatorial ROE chief, else 0).
pub fn form_error_to_c(e: FormError) -> (i32, f64, f64) {
    match e {
        FormError::NotFinite => (RECONFIG_B_FORM_NOT_FINITE, 0.0, 0.0),
        FormError::NotAnEllipse => (RECONFIG_B_FORM_NOT_AN_ELLIPSE, 0.0, 0.0),
        FormError::Kepler => (RECONFIG_B_FORM_KEPLER, 0.0, 0.0),
        FormError::MeanNotConverged => (RECONFIG_B_FORM_MEAN_NOT_CONVERGED, 0.0, 0.0),
        FormError::RoeEquatorialChief { sin_inc, min } => {
            (RECONFIG_B_FORM_ROE_EQUATORIAL_CHIEF, sin_inc, min)
        }
    }
}

/// The refusal of a request part that could not be converted: `field` the part
/// (`RECONFIG_FIELD_CHIEF`, `_INITIAL`, `_TARGET`), `detail` the form error.
pub fn input_form_error_to_c(part: FormPart, error: FormError) -> ReconfigError {
    let field = match part {
        FormPart::Chief => RECONFIG_FIELD_CHIEF,
        FormPart::Initial => RECONFIG_FIELD_INITIAL,
        FormPart::Target => RECONFIG_FIELD_TARGET,
    };
    let (detail, value, limit) = form_error_to_c(error);
    ReconfigError::new(RECONFIG_B_ERR_INPUT_FORM, field, value, limit).with_detail(detail)
}

/// The C status code of a core status (`status::status_code`), and its payload: (code,
/// numerical stage, unsafe arc, unsafe perigee altitude km, linearised miss m).
pub fn status_to_c(s: SolveStatus) -> (i32, i32, i32, f64, f64) {
    let code = status_code(B_STATUS_BASE, &s);
    match s {
        SolveStatus::NumericalFailure(stage) => (
            code,
            match stage {
                Stage::Kepler => 0,
                Stage::Svd => 1,
                Stage::SingularState => 2,
                Stage::NonFinite => 3,
            },
            0,
            0.0,
            0.0,
        ),
        SolveStatus::UnsafePerigee {
            arc,
            perigee_altitude_km,
        } => (code, 0, i32::from(arc), perigee_altitude_km, 0.0),
        SolveStatus::Linearised { miss_m } => (code, 0, 0, 0.0, miss_m),
        _ => (code, 0, 0, 0.0, 0.0),
    }
}

/// The C solution of the core's solution.
pub fn solution_to_c(s: &Solution) -> ReconfigBSolution {
    let (status, numerical_stage, unsafe_arc, unsafe_perigee_altitude_km, linearised_miss_m) =
        status_to_c(s.info.status);
    let terminal = s.terminal_error.as_ref();
    let mut impulses = [ReconfigBImpulse::default(); RECONFIG_B_MAX_IMPULSES];
    for (slot, i) in impulses.iter_mut().zip(s.impulses.iter()) {
        *slot = ReconfigBImpulse {
            time_s: i.time_s,
            arg_latitude_rad: i.arg_latitude_rad,
            true_arg_latitude_rad: i.true_arg_latitude_rad,
            dv_rtn_mps: i.dv_rtn_mps,
            revolutions: i.revolutions,
        };
    }
    ReconfigBSolution {
        status,
        numerical_stage,
        error: ReconfigError::default(),
        unsafe_arc,
        unsafe_perigee_altitude_km,
        linearised_miss_m,
        usable: u8::from(s.info.status.is_usable()),
        // At most MAX_IMPULSES (6): the vector's capacity.
        impulse_count: u8::try_from(s.impulses.len()).unwrap_or(u8::MAX),
        rank: s.info.rank,
        min_fuel_used: u8::from(s.info.min_fuel_used),
        correction_used: u8::from(s.info.correction_used),
        iterations: s.info.iterations,
        min_fuel_iterations: s.info.min_fuel_iterations,
        correction_iterations: s.info.correction_iterations,
        evaluations: s.info.evaluations,
        work_units: s.info.work_units,
        has_condition_number: u8::from(s.info.condition_number.is_some()),
        has_min_norm_total_dv_mps: u8::from(s.min_norm_total_dv_mps.is_some()),
        has_linear_total_dv_mps: u8::from(s.linear_total_dv_mps.is_some()),
        has_terminal_error: u8::from(terminal.is_some()),
        condition_number: s.info.condition_number.unwrap_or_default(),
        min_fuel_gap_mps: s.info.min_fuel_gap_mps,
        total_dv_mps: s.total_dv_mps,
        min_norm_total_dv_mps: s.min_norm_total_dv_mps.unwrap_or_default(),
        linear_total_dv_mps: s.linear_total_dv_mps.unwrap_or_default(),
        final_time_s: s.final_time_s,
        terminal_error_m: terminal.map_or(0.0, |t| t.along_track_m),
        terminal_position_error_m: terminal.map_or(0.0, |t| t.position_m),
        terminal_error_elements: terminal.map_or_else(ReconfigBRelativeElements::default, |t| {
            relative_to_c(&t.elements)
        }),
        terminal_error_equinoctial: terminal
            .map_or_else(ReconfigBEquinoctialElements::default, |t| {
                equinoctial_to_c(&t.equinoctial)
            }),
        impulses,
    }
}

/// A C solution holding only a refusal.
pub fn refusal_to_c(error: ReconfigError) -> ReconfigBSolution {
    ReconfigBSolution {
        status: error.code,
        error,
        ..ReconfigBSolution::default()
    }
}
