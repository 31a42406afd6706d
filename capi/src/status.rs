//! Status codes (`int32_t`), field codes and the error detail every refusal fills in.
//!
//! Codes `>= 0` are the core's solve statuses (the solution is written); codes `< 0` are
//! refusals (nothing was solved; the solution's `error` says why when the solution pointer is
//! usable). Each core status and each refusal has its own code; the table is in docs/c-api.md.
//!
//! A status code is the planner's base (A 0, B 100, GEO 200) plus the core status's own code
//! (`contract::Status::code`), plus one for a budget stop whose plan is not verified (the core
//! has one `BudgetExhausted { verified }` variant, C one code for each answer to "may it be
//! flown?"); `Unsolved` is 0 for every planner ([`status_code`]; the unit test
//! `c_codes_are_base_plus_the_core_code` checks every constant below against it). The LEO arc
//! (base 300) is mapped by hand (`convert_leo::status_to_c`): its `BudgetExhausted` is not its
//! last status, so its unverified budget stop takes the code after its last (306). So is the
//! hybrid transfer (base 500, `convert_hybrid::status_to_c`; its unverified budget stop 508).
//! A planner's base is its wire planner code (`contract::PlannerKind`) times 100 and its
//! refusals are below minus (code + 1) times 100: the LEO sequencing (planner code 4, no C
//! interface yet) keeps 400 and -501 ..

/// No solve has written this solution.
pub const RECONFIG_UNSOLVED: i32 = 0;

/// Planner A: verified feasible on the continuous trajectory and certified a local optimum.
pub const RECONFIG_A_SOLVED: i32 = 1;
/// Planner A: the continuous separation is below the keep-out somewhere. Not feasible.
pub const RECONFIG_A_SEPARATION_NOT_VERIFIED: i32 = 2;
/// Planner A: the SQP iteration limit was reached, last iterate not verified. Not feasible.
pub const RECONFIG_A_MAX_ITERATIONS: i32 = 3;
/// Planner A: a QP subproblem was infeasible. Not feasible.
pub const RECONFIG_A_INFEASIBLE: i32 = 4;
/// Planner A: a QP hit its iteration limit, last iterate not verified. Not feasible.
pub const RECONFIG_A_QP_LIMIT: i32 = 5;
/// Planner A: a factorisation failed; `numerical_stage` says where. Not feasible.
pub const RECONFIG_A_NUMERICAL_FAILURE: i32 = 6;
/// Planner A: verified feasible, not certified optimal. May be flown.
pub const RECONFIG_A_FEASIBLE: i32 = 7;
/// Planner A: the work budget ran out; the returned trajectory is verified feasible. May be
/// flown.
pub const RECONFIG_A_BUDGET_EXHAUSTED_VERIFIED: i32 = 8;
/// Planner A: the work budget ran out; the returned trajectory is not verified. Not feasible.
pub const RECONFIG_A_BUDGET_EXHAUSTED_UNVERIFIED: i32 = 9;

/// Planner B: reaches the target (nonlinear check), full rank, safe perigees. May be flown.
pub const RECONFIG_B_SOLVED: i32 = 101;
/// Planner B: F is rank-deficient; least-squares impulses that do not reach the target.
pub const RECONFIG_B_RANK_DEFICIENT: i32 = 102;
/// Planner B: the fixed point hit its iteration limit.
pub const RECONFIG_B_MAX_ITERATIONS: i32 = 103;
/// Planner B: the nonlinear correction hit its iteration limit above its tolerance.
pub const RECONFIG_B_CORRECTION_NOT_CONVERGED: i32 = 104;
/// Planner B: a numerical step failed; `numerical_stage` says where.
pub const RECONFIG_B_NUMERICAL_FAILURE: i32 = 105;
/// Planner B: a transfer arc's perigee is too low (`unsafe_arc`,
/// `unsafe_perigee_altitude_km`). Not flyable.
pub const RECONFIG_B_UNSAFE_PERIGEE: i32 = 106;
/// Planner B: linear-model fixed point, correction off; misses by `linearised_miss_m`.
pub const RECONFIG_B_LINEARISED: i32 = 107;
/// Planner B: the work budget ran out; the returned plan meets every condition of SOLVED.
pub const RECONFIG_B_BUDGET_EXHAUSTED_VERIFIED: i32 = 108;
/// Planner B: the work budget ran out; the returned plan is not verified.
pub const RECONFIG_B_BUDGET_EXHAUSTED_UNVERIFIED: i32 = 109;

