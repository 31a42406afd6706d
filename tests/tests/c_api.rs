//! The C interface end to end: build the static library once, write the fixtures as C data,
//! compile `examples/c/plan_fixtures.c` with `cc`, run it, and check every line against the
//! Rust API's solve of the same fixture (status, cost or total delta-v bits, work units, and a
//! checksum over the bits of the whole trajectory or plan): bit-identical or the test fails.
//!
//! The problems come from `firmware/fixture_set.rs` (the same decoded request bytes the firmware
//! and the QEMU tests use), planner A with default settings, planner B with default settings or
//! `Settings::fixed_point_only()` (`+fixed-point` runs), and planner B's other input forms
//! (ROE, osculating states, the deputy's orbits) through `reconfig_impulsive_solve_form`, whose
//! end state in the request's form is compared too, and the GEO tour's fixtures with their own
//! settings through `reconfig_geo_tour_solve`, and the LEO tour's arcs (the paper's single arc and
//! the arcs of a sequencing fixture's on-board part) with their requests' settings through
//! `reconfig_leo_arc_solve`, plus the first arc once more with `min_gap_s = -1`, refused before
//! planning naming the setting, its value and the end of its range, and the hybrid transfer's
//! fixtures with their own settings through `reconfig_hybrid_solve`, plus the first once more
//! with its arrival velocity moved off the halo orbit, refused naming the miss and the
//! tolerance. The Rust side answers each through the one
//! request path, `wire::answer` with the built-in limits, as the C interface does: the
//! `+fixed-point` runs ask for `nonlinear_correction = 0`, which the limits refuse, and both
//! sides print the refusal (code, field, the setting's code and name, the bits of the value and
//! the limit). Needs `cc`; skipped with a notice when it is missing unless
//! `RECONFIG_REQUIRE_CC=1`.

#[path = "../../firmware/fixture_set.rs"]
mod fixture_set;
#[path = "../../firmware/image_limits.rs"]
mod image_limits;

use reconfig_core::limits::{LimitViolation, Limits};
use reconfig_core::wire::Request;
use reconfig_core::{geo_tour, hybrid, impulsive, leo_tour, pseudospectral, wire};
use std::fmt::Write as _;
use std::path::{Path, PathBuf};
use std::process::Command;
use std::sync::OnceLock;

fn root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .parent()
        .expect("tests/ sits in the workspace")
        .to_path_buf()
}

/// An f64 as a C99 hex-float literal: exact, so C reads the very bits Rust has.
fn hexf(x: f64) -> String {
    let bits = x.to_bits();
    let sign = if bits >> 63 == 1 { "-" } else { "" };
    let exponent = (bits >> 52) & 0x7ff;
    let mantissa = bits & ((1_u64 << 52) - 1);
    assert!(exponent != 0x7ff, "fixtures are finite");
    match exponent {
        0 if mantissa == 0 => format!("{sign}0x0p+0"),
        0 => format!("{sign}0x0.{mantissa:013x}p-1022"),
        e => format!(
            "{sign}0x1.{mantissa:013x}p{:+}",
            i64::try_from(e).unwrap() - 1023
        ),
    }
}

fn doubles(values: &[f64]) -> String {
    let all: Vec<String> = values.iter().map(|v| hexf(*v)).collect();
    format!("{{{}}}", all.join(", "))
}

fn a_case(name: &str, p: &pseudospectral::Problem) -> String {
    let mut sc = String::new();
    for s in &p.spacecraft {
        let _ = write!(
            sc,
            "{{{}, {}, {}}}, ",
            hexf(s.mass_mu),
            doubles(&s.initial_state),
            doubles(&s.final_state)
        );
    }
    format!(
        "    {{\"{name}\", {{{}, {}, {}, {}, {}, {}, {{{sc}}}}}}},\n",
        hexf(p.horizon_tu),
        hexf(p.max_control_fu),
        hexf(p.keep_out_lu),
        p.degree,
        u8::from(p.test_points),
        p.spacecraft.len()
    )
}

fn b_case(name: &str, fixed_point_only: bool, p: &impulsive::Problem) -> String {
    let c = &p.chief;
    let chief = doubles(&[
        c.sma_km,
        c.ecc,
        c.inc_rad,
        c.raan_rad,
        c.argp_rad,
        c.mean_anomaly_rad,
    ]);
    let rel = |r: &impulsive::RelativeElements| {
        doubles(&[
            r.dsma_km,
            r.decc,
            r.dinc_rad,
            r.draan_rad,
            r.dargp_rad,
            r.dmean_anomaly_rad,
        ])
    };
    let (search, count, max_revolutions, points) = plan_fields(&p.plan);
    format!(
        "    {{\"{name}\", {}, {{{chief}, {}, {}, {search}, {count}, {max_revolutions}, {{{points}}}}}}},\n",
        u8::from(fixed_point_only),
        rel(&p.initial),
        rel(&p.target),
    )
}

/// A C99 designated initializer of the six numbers of a struct whose members are given.
fn members(names: [&str; 6], values: [f64; 6]) -> String {
    let fields: Vec<String> = names
        .iter()
        .zip(values)
        .map(|(n, v)| format!(".{n} = {}", hexf(v)))
        .collect();
    format!("{{{}}}", fields.join(", "))
}

const MEAN: [&str; 6] = [
    "sma_km",
    "ecc",
    "inc_rad",
    "raan_rad",
    "argp_rad",
    "mean_anomaly_rad",
];
const RELATIVE: [&str; 6] = [
    "dsma_km",
    "decc",
    "dinc_rad",
    "draan_rad",
    "dargp_rad",
    "dmean_anomaly_rad",
];
const EQUINOCTIAL: [&str; 6] = ["sma_km", "mean_longitude_rad", "ex", "ey", "hx", "hy"];
const ROE: [&str; 6] = ["da_m", "dlambda_m", "dex_m", "dey_m", "dix_m", "diy_m"];

fn mean_values(m: &impulsive::MeanElements) -> [f64; 6] {
    [
        m.sma_km,
        m.ecc,
        m.inc_rad,
        m.raan_rad,
        m.argp_rad,
        m.mean_anomaly_rad,
    ]
}

