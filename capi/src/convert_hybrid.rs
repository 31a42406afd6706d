//! The hybrid transfer: the one place where its C structs become core types and back.

use crate::status::*;
use crate::types_hybrid::*;
use reconfig_core::hybrid::{
    Field, FlownPlan, Objective, PlanError, Problem, SettingId, Settings, Solution, SolveStatus,
    Stopped,
};

crate::mirror_settings!(ReconfigHybridSettings => Settings, SettingId {
    tolerance,
    hamiltonian_tol,
    relative_tol,
    absolute_tol,
    halo_closure_tol,
    flight_tol,
    work_budget,
    max_iterations,
    max_halvings,
    check_segments,
    continuation_steps,
});

fn code_error(field: i32, value: u8, largest: u8) -> ReconfigError {
    ReconfigError::new(
        RECONFIG_ERR_INVALID_CODE,
        field,
        f64::from(value),
        f64::from(largest),
    )
}

fn flag(field: i32, value: u8) -> Result<bool, ReconfigError> {
    match value {
        0 => Ok(false),
        1 => Ok(true),
        other => Err(code_error(field, other, 1)),
    }
}

/// The core's objective of a C code, if it is one.
pub fn objective_from_c(code: u8) -> Option<Objective> {
    match code {
        RECONFIG_HYBRID_OBJECTIVE_MIN_FUEL => Some(Objective::MinFuel),
        RECONFIG_HYBRID_OBJECTIVE_MIN_ENERGY => Some(Objective::MinEnergy),
        RECONFIG_HYBRID_OBJECTIVE_MIN_TIME => Some(Objective::MinTime),
        _ => None,
    }
}

/// The C code of the core's objective.
pub const fn objective_to_c(objective: Objective) -> u8 {
    match objective {
        Objective::MinFuel => RECONFIG_HYBRID_OBJECTIVE_MIN_FUEL,
        Objective::MinEnergy => RECONFIG_HYBRID_OBJECTIVE_MIN_ENERGY,
        Objective::MinTime => RECONFIG_HYBRID_OBJECTIVE_MIN_TIME,
    }
}

/// The core's problem from the C struct, written into `out` (kept in the caller's workspace).
/// Every number has its core value: the core's validation and the limits decide what is
/// refused.
///
/// # Errors
/// An objective code outside its set, a free flag other than 0 or 1
/// (`RECONFIG_ERR_INVALID_CODE` naming the field, `limit` the largest code).
pub fn problem_from_c(c: &ReconfigHybridProblem, out: &mut Problem) -> Result<(), ReconfigError> {
    let Some(objective) = objective_from_c(c.objective) else {
        return Err(code_error(
            RECONFIG_FIELD_HYBRID_OBJECTIVE,
            c.objective,
            RECONFIG_HYBRID_OBJECTIVE_MIN_TIME,
        ));
    };
    let free_kappa = flag(RECONFIG_FIELD_HYBRID_FREE_KAPPA, c.free_kappa)?;
    let free_theta = flag(RECONFIG_FIELD_HYBRID_FREE_THETA, c.free_theta)?;
    *out = Problem {
        objective,
        kappa: c.kappa,
        theta_rad: c.theta_rad,
        free_kappa,
        free_theta,
        duration_days: c.duration_days,
        thrust_n: c.thrust_n,
        specific_impulse_s: c.specific_impulse_s,
        chemical_specific_impulse_s: c.chemical_specific_impulse_s,
        parking_radius_km: c.parking_radius_km,
        departure_offset: c.departure_offset,
        arrival_r_lu: c.arrival_r_lu,
        arrival_v_vu: c.arrival_v_vu,
        halo_period_tu: c.halo_period_tu,
        costates: c.costates,
        cost_multiplier: c.cost_multiplier,
        design_duration_days: c.design_duration_days,
        design_thrust_n: c.design_thrust_n,
    };
    Ok(())
}