/// GEO tour: the plan meets the mission time and the burn cap, checked. May be flown.
pub const RECONFIG_GEO_SOLVED: i32 = 201;
/// GEO tour: even the fastest admissible tour overruns the mission time (`status_leg` the leg
/// that needs the most time, `fastest_tour_s` how long the fastest tour takes when
/// `has_fastest_tour_s`).
pub const RECONFIG_GEO_MISSION_TOO_SHORT: i32 = 202;
/// GEO tour: the tour fits without the burn cap but not with it (`status_leg`).
pub const RECONFIG_GEO_CAP_TOO_LOW: i32 = 203;
/// GEO tour, paper's rule: the rule's method for `status_leg` is not admissible.
pub const RECONFIG_GEO_RULE_METHOD_INADMISSIBLE: i32 = 204;
/// GEO tour: the final check failed at `status_leg`; the plan is for inspection only.
pub const RECONFIG_GEO_CHECK_FAILED: i32 = 205;
/// GEO tour: the work budget ran out; the returned plan (the best found) meets every condition
/// of SOLVED. May be flown.
pub const RECONFIG_GEO_BUDGET_EXHAUSTED_VERIFIED: i32 = 206;
/// GEO tour: the work budget ran out; the returned plan is not verified (or there is none:
/// `leg_count` 0). Not usable.
pub const RECONFIG_GEO_BUDGET_EXHAUSTED_UNVERIFIED: i32 = 207;

/// LEO arc: the plan, flown from scratch in the planning model, arrives within
/// `arrival_tol_km` with the client's velocity, its transfer above `min_transfer_altitude_km`.
/// May be flown.
pub const RECONFIG_LEO_SOLVED: i32 = 301;
/// LEO arc: the best plan found misses by more than `arrival_tol_km` (`miss_m`). Not usable.
pub const RECONFIG_LEO_ARRIVAL_MISSED: i32 = 302;
/// LEO arc: the work budget ran out; the returned plan arrives and stays above
/// `min_transfer_altitude_km` as for SOLVED. May be flown.
pub const RECONFIG_LEO_BUDGET_EXHAUSTED_VERIFIED: i32 = 303;
/// LEO arc: no transfer of the search reached the client (no burns). Not usable.
pub const RECONFIG_LEO_NO_TRANSFER: i32 = 304;
/// LEO arc: the best plan found arrives but dips below `min_transfer_altitude_km`
/// (`lowest_altitude_km`). Not usable.
pub const RECONFIG_LEO_BELOW_MIN_ALTITUDE: i32 = 305;
/// LEO arc: the work budget ran out; the returned plan misses or dips below (its burns, miss
/// and lowest altitude are returned), or there is none (`impulses` 0). Not usable.
pub const RECONFIG_LEO_BUDGET_EXHAUSTED_UNVERIFIED: i32 = 306;