fn relative_values(r: &impulsive::RelativeElements) -> [f64; 6] {
    [
        r.dsma_km,
        r.decc,
        r.dinc_rad,
        r.draan_rad,
        r.dargp_rad,
        r.dmean_anomaly_rad,
    ]
}

fn equinoctial_values(q: &impulsive::EquinoctialElements) -> [f64; 6] {
    [q.sma_km, q.mean_longitude_rad, q.ex, q.ey, q.hx, q.hy]
}

fn roe_values(r: &impulsive::Roe) -> [f64; 6] {
    [r.da_m, r.dlambda_m, r.dex_m, r.dey_m, r.dix_m, r.diy_m]
}

fn state_values(s: &impulsive::CartesianState) -> [f64; 6] {
    [
        s.pos_km[0],
        s.pos_km[1],
        s.pos_km[2],
        s.vel_km_s[0],
        s.vel_km_s[1],
        s.vel_km_s[2],
    ]
}

/// A `ReconfigBOrbitForm` initializer.
fn orbit_form(o: &impulsive::OrbitForm) -> String {
    match o {
        impulsive::OrbitForm::Classical(m) => format!(
            "{{.form = RECONFIG_B_ORBIT_CLASSICAL, .classical = {}}}",
            members(MEAN, mean_values(m))
        ),
        impulsive::OrbitForm::Equinoctial(q) => format!(
            "{{.form = RECONFIG_B_ORBIT_EQUINOCTIAL, .equinoctial = {}}}",
            members(EQUINOCTIAL, equinoctial_values(q))
        ),
        impulsive::OrbitForm::State(s) => format!(
            "{{.form = RECONFIG_B_ORBIT_STATE, .state = {{.pos_km = {}, .vel_km_s = {}}}}}",
            doubles(&s.pos_km),
            doubles(&s.vel_km_s)
        ),
    }
}

fn f_case(name: &str, fixed_point_only: bool, p: &impulsive::FormProblem) -> String {
    let relative = match &p.relative {
        impulsive::RelativeForm::Elements { initial, target } => format!(
            "{{.form = RECONFIG_B_RELATIVE_ELEMENTS, .initial_elements = {}, .target_elements = {}}}",
            members(RELATIVE, relative_values(initial)),
            members(RELATIVE, relative_values(target))
        ),
        impulsive::RelativeForm::Roe { initial, target } => format!(
            "{{.form = RECONFIG_B_RELATIVE_ROE, .initial_roe = {}, .target_roe = {}}}",
            members(ROE, roe_values(initial)),
            members(ROE, roe_values(target))
        ),
        impulsive::RelativeForm::Deputy { initial, target } => format!(
            "{{.form = RECONFIG_B_RELATIVE_DEPUTY, .initial_orbit = {}, .target_orbit = {}}}",
            orbit_form(initial),
            orbit_form(target)
        ),
    };
    let (search, count, max_revolutions, points) = plan_fields(&p.plan);
    format!(
        "    {{\"{name}\", {}, {{.chief = {}, .relative = {relative}, .search = {search}, \
         .impulse_count = {count}, .max_revolutions = {max_revolutions}, .points = {{{points}}}}}}},\n",
        u8::from(fixed_point_only),
        orbit_form(&p.chief),
    )
}

/// The plan fields every planner-B problem form shares: (search flag, impulse count, maximum
/// revolutions, the fixed points' initializers).
fn plan_fields(plan: &impulsive::ImpulsePlan) -> (u8, usize, i32, String) {
    match plan {
        impulsive::ImpulsePlan::Fixed(points) => {
            let text: Vec<String> = points
                .iter()
                .map(|q| format!("{{{}, {}}}", hexf(q.arg_latitude_rad), q.revolutions))
                .collect();
            (0, points.len(), 0, text.join(", "))
        }
        impulsive::ImpulsePlan::Search {
            impulses,
            max_revolutions,
        } => (1, usize::from(*impulses), *max_revolutions, String::new()),
    }
}

fn g_case(name: &str, p: &geo_tour::Problem, st: &geo_tour::Settings) -> String {
    let targets: Vec<String> = p.targets_lon_rad.iter().map(|v| hexf(*v)).collect();
    let sweep = match p.sweep {
        geo_tour::SweepChoice::Cheaper => "RECONFIG_GEO_SWEEP_CHEAPER",
        geo_tour::SweepChoice::East => "RECONFIG_GEO_SWEEP_EAST",
        geo_tour::SweepChoice::West => "RECONFIG_GEO_SWEEP_WEST",
    };
    let policy = match p.policy {
        geo_tour::MethodPolicy::ByCost => "RECONFIG_GEO_POLICY_BY_COST",
        geo_tour::MethodPolicy::PaperRule => "RECONFIG_GEO_POLICY_PAPER_RULE",
        geo_tour::MethodPolicy::PaperRuleFreeLambert => {
            "RECONFIG_GEO_POLICY_PAPER_RULE_FREE_LAMBERT"
        }
    };
    format!(
        "    {{\"{name}\", {{.start_lon_rad = {}, .mission_time_s = {}, .max_burn_mps = {}, \
         .target_count = {}, .sweep = {sweep}, .policy = {policy}, .targets_lon_rad = {{{}}}}}, \
         {{.lambert_tol = {}, .time_tol_s = {}, .exchange_margin_mps = {}, .min_radius_km = {}, \
         .rule_drift_above_rad = {}, .rule_hohmann_above_rad = {}, .rule_radial_above_rad = {}, \
         .lambert_direct_time_s = {}, .lambert_max_revolutions = {}, .lambert_max_iter = {}, \
         .well_iterations = {}, .root_max_iter = {}, .price_max_iter = {}, .exchange_rounds = {}, \
         .gap_max_legs = {}, .work_budget = {}ULL}}}},\n",
        hexf(p.start_lon_rad),
        hexf(p.mission_time_s),
        hexf(p.max_burn_mps),
        p.targets_lon_rad.len(),
        targets.join(", "),
        hexf(st.lambert_tol),
        hexf(st.time_tol_s),
        hexf(st.exchange_margin_mps),
        hexf(st.min_radius_km),
        hexf(st.rule_drift_above_rad),
        hexf(st.rule_hohmann_above_rad),
        hexf(st.rule_radial_above_rad),
        hexf(st.lambert_direct_time_s),
        st.lambert_max_revolutions,
        st.lambert_max_iter,
        st.well_iterations,
        st.root_max_iter,
        st.price_max_iter,
        st.exchange_rounds,
        st.gap_max_legs,
        st.work_budget,
    )
}

