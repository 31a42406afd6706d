//! The GEO tour: the one place where its C structs become core types and back.

use crate::status::*;
use crate::types_geo::*;
use reconfig_core::geo_tour::{
    Direction, Field, Leg, Method, MethodPolicy, PlanError, Problem, SettingId, Settings, Solution,
    SolveStatus, SweepChoice, MAX_TARGETS,
};

crate::mirror_settings!(ReconfigGeoSettings => Settings, SettingId {
    lambert_tol,
    time_tol_s,
    exchange_margin_mps,
    min_radius_km,
    rule_drift_above_rad,
    rule_hohmann_above_rad,
    rule_radial_above_rad,
    lambert_direct_time_s,
    work_budget,
    lambert_max_revolutions,
    lambert_max_iter,
    well_iterations,
    root_max_iter,
    price_max_iter,
    exchange_rounds,
    gap_max_legs,
});

fn code_error(field: i32, value: u8, largest: u8) -> ReconfigError {
    ReconfigError::new(
        RECONFIG_ERR_INVALID_CODE,
        field,
        f64::from(value),
        f64::from(largest),
    )
}

/// The core's problem from the C struct, written into `out` (kept in the caller's workspace).
///
/// # Errors
/// `target_count` above the capacity, a sweep or policy code outside its set.
pub fn problem_from_c(c: &ReconfigGeoProblem, out: &mut Problem) -> Result<(), ReconfigError> {
    let count = usize::from(c.target_count);
    let over = ReconfigError::new(
        RECONFIG_GEO_ERR_CAPACITY_EXCEEDED,
        RECONFIG_FIELD_GEO_TARGET_COUNT,
        f64::from(c.target_count),
        MAX_TARGETS as f64,
    );
    if count > MAX_TARGETS {
        return Err(over);
    }
    out.sweep = match c.sweep {
        RECONFIG_GEO_SWEEP_CHEAPER => SweepChoice::Cheaper,
        RECONFIG_GEO_SWEEP_EAST => SweepChoice::East,
        RECONFIG_GEO_SWEEP_WEST => SweepChoice::West,
        other => return Err(code_error(RECONFIG_FIELD_GEO_SWEEP, other, 2)),
    };
    out.policy = match c.policy {
        RECONFIG_GEO_POLICY_BY_COST => MethodPolicy::ByCost,
        RECONFIG_GEO_POLICY_PAPER_RULE => MethodPolicy::PaperRule,
        RECONFIG_GEO_POLICY_PAPER_RULE_FREE_LAMBERT => MethodPolicy::PaperRuleFreeLambert,
        other => return Err(code_error(RECONFIG_FIELD_GEO_POLICY, other, 2)),
    };
    out.start_lon_rad = c.start_lon_rad;
    out.mission_time_s = c.mission_time_s;
    out.max_burn_mps = c.max_burn_mps;
    out.targets_lon_rad.clear();
    for lon in c.targets_lon_rad.iter().take(count) {
        // Cannot fail: `count <= MAX_TARGETS`, the vector's capacity; reported if it did.
        out.targets_lon_rad.push(*lon).map_err(|_| over)?;
    }
    Ok(())
}

fn field_to_c(field: Field) -> i32 {
    match field {
        Field::StartLongitude => RECONFIG_FIELD_GEO_START_LONGITUDE,
        Field::TargetLongitude => RECONFIG_FIELD_GEO_TARGET_LONGITUDE,
        Field::MissionTime => RECONFIG_FIELD_GEO_MISSION_TIME,
        Field::MaxBurn => RECONFIG_FIELD_GEO_MAX_BURN,
    }
}

/// The C refusal of a core refusal: the field, the client index for a longitude, the value,
/// which end of the range it broke (`detail`) and that end (`limit`).
pub fn error_to_c(e: &PlanError) -> ReconfigError {
    match *e {
        PlanError::OutOfRange {
            field,
            index,
            value,
            min,
            max,
        } => {
            let (detail, limit) = range_break(value, min, max, false);
            let error = ReconfigError::new(
                RECONFIG_GEO_ERR_OUT_OF_RANGE,
                field_to_c(field),
                value,
                limit,
            )
            .with_detail(detail);
            if field == Field::TargetLongitude {
                error.at(i32::from(index))
            } else {
                error
            }
        }
        PlanError::NoTargets => ReconfigError::new(
            RECONFIG_GEO_ERR_NO_TARGETS,
            RECONFIG_FIELD_GEO_TARGET_COUNT,
            0.0,
            1.0,
        ),
        PlanError::InvalidSetting(s) => setting_error_to_c(&s),
    }
}

/// The C status code of a core status and the leg it names (-1 when none). Written out: the
/// GEO tour's status does not implement `contract::Status` yet (planners A and B take theirs
/// from `status::status_code`).
pub fn status_to_c(s: SolveStatus) -> (i32, i32) {
    match s {
        SolveStatus::Unsolved => (RECONFIG_UNSOLVED, -1),
        SolveStatus::Solved => (RECONFIG_GEO_SOLVED, -1),
        SolveStatus::MissionTooShort { leg } => (RECONFIG_GEO_MISSION_TOO_SHORT, i32::from(leg)),
        SolveStatus::CapTooLow { leg } => (RECONFIG_GEO_CAP_TOO_LOW, i32::from(leg)),
        SolveStatus::RuleMethodInadmissible { leg } => {
            (RECONFIG_GEO_RULE_METHOD_INADMISSIBLE, i32::from(leg))
        }
        SolveStatus::CheckFailed { leg } => (RECONFIG_GEO_CHECK_FAILED, i32::from(leg)),
        SolveStatus::BudgetExhausted { verified: true } => {
            (RECONFIG_GEO_BUDGET_EXHAUSTED_VERIFIED, -1)
        }
        SolveStatus::BudgetExhausted { verified: false } => {
            (RECONFIG_GEO_BUDGET_EXHAUSTED_UNVERIFIED, -1)
        }
    }
}