/// Hybrid transfer: the shooting converged and the plan, flown once more, reaches the arrival to
/// `flight_tol` with the Hamiltonian constant to `hamiltonian_tol`. May be flown.
pub const RECONFIG_HYBRID_SOLVED: i32 = 501;
/// Hybrid transfer: the work budget ran out; the returned plan passed the checks of SOLVED
/// (never today: the core offers no unverified plan as verified). May be flown.
pub const RECONFIG_HYBRID_BUDGET_EXHAUSTED_VERIFIED: i32 = 502;
/// Hybrid transfer: `max_iterations` Newton iterations did not converge. Not usable.
pub const RECONFIG_HYBRID_ITERATION_LIMIT: i32 = 503;
/// Hybrid transfer: no step along the last Newton direction lowered the residual. Not usable.
pub const RECONFIG_HYBRID_NO_DESCENT: i32 = 504;
/// Hybrid transfer: the shooting's Jacobian was singular. Not usable.
pub const RECONFIG_HYBRID_SINGULAR: i32 = 505;
/// Hybrid transfer: a propagation stopped early (`stopped` says why). Not usable.
pub const RECONFIG_HYBRID_INTEGRATION_STOPPED: i32 = 506;
/// Hybrid transfer: the shooting converged but the check flight missed the arrival by more
/// than `flight_tol` or the Hamiltonian drifted beyond `hamiltonian_tol`. Not usable.
pub const RECONFIG_HYBRID_CHECK_FAILED: i32 = 507;
/// Hybrid transfer: the work budget ran out before the shooting converged or the check flight
/// ended; the costates are the best iterate. Not usable.
pub const RECONFIG_HYBRID_BUDGET_EXHAUSTED_UNVERIFIED: i32 = 508;

/// Refused: a pointer argument is null (`error.field` names it when the solution is usable).
pub const RECONFIG_ERR_NULL_POINTER: i32 = -1;
/// Refused: a pointer is not aligned for its type.
pub const RECONFIG_ERR_MISALIGNED: i32 = -2;
/// Refused: the workspace is smaller than `_workspace_size()` (`value` given, `limit` needed).
pub const RECONFIG_ERR_WORKSPACE_TOO_SMALL: i32 = -3;
/// Refused: the workspace was not initialised by this planner's `_init`.
pub const RECONFIG_ERR_WORKSPACE_NOT_INITIALISED: i32 = -4;
/// Refused: a flag or enumeration field of the problem holds a value outside its set (`value`;
/// `limit` is the largest accepted value). A setting's flag or code outside its set is
/// `RECONFIG_ERR_SETTING_OUT_OF_RANGE` naming the setting.
pub const RECONFIG_ERR_INVALID_CODE: i32 = -5;
/// Refused: a setting is outside the range the planner accepts (`field` =
/// `RECONFIG_FIELD_SETTINGS`, `index` the setting's code in its planner's settings table, named
/// by `reconfig_setting_name`; `value`; `limit` the end of the range it broke; `detail` 0 below
/// the range, 1 above it, 2 not finite). The same code for every planner; also a flag other
/// than 0 or 1 or an enumeration code outside its set (`limit` the largest code, `detail` 1).
pub const RECONFIG_ERR_SETTING_OUT_OF_RANGE: i32 = -6;
/// Refused: the request asks for more work or less safety than the built-in limits allow (the
/// same limits as the flight service's, checked before the planner's own validation, as the
/// service checks them): `field` = `RECONFIG_FIELD_SETTINGS`, `index` the setting's code (a
/// problem quantity's code is 128 and up), named by `reconfig_setting_name`, `value`, `limit`,
/// `detail` the rule (0 at most, 1 at least, 2 must be on, 3 must be off, 4 below). Nothing was
/// solved.
pub const RECONFIG_ERR_LIMIT_EXCEEDED: i32 = -7;

/// Planner A refused: a number is NaN or infinite.
pub const RECONFIG_A_ERR_NOT_FINITE: i32 = -101;
/// Planner A refused: a quantity that must be positive is not.
pub const RECONFIG_A_ERR_NOT_POSITIVE: i32 = -102;
/// Planner A refused: a size is above the compiled capacity (`value` requested, `limit`).
pub const RECONFIG_A_ERR_CAPACITY_EXCEEDED: i32 = -103;
/// Planner A refused: the degree is below the minimum (`limit`).
pub const RECONFIG_A_ERR_DEGREE_TOO_LOW: i32 = -104;
/// Planner A refused: no spacecraft.
pub const RECONFIG_A_ERR_NO_SPACECRAFT: i32 = -105;
/// Planner A refused: two spacecraft start or end closer than the keep-out (`index`,
/// `index2`; `detail` 0 = initial, 1 = final).
pub const RECONFIG_A_ERR_BOUNDARY_TOO_CLOSE: i32 = -106;
/// Planner A refused: bang-bang control at the bound cannot meet one axis (`index` spacecraft,
/// `detail` axis).
pub const RECONFIG_A_ERR_MANOEUVRE_INFEASIBLE: i32 = -107;
/// Planner A refused: a warm start does not match the problem (not reachable from C, which has
/// no warm start; kept so that every core refusal has a code).
pub const RECONFIG_A_ERR_WARM_START_MISMATCH: i32 = -108;
/// Planner A refused: a number is outside the accepted magnitude range (`limit`).
pub const RECONFIG_A_ERR_OUT_OF_RANGE: i32 = -110;