/// A `LCase` initializer: the arc's states split into positions and velocities, its settings
/// field by field (every field of `ReconfigLeoArcSettings` named).
fn l_case(name: &str, p: &leo_tour::ArcProblem, st: &leo_tour::Settings) -> String {
    let model = match st.search_model {
        leo_tour::flight::Model::Planning => "RECONFIG_LEO_MODEL_PLANNING",
        leo_tour::flight::Model::MeanElements => "RECONFIG_LEO_MODEL_MEAN_ELEMENTS",
    };
    let [fp @ .., _, _, _] = p.from;
    let [_, _, _, fv @ ..] = p.from;
    let [tp @ .., _, _, _] = p.to;
    let [_, _, _, tv @ ..] = p.to;
    format!(
        "    {{\"{name}\", {{.from_position_km = {}, .from_velocity_km_s = {}, \
         .to_position_km = {}, .to_velocity_km_s = {}, .duration_s = {}, .impulses = {}}}, \
         {{.mu_km3_s2 = {}, .re_km = {}, .j2 = {}, .step_s = {}, .lambert_tol = {}, \
         .arrival_tol_km = {}, .search_step_s = {}, .search_step_km_s = {}, \
         .search_min_step_s = {}, .min_gap_s = {}, .min_transfer_altitude_km = {}, \
         .work_budget = {}ULL, .max_steps = {}u, .search_max_evals = {}u, \
         .polish_max_evals = {}u, .lambert_max_iter = {}, .max_revolutions = {}, \
         .shoot_max_iter = {}, .grid_points = {}, .candidates = {}, .hop_rounds = {}, \
         .search_model = {model}}}}},\n",
        doubles(&fp),
        doubles(&fv),
        doubles(&tp),
        doubles(&tv),
        hexf(p.duration_s),
        p.impulses,
        hexf(st.mu_km3_s2),
        hexf(st.re_km),
        hexf(st.j2),
        hexf(st.step_s),
        hexf(st.lambert_tol),
        hexf(st.arrival_tol_km),
        hexf(st.search_step_s),
        hexf(st.search_step_km_s),
        hexf(st.search_min_step_s),
        hexf(st.min_gap_s),
        hexf(st.min_transfer_altitude_km),
        st.work_budget,
        st.max_steps,
        st.search_max_evals,
        st.polish_max_evals,
        st.lambert_max_iter,
        st.max_revolutions,
        st.shoot_max_iter,
        st.grid_points,
        st.candidates,
        st.hop_rounds,
    )
}

/// An `HCase` initializer: the request's problem and settings field by field (every field of
/// `ReconfigHybridProblem` and `ReconfigHybridSettings` named).
fn h_case(name: &str, p: &hybrid::Problem, st: &hybrid::Settings) -> String {
    let objective = match p.objective {
        hybrid::Objective::MinFuel => "RECONFIG_HYBRID_OBJECTIVE_MIN_FUEL",
        hybrid::Objective::MinEnergy => "RECONFIG_HYBRID_OBJECTIVE_MIN_ENERGY",
        hybrid::Objective::MinTime => "RECONFIG_HYBRID_OBJECTIVE_MIN_TIME",
    };
    format!(
        "    {{\"{name}\", {{.kappa = {}, .theta_rad = {}, .duration_days = {}, .thrust_n = {}, \
         .specific_impulse_s = {}, .chemical_specific_impulse_s = {}, .parking_radius_km = {}, \
         .departure_offset = {}, .arrival_r_lu = {}, .arrival_v_vu = {}, .halo_period_tu = {}, \
         .costates = {}, .cost_multiplier = {}, .design_duration_days = {}, \
         .design_thrust_n = {}, .objective = {objective}, .free_kappa = {}, .free_theta = {}}}, \
         {{.tolerance = {}, .hamiltonian_tol = {}, .relative_tol = {}, .absolute_tol = {}, \
         .halo_closure_tol = {}, .flight_tol = {}, .work_budget = {}ULL, .max_iterations = {}, \
         .max_halvings = {}, .check_segments = {}, .continuation_steps = {}}}}},\n",
        hexf(p.kappa),
        hexf(p.theta_rad),
        hexf(p.duration_days),
        hexf(p.thrust_n),
        hexf(p.specific_impulse_s),
        hexf(p.chemical_specific_impulse_s),
        hexf(p.parking_radius_km),
        doubles(&p.departure_offset),
        doubles(&p.arrival_r_lu),
        doubles(&p.arrival_v_vu),
        hexf(p.halo_period_tu),
        doubles(&p.costates),
        hexf(p.cost_multiplier),
        hexf(p.design_duration_days),
        hexf(p.design_thrust_n),
        u8::from(p.free_kappa),
        u8::from(p.free_theta),
        hexf(st.tolerance),
        hexf(st.hamiltonian_tol),
        hexf(st.relative_tol),
        hexf(st.absolute_tol),
        hexf(st.halo_closure_tol),
        hexf(st.flight_tol),
        st.work_budget,
        st.max_iterations,
        st.max_halvings,
        st.check_segments,
        st.continuation_steps,
    )
}

const FNV_OFFSET: u64 = 0xcbf2_9ce4_8422_2325;
const FNV_PRIME: u64 = 0x0000_0100_0000_01b3;

fn mix(h: u64, x: f64) -> u64 {
    (h ^ x.to_bits()).wrapping_mul(FNV_PRIME)
}

