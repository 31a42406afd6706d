//! Planner A: the one place where C structs become core types and back.

use crate::status::*;
use crate::types_a::*;
use reconfig_core::capacity::MAX_SPACECRAFT;
use reconfig_core::pseudospectral::{
    ActiveConstraint, Boundary, Capacity, PlanError, Problem, Quantity, SettingId, Settings,
    Solution, SolveStatus, Spacecraft, Stage, UnmetConstraint, MAX_MAGNITUDE,
};

/// A C flag (0 or 1) as a bool, or the refusal naming it.
pub(crate) fn flag(value: u8, field: i32, index: i32) -> Result<bool, ReconfigError> {
    match value {
        0 => Ok(false),
        1 => Ok(true),
        _ => Err(
            ReconfigError::new(RECONFIG_ERR_INVALID_CODE, field, f64::from(value), 1.0).at(index),
        ),
    }
}

crate::mirror_settings!(ReconfigASettings => Settings, SettingId {
    work_budget,
    sqp_tol_cost,
    sqp_tol_step_lu,
    qp_tol_feas,
    verify_tol_lu,
    keep_out_margin_lu,
    sqp_max_iter,
    qp_max_iter,
    newton_max_iter,
    refine_max_iter,
    acceleration_memory,
    continuous_verification,
    verify_max_rounds,
});

/// The core's problem from the C struct, written into `out` (kept in the caller's workspace).
///
/// # Errors
/// `spacecraft_count` above the array (the core's capacity), or a flag other than 0 or 1.
pub fn problem_from_c(c: &ReconfigAProblem, out: &mut Problem) -> Result<(), ReconfigError> {
    let count = usize::from(c.spacecraft_count);
    if count > MAX_SPACECRAFT {
        return Err(capacity_error(
            RECONFIG_FIELD_SPACECRAFT_COUNT,
            count,
            MAX_SPACECRAFT,
        ));
    }
    out.horizon_tu = c.horizon_tu;
    out.max_control_fu = c.max_control_fu;
    out.keep_out_lu = c.keep_out_lu;
    out.degree = c.degree;
    out.test_points = flag(c.test_points, RECONFIG_FIELD_TEST_POINTS, -1)?;
    out.spacecraft.clear();
    for sc in c.spacecraft.iter().take(count) {
        let pushed = out.spacecraft.push(Spacecraft {
            mass_mu: sc.mass_mu,
            initial_state: sc.initial_state_lu_lutu,
            final_state: sc.final_state_lu_lutu,
        });
        // Cannot fail: `count <= MAX_SPACECRAFT`, the vector's capacity; reported if it did.
        if pushed.is_err() {
            return Err(capacity_error(
                RECONFIG_FIELD_SPACECRAFT_COUNT,
                count,
                MAX_SPACECRAFT,
            ));
        }
    }
    Ok(())
}

fn capacity_error(field: i32, requested: usize, capacity: usize) -> ReconfigError {
    ReconfigError::new(
        RECONFIG_A_ERR_CAPACITY_EXCEEDED,
        field,
        requested as f64,
        capacity as f64,
    )
}