fn method_to_c(m: Method) -> u8 {
    match m {
        Method::None => RECONFIG_GEO_METHOD_NONE,
        Method::Drift => RECONFIG_GEO_METHOD_DRIFT,
        Method::Hohmann => RECONFIG_GEO_METHOD_HOHMANN,
        Method::Radial => RECONFIG_GEO_METHOD_RADIAL,
        Method::Lambert => RECONFIG_GEO_METHOD_LAMBERT,
    }
}

/// Write one leg into its C slot, field by field (every field named).
fn leg_to_c(leg: &Leg, out: &mut ReconfigGeoLeg) {
    let ReconfigGeoLeg {
        from_lon_rad,
        to_lon_rad,
        phase_rad,
        start_s,
        duration_s,
        transfer_s,
        wait_s,
        dv_mps,
        max_burn_mps,
        orbit_sma_km,
        revolutions,
        target_index,
        method,
        burn_count,
        burns,
    } = out;
    *from_lon_rad = leg.from_lon_rad;
    *to_lon_rad = leg.to_lon_rad;
    *phase_rad = leg.phase_rad;
    *start_s = leg.start_s;
    *duration_s = leg.duration_s;
    *transfer_s = leg.transfer_s;
    *wait_s = leg.wait_s;
    *dv_mps = leg.dv_mps;
    *max_burn_mps = leg.max_burn_mps;
    *orbit_sma_km = leg.orbit_sma_km;
    *revolutions = leg.revolutions;
    *target_index = leg.target_index;
    *method = method_to_c(leg.method);
    // At most MAX_BURNS (4): the vector's capacity.
    *burn_count = u8::try_from(leg.burns.len()).unwrap_or(u8::MAX);
    *burns = [ReconfigGeoBurn::default(); RECONFIG_GEO_MAX_BURNS];
    for (slot, b) in burns.iter_mut().zip(leg.burns.iter()) {
        *slot = ReconfigGeoBurn {
            offset_s: b.offset_s,
            dv_rtn_mps: b.dv_rtn_mps,
        };
    }
}

/// Write the core's solution into the C one, field by field (no temporary of the C solution's
/// 3.5 KB on the stack). The destructuring names every field: a field added to the C struct
/// fails to compile here until it is written.
pub fn solution_to_c(s: &Solution, out: &mut ReconfigGeoSolution) {
    let ReconfigGeoSolution {
        status,
        status_leg,
        error,
        usable,
        has_fastest_tour_s,
        direction,
        leg_count,
        refined_legs,
        price_iterations,
        gap_assignments,
        total_dv_mps,
        mission_time_s,
        max_burn_mps,
        price_mps_per_s,
        fastest_tour_s,
        work_units,
        legs,
    } = out;
    (*status, *status_leg) = status_to_c(s.info.status);
    *error = ReconfigError::default();
    *usable = u8::from(s.info.status.is_usable());
    *has_fastest_tour_s = u8::from(s.info.fastest_tour_s.is_some());
    *direction = match s.info.direction {
        Some(Direction::East) => RECONFIG_GEO_DIRECTION_EAST,
        Some(Direction::West) => RECONFIG_GEO_DIRECTION_WEST,
        None => RECONFIG_GEO_DIRECTION_NONE,
    };
    // At most MAX_TARGETS (16): the vector's capacity.
    *leg_count = u8::try_from(s.legs.len()).unwrap_or(u8::MAX);
    *refined_legs = s.info.refined_legs;
    *price_iterations = s.info.price_iterations;
    *gap_assignments = s.info.gap_assignments;
    *total_dv_mps = s.total_dv_mps;
    *mission_time_s = s.mission_time_s;
    *max_burn_mps = s.max_burn_mps;
    *price_mps_per_s = s.info.price_mps_per_s;
    *fastest_tour_s = s.info.fastest_tour_s.unwrap_or(0.0);
    *work_units = s.info.work_units;
    for leg in legs.iter_mut() {
        *leg = ReconfigGeoLeg::default();
    }
    for (slot, leg) in legs.iter_mut().zip(s.legs.iter()) {
        leg_to_c(leg, slot);
    }
}

/// Reset a C solution to "unsolved" with a refusal in it, field by field (every field named, as
/// in [`solution_to_c`]).
pub fn refusal_to_c(e: ReconfigError, out: &mut ReconfigGeoSolution) {
    let ReconfigGeoSolution {
        status,
        status_leg,
        error,
        usable,
        direction,
        leg_count,
        refined_legs,
        price_iterations,
        gap_assignments,
        total_dv_mps,
        mission_time_s,
        max_burn_mps,
        price_mps_per_s,
        fastest_tour_s,
        has_fastest_tour_s,
        work_units,
        legs,
    } = out;
    *status = e.code;
    *status_leg = -1;
    *error = e;
    (*usable, *direction, *leg_count, *refined_legs) = (0, 0, 0, 0);
    (*price_iterations, *gap_assignments) = (0, 0);
    *total_dv_mps = 0.0;
    *mission_time_s = 0.0;
    *max_burn_mps = 0.0;
    *price_mps_per_s = 0.0;
    *fastest_tour_s = 0.0;
    *has_fastest_tour_s = 0;
    *work_units = 0;
    for leg in legs.iter_mut() {
        *leg = ReconfigGeoLeg::default();
    }
}