/// The Rust API's answer to `request`: the one request path every front end answers through,
/// with the built-in limits (the flight service's, and the C interface's).
fn answer_with<T>(request: &wire::Request, line: impl FnOnce(wire::OutcomeRef<'_>) -> T) -> T {
    thread_local! {
        static BUFFERS: std::cell::RefCell<Box<wire::AllPlanners>> =
            std::cell::RefCell::new(Box::new(wire::AllPlanners::new()));
    }
    BUFFERS.with(|b| {
        let mut buffers = b.borrow_mut();
        line(wire::answer(request, &Limits::default(), &mut **buffers))
    })
}

/// The line the C example must print for a request the limits refuse: the refusal's code,
/// field, index, the setting's name (`reconfig_setting_name` in C, the core's table here), and
/// the bits of the value and the limit.
fn refusal_line(kind: char, name: &str, v: &LimitViolation) -> String {
    let e = reconfig_capi::status::limit_violation_to_c(v);
    format!(
        "{kind} {name} status={} field={} index={} setting={} value_bits={:016x} limit_bits={:016x}",
        e.code,
        e.field,
        e.index,
        v.setting.name(),
        e.value.to_bits(),
        e.limit.to_bits()
    )
}

/// The line the C example must print for a planner-A fixture, from the Rust API.
fn a_expected(name: &str, p: &pseudospectral::Problem) -> String {
    let request = wire::Request::Pseudospectral {
        problem: p.clone(),
        settings: pseudospectral::Settings::default(),
    };
    answer_with(&request, |outcome| {
        let s = match outcome {
            wire::OutcomeRef::Pseudospectral(s) => s,
            wire::OutcomeRef::LimitExceeded(v) => return refusal_line('A', name, &v),
            other => panic!("{name}: every planner-A fixture is planned ({other:?})"),
        };
        let mut h = FNV_OFFSET;
        for (states, controls) in s.states.iter().zip(s.controls_fu.iter()) {
            for (x, u) in states.iter().zip(controls.iter()) {
                h = x.iter().chain(u.iter()).fold(h, |h, v| mix(h, *v));
            }
        }
        let (status, _) = reconfig_capi::convert_a::status_to_c(s.info.status);
        format!(
            "A {name} status={status} usable={} J={:.9} J_bits={:016x} min_sep_bits={:016x} work_units={} checksum={h:016x}",
            u8::from(s.info.status.is_usable()),
            s.cost,
            s.cost.to_bits(),
            s.min_separation_lu.unwrap_or(0.0).to_bits(),
            s.info.work_units
        )
    })
}

/// Planner B's settings of a run: the defaults, or `+fixed-point` (the C example's
/// `min_fuel = 0`, `nonlinear_correction = 0`, which the built-in limits refuse: they require
/// the nonlinear correction).
fn b_settings(fixed_point_only: bool) -> impulsive::Settings {
    if fixed_point_only {
        impulsive::Settings::fixed_point_only()
    } else {
        impulsive::Settings::default()
    }
}

/// The line the C example must print for a planner-B fixture, from the Rust API.
fn b_expected(name: &str, fixed_point_only: bool, p: &impulsive::Problem) -> String {
    let request = wire::Request::Impulsive {
        problem: p.clone(),
        settings: b_settings(fixed_point_only),
    };
    answer_with(&request, |outcome| {
        let s = match outcome {
            wire::OutcomeRef::Impulsive(s) => s,
            wire::OutcomeRef::LimitExceeded(v) => return refusal_line('B', name, &v),
            other => panic!("{name}: every planner-B fixture is planned ({other:?})"),
        };
        let mut h = FNV_OFFSET;
        for i in &s.impulses {
            h = mix(h, i.time_s);
            h = i.dv_rtn_mps.iter().fold(h, |h, v| mix(h, *v));
        }
        // C writes 0 with has_terminal_error = 0 when the check was not flown.
        h = mix(h, s.terminal_error.map_or(0.0, |t| t.position_m));
        let (status, ..) = reconfig_capi::convert_b::status_to_c(s.info.status);
        format!(
            "B {name} status={status} usable={} impulses={} dv_mps={:.9} dv_bits={:016x} work_units={} checksum={h:016x}",
            u8::from(s.info.status.is_usable()),
            s.impulses.len(),
            s.total_dv_mps,
            s.total_dv_mps.to_bits(),
            s.info.work_units
        )
    })
}

/// The line the C example must print for a fixture in other forms, from the Rust API
/// (`Request::ImpulsiveForm`): as planner B's, plus the end state's form and a checksum over
/// its numbers.
fn f_expected(name: &str, fixed_point_only: bool, p: &impulsive::FormProblem) -> String {
    let request = wire::Request::ImpulsiveForm {
        problem: p.clone(),
        settings: b_settings(fixed_point_only),
    };
    answer_with(&request, |outcome| {
        let (s, end) = match outcome {
            wire::OutcomeRef::ImpulsiveForm {
                solution,
                end_state,
            } => (solution, end_state),
            wire::OutcomeRef::LimitExceeded(v) => return refusal_line('F', name, &v),
            other => panic!("{name}: every form fixture is planned ({other:?})"),
        };
        let mut h = FNV_OFFSET;
        for i in &s.impulses {
            h = mix(h, i.time_s);
            h = i.dv_rtn_mps.iter().fold(h, |h, v| mix(h, *v));
        }
        // C writes 0 with has_terminal_error = 0 when the check was not flown.
        h = mix(h, s.terminal_error.map_or(0.0, |t| t.position_m));
        let c_end = reconfig_capi::convert_b_form::end_state_to_c(&end);
        let values: Option<[f64; 6]> = match &end {
            impulsive::EndState::Elements(r) => Some(relative_values(r)),
            impulsive::EndState::Roe(r) => Some(roe_values(r)),
            impulsive::EndState::DeputyClassical(m) => Some(mean_values(m)),
            impulsive::EndState::DeputyEquinoctial(q) => Some(equinoctial_values(q)),
            impulsive::EndState::DeputyState(st) => Some(state_values(st)),
            impulsive::EndState::Unavailable(_) | impulsive::EndState::NotFlown => None,
        };
        let end_checksum = values.iter().flatten().fold(FNV_OFFSET, |h, v| mix(h, *v));
        let (status, ..) = reconfig_capi::convert_b::status_to_c(s.info.status);
        format!(
            "F {name} status={status} usable={} impulses={} dv_mps={:.9} dv_bits={:016x} work_units={} checksum={h:016x} end_form={} end_checksum={end_checksum:016x}",
            u8::from(s.info.status.is_usable()),
            s.impulses.len(),
            s.total_dv_mps,
            s.total_dv_mps.to_bits(),
            s.info.work_units,
            c_end.form,
        )
    })
}

/// The line the C example must print for a GEO tour fixture, from the Rust API.
fn g_expected(name: &str, p: &geo_tour::Problem, settings: &geo_tour::Settings) -> String {
    let request = wire::Request::GeoTour {
        problem: p.clone(),
        settings: *settings,
    };
    answer_with(&request, |outcome| {
        let s = match outcome {
            wire::OutcomeRef::GeoTour(s) => s,
            wire::OutcomeRef::LimitExceeded(v) => return refusal_line('G', name, &v),
            other => panic!("{name}: every GEO fixture is planned ({other:?})"),
        };
        let mut h = FNV_OFFSET;
        for leg in &s.legs {
            h = mix(mix(mix(h, leg.start_s), leg.duration_s), leg.dv_mps);
            for b in &leg.burns {
                h = b
                    .dv_rtn_mps
                    .iter()
                    .fold(mix(h, b.offset_s), |h, v| mix(h, *v));
            }
        }
        h = mix(h, s.mission_time_s);
        let (status, _) = reconfig_capi::convert_geo::status_to_c(s.info.status);
        let fastest = s
            .info
            .fastest_tour_s
            .map_or_else(|| "none".to_owned(), |t| format!("{:016x}", t.to_bits()));
        format!(
            "G {name} status={status} usable={} legs={} dv_mps={:.9} dv_bits={:016x} \
             work_units={} fastest_tour={fastest} checksum={h:016x}",
            u8::from(s.info.status.is_usable()),
            s.legs.len(),
            s.total_dv_mps,
            s.total_dv_mps.to_bits(),
            s.info.work_units,
        )
    })
}

/// The line the C example must print for a LEO arc, from the Rust API: the status, the burns'
/// count, the total delta-v and its bits, the work units and a checksum over every burn's epoch
/// and components (RTN m/s, inertial km/s), the miss and the lowest altitude (0 when absent, as
/// C writes them). A refusal by the arc's own validation prints its code, field, index, the
/// setting's name, the value's and the limit's bits, as C's `print_refusal`.
fn l_expected(name: &str, p: &leo_tour::ArcProblem, settings: &leo_tour::Settings) -> String {
    let request = wire::Request::LeoArc {
        problem: *p,
        settings: *settings,
    };
    answer_with(&request, |outcome| {
        let s = match outcome {
            wire::OutcomeRef::LeoArc(s) => s,
            wire::OutcomeRef::LimitExceeded(v) => return refusal_line('L', name, &v),
            wire::OutcomeRef::LeoArcRejected(leo_tour::PlanError::InvalidSetting(e)) => {
                // The C refusal of a setting out of range: the end of the range it broke.
                let r = e.range;
                let limit = if e.value < r.min { r.min } else { r.max };
                return format!(
                    "L {name} status={} field={} index={} setting={} value_bits={:016x} \
                     limit_bits={:016x}",
                    reconfig_capi::status::RECONFIG_ERR_SETTING_OUT_OF_RANGE,
                    reconfig_capi::status::RECONFIG_FIELD_SETTINGS,
                    e.setting as u8,
                    e.setting.name(),
                    e.value.to_bits(),
                    limit.to_bits()
                );
            }
            other => panic!("{name}: every LEO arc fixture is planned ({other:?})"),
        };
        let mut h = FNV_OFFSET;
        for b in s.burns.iter().take(usize::from(s.impulses)) {
            h = mix(h, b.epoch_s);
            h = b.rtn_mps.iter().fold(h, |h, v| mix(h, *v));
            h = b.dv_km_s.iter().fold(h, |h, v| mix(h, *v));
        }
        h = mix(h, s.miss_m.unwrap_or(0.0));
        h = mix(h, s.lowest_altitude_km.unwrap_or(0.0));
        let status = reconfig_capi::convert_leo::status_to_c(s.info.status);
        format!(
            "L {name} status={status} usable={} impulses={} dv_mps={:.9} dv_bits={:016x} \
             work_units={} checksum={h:016x}",
            u8::from(s.info.status.is_usable()),
            s.impulses,
            s.total_dv_mps,
            s.total_dv_mps.to_bits(),
            s.info.work_units,
        )
    })
}

/// The line the C example must print for a hybrid transfer, from the Rust API: the status,
/// the Newton iterations, the walk's shootings, the check flight's final mass (0 when it was not
/// flown) and its bits, the bits of the time of flight, the work units and a checksum over every
/// number of the answer (as examples/c/checksum.h's `hybrid_checksum`, absent values 0 as C
/// writes them). A refusal by the planner prints the C refusal (`convert_hybrid::error_to_c`):
/// code, field, index, the setting's name when it names a setting, the value's and the limit's
/// bits, as C's `print_refusal`.
fn h_expected(name: &str, p: &hybrid::Problem, settings: &hybrid::Settings) -> String {
    let request = wire::Request::Hybrid {
        problem: *p,
        settings: *settings,
    };
    answer_with(&request, |outcome| {
        let s = match outcome {
            wire::OutcomeRef::Hybrid(s) => s,
            wire::OutcomeRef::LimitExceeded(v) => return refusal_line('H', name, &v),
            wire::OutcomeRef::HybridRejected(e) => {
                let c = reconfig_capi::convert_hybrid::error_to_c(&e);
                let setting = match e {
                    hybrid::PlanError::InvalidSetting(s) => s.setting.name(),
                    _ => "-",
                };
                return format!(
                    "H {name} status={} field={} index={} setting={setting} value_bits={:016x} \
                     limit_bits={:016x}",
                    c.code,
                    c.field,
                    c.index,
                    c.value.to_bits(),
                    c.limit.to_bits()
                );
            }
            other => panic!("{name}: every hybrid fixture is planned ({other:?})"),
        };
        let flown = s.flown.unwrap_or_default();
        let mut h = FNV_OFFSET;
        for x in [s.kappa, s.theta_rad, s.duration_tu] {
            h = mix(h, x);
        }
        h = s.costates.iter().fold(h, |h, v| mix(h, *v));
        for x in [
            s.cost_multiplier,
            s.mass_after_impulse,
            s.residual.unwrap_or(0.0),
            s.info.walked.reached,
            flown.final_mass,
            flown.end_miss,
            flown.hamiltonian_drift,
        ] {
            h = mix(h, x);
        }
        h = flown.switch_times_tu.iter().fold(h, |h, v| mix(h, *v));
        let (status, _) = reconfig_capi::convert_hybrid::status_to_c(s.info.status);
        format!(
            "H {name} status={status} usable={} iterations={} walked={} m_f={:.9} \
             mass_bits={:016x} tf_bits={:016x} work_units={} checksum={h:016x}",
            u8::from(s.info.status.is_usable()),
            s.info.iterations,
            s.info.walked.shootings,
            flown.final_mass,
            flown.final_mass.to_bits(),
            s.duration_tu.to_bits(),
            s.info.work_units,
        )
    })
}

fn run(cmd: &mut Command, what: &str) -> String {
    let out = cmd
        .output()
        .unwrap_or_else(|e| panic!("{what}: cannot start: {e}"));
    assert!(
        out.status.success(),
        "{what} failed ({}):\n{}\n{}",
        out.status,
        String::from_utf8_lossy(&out.stdout),
        String::from_utf8_lossy(&out.stderr)
    );
    String::from_utf8_lossy(&out.stdout).into_owned()
}

/// The fixtures as C data and the Rust API's expected lines, made once per test run.
struct Prepared {
    dir: PathBuf,
    expected: Vec<String>,
}

fn prepared() -> &'static Prepared {
    static PREPARED: OnceLock<Prepared> = OnceLock::new();
    PREPARED.get_or_init(|| {
        let fixtures =
            fixture_set::encode_all(&root().join("fixtures"), &image_limits::IMAGE_LIMITS)
                .expect("fixtures load");
        let mut a_cases = String::new();
        let mut b_cases = String::new();
        let mut f_cases = String::new();
        let mut g_cases = String::new();
        let mut l_cases = String::new();
        let mut l_first = None;
        let mut h_cases = String::new();
        let mut h_first = None;
        let mut expected = Vec::new();
        for f in &fixtures {
            let request: Request = postcard::from_bytes(&f.request).unwrap();
            let fixed = |settings: &impulsive::Settings| {
                *settings == impulsive::Settings::fixed_point_only()
            };
            match &request {
                Request::Pseudospectral { problem: p, .. } => {
                    a_cases.push_str(&a_case(&f.name, p));
                    expected.push(a_expected(&f.name, p));
                }
                Request::Impulsive {
                    problem: p,
                    settings,
                } => {
                    b_cases.push_str(&b_case(&f.name, fixed(settings), p));
                    expected.push(b_expected(&f.name, fixed(settings), p));
                }
                Request::ImpulsiveForm {
                    problem: p,
                    settings,
                } => {
                    f_cases.push_str(&f_case(&f.name, fixed(settings), p));
                    expected.push(f_expected(&f.name, fixed(settings), p));
                }
                Request::GeoTour {
                    problem: p,
                    settings: st,
                } => {
                    g_cases.push_str(&g_case(&f.name, p, st));
                    expected.push(g_expected(&f.name, p, st));
                }
                Request::LeoArc {
                    problem: p,
                    settings: st,
                } => {
                    l_cases.push_str(&l_case(&f.name, p, st));
                    expected.push(l_expected(&f.name, p, st));
                    l_first.get_or_insert((f.name.clone(), *p));
                }
                Request::Hybrid {
                    problem: p,
                    settings: st,
                } => {
                    h_cases.push_str(&h_case(&f.name, p, st));
                    expected.push(h_expected(&f.name, p, st));
                    h_first.get_or_insert((f.name.clone(), *p, *st));
                }
                // The LEO tour's order has no C interface.
                Request::LeoSequence { .. } => {}
            }
        }
        // The first arc once more with `min_gap_s = -1` (the C programs' last line): refused
        // by the arc's own validation, named.
        let (first_name, first_arc) = l_first.expect("the LEO arc fixtures are among the fixtures");
        let bad = leo_tour::Settings {
            min_gap_s: -1.0,
            ..leo_tour::Settings::default()
        };
        expected.push(l_expected(
            &format!("{first_name}+bad-min-gap"),
            &first_arc,
            &bad,
        ));
        // The first hybrid transfer once more with its arrival velocity off the halo orbit (the
        // C programs' last line): refused by the planner's halo check, the miss and the
        // tolerance.
        let (h_name, h_problem, h_settings) =
            h_first.expect("the hybrid fixtures are among the fixtures");
        let mut off = h_problem;
        off.arrival_v_vu[1] += 1e-3;
        expected.push(h_expected(&format!("{h_name}+off-halo"), &off, &h_settings));
        // Planner A lines first, then planner B, its other forms, the GEO tour, the LEO arcs and
        // the hybrid transfer, as the programs print them (the sort is stable: fixture order
        // within each).
        expected.sort_by_key(|line| match line.as_bytes().first() {
            Some(b'A') => 0,
            Some(b'B') => 1,
            Some(b'F') => 2,
            Some(b'G') => 3,
            Some(b'L') => 4,
            _ => 5,
        });
        assert!(
            expected.iter().any(|l| l.starts_with("F ")),
            "the planner-B form fixtures are among the fixtures"
        );
        assert!(
            expected.iter().any(|l| l.starts_with("G ")),
            "the GEO tour fixtures are among the fixtures"
        );
        assert!(
            expected
                .iter()
                .any(|l| l.contains("huang2012-three-sats-n10 "))
                && expected.iter().any(|l| l.starts_with("B wang2018")),
            "the paper cases are among the fixtures"
        );
        // The paper's single arc is planned through C, usable (301, or 303: the default work
        // budget stops the search with a verified plan); the bad-gap run is refused naming
        // `min_gap_s`, its value -1 and the end 0 of its range.
        assert!(
            expected.iter().any(|l| {
                l.starts_with("L leo-tour-example1-single-arc status=30")
                    && l.contains(" usable=1 impulses=3 ")
            }),
            "the paper's single arc is among the fixtures, solved: {expected:#?}"
        );
        assert!(
            expected.iter().any(|l| l.ends_with(&format!(
                "+bad-min-gap status=-6 field=6 index=17 setting=min_gap_s value_bits={:016x} \
                 limit_bits={:016x}",
                (-1.0_f64).to_bits(),
                0.0_f64.to_bits()
            ))),
            "the bad-gap run is refused by name, value and limit: {expected:#?}"
        );
        // Every hybrid fixture (the paper's kappa = 1.40 rows and minimum time) is planned
        // through C, solved and usable; the off-halo run is refused by the halo check.
        let hybrid: Vec<&String> = expected
            .iter()
            .filter(|l| l.starts_with("H hybrid-") && !l.contains("+off-halo"))
            .collect();
        assert!(
            hybrid.len() == 8 && hybrid.iter().all(|l| l.contains(" status=501 usable=1 ")),
            "the 8 hybrid fixtures are solved through C: {hybrid:#?}"
        );
        assert!(
            expected.iter().any(|l| l.contains(
                "+off-halo status=-602 field=110 index=-1 \
                 setting=- "
            )),
            "the off-halo run is refused by the halo check: {expected:#?}"
        );
        // The built-in limits require the nonlinear correction: the `+fixed-point` runs are
        // refused (in C as by the flight service), naming the setting, its value and limit.
        let refused: Vec<&String> = expected
            .iter()
            .filter(|l| l.contains(" status=-7 "))
            .collect();
        assert!(
            !refused.is_empty()
                && refused
                    .iter()
                    .all(|l| l.contains("+fixed-point ")
                        && l.contains(" setting=nonlinear_correction ")),
            "the +fixed-point runs and only they are refused by the limits: {refused:#?}"
        );
        let dir = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("c_api");
        std::fs::create_dir_all(&dir).unwrap();
        std::fs::write(
            dir.join("fixture_data.h"),
            format!(
                "/* Generated by tests/tests/c_api.rs from the fixture files. */\n\
                 static const ACase A_CASES[] = {{\n{a_cases}}};\n\
                 static const BCase B_CASES[] = {{\n{b_cases}}};\n\
                 static const FCase F_CASES[] = {{\n{f_cases}}};\n\
                 static const GCase G_CASES[] = {{\n{g_cases}}};\n\
                 static const LCase L_CASES[] = {{\n{l_cases}}};\n\
                 static const HCase H_CASES[] = {{\n{h_cases}}};\n"
            ),
        )
        .unwrap();
        Prepared { dir, expected }
    })
}