/// Planner B refused: a number is NaN or infinite.
pub const RECONFIG_B_ERR_NOT_FINITE: i32 = -201;
/// Planner B refused: eccentricity below the classical set's threshold.
pub const RECONFIG_B_ERR_ECCENTRICITY_TOO_SMALL: i32 = -202;
/// Planner B refused: eccentricity not in [0, 1).
pub const RECONFIG_B_ERR_NOT_ELLIPTIC: i32 = -203;
/// Planner B refused: semi-major axis out of range (`value`, `limit` the violated end).
pub const RECONFIG_B_ERR_SMA_OUT_OF_RANGE: i32 = -204;
/// Planner B refused: |sin i| below the threshold.
pub const RECONFIG_B_ERR_INCLINATION_SINGULAR: i32 = -205;
/// Planner B refused: a revolution count is negative.
pub const RECONFIG_B_ERR_NEGATIVE_REVOLUTIONS: i32 = -206;
/// Planner B refused: the revolution counts sum above the limit.
pub const RECONFIG_B_ERR_REVOLUTIONS_OVER_LIMIT: i32 = -207;
/// Planner B refused: more impulses than the capacity.
pub const RECONFIG_B_ERR_CAPACITY_EXCEEDED: i32 = -208;
/// Planner B refused: no impulse in the plan.
pub const RECONFIG_B_ERR_NO_IMPULSES: i32 = -209;
/// Planner B refused: a perigee altitude is below the limit.
pub const RECONFIG_B_ERR_PERIGEE_TOO_LOW: i32 = -211;
/// Planner B refused: inclination not in [0, pi].
pub const RECONFIG_B_ERR_INCLINATION_OUT_OF_RANGE: i32 = -212;
/// Planner B refused: an angle's magnitude is above the limit.
pub const RECONFIG_B_ERR_ANGLE_OUT_OF_RANGE: i32 = -213;
/// Planner B refused: an input in another form (`reconfig_impulsive_solve_form`) could not be
/// converted: `field` the part (`RECONFIG_FIELD_CHIEF`, `_INITIAL`, `_TARGET`), `detail` why
/// (`RECONFIG_B_FORM_*`), `value`/`limit` the chief's `|sin i|` and its minimum for ROE.
pub const RECONFIG_B_ERR_INPUT_FORM: i32 = -214;

/// GEO tour refused: a value is not finite or outside its range (`field` a
/// `RECONFIG_FIELD_GEO_*`, `index` the client for a longitude, `detail` 0 below the range, 1
/// above it, 2 not finite; `limit` the end it broke, the upper end when not finite).
pub const RECONFIG_GEO_ERR_OUT_OF_RANGE: i32 = -301;
/// GEO tour refused: no clients.
pub const RECONFIG_GEO_ERR_NO_TARGETS: i32 = -302;
/// GEO tour refused: `target_count` above the capacity (`value`, `limit`).
pub const RECONFIG_GEO_ERR_CAPACITY_EXCEEDED: i32 = -303;