/// The C field code of a core field: 100 plus its code (written out, so that a new core field
/// fails to compile here).
pub const fn field_to_c(field: Field) -> i32 {
    match field {
        Field::Kappa => RECONFIG_FIELD_HYBRID_KAPPA,
        Field::Theta => RECONFIG_FIELD_HYBRID_THETA,
        Field::Duration => RECONFIG_FIELD_HYBRID_DURATION,
        Field::Thrust => RECONFIG_FIELD_HYBRID_THRUST,
        Field::SpecificImpulse => RECONFIG_FIELD_HYBRID_SPECIFIC_IMPULSE,
        Field::ChemicalSpecificImpulse => RECONFIG_FIELD_HYBRID_CHEMICAL_SPECIFIC_IMPULSE,
        Field::ParkingRadius => RECONFIG_FIELD_HYBRID_PARKING_RADIUS,
        Field::DepartureOffset => RECONFIG_FIELD_HYBRID_DEPARTURE_OFFSET,
        Field::ArrivalPosition => RECONFIG_FIELD_HYBRID_ARRIVAL_POSITION,
        Field::ArrivalVelocity => RECONFIG_FIELD_HYBRID_ARRIVAL_VELOCITY,
        Field::HaloPeriod => RECONFIG_FIELD_HYBRID_HALO_PERIOD,
        Field::Costates => RECONFIG_FIELD_HYBRID_COSTATES,
        Field::CostMultiplier => RECONFIG_FIELD_HYBRID_COST_MULTIPLIER,
        Field::FreeKappa => RECONFIG_FIELD_HYBRID_FREE_KAPPA,
        Field::FreeTheta => RECONFIG_FIELD_HYBRID_FREE_THETA,
        Field::DesignDuration => RECONFIG_FIELD_HYBRID_DESIGN_DURATION,
        Field::DesignThrust => RECONFIG_FIELD_HYBRID_DESIGN_THRUST,
    }
}

/// The C refusal of a core refusal: the field (and the component of an array), the value,
/// which end of the range it broke (`detail`) and that end (`limit`); the halo check's miss
/// and tolerance; a setting as every planner's (named by its code).
pub fn error_to_c(e: &PlanError) -> ReconfigError {
    match *e {
        PlanError::OutOfRange {
            field,
            index,
            value,
            min,
            max,
            max_open: _,
        } => {
            // An open upper end is refused at `max` itself: `range_break` names it "above" as
            // for any value past a closed end.
            let (detail, limit) = range_break(value, min, max, false);
            let error = ReconfigError::new(
                RECONFIG_HYBRID_ERR_OUT_OF_RANGE,
                field_to_c(field),
                value,
                limit,
            )
            .with_detail(detail);
            match field {
                Field::DepartureOffset
                | Field::ArrivalPosition
                | Field::ArrivalVelocity
                | Field::Costates => error.at(i32::from(index)),
                _ => error,
            }
        }
        PlanError::NotOnPeriodicOrbit { miss, limit } => ReconfigError::new(
            RECONFIG_HYBRID_ERR_NOT_ON_PERIODIC_ORBIT,
            RECONFIG_FIELD_HYBRID_HALO_PERIOD,
            miss,
            limit,
        ),
        PlanError::HaloCheckUnfinished => ReconfigError::new(
            RECONFIG_HYBRID_ERR_HALO_CHECK_UNFINISHED,
            RECONFIG_FIELD_HYBRID_HALO_PERIOD,
            0.0,
            0.0,
        ),
        PlanError::InvalidSetting(s) => setting_error_to_c(&s),
    }
}

/// The C status code of a core status and, for `IntegrationStopped`, why
/// (`RECONFIG_HYBRID_STOPPED_*`; else 0). Written out: the core's `BudgetExhausted` (2) is not
/// its last status, so the unverified budget stop takes the code after the last (508), not
/// base + code + 1 (which is `IterationLimit`'s).
pub fn status_to_c(s: SolveStatus) -> (i32, i32) {
    match s {
        SolveStatus::Unsolved => (RECONFIG_UNSOLVED, 0),
        SolveStatus::Solved => (RECONFIG_HYBRID_SOLVED, 0),
        SolveStatus::BudgetExhausted { verified: true } => {
            (RECONFIG_HYBRID_BUDGET_EXHAUSTED_VERIFIED, 0)
        }
        SolveStatus::IterationLimit => (RECONFIG_HYBRID_ITERATION_LIMIT, 0),
        SolveStatus::NoDescent => (RECONFIG_HYBRID_NO_DESCENT, 0),
        SolveStatus::Singular => (RECONFIG_HYBRID_SINGULAR, 0),
        SolveStatus::IntegrationStopped(why) => (
            RECONFIG_HYBRID_INTEGRATION_STOPPED,
            match why {
                Stopped::StepTooSmall => RECONFIG_HYBRID_STOPPED_STEP_TOO_SMALL,
                Stopped::NotFinite => RECONFIG_HYBRID_STOPPED_NOT_FINITE,
                Stopped::SwitchLimit => RECONFIG_HYBRID_STOPPED_SWITCH_LIMIT,
            },
        ),
        SolveStatus::CheckFailed => (RECONFIG_HYBRID_CHECK_FAILED, 0),
        SolveStatus::BudgetExhausted { verified: false } => {
            (RECONFIG_HYBRID_BUDGET_EXHAUSTED_UNVERIFIED, 0)
        }
    }
}

