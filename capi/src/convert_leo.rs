//! The LEO arc: the one place where its C structs become core types and back.

use crate::status::*;
use crate::types_leo::*;
use reconfig_core::lambert::Branch;
use reconfig_core::leo_tour::{
    ArcProblem, ArcSolution, Burn, Field, PlanError, SettingId, Settings, SolveStatus,
};

crate::mirror_settings!(ReconfigLeoArcSettings => Settings, SettingId {
    mu_km3_s2,
    re_km,
    j2,
    step_s,
    lambert_tol,
    arrival_tol_km,
    search_step_s,
    search_step_km_s,
    search_min_step_s,
    min_gap_s,
    min_transfer_altitude_km,
    work_budget,
    max_steps,
    search_max_evals,
    polish_max_evals,
    lambert_max_iter,
    max_revolutions,
    shoot_max_iter,
    grid_points,
    candidates,
    hop_rounds,
    search_model,
});

/// `position` then `velocity`: the core's state.
fn state(position: &[f64; 3], velocity: &[f64; 3]) -> [f64; 6] {
    let [x, y, z] = *position;
    let [vx, vy, vz] = *velocity;
    [x, y, z, vx, vy, vz]
}

/// The core's problem from the C struct, written into `out` (kept in the caller's workspace).
/// Every C value has its core value: the core's validation and the limits decide what is
/// refused.
pub fn problem_from_c(c: &ReconfigLeoArcProblem, out: &mut ArcProblem) {
    out.from = state(&c.from_position_km, &c.from_velocity_km_s);
    out.to = state(&c.to_position_km, &c.to_velocity_km_s);
    out.duration_s = c.duration_s;
    out.impulses = c.impulses;
}

fn field_to_c(field: Field) -> i32 {
    match field {
        Field::From => RECONFIG_FIELD_LEO_FROM,
        Field::To => RECONFIG_FIELD_LEO_TO,
        Field::Duration => RECONFIG_FIELD_LEO_DURATION,
        Field::Impulses => RECONFIG_FIELD_LEO_IMPULSES,
        Field::FromPerigeeAltitudeKm => RECONFIG_FIELD_LEO_FROM_PERIGEE_ALTITUDE,
        Field::ToPerigeeAltitudeKm => RECONFIG_FIELD_LEO_TO_PERIGEE_ALTITUDE,
    }
}

/// The C refusal of a core refusal: the field, the value, which end of the range it broke
/// (`detail`) and that end (`limit`); a setting as every planner's (named by its code).
pub fn error_to_c(e: &PlanError) -> ReconfigError {
    match *e {
        PlanError::OutOfRange {
            field,
            value,
            min,
            max,
        } => {
            let (detail, limit) = range_break(value, min, max, false);
            ReconfigError::new(
                RECONFIG_LEO_ERR_OUT_OF_RANGE,
                field_to_c(field),
                value,
                limit,
            )
            .with_detail(detail)
        }
        PlanError::Propagation { field } => {
            ReconfigError::new(RECONFIG_LEO_ERR_PROPAGATION, field_to_c(field), 0.0, 0.0)
        }
        PlanError::InvalidSetting(s) => setting_error_to_c(&s),
    }
}

/// The C status code of a core status. Written out: the core's `BudgetExhausted` (3) is not its
/// last status, so the unverified budget stop takes the code after the last (306), not base +
/// code + 1 (which is `NoTransfer`'s).
pub fn status_to_c(s: SolveStatus) -> i32 {
    match s {
        SolveStatus::Unsolved => RECONFIG_UNSOLVED,
        SolveStatus::Solved => RECONFIG_LEO_SOLVED,
        SolveStatus::ArrivalMissed => RECONFIG_LEO_ARRIVAL_MISSED,
        SolveStatus::BudgetExhausted { verified: true } => RECONFIG_LEO_BUDGET_EXHAUSTED_VERIFIED,
        SolveStatus::NoTransfer => RECONFIG_LEO_NO_TRANSFER,
        SolveStatus::BelowMinAltitude => RECONFIG_LEO_BELOW_MIN_ALTITUDE,
        SolveStatus::BudgetExhausted { verified: false } => {
            RECONFIG_LEO_BUDGET_EXHAUSTED_UNVERIFIED
        }
    }
}