fn cargo() -> Command {
    let mut cmd = Command::new(std::env::var("CARGO").unwrap_or_else(|_| "cargo".into()));
    cmd.current_dir(root());
    cmd
}

#[test]
fn c_example_is_bit_identical_to_the_rust_api_on_every_fixture() {
    if Command::new("cc").arg("--version").output().is_err() {
        assert!(
            std::env::var_os("RECONFIG_REQUIRE_CC").is_none(),
            "cc is required (RECONFIG_REQUIRE_CC=1)"
        );
        eprintln!("c_api: skipped, no C compiler `cc`");
        return;
    }
    let root = root();
    let Prepared { dir, expected } = prepared();
    // The static library, built once for the whole run (release: the flight build's profile).
    run(
        cargo().args(["build", "--release", "-p", "reconfig-capi"]),
        "cargo build -p reconfig-capi",
    );
    let lib = root.join("target/release/libreconfig_capi.a");
    let exe = dir.join("plan_fixtures");
    run(
        Command::new("cc")
            .args(["-std=c99", "-O2", "-Wall", "-Wextra", "-Werror"])
            .arg("-I")
            .arg(root.join("capi/include"))
            .arg("-I")
            .arg(root.join("examples/c"))
            .arg("-I")
            .arg(dir)
            .arg(root.join("examples/c/plan_fixtures.c"))
            .arg(&lib)
            .args(["-lpthread", "-ldl", "-lm", "-o"])
            .arg(&exe),
        "cc examples/c/plan_fixtures.c",
    );
    let stdout = run(&mut Command::new(&exe), "plan_fixtures");
    let got: Vec<&str> = stdout.lines().collect();
    assert_eq!(got.len(), expected.len(), "one line per fixture:\n{stdout}");
    for (g, e) in got.iter().zip(expected.iter()) {
        assert_eq!(*g, e.as_str(), "C and Rust differ");
    }
    reconfig_host::figure_record::hold(
        "c-interface",
        &reconfig_host::figure_record::Figure {
            what: "C interface vs Rust, host (the M7 C image under QEMU: the same lines)".into(),
            target: "bit-identical".into(),
            measured: format!("{} of {} runs", got.len(), expected.len()),
            met: true,
            doc: "c-api".into(),
            command: "cargo test -p reconfig-tests --test c_api".into(),
        },
    )
    .unwrap();
}