/// A present value: (1, value); absent: (0, 0). Every number of an answer is finite (the core
/// writes no NaN or infinity), so values are copied as they are.
fn present(x: Option<f64>) -> (u8, f64) {
    x.map_or((0, 0.0), |v| (1, v))
}

/// The C check flight of the core's (every field named: a field added to the C struct fails
/// to compile here until it is written).
fn flown_to_c(f: &FlownPlan) -> ReconfigHybridFlown {
    let FlownPlan {
        final_mass,
        end_miss,
        hamiltonian_drift,
        thrust_arcs,
        switches,
        switch_times_tu,
    } = *f;
    ReconfigHybridFlown {
        final_mass,
        end_miss,
        hamiltonian_drift,
        thrust_arcs,
        switches,
        switch_times_tu,
    }
}

/// Write the core's solution into the C one, field by field. The destructuring names every
/// field: a field added to the C struct fails to compile here until it is written.
pub fn solution_to_c(s: &Solution, out: &mut ReconfigHybridSolution) {
    let ReconfigHybridSolution {
        status,
        stopped,
        error,
        usable,
        objective,
        has_residual,
        has_flown,
        walked_shootings,
        iterations,
        work_units,
        evaluations,
        walked_reached,
        kappa,
        theta_rad,
        duration_tu,
        costates,
        cost_multiplier,
        mass_after_impulse,
        residual,
        flown,
    } = out;
    (*status, *stopped) = status_to_c(s.info.status);
    *error = ReconfigError::default();
    *usable = u8::from(s.info.status.is_usable());
    *objective = objective_to_c(s.objective);
    (*has_residual, *residual) = present(s.residual);
    *has_flown = u8::from(s.flown.is_some());
    *flown = s
        .flown
        .as_ref()
        .map_or_else(ReconfigHybridFlown::default, flown_to_c);
    *walked_shootings = s.info.walked.shootings;
    *walked_reached = s.info.walked.reached;
    *iterations = s.info.iterations;
    *work_units = s.info.work_units;
    *evaluations = s.info.evaluations;
    *kappa = s.kappa;
    *theta_rad = s.theta_rad;
    *duration_tu = s.duration_tu;
    *costates = s.costates;
    *cost_multiplier = s.cost_multiplier;
    *mass_after_impulse = s.mass_after_impulse;
}

/// Reset a C solution to "unsolved" with a refusal in it, field by field (every field named, as
/// in [`solution_to_c`]).
pub fn refusal_to_c(e: ReconfigError, out: &mut ReconfigHybridSolution) {
    let ReconfigHybridSolution {
        status,
        stopped,
        error,
        usable,
        objective,
        has_residual,
        has_flown,
        walked_shootings,
        iterations,
        work_units,
        evaluations,
        walked_reached,
        kappa,
        theta_rad,
        duration_tu,
        costates,
        cost_multiplier,
        mass_after_impulse,
        residual,
        flown,
    } = out;
    *status = e.code;
    *stopped = 0;
    *error = e;
    (*usable, *objective, *has_residual, *has_flown) = (0, 0, 0, 0);
    *walked_shootings = 0;
    *iterations = 0;
    (*work_units, *evaluations) = (0, 0);
    *walked_reached = 0.0;
    (*kappa, *theta_rad, *duration_tu) = (0.0, 0.0, 0.0);
    *costates = [0.0; RECONFIG_HYBRID_STATE_LEN];
    (*cost_multiplier, *mass_after_impulse, *residual) = (0.0, 0.0, 0.0);
    *flown = ReconfigHybridFlown::default();
}