/// LEO arc refused: a value is not finite or outside its range (`field` a
/// `RECONFIG_FIELD_LEO_*`, `detail` 0 below the range, 1 above it, 2 not finite; `limit` the
/// end it broke, the upper end when not finite). A client's perigee altitude (computed with
/// the settings' `mu_km3_s2` and `re_km`) is named by its own field.
pub const RECONFIG_LEO_ERR_OUT_OF_RANGE: i32 = -401;
/// LEO arc refused: a client's trajectory over the arc needs more than `max_steps` RK4 steps
/// or leaves the finite numbers (`field` `RECONFIG_FIELD_LEO_FROM` or `_TO`).
pub const RECONFIG_LEO_ERR_PROPAGATION: i32 = -402;

/// Hybrid transfer refused: a value is not finite or outside its range (`field` a
/// `RECONFIG_FIELD_HYBRID_*`, `index` the component of an array, else -1; `detail` 0 below the
/// range, 1 above it, 2 not finite; `limit` the end it broke, the upper end when not finite).
/// With the minimum-time objective a free flag of 1 is this code too (`limit` 0).
pub const RECONFIG_HYBRID_ERR_OUT_OF_RANGE: i32 = -601;
/// Hybrid transfer refused: the arrival point does not return to itself after
/// `halo_period_tu` (`field` `RECONFIG_FIELD_HYBRID_HALO_PERIOD`, `value` the largest component
/// of the miss, LU or LU/TU, `limit` `halo_closure_tol`).
pub const RECONFIG_HYBRID_ERR_NOT_ON_PERIODIC_ORBIT: i32 = -602;
/// Hybrid transfer refused: the flight over `halo_period_tu` that checks the arrival point did
/// not finish within its share of the work budget (a sixteenth) or met a singularity (`field`
/// `RECONFIG_FIELD_HYBRID_HALO_PERIOD`).
pub const RECONFIG_HYBRID_ERR_HALO_CHECK_UNFINISHED: i32 = -603;