/// The C refusal of a core refusal: the core's variant picks the code and the field; the value
/// is read back from the request the core refused.
pub fn error_to_c(e: &PlanError, problem: &ReconfigAProblem) -> ReconfigError {
    match *e {
        PlanError::NotFinite {
            what, spacecraft, ..
        } => {
            let (field, value, component) = quantity(what, spacecraft, problem, |v| !v.is_finite());
            ReconfigError::new(RECONFIG_A_ERR_NOT_FINITE, field, value, 0.0)
                .at(i32::from(spacecraft))
                .with_detail(component)
        }
        PlanError::NotPositive {
            what, spacecraft, ..
        } => {
            let (field, value, component) = quantity(what, spacecraft, problem, |v| v <= 0.0);
            ReconfigError::new(RECONFIG_A_ERR_NOT_POSITIVE, field, value, 0.0)
                .at(i32::from(spacecraft))
                .with_detail(component)
        }
        PlanError::OutOfRange {
            what,
            spacecraft,
            limit,
            ..
        } => {
            let (field, value, component) =
                quantity(what, spacecraft, problem, |v| v.abs() > MAX_MAGNITUDE);
            ReconfigError::new(RECONFIG_A_ERR_OUT_OF_RANGE, field, value, limit)
                .at(i32::from(spacecraft))
                .with_detail(component)
        }
        PlanError::CapacityExceeded {
            what,
            requested,
            capacity,
        } => ReconfigError::new(
            RECONFIG_A_ERR_CAPACITY_EXCEEDED,
            match what {
                Capacity::Spacecraft => RECONFIG_FIELD_SPACECRAFT_COUNT,
                Capacity::Degree => RECONFIG_FIELD_DEGREE,
            },
            f64::from(requested),
            f64::from(capacity),
        ),
        PlanError::DegreeTooLow { requested } => ReconfigError::new(
            RECONFIG_A_ERR_DEGREE_TOO_LOW,
            RECONFIG_FIELD_DEGREE,
            f64::from(requested),
            reconfig_core::capacity::MIN_DEGREE as f64,
        ),
        PlanError::NoSpacecraft => ReconfigError::new(
            RECONFIG_A_ERR_NO_SPACECRAFT,
            RECONFIG_FIELD_SPACECRAFT_COUNT,
            0.0,
            1.0,
        ),
        PlanError::BoundaryTooClose {
            first,
            second,
            boundary,
        } => ReconfigError::new(
            RECONFIG_A_ERR_BOUNDARY_TOO_CLOSE,
            RECONFIG_FIELD_SPACECRAFT_PAIR,
            0.0,
            problem.keep_out_lu,
        )
        .at(i32::from(first))
        .and(i32::from(second))
        .with_detail(match boundary {
            Boundary::Initial => 0,
            Boundary::Final => 1,
        }),
        PlanError::ManoeuvreInfeasible { spacecraft, axis } => ReconfigError::new(
            RECONFIG_A_ERR_MANOEUVRE_INFEASIBLE,
            RECONFIG_FIELD_MAX_CONTROL_FU,
            problem.max_control_fu,
            0.0,
        )
        .at(i32::from(spacecraft))
        .with_detail(i32::from(axis)),
        PlanError::InvalidSetting(s) => setting_error_to_c(&s),
        // The C interface has no warm start; kept so that every core refusal maps to a code.
        PlanError::WarmStartMismatch => ReconfigError::new(
            RECONFIG_A_ERR_WARM_START_MISMATCH,
            RECONFIG_FIELD_NONE,
            0.0,
            0.0,
        ),
    }
}

/// Component numbers of a boundary state in refusals: 0..5 initial, 6..11 final (an array, not
/// a counter, so that no overflow check is compiled in).
const COMPONENTS: [i32; 12] = [0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11];

/// The field code, the value and (for a boundary state) the component (0..5 initial, 6..11
/// final) of the quantity a refusal names; `bad` picks the first offending component.
fn quantity(
    what: Quantity,
    spacecraft: u8,
    problem: &ReconfigAProblem,
    bad: impl Fn(f64) -> bool,
) -> (i32, f64, i32) {
    let sc = problem.spacecraft.get(usize::from(spacecraft));
    match what {
        Quantity::Horizon => (RECONFIG_FIELD_HORIZON_TU, problem.horizon_tu, 0),
        Quantity::MaxControl => (RECONFIG_FIELD_MAX_CONTROL_FU, problem.max_control_fu, 0),
        Quantity::KeepOut => (RECONFIG_FIELD_KEEP_OUT_LU, problem.keep_out_lu, 0),
        Quantity::Mass => (RECONFIG_FIELD_MASS_MU, sc.map_or(0.0, |s| s.mass_mu), 0),
        Quantity::BoundaryState => {
            let found = sc.and_then(|s| {
                s.initial_state_lu_lutu
                    .iter()
                    .chain(s.final_state_lu_lutu.iter())
                    .zip(COMPONENTS)
                    .find(|(v, _)| bad(**v))
            });
            match found {
                Some((v, component)) => (RECONFIG_FIELD_BOUNDARY_STATE, *v, component),
                None => (RECONFIG_FIELD_BOUNDARY_STATE, 0.0, -1),
            }
        }
        Quantity::Setting => (RECONFIG_FIELD_SETTINGS, 0.0, 0),
        Quantity::WarmStart => (RECONFIG_FIELD_NONE, 0.0, 0),
    }
}