/// The first tool of `candidates` that runs, if any.
fn first_tool(candidates: &[&'static str]) -> Option<&'static str> {
    candidates.iter().copied().find(|tool| {
        Command::new(tool)
            .arg("--version")
            .output()
            .is_ok_and(|o| o.status.success())
    })
}

/// The expected M7 line: the host line's fields that do not need `printf` (status, bits, work
/// units, checksum).
fn m7_fields(host_line: &str) -> String {
    const KEPT: [&str; 15] = [
        "status=",
        "J_bits=",
        "min_sep_bits=",
        "dv_bits=",
        "mass_bits=",
        "tf_bits=",
        "work_units=",
        "checksum=",
        "end_form=",
        "end_checksum=",
        "field=",
        "index=",
        "setting=",
        "value_bits=",
        "limit_bits=",
    ];
    host_line
        .split(' ')
        .enumerate()
        .filter(|(i, t)| *i < 2 || KEPT.iter().any(|k| t.starts_with(k)))
        .map(|(_, t)| t)
        .collect::<Vec<_>>()
        .join(" ")
}

#[test]
fn m7_c_image_is_bit_identical_to_the_rust_api_on_every_fixture() {
    let required = std::env::var_os("RECONFIG_REQUIRE_QEMU").is_some();
    let clang = first_tool(&["clang", "clang-14", "clang-15", "clang-16"]);
    let tools = (
        clang,
        first_tool(&["arm-none-eabi-ld"]),
        first_tool(&["qemu-system-arm"]),
    );
    let (Some(clang), Some(ld), Some(qemu)) = tools else {
        assert!(
            !required,
            "RECONFIG_REQUIRE_QEMU=1: the M7 C image needs clang, arm-none-eabi-ld and \
             qemu-system-arm ({tools:?})"
        );
        eprintln!("c_api: M7 C image skipped, missing clang / arm-none-eabi-ld / qemu-system-arm");
        return;
    };
    let root = root();
    let Prepared { dir, expected } = prepared();
    run(
        cargo().args([
            "rustc",
            "-p",
            "reconfig-capi",
            "--release",
            "--target",
            "thumbv7em-none-eabihf",
            "--lib",
            "--crate-type",
            "staticlib",
            "--no-default-features",
            "--features",
            "abort-proof",
        ]),
        "cargo rustc -p reconfig-capi (thumbv7em staticlib)",
    );
    let lib = root.join("target/thumbv7em-none-eabihf/release/libreconfig_capi.a");
    let object = dir.join("m7_main.o");
    run(
        Command::new(clang)
            .args([
                "--target=thumbv7em-none-eabihf",
                "-mcpu=cortex-m7",
                "-mfloat-abi=hard",
                "-ffreestanding",
                "-fno-builtin",
                "-ffp-contract=off",
                "-O2",
                "-Wall",
                "-Wextra",
                "-Werror",
            ])
            .arg("-I")
            .arg(root.join("capi/include"))
            .arg("-I")
            .arg(root.join("examples/c"))
            .arg("-I")
            .arg(dir)
            .arg("-c")
            .arg(root.join("examples/c/m7/main.c"))
            .arg("-o")
            .arg(&object),
        "clang examples/c/m7/main.c",
    );
    let elf = dir.join("m7_c_image.elf");
    run(
        Command::new(ld)
            .arg("-T")
            .arg(root.join("examples/c/m7/link.ld"))
            .arg("--gc-sections")
            .arg(&object)
            .arg(&lib)
            .arg("-o")
            .arg(&elf),
        "arm-none-eabi-ld (the M7 C image)",
    );
    // Semihosting's SYS_WRITE0 output arrives on QEMU's stderr.
    let qemu_run = reconfig_tests::qemu::run_m7(Path::new(&qemu), &elf, &[])
        .unwrap_or_else(|e| panic!("the M7 C image: {e}"));
    let stdout = qemu_run.stderr;
    assert!(
        qemu_run.status.success(),
        "the M7 C image failed ({}):\n{stdout}",
        qemu_run.status
    );
    let mut got = Vec::new();
    for line in stdout.lines().filter(|l| {
        ["A ", "B ", "F ", "G ", "L ", "H "]
            .iter()
            .any(|p| l.starts_with(p))
    }) {
        let (fields, stack) = line
            .rsplit_once(" stack_bytes=")
            .unwrap_or_else(|| panic!("no stack figure in {line:?}"));
        eprintln!("m7 C image: {fields} stack_bytes={stack}");
        got.push(fields.to_owned());
    }
    let want: Vec<String> = expected.iter().map(|l| m7_fields(l)).collect();
    assert_eq!(got.len(), want.len(), "one line per fixture:\n{stdout}");
    for (g, e) in got.iter().zip(want.iter()) {
        assert_eq!(g, e, "the M7 C image and the Rust API differ");
    }
}

/// The abort-free proof on the host (docs/c-api.md, "Abort-free"): the library built without
/// std, with `-C panic=abort` and the `abort-proof` panic handler, which calls
/// `reconfig_capi_panic_path_survived_optimisation`, a function no one defines. The C example
/// links (it does not define it either) only if no panic path survives optimisation, and then
/// prints what the Rust API gives. The M7 C image above is the same proof on the flight target.
#[test]
fn abort_proof_library_links_with_no_panic_path_left() {
    if Command::new("cc").arg("--version").output().is_err() {
        assert!(
            std::env::var_os("RECONFIG_REQUIRE_CC").is_none(),
            "cc is required (RECONFIG_REQUIRE_CC=1)"
        );
        eprintln!("c_api: skipped, no C compiler `cc`");
        return;
    }
    let root = root();
    let Prepared { dir, expected } = prepared();
    // A target folder of its own: `-C panic=abort` and the features differ from the std build.
    let target_dir = root.join("target/abort-proof");
    run(
        cargo()
            .args([
                "rustc",
                "-p",
                "reconfig-capi",
                "--release",
                "--lib",
                "--crate-type",
                "staticlib",
                "--no-default-features",
                "--features",
                "abort-proof",
                "--target-dir",
            ])
            .arg(&target_dir)
            .args(["--", "-C", "panic=abort"]),
        "cargo rustc -p reconfig-capi (abort-proof staticlib)",
    );
    let exe = dir.join("plan_fixtures_abort_proof");
    run(
        Command::new("cc")
            .args(["-std=c99", "-O2", "-Wall", "-Wextra", "-Werror"])
            .arg("-I")
            .arg(root.join("capi/include"))
            .arg("-I")
            .arg(root.join("examples/c"))
            .arg("-I")
            .arg(dir)
            .arg(root.join("examples/c/plan_fixtures.c"))
            .arg(target_dir.join("release/libreconfig_capi.a"))
            .args(["-Wl,--gc-sections", "-lm", "-o"])
            .arg(&exe),
        "cc examples/c/plan_fixtures.c against the abort-proof library (an undefined \
         reconfig_capi_panic_path_survived_optimisation means a panic path is back)",
    );
    let stdout = run(&mut Command::new(&exe), "plan_fixtures (abort-proof)");
    let got: Vec<&str> = stdout.lines().collect();
    assert_eq!(got.len(), expected.len(), "one line per fixture:\n{stdout}");
    for (g, e) in got.iter().zip(expected.iter()) {
        assert_eq!(*g, e.as_str(), "the abort-proof library and Rust differ");
    }
}