/// No field (the refusal is about the request as a whole).
pub const RECONFIG_FIELD_NONE: i32 = 0;
/// Planner A: `horizon_tu`.
pub const RECONFIG_FIELD_HORIZON_TU: i32 = 1;
/// Planner A: `max_control_fu`.
pub const RECONFIG_FIELD_MAX_CONTROL_FU: i32 = 2;
/// Planner A: `keep_out_lu`.
pub const RECONFIG_FIELD_KEEP_OUT_LU: i32 = 3;
/// Planner A: `spacecraft[index].mass_mu`.
pub const RECONFIG_FIELD_MASS_MU: i32 = 4;
/// Planner A: `spacecraft[index].initial_state` or `final_state`.
pub const RECONFIG_FIELD_BOUNDARY_STATE: i32 = 5;
/// A setting (`index` = its code in the planner's settings table, named by
/// `reconfig_setting_name`).
pub const RECONFIG_FIELD_SETTINGS: i32 = 6;
/// Planner A: `spacecraft_count`.
pub const RECONFIG_FIELD_SPACECRAFT_COUNT: i32 = 7;
/// Planner A: `degree`.
pub const RECONFIG_FIELD_DEGREE: i32 = 8;
/// Planner A: `test_points` (0 or 1).
pub const RECONFIG_FIELD_TEST_POINTS: i32 = 9;
/// Planner A: the pair of spacecraft `index`, `index2`.
pub const RECONFIG_FIELD_SPACECRAFT_PAIR: i32 = 10;
/// Planner B: `chief` (element `index`: 0 a, 1 e, 2 i, 3 RAAN, 4 argp, 5 M).
pub const RECONFIG_FIELD_CHIEF: i32 = 20;
/// Planner B: `initial` (element `index`).
pub const RECONFIG_FIELD_INITIAL: i32 = 21;
/// Planner B: `target` (element `index`).
pub const RECONFIG_FIELD_TARGET: i32 = 22;
/// Planner B: `points[index].arg_latitude_rad`.
pub const RECONFIG_FIELD_IMPULSE_POINT: i32 = 23;
/// Planner B: the deputy's initial orbit (chief + initial).
pub const RECONFIG_FIELD_DEPUTY_INITIAL: i32 = 24;
/// Planner B: the deputy's target orbit (chief + target).
pub const RECONFIG_FIELD_DEPUTY_TARGET: i32 = 25;
/// Planner B: `impulse_count`.
pub const RECONFIG_FIELD_IMPULSE_COUNT: i32 = 26;
/// Planner B: `points[index].revolutions`, or `max_revolutions` of a search.
pub const RECONFIG_FIELD_REVOLUTIONS: i32 = 27;
/// Planner B: `search` (0 or 1).
pub const RECONFIG_FIELD_SEARCH: i32 = 28;
/// GEO tour: `start_lon_rad`.
pub const RECONFIG_FIELD_GEO_START_LONGITUDE: i32 = 50;
/// GEO tour: `targets_lon_rad[index]`.
pub const RECONFIG_FIELD_GEO_TARGET_LONGITUDE: i32 = 51;
/// GEO tour: `mission_time_s`.
pub const RECONFIG_FIELD_GEO_MISSION_TIME: i32 = 52;
/// GEO tour: `max_burn_mps`.
pub const RECONFIG_FIELD_GEO_MAX_BURN: i32 = 53;
/// GEO tour: `target_count`.
pub const RECONFIG_FIELD_GEO_TARGET_COUNT: i32 = 69;
/// GEO tour: `sweep` (`RECONFIG_GEO_SWEEP_*`).
pub const RECONFIG_FIELD_GEO_SWEEP: i32 = 70;
/// GEO tour: `policy` (`RECONFIG_GEO_POLICY_*`).
pub const RECONFIG_FIELD_GEO_POLICY: i32 = 71;
/// LEO arc: `from_position_km` / `from_velocity_km_s` (a component).
pub const RECONFIG_FIELD_LEO_FROM: i32 = 80;
/// LEO arc: `to_position_km` / `to_velocity_km_s` (a component).
pub const RECONFIG_FIELD_LEO_TO: i32 = 81;
/// LEO arc: `duration_s`.
pub const RECONFIG_FIELD_LEO_DURATION: i32 = 82;
/// LEO arc: `impulses`.
pub const RECONFIG_FIELD_LEO_IMPULSES: i32 = 83;
/// LEO arc: the perigee altitude of the `from` state's osculating orbit, km.
pub const RECONFIG_FIELD_LEO_FROM_PERIGEE_ALTITUDE: i32 = 84;
/// LEO arc: the perigee altitude of the `to` state's osculating orbit, km.
pub const RECONFIG_FIELD_LEO_TO_PERIGEE_ALTITUDE: i32 = 85;
/// Hybrid transfer: `kappa` (the field codes are 100 plus the core's `hybrid::Field` code).
pub const RECONFIG_FIELD_HYBRID_KAPPA: i32 = 100;
/// Hybrid transfer: `theta_rad`.
pub const RECONFIG_FIELD_HYBRID_THETA: i32 = 101;
/// Hybrid transfer: `duration_days`.
pub const RECONFIG_FIELD_HYBRID_DURATION: i32 = 102;
/// Hybrid transfer: `thrust_n`.
pub const RECONFIG_FIELD_HYBRID_THRUST: i32 = 103;
/// Hybrid transfer: `specific_impulse_s`.
pub const RECONFIG_FIELD_HYBRID_SPECIFIC_IMPULSE: i32 = 104;
/// Hybrid transfer: `chemical_specific_impulse_s`.
pub const RECONFIG_FIELD_HYBRID_CHEMICAL_SPECIFIC_IMPULSE: i32 = 105;
/// Hybrid transfer: `parking_radius_km`.
pub const RECONFIG_FIELD_HYBRID_PARKING_RADIUS: i32 = 106;
/// Hybrid transfer: `departure_offset[index]`.
pub const RECONFIG_FIELD_HYBRID_DEPARTURE_OFFSET: i32 = 107;
/// Hybrid transfer: `arrival_r_lu[index]`.
pub const RECONFIG_FIELD_HYBRID_ARRIVAL_POSITION: i32 = 108;
/// Hybrid transfer: `arrival_v_vu[index]`.
pub const RECONFIG_FIELD_HYBRID_ARRIVAL_VELOCITY: i32 = 109;
/// Hybrid transfer: `halo_period_tu` (also the halo check's refusals).
pub const RECONFIG_FIELD_HYBRID_HALO_PERIOD: i32 = 110;
/// Hybrid transfer: `costates[index]`.
pub const RECONFIG_FIELD_HYBRID_COSTATES: i32 = 111;
/// Hybrid transfer: `cost_multiplier`.
pub const RECONFIG_FIELD_HYBRID_COST_MULTIPLIER: i32 = 112;
/// Hybrid transfer: `free_kappa` (0 or 1; 0 for minimum time).
pub const RECONFIG_FIELD_HYBRID_FREE_KAPPA: i32 = 113;
/// Hybrid transfer: `free_theta` (0 or 1; 0 for minimum time).
pub const RECONFIG_FIELD_HYBRID_FREE_THETA: i32 = 114;
/// Hybrid transfer: `design_duration_days`.
pub const RECONFIG_FIELD_HYBRID_DESIGN_DURATION: i32 = 115;
/// Hybrid transfer: `design_thrust_n`.
pub const RECONFIG_FIELD_HYBRID_DESIGN_THRUST: i32 = 116;
/// Hybrid transfer: `objective` (`RECONFIG_HYBRID_OBJECTIVE_*`).
pub const RECONFIG_FIELD_HYBRID_OBJECTIVE: i32 = 117;
/// The `workspace` argument.
pub const RECONFIG_FIELD_WORKSPACE: i32 = 40;
/// The `problem` argument.
pub const RECONFIG_FIELD_PROBLEM: i32 = 41;
/// The `settings` argument.
pub const RECONFIG_FIELD_SETTINGS_ARG: i32 = 42;