/// A present value: (1, value); absent: (0, 0). Every number of an answer is finite (the core
/// writes no NaN or infinity; `tests/tests/finite_answers.rs` checks this C view too), so
/// values are copied as they are: a non-finite one would be a core defect to show, not hide.
fn present(x: Option<f64>) -> (u8, f64) {
    x.map_or((0, 0.0), |v| (1, v))
}

fn burn_to_c(b: &Burn) -> ReconfigLeoBurn {
    ReconfigLeoBurn {
        epoch_s: b.epoch_s,
        dv_rtn_mps: b.rtn_mps,
        dv_km_s: b.dv_km_s,
    }
}

/// Write the core's solution into the C one, field by field. The destructuring names every
/// field: a field added to the C struct fails to compile here until it is written.
pub fn solution_to_c(s: &ArcSolution, out: &mut ReconfigLeoArcSolution) {
    let ReconfigLeoArcSolution {
        status,
        error,
        usable,
        impulses,
        has_miss_m,
        has_lowest_altitude_km,
        last_leg_branch,
        last_leg_revolutions,
        evaluations,
        total_dv_mps,
        miss_m,
        lowest_altitude_km,
        work_units,
        burns,
    } = out;
    *status = status_to_c(s.info.status);
    *error = ReconfigError::default();
    *usable = u8::from(s.info.status.is_usable());
    // At most MAX_IMPULSES (4) burns are written: the arrays' length.
    let used = usize::from(s.impulses).min(RECONFIG_LEO_MAX_IMPULSES);
    *impulses = u8::try_from(used).unwrap_or(0);
    (*has_miss_m, *miss_m) = present(s.miss_m);
    (*has_lowest_altitude_km, *lowest_altitude_km) = present(s.lowest_altitude_km);
    *last_leg_branch = match s.last_leg_branch {
        Branch::Left => RECONFIG_LEO_BRANCH_LEFT,
        Branch::Right => RECONFIG_LEO_BRANCH_RIGHT,
    };
    *last_leg_revolutions = s.last_leg_revolutions;
    *evaluations = s.info.evaluations;
    *total_dv_mps = s.total_dv_mps;
    *work_units = s.info.work_units;
    *burns = [ReconfigLeoBurn::default(); RECONFIG_LEO_MAX_IMPULSES];
    for (slot, b) in burns.iter_mut().zip(s.burns.iter()).take(used) {
        *slot = burn_to_c(b);
    }
}

/// Reset a C solution to "unsolved" with a refusal in it, field by field (every field named, as
/// in [`solution_to_c`]).
pub fn refusal_to_c(e: ReconfigError, out: &mut ReconfigLeoArcSolution) {
    let ReconfigLeoArcSolution {
        status,
        error,
        usable,
        impulses,
        has_miss_m,
        has_lowest_altitude_km,
        last_leg_branch,
        last_leg_revolutions,
        evaluations,
        total_dv_mps,
        miss_m,
        lowest_altitude_km,
        work_units,
        burns,
    } = out;
    *status = e.code;
    *error = e;
    (*usable, *impulses, *has_miss_m, *has_lowest_altitude_km) = (0, 0, 0, 0);
    *last_leg_branch = RECONFIG_LEO_BRANCH_LEFT;
    *last_leg_revolutions = 0;
    *evaluations = 0;
    *total_dv_mps = 0.0;
    *miss_m = 0.0;
    *lowest_altitude_km = 0.0;
    *work_units = 0;
    *burns = [ReconfigLeoBurn::default(); RECONFIG_LEO_MAX_IMPULSES];
}