/// The C status code of a core status (`status::status_code`), and the numerical stage where
/// one applies.
pub fn status_to_c(s: SolveStatus) -> (i32, i32) {
    let stage = match s {
        SolveStatus::NumericalFailure(stage) => match stage {
            Stage::Transcription => 0,
            Stage::Basis => 1,
            Stage::QpFactor => 2,
        },
        _ => 0,
    };
    (status_code(A_STATUS_BASE, &s), stage)
}

/// Write the core's solution into the C one, field by field (no large temporary).
pub fn solution_to_c(s: &Solution, out: &mut ReconfigASolution) {
    let (status, stage) = status_to_c(s.info.status);
    out.status = status;
    out.numerical_stage = stage;
    out.error = ReconfigError::default();
    out.usable = u8::from(s.info.status.is_usable());
    out.spacecraft_count = s.spacecraft_count;
    out.degree = s.degree;
    out.sqp_iterations = s.info.sqp_iterations;
    out.verify_rounds = s.info.verify_rounds;
    out.saddle_escapes = s.info.saddle_escapes;
    out.qp_iterations = s.info.qp_iterations;
    out.work_units = s.info.work_units;
    out.horizon_tu = s.horizon_tu;
    out.cost_fu2_tu = s.cost;
    out.has_min_separation = u8::from(s.min_separation_lu.is_some());
    out.min_separation_lu = s.min_separation_lu.unwrap_or(0.0);
    out.min_separation_time_tu = s.min_separation_time_tu;
    out.min_separation_pair = [s.min_separation_pair.0, s.min_separation_pair.1];
    out.max_dynamics_error = s.max_dynamics_error;
    out.max_violation = s.info.max_violation;
    out.node_times_tu = s.node_times_tu;
    out.states_lu_lutu = s.states;
    out.controls_fu = s.controls_fu;
    out.unmet_count = s.unmet.count;
    out.unmet_truncated = u8::from(s.unmet.truncated);
    out.unmet = [ReconfigAUnmet::default(); RECONFIG_A_MAX_UNMET];
    for (slot, unmet) in out.unmet.iter_mut().zip(s.unmet.named()) {
        *slot = unmet_to_c(unmet);
    }
}

/// One named constraint as the C struct.
fn unmet_to_c(unmet: &UnmetConstraint) -> ReconfigAUnmet {
    let mut c = ReconfigAUnmet {
        shortfall: unmet.shortfall,
        shortfall_rel: unmet.shortfall_rel,
        ..ReconfigAUnmet::default()
    };
    match unmet.constraint {
        ActiveConstraint::KeepOut { pair, time_tu } => {
            c.kind = 0;
            c.pair = [pair.0, pair.1];
            c.time_tu = time_tu;
        }
        ActiveConstraint::Control {
            spacecraft,
            axis,
            node,
            upper,
        } => {
            c.kind = 1;
            c.spacecraft = spacecraft;
            c.axis = axis;
            c.node = node;
            c.upper = u8::from(upper);
        }
    }
    c
}

/// Reset a C solution to "unsolved" with a refusal in it, field by field.
pub fn refusal_to_c(error: ReconfigError, out: &mut ReconfigASolution) {
    out.status = error.code;
    out.numerical_stage = 0;
    out.error = error;
    out.usable = 0;
    out.spacecraft_count = 0;
    out.degree = 0;
    out.sqp_iterations = 0;
    out.verify_rounds = 0;
    out.saddle_escapes = 0;
    out.qp_iterations = 0;
    out.work_units = 0;
    out.horizon_tu = 0.0;
    out.cost_fu2_tu = 0.0;
    out.has_min_separation = 0;
    out.min_separation_lu = 0.0;
    out.min_separation_time_tu = 0.0;
    out.min_separation_pair = [0, 0];
    out.max_dynamics_error = 0.0;
    out.max_violation = 0.0;
    out.node_times_tu.fill(0.0);
    for sc in out.states_lu_lutu.iter_mut() {
        sc.fill([0.0; 6]);
    }
    for sc in out.controls_fu.iter_mut() {
        sc.fill([0.0; 3]);
    }
    out.unmet_count = 0;
    out.unmet_truncated = 0;
    out.unmet = [ReconfigAUnmet::default(); RECONFIG_A_MAX_UNMET];
}