/// Why a request was refused: which field, which element, the value and the limit it broke.
/// All zero after a solve that was not refused.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct ReconfigError {
    /// The status code of the refusal (`RECONFIG_*ERR_*`), or 0.
    pub code: i32,
    /// Which field (`RECONFIG_FIELD_*`).
    pub field: i32,
    /// Spacecraft, impulse or element index where it applies, else -1.
    pub index: i32,
    /// A second index (the second spacecraft of a pair), else -1.
    pub index2: i32,
    /// A refusal-specific code: settings error class, axis, boundary (see docs/c-api.md), else 0.
    pub detail: i32,
    /// The offending value, in the field's units (counts as numbers).
    pub value: f64,
    /// The limit it broke, in the field's units (0 where the limit is "finite" or "present").
    pub limit: f64,
}

impl ReconfigError {
    /// A refusal with no index.
    pub const fn new(code: i32, field: i32, value: f64, limit: f64) -> Self {
        Self {
            code,
            field,
            index: -1,
            index2: -1,
            detail: 0,
            value,
            limit,
        }
    }

    /// The same refusal about element `index`.
    pub const fn at(self, index: i32) -> Self {
        Self { index, ..self }
    }

    /// The same refusal with its second index.
    pub const fn and(self, index2: i32) -> Self {
        Self { index2, ..self }
    }

    /// The same refusal with its refusal-specific code.
    pub const fn with_detail(self, detail: i32) -> Self {
        Self { detail, ..self }
    }
}

/// Which end of the range `[min, max]` (`(min, max]` with `min_open`) a refused `value` broke
/// and that end, as a refusal's `(detail, limit)`: 0 below (`min`), 1 above (`max`), 2 not
/// finite (`max`). Every planner's out-of-range refusal and every setting's say it this way.
pub fn range_break(value: f64, min: f64, max: f64, min_open: bool) -> (i32, f64) {
    if !value.is_finite() {
        (2, max)
    } else if value < min || (min_open && value <= min) {
        (0, min)
    } else {
        (1, max)
    }
}

/// The C refusal of a setting outside its range.
pub fn setting_error_to_c<S: reconfig_core::contract::SettingId>(
    e: &reconfig_core::contract::SettingError<S>,
) -> ReconfigError {
    let r = e.range;
    let (detail, limit) = range_break(e.value, r.min, r.max, r.min_open);
    ReconfigError::new(
        RECONFIG_ERR_SETTING_OUT_OF_RANGE,
        RECONFIG_FIELD_SETTINGS,
        e.value,
        limit,
    )
    .at(i32::from(e.setting.code()))
    .with_detail(detail)
}

/// The C refusal of a request outside the built-in limits.
pub fn limit_violation_to_c(v: &reconfig_core::limits::LimitViolation) -> ReconfigError {
    ReconfigError::new(
        RECONFIG_ERR_LIMIT_EXCEEDED,
        RECONFIG_FIELD_SETTINGS,
        v.value,
        v.limit,
    )
    .at(i32::from(v.setting.code()))
    .with_detail(i32::from(v.rule as u8))
}

/// First status code of planner A (its statuses are this plus the core's code).
pub(crate) const A_STATUS_BASE: i32 = 0;
/// First status code of planner B.
pub(crate) const B_STATUS_BASE: i32 = 100;

/// The C status code of a core status: `base` plus the status's code, plus one for a budget
/// stop whose plan is not verified; `RECONFIG_UNSOLVED` for `Unsolved`.
pub fn status_code<S: reconfig_core::contract::Status>(base: i32, status: &S) -> i32 {
    match status.code() {
        0 => RECONFIG_UNSOLVED,
        code => base
            .saturating_add(i32::from(code))
            .saturating_add(i32::from(status.budget_exhausted() == Some(false))),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use reconfig_core::{impulsive, pseudospectral};

    #[test]
    fn c_codes_are_base_plus_the_core_code() {
        use pseudospectral::{SolveStatus as A, Stage as AS};
        let a = [
            (A::Unsolved, RECONFIG_UNSOLVED),
            (A::Solved, RECONFIG_A_SOLVED),
            (A::SeparationNotVerified, RECONFIG_A_SEPARATION_NOT_VERIFIED),
            (A::MaxIterations, RECONFIG_A_MAX_ITERATIONS),
            (A::Infeasible, RECONFIG_A_INFEASIBLE),
            (A::QpLimit, RECONFIG_A_QP_LIMIT),
            (A::NumericalFailure(AS::Basis), RECONFIG_A_NUMERICAL_FAILURE),
            (A::Feasible, RECONFIG_A_FEASIBLE),
            (
                A::BudgetExhausted { verified: true },
                RECONFIG_A_BUDGET_EXHAUSTED_VERIFIED,
            ),
            (
                A::BudgetExhausted { verified: false },
                RECONFIG_A_BUDGET_EXHAUSTED_UNVERIFIED,
            ),
        ];
        for (s, c) in a {
            assert_eq!(status_code(A_STATUS_BASE, &s), c, "{s:?}");
        }
        use impulsive::{SolveStatus as B, Stage as BS};
        let b = [
            (B::Unsolved, RECONFIG_UNSOLVED),
            (B::Solved, RECONFIG_B_SOLVED),
            (B::RankDeficient, RECONFIG_B_RANK_DEFICIENT),
            (B::MaxIterations, RECONFIG_B_MAX_ITERATIONS),
            (
                B::CorrectionNotConverged,
                RECONFIG_B_CORRECTION_NOT_CONVERGED,
            ),
            (B::NumericalFailure(BS::Svd), RECONFIG_B_NUMERICAL_FAILURE),
            (
                B::UnsafePerigee {
                    arc: 1,
                    perigee_altitude_km: 50.0,
                },
                RECONFIG_B_UNSAFE_PERIGEE,
            ),
            (B::Linearised { miss_m: 1.0 }, RECONFIG_B_LINEARISED),
            (
                B::BudgetExhausted { verified: true },
                RECONFIG_B_BUDGET_EXHAUSTED_VERIFIED,
            ),
            (
                B::BudgetExhausted { verified: false },
                RECONFIG_B_BUDGET_EXHAUSTED_UNVERIFIED,
            ),
        ];
        for (s, c) in b {
            assert_eq!(status_code(B_STATUS_BASE, &s), c, "{s:?}");
        }
    }
}
