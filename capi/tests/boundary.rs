//! The C entry points called from Rust: every refusal at the boundary, and a solve through the
//! C structs bit-identical to the core's own API.
#![allow(
    clippy::unwrap_used,
    clippy::indexing_slicing,
    clippy::float_cmp,
    clippy::arithmetic_side_effects,
    clippy::undocumented_unsafe_blocks
)]

mod common;
use common::circular;
use core::ffi::c_void;
use reconfig_capi::impulsive::*;
use reconfig_capi::pseudospectral::*;
use reconfig_capi::status::*;
use reconfig_capi::types_a::*;
use reconfig_capi::types_b::*;
use reconfig_core::pseudospectral;

/// The name `reconfig_setting_name` gives, as a Rust string.
fn setting_name(planner: i32, code: i32) -> Option<String> {
    let p = reconfig_capi::names::reconfig_setting_name(planner, code);
    // SAFETY: null or a static NUL-terminated string.
    (!p.is_null()).then(|| {
        unsafe { std::ffi::CStr::from_ptr(p) }
            .to_str()
            .unwrap()
            .to_owned()
    })
}

/// Caller memory of `size` bytes aligned to 8 (a `u64` vector).
fn memory(size: usize) -> Vec<u64> {
    vec![0; size.div_ceil(8) + 1]
}

fn three_sats() -> ReconfigAProblem {
    // Huang 2012's three-spacecraft case, N = 10 (fixtures/huang2012-three-sats-n10.toml).
    let mut p = ReconfigAProblem {
        horizon_tu: 10.0,
        max_control_fu: 1.0,
        keep_out_lu: 2.0,
        degree: 10,
        test_points: 1,
        spacecraft_count: 3,
        ..ReconfigAProblem::default()
    };
    let ends = [
        ([0.0, 0.0, 0.0], [12.0, 12.0, 12.0]),
        ([8.0, 0.0, 0.0], [0.0, 12.0, 12.0]),
        ([8.0, 0.0, 8.0], [0.0, 12.0, 0.0]),
    ];
    for (sc, (a, b)) in p.spacecraft.iter_mut().zip(ends) {
        sc.mass_mu = 1.0;
        sc.initial_state_lu_lutu[..3].copy_from_slice(&a);
        sc.final_state_lu_lutu[..3].copy_from_slice(&b);
    }
    p
}

fn a_settings() -> ReconfigASettings {
    let mut s = ReconfigASettings::default();
    // SAFETY: a valid, aligned out-pointer.
    assert_eq!(
        unsafe { reconfig_pseudospectral_default_settings(&mut s) },
        0
    );
    s
}

#[test]
fn init_refuses_null_misaligned_and_small_memory() {
    let size = reconfig_pseudospectral_workspace_size();
    assert!(reconfig_pseudospectral_workspace_align() <= 8);
    let mut mem = memory(size);
    let base = mem.as_mut_ptr().cast::<u8>();
    // SAFETY: each pointer is null or inside `mem` with the size given.
    unsafe {
        assert_eq!(
            reconfig_pseudospectral_init(core::ptr::null_mut(), size),
            RECONFIG_ERR_NULL_POINTER
        );
        assert_eq!(
            reconfig_pseudospectral_init(base.add(1).cast(), size),
            RECONFIG_ERR_MISALIGNED
        );
        assert_eq!(
            reconfig_pseudospectral_init(base.cast(), size - 1),
            RECONFIG_ERR_WORKSPACE_TOO_SMALL
        );
        assert_eq!(reconfig_pseudospectral_init(base.cast(), size), 0);
    }
}

#[test]
fn solve_refuses_uninitialised_workspace_and_null_arguments() {
    let size = reconfig_pseudospectral_workspace_size();
    let mut mem = memory(size);
    let ws = mem.as_mut_ptr().cast::<c_void>();
    let (problem, settings) = (three_sats(), a_settings());
    let mut out = Box::new(ReconfigASolution {
        status: 99,
        ..unsafe_zeroed_solution()
    });
    // SAFETY: valid pointers or null; `ws` has `size` bytes.
    unsafe {
        let code = reconfig_pseudospectral_solve(ws, &problem, &settings, &mut *out);
        assert_eq!(code, RECONFIG_ERR_WORKSPACE_NOT_INITIALISED);
        assert_eq!(out.error.field, RECONFIG_FIELD_WORKSPACE);
        assert_eq!(reconfig_pseudospectral_init(ws, size), 0);
        let code = reconfig_pseudospectral_solve(ws, core::ptr::null(), &settings, &mut *out);
        assert_eq!(code, RECONFIG_ERR_NULL_POINTER);
        assert_eq!(out.error.field, RECONFIG_FIELD_PROBLEM);
        let code = reconfig_pseudospectral_solve(ws, &problem, &settings, core::ptr::null_mut());
        assert_eq!(code, RECONFIG_ERR_NULL_POINTER);
    }
}

/// A zeroed planner-A solution (all fields are plain numbers, so zero is valid).
fn unsafe_zeroed_solution() -> ReconfigASolution {
    // SAFETY: every field is an integer or float array; all-zero bits are valid values.
    unsafe { core::mem::zeroed() }
}

#[test]
fn refusals_name_field_index_value_and_limit() {
    let size = reconfig_pseudospectral_workspace_size();
    let mut mem = memory(size);
    let ws = mem.as_mut_ptr().cast::<c_void>();
    let settings = a_settings();
    let mut out = Box::new(unsafe_zeroed_solution());
    // SAFETY: valid pointers; `ws` has `size` bytes.
    unsafe {
        assert_eq!(reconfig_pseudospectral_init(ws, size), 0);
        let mut p = three_sats();
        p.spacecraft[1].final_state_lu_lutu[4] = f64::INFINITY;
        let code = reconfig_pseudospectral_solve(ws, &p, &settings, &mut *out);
        assert_eq!(code, RECONFIG_A_ERR_NOT_FINITE);
        assert_eq!(
            (out.error.field, out.error.index, out.error.detail),
            (RECONFIG_FIELD_BOUNDARY_STATE, 1, 10)
        );
        assert_eq!(out.error.value, f64::INFINITY);

        let mut p = three_sats();
        p.degree = 30;
        assert_eq!(
            reconfig_pseudospectral_solve(ws, &p, &settings, &mut *out),
            RECONFIG_A_ERR_CAPACITY_EXCEEDED
        );
        assert_eq!(
            (out.error.field, out.error.value, out.error.limit),
            (RECONFIG_FIELD_DEGREE, 30.0, 24.0)
        );

        let mut p = three_sats();
        p.spacecraft_count = 9;
        assert_eq!(
            reconfig_pseudospectral_solve(ws, &p, &settings, &mut *out),
            RECONFIG_A_ERR_CAPACITY_EXCEEDED
        );
        assert_eq!((out.error.value, out.error.limit), (9.0, 8.0));

        let mut p = three_sats();
        p.test_points = 2;
        assert_eq!(
            reconfig_pseudospectral_solve(ws, &p, &settings, &mut *out),
            RECONFIG_ERR_INVALID_CODE
        );
        assert_eq!(out.error.field, RECONFIG_FIELD_TEST_POINTS);

        let mut s = settings;
        s.sqp_max_iter = 0;
        assert_eq!(
            reconfig_pseudospectral_solve(ws, &three_sats(), &s, &mut *out),
            RECONFIG_ERR_SETTING_OUT_OF_RANGE
        );
        // Named: the setting's code, the value and the end of the range it broke.
        assert_eq!(
            (
                out.error.field,
                out.error.index,
                out.error.detail,
                out.error.value,
                out.error.limit
            ),
            (
                RECONFIG_FIELD_SETTINGS,
                reconfig_core::pseudospectral::SettingId::SqpMaxIter as i32,
                0,
                0.0,
                1.0
            )
        );
    }
}

#[test]
fn paper_case_through_c_structs_is_bit_identical_to_the_core() {
    let size = reconfig_pseudospectral_workspace_size();
    let mut mem = memory(size);
    let ws = mem.as_mut_ptr().cast::<c_void>();
    let c_problem = three_sats();
    let mut out = Box::new(unsafe_zeroed_solution());
    // SAFETY: valid pointers; `ws` has `size` bytes.
    let code = unsafe {
        assert_eq!(reconfig_pseudospectral_init(ws, size), 0);
        reconfig_pseudospectral_solve(ws, &c_problem, &a_settings(), &mut *out)
    };
    assert_eq!(code, RECONFIG_A_SOLVED);

    let mut problem = pseudospectral::Problem {
        horizon_tu: 10.0,
        max_control_fu: 1.0,
        keep_out_lu: 2.0,
        degree: 10,
        test_points: true,
        spacecraft: heapless::Vec::new(),
    };
    for sc in &c_problem.spacecraft[..3] {
        problem
            .spacecraft
            .push(pseudospectral::Spacecraft {
                mass_mu: sc.mass_mu,
                initial_state: sc.initial_state_lu_lutu,
                final_state: sc.final_state_lu_lutu,
            })
            .unwrap();
    }
    let mut workspace = Box::new(pseudospectral::Workspace::new());
    let mut solution = Box::new(pseudospectral::Solution::new());
    pseudospectral::solve(
        &problem,
        &pseudospectral::Settings::default(),
        &mut workspace,
        &mut solution,
    )
    .unwrap();
    assert_eq!(out.cost_fu2_tu.to_bits(), solution.cost.to_bits());
    assert_eq!(out.work_units, solution.info.work_units);
    assert_eq!(out.states_lu_lutu, solution.states);
    assert_eq!(out.controls_fu, solution.controls_fu);
    assert_eq!(out.usable, 1);
}

#[test]
fn impulsive_refusals_reach_the_caller() {
    let size = reconfig_impulsive_workspace_size();
    let mut mem = memory(size);
    let ws = mem.as_mut_ptr().cast::<c_void>();
    let mut settings = ReconfigBSettings::default();
    let mut out = ReconfigBSolution::default();
    let problem = ReconfigBProblem {
        chief: ReconfigBMeanElements {
            sma_km: 7000.0,
            ecc: 0.01,
            inc_rad: 1.0,
            ..Default::default()
        },
        impulse_count: 7,
        ..Default::default()
    };
    // SAFETY: valid pointers; `ws` has `size` bytes.
    unsafe {
        assert_eq!(reconfig_impulsive_default_settings(&mut settings), 0);
        assert_eq!(reconfig_impulsive_init(ws, size), 0);
        assert_eq!(
            reconfig_impulsive_solve(ws, &problem, &settings, &mut out),
            RECONFIG_B_ERR_CAPACITY_EXCEEDED
        );
        assert_eq!((out.error.value, out.error.limit), (7.0, 6.0));
        let mut p = problem;
        p.impulse_count = 2;
        p.chief.sma_km = 200_000.0;
        assert_eq!(
            reconfig_impulsive_solve(ws, &p, &settings, &mut out),
            RECONFIG_B_ERR_SMA_OUT_OF_RANGE
        );
        assert_eq!(
            (out.error.field, out.error.value, out.error.limit),
            (RECONFIG_FIELD_CHIEF, 200_000.0, 100_000.0)
        );
        // A planner-A workspace is not a planner-B one.
        let a_size = reconfig_pseudospectral_workspace_size();
        let mut a_mem = memory(a_size);
        let a_ws = a_mem.as_mut_ptr().cast::<c_void>();
        assert_eq!(reconfig_pseudospectral_init(a_ws, a_size), 0);
        assert_eq!(
            reconfig_impulsive_solve(a_ws, &p, &settings, &mut out),
            RECONFIG_ERR_WORKSPACE_NOT_INITIALISED
        );
    }
}

#[test]
fn init_builds_no_workspace_on_the_stack() {
    // A thread with a 64 KiB stack initialises both workspaces (each far larger): a stack
    // temporary of the block would overflow it and abort the test.
    let a = reconfig_pseudospectral_workspace_size();
    let b = reconfig_impulsive_workspace_size();
    assert!(a > 128 * 1024, "{a}");
    std::thread::Builder::new()
        .stack_size(64 * 1024)
        .spawn(move || {
            let mut ma = memory(a);
            let mut mb = memory(b);
            // SAFETY: each buffer has the size given and is aligned to 8.
            unsafe {
                assert_eq!(reconfig_pseudospectral_init(ma.as_mut_ptr().cast(), a), 0);
                assert_eq!(reconfig_impulsive_init(mb.as_mut_ptr().cast(), b), 0);
            }
        })
        .unwrap()
        .join()
        .unwrap();
}

#[test]
fn form_refusals_name_the_part_and_the_reason() {
    use reconfig_capi::convert_b_form::RECONFIG_FIELD_RELATIVE_FORM;
    use reconfig_capi::types_b_form::*;
    let size = reconfig_impulsive_workspace_size();
    let mut mem = memory(size);
    let ws = mem.as_mut_ptr().cast::<c_void>();
    let mut settings = ReconfigBSettings::default();
    let mut out = ReconfigBFormSolution::default();
    // An equatorial chief (i = 0): ROE cannot be given on it (their node difference divides by
    // sin i).
    let mut problem = ReconfigBFormProblem {
        chief: ReconfigBOrbitForm {
            form: RECONFIG_B_ORBIT_CLASSICAL,
            classical: ReconfigBMeanElements {
                sma_km: 42_164.0,
                ecc: 0.001,
                ..Default::default()
            },
            ..Default::default()
        },
        relative: ReconfigBRelativeForm {
            form: RECONFIG_B_RELATIVE_ROE,
            ..Default::default()
        },
        impulse_count: 2,
        ..Default::default()
    };
    problem.points[1].revolutions = 1;
    // SAFETY: valid pointers; `ws` has `size` bytes.
    unsafe {
        assert_eq!(reconfig_impulsive_default_settings(&mut settings), 0);
        assert_eq!(reconfig_impulsive_init(ws, size), 0);
        // The built-in limits bound the chief's |sin i| under ROE (as the flight service's
        // do), before the conversion: refused by name, the value and the limit.
        assert_eq!(
            reconfig_impulsive_solve_form(ws, &problem, &settings, &mut out),
            RECONFIG_ERR_LIMIT_EXCEEDED
        );
        let e = out.plan.error;
        assert_eq!(
            (e.code, e.field, e.index, e.detail, e.value, e.limit),
            (
                RECONFIG_ERR_LIMIT_EXCEEDED,
                RECONFIG_FIELD_SETTINGS,
                128 + 10,
                1,
                0.0,
                settings.min_sin_inclination
            )
        );
        assert_eq!(
            setting_name(reconfig_capi::names::RECONFIG_PLANNER_IMPULSIVE, e.index),
            Some("relative.roe chief |sin i|".to_owned())
        );
        // A part the limits pass but the conversion cannot take (a NaN in the chief's state)
        // is the conversion's refusal: the part and the reason.
        let mut nan_chief = problem;
        nan_chief.chief.form = RECONFIG_B_ORBIT_STATE;
        nan_chief.chief.state = ReconfigBCartesianState {
            pos_km: [7000.0, 0.0, f64::NAN],
            vel_km_s: [0.0, 7.5, 1.0],
        };
        nan_chief.relative.form = RECONFIG_B_RELATIVE_ELEMENTS;
        assert_eq!(
            reconfig_impulsive_solve_form(ws, &nan_chief, &settings, &mut out),
            RECONFIG_B_ERR_INPUT_FORM
        );
        let e = out.plan.error;
        assert_eq!(
            (e.field, e.detail),
            (RECONFIG_FIELD_CHIEF, RECONFIG_B_FORM_NOT_FINITE)
        );
        // A form code outside its set names the field that holds it and the largest code.
        let mut bad = problem;
        bad.relative.form = 7;
        assert_eq!(
            reconfig_impulsive_solve_form(ws, &bad, &settings, &mut out),
            RECONFIG_ERR_INVALID_CODE
        );
        let e = out.plan.error;
        assert_eq!(
            (e.field, e.value, e.limit),
            (RECONFIG_FIELD_RELATIVE_FORM, 7.0, 2.0)
        );
        let mut bad = problem;
        bad.relative.form = RECONFIG_B_RELATIVE_DEPUTY;
        bad.relative.target_orbit.form = 3;
        assert_eq!(
            reconfig_impulsive_solve_form(ws, &bad, &settings, &mut out),
            RECONFIG_ERR_INVALID_CODE
        );
        assert_eq!(out.plan.error.field, RECONFIG_FIELD_DEPUTY_TARGET);
        // A hyperbolic osculating chief state.
        let mut bad = problem;
        bad.chief.form = RECONFIG_B_ORBIT_STATE;
        bad.chief.state = ReconfigBCartesianState {
            pos_km: [7000.0, 0.0, 0.0],
            vel_km_s: [0.0, 12.0, 1.0],
        };
        bad.relative.form = RECONFIG_B_RELATIVE_ELEMENTS;
        // The limits bound the orbits as given: eccentricity below 1, named as the chief's.
        assert_eq!(
            reconfig_impulsive_solve_form(ws, &bad, &settings, &mut out),
            RECONFIG_ERR_LIMIT_EXCEEDED
        );
        let e = out.plan.error;
        assert_eq!((e.index, e.detail, e.limit), (128 + 4, 4, 1.0));
        assert!(e.value > 1.0, "{}", e.value);
        assert_eq!(
            setting_name(reconfig_capi::names::RECONFIG_PLANNER_IMPULSIVE, e.index),
            Some("chief.eccentricity".to_owned())
        );
        // A null problem is refused like the mean-element form's.
        assert_eq!(
            reconfig_impulsive_solve_form(ws, core::ptr::null(), &settings, &mut out),
            RECONFIG_ERR_NULL_POINTER
        );
        assert_eq!(out.plan.error.field, RECONFIG_FIELD_PROBLEM);
    }
}

#[test]
fn geo_tour_refusals_name_field_index_value_and_limit() {
    use reconfig_capi::geo_tour::*;
    use reconfig_capi::types_geo::*;
    let size = reconfig_geo_tour_workspace_size();
    let mut mem = memory(size);
    let ws = mem.as_mut_ptr().cast::<c_void>();
    let mut settings = ReconfigGeoSettings::default();
    let mut out = ReconfigGeoSolution::default();
    let mut problem = ReconfigGeoProblem {
        start_lon_rad: 0.1,
        mission_time_s: 30.0 * 86_400.0,
        max_burn_mps: 10.0,
        target_count: 2,
        ..Default::default()
    };
    problem.targets_lon_rad[0] = 0.5;
    problem.targets_lon_rad[1] = 7.0; // above 2 pi
                                      // SAFETY: valid pointers; `ws` has `size` bytes.
    unsafe {
        assert_eq!(reconfig_geo_tour_default_settings(&mut settings), 0);
        assert_eq!(
            reconfig_geo_tour_solve(ws, &problem, &settings, &mut out),
            RECONFIG_ERR_WORKSPACE_NOT_INITIALISED
        );
        assert_eq!(reconfig_geo_tour_init(ws, size), 0);
        assert_eq!(
            reconfig_geo_tour_solve(ws, &problem, &settings, &mut out),
            RECONFIG_GEO_ERR_OUT_OF_RANGE
        );
        let e = out.error;
        assert_eq!(
            (e.field, e.index, e.detail, e.value),
            (RECONFIG_FIELD_GEO_TARGET_LONGITUDE, 1, 1, 7.0)
        );
        assert_eq!(e.limit, 2.0 * core::f64::consts::PI);
        problem.targets_lon_rad[1] = 0.7;
        problem.target_count = 17;
        assert_eq!(
            reconfig_geo_tour_solve(ws, &problem, &settings, &mut out),
            RECONFIG_GEO_ERR_CAPACITY_EXCEEDED
        );
        assert_eq!((out.error.value, out.error.limit), (17.0, 16.0));
        problem.target_count = 0;
        assert_eq!(
            reconfig_geo_tour_solve(ws, &problem, &settings, &mut out),
            RECONFIG_GEO_ERR_NO_TARGETS
        );
        problem.target_count = 2;
        problem.sweep = 3;
        assert_eq!(
            reconfig_geo_tour_solve(ws, &problem, &settings, &mut out),
            RECONFIG_ERR_INVALID_CODE
        );
        assert_eq!(
            (out.error.field, out.error.value, out.error.limit),
            (RECONFIG_FIELD_GEO_SWEEP, 3.0, 2.0)
        );
        problem.sweep = RECONFIG_GEO_SWEEP_EAST;
        let mut bad = settings;
        bad.lambert_tol = f64::NAN;
        assert_eq!(
            reconfig_geo_tour_solve(ws, &problem, &bad, &mut out),
            RECONFIG_ERR_SETTING_OUT_OF_RANGE
        );
        assert_eq!(
            (out.error.field, out.error.index, out.error.detail),
            (
                RECONFIG_FIELD_SETTINGS,
                reconfig_core::geo_tour::SettingId::LambertTol as i32,
                2
            )
        );
        // A plannable tour: solved, through the C structs as through the core.
        assert_eq!(
            reconfig_geo_tour_solve(ws, &problem, &settings, &mut out),
            RECONFIG_GEO_SOLVED
        );
        assert_eq!((out.usable, out.leg_count, out.status_leg), (1, 2, -1));
        let mut core_problem = reconfig_core::geo_tour::Problem {
            start_lon_rad: 0.1,
            targets_lon_rad: heapless::Vec::new(),
            mission_time_s: 30.0 * 86_400.0,
            max_burn_mps: 10.0,
            sweep: reconfig_core::geo_tour::SweepChoice::East,
            policy: reconfig_core::geo_tour::MethodPolicy::ByCost,
        };
        core_problem.targets_lon_rad.push(0.5).unwrap();
        core_problem.targets_lon_rad.push(0.7).unwrap();
        let mut workspace = Box::new(reconfig_core::geo_tour::Workspace::new());
        let mut solution = Box::new(reconfig_core::geo_tour::Solution::new());
        reconfig_core::geo_tour::solve(
            &core_problem,
            &reconfig_core::geo_tour::Settings::default(),
            &mut workspace,
            &mut solution,
        )
        .unwrap();
        assert_eq!(out.total_dv_mps.to_bits(), solution.total_dv_mps.to_bits());
        assert_eq!(
            out.legs[1].burns[0].dv_rtn_mps[1].to_bits(),
            solution.legs[1].burns[0].dv_rtn_mps[1].to_bits()
        );
    }
}

#[test]
fn an_infeasible_answer_names_the_pair_that_cannot_be_separated_through_c() {
    // Two spacecraft swap places along x in T = 10 with Umax = 1 and must keep 20 LU apart:
    // off the x axis each can reach 6.25 LU per axis and return, so the pair cannot pass
    // (core test `an_unseparable_swap_is_infeasible_and_names_the_pair_and_the_bounds`).
    let mut p = ReconfigAProblem {
        horizon_tu: 10.0,
        max_control_fu: 1.0,
        keep_out_lu: 20.0,
        degree: 12,
        test_points: 1,
        spacecraft_count: 2,
        ..ReconfigAProblem::default()
    };
    for (sc, x0) in p.spacecraft.iter_mut().zip([11.0, -11.0]) {
        sc.mass_mu = 1.0;
        sc.initial_state_lu_lutu[0] = x0;
        sc.final_state_lu_lutu[0] = -x0;
    }
    let size = reconfig_pseudospectral_workspace_size();
    let mut mem = memory(size);
    let ws = mem.as_mut_ptr().cast::<c_void>();
    let mut out = Box::new(unsafe_zeroed_solution());
    // SAFETY: valid pointers; `ws` has `size` bytes.
    unsafe {
        assert_eq!(reconfig_pseudospectral_init(ws, size), 0);
        let code = reconfig_pseudospectral_solve(ws, &p, &a_settings(), &mut *out);
        assert_eq!(code, RECONFIG_A_INFEASIBLE);
    }
    assert_eq!(out.usable, 0);
    assert!(out.unmet_count > 0 && usize::from(out.unmet_count) <= RECONFIG_A_MAX_UNMET);
    let first = out.unmet[0];
    assert_eq!((first.kind, first.pair), (0, [0, 1]));
    assert!(first.time_tu > 2.0 && first.time_tu < 8.0 && first.shortfall > 0.0);
    // The slots past the count are zero.
    assert!(out.unmet[usize::from(out.unmet_count)..]
        .iter()
        .all(|u| *u == ReconfigAUnmet::default()));
}

#[test]
fn leo_arc_refusals_name_field_value_and_limit_and_a_solve_matches_the_core() {
    use reconfig_capi::leo_tour::*;
    use reconfig_capi::names::RECONFIG_PLANNER_LEO_ARC;
    use reconfig_capi::types_leo::*;
    use reconfig_core::leo_tour;
    let size = reconfig_leo_arc_workspace_size();
    let mut mem = memory(size);
    let ws = mem.as_mut_ptr().cast::<c_void>();
    let mut settings = ReconfigLeoArcSettings::default();
    let mut out = ReconfigLeoArcSolution::default();
    let (from_position_km, from_velocity_km_s) = circular(6778.14, 1.6936, 0.4363);
    let (to_position_km, to_velocity_km_s) = circular(6878.14, 1.7001, 0.2269);
    let good = ReconfigLeoArcProblem {
        from_position_km,
        from_velocity_km_s,
        to_position_km,
        to_velocity_km_s,
        duration_s: 20_000.0,
        impulses: 3,
    };
    // SAFETY: valid pointers; `ws` has `size` bytes.
    unsafe {
        assert_eq!(reconfig_leo_arc_default_settings(&mut settings), 0);
        assert_eq!(
            reconfig_leo_arc_solve(ws, &good, &settings, &mut out),
            RECONFIG_ERR_WORKSPACE_NOT_INITIALISED
        );
        assert_eq!(reconfig_leo_arc_init(ws, size), 0);
        // A field out of range: named, value, the end broken.
        let mut p = good;
        p.duration_s = 100.0;
        assert_eq!(
            reconfig_leo_arc_solve(ws, &p, &settings, &mut out),
            RECONFIG_LEO_ERR_OUT_OF_RANGE
        );
        let e = out.error;
        assert_eq!(
            (e.field, e.detail, e.value, e.limit, out.usable),
            (RECONFIG_FIELD_LEO_DURATION, 0, 100.0, 600.0, 0)
        );
        let mut p = good;
        p.impulses = 1;
        assert_eq!(
            reconfig_leo_arc_solve(ws, &p, &settings, &mut out),
            RECONFIG_LEO_ERR_OUT_OF_RANGE
        );
        assert_eq!(
            (out.error.field, out.error.value, out.error.limit),
            (RECONFIG_FIELD_LEO_IMPULSES, 1.0, 2.0)
        );
        // Above the capacity: the built-in limits refuse it first, named as a problem quantity.
        p.impulses = 5;
        assert_eq!(
            reconfig_leo_arc_solve(ws, &p, &settings, &mut out),
            RECONFIG_ERR_LIMIT_EXCEEDED
        );
        assert_eq!((out.error.value, out.error.limit), (5.0, 4.0));
        assert_eq!(
            setting_name(RECONFIG_PLANNER_LEO_ARC, out.error.index).as_deref(),
            Some("impulses")
        );
        // A client inside the atmosphere: its perigee altitude named.
        let mut p = good;
        let (low_p, low_v) = circular(6400.0, 1.7, 0.0);
        (p.to_position_km, p.to_velocity_km_s) = (low_p, low_v);
        assert_eq!(
            reconfig_leo_arc_solve(ws, &p, &settings, &mut out),
            RECONFIG_LEO_ERR_OUT_OF_RANGE
        );
        assert_eq!(
            (out.error.field, out.error.detail, out.error.limit),
            (RECONFIG_FIELD_LEO_TO_PERIGEE_ALTITUDE, 0, 100.0)
        );
        // A setting: NaN (not finite), a search-model code outside its set.
        let mut bad = settings;
        bad.arrival_tol_km = f64::NAN;
        assert_eq!(
            reconfig_leo_arc_solve(ws, &good, &bad, &mut out),
            RECONFIG_ERR_SETTING_OUT_OF_RANGE
        );
        assert_eq!(
            (out.error.field, out.error.index, out.error.detail),
            (
                RECONFIG_FIELD_SETTINGS,
                leo_tour::SettingId::ArrivalTolKm as i32,
                2
            )
        );
        let mut bad = settings;
        bad.search_model = 2;
        assert_eq!(
            reconfig_leo_arc_solve(ws, &good, &bad, &mut out),
            RECONFIG_ERR_SETTING_OUT_OF_RANGE
        );
        assert_eq!(
            setting_name(RECONFIG_PLANNER_LEO_ARC, out.error.index).as_deref(),
            Some("search_model")
        );
        assert_eq!((out.error.value, out.error.limit), (2.0, 1.0));
        // A small budget: a plan through the C structs, as through the core, bit for bit.
        let mut small = settings;
        small.work_budget = 300_000;
        let status = reconfig_leo_arc_solve(ws, &good, &small, &mut out);
        assert!(status > 0, "{status}");
        let core_problem = leo_tour::ArcProblem {
            from: [
                from_position_km[0],
                from_position_km[1],
                from_position_km[2],
                from_velocity_km_s[0],
                from_velocity_km_s[1],
                from_velocity_km_s[2],
            ],
            to: [
                to_position_km[0],
                to_position_km[1],
                to_position_km[2],
                to_velocity_km_s[0],
                to_velocity_km_s[1],
                to_velocity_km_s[2],
            ],
            duration_s: 20_000.0,
            impulses: 3,
        };
        let core_settings = leo_tour::Settings {
            work_budget: 300_000,
            ..Default::default()
        };
        let mut workspace = Box::new(leo_tour::Workspace::new());
        let mut solution = Box::new(leo_tour::ArcSolution::new());
        leo_tour::solve_arc(&core_problem, &core_settings, &mut workspace, &mut solution).unwrap();
        assert_eq!(
            status,
            reconfig_capi::convert_leo::status_to_c(solution.info.status)
        );
        assert_eq!(out.usable, u8::from(solution.info.status.is_usable()));
        assert_eq!(out.impulses, solution.impulses);
        assert_eq!(out.total_dv_mps.to_bits(), solution.total_dv_mps.to_bits());
        assert_eq!(out.work_units, solution.info.work_units);
        assert_eq!(out.has_miss_m, u8::from(solution.miss_m.is_some()));
        assert_eq!(
            out.miss_m.to_bits(),
            solution.miss_m.unwrap_or(0.0).to_bits()
        );
        for (c, b) in out.burns.iter().zip(solution.burns.iter()) {
            assert_eq!(c.epoch_s.to_bits(), b.epoch_s.to_bits());
            for k in 0..3 {
                assert_eq!(c.dv_rtn_mps[k].to_bits(), b.rtn_mps[k].to_bits());
                assert_eq!(c.dv_km_s[k].to_bits(), b.dv_km_s[k].to_bits());
            }
        }
    }
}

#[test]
fn leo_arc_status_codes_are_distinct() {
    use reconfig_capi::convert_leo::status_to_c;
    use reconfig_core::leo_tour::SolveStatus as L;
    let all = [
        (L::Unsolved, RECONFIG_UNSOLVED),
        (L::Solved, RECONFIG_LEO_SOLVED),
        (L::ArrivalMissed, RECONFIG_LEO_ARRIVAL_MISSED),
        (
            L::BudgetExhausted { verified: true },
            RECONFIG_LEO_BUDGET_EXHAUSTED_VERIFIED,
        ),
        (L::NoTransfer, RECONFIG_LEO_NO_TRANSFER),
        (L::BelowMinAltitude, RECONFIG_LEO_BELOW_MIN_ALTITUDE),
        (
            L::BudgetExhausted { verified: false },
            RECONFIG_LEO_BUDGET_EXHAUSTED_UNVERIFIED,
        ),
    ];
    let mut codes: Vec<i32> = all.iter().map(|(s, _)| status_to_c(*s)).collect();
    for (s, c) in all {
        assert_eq!(status_to_c(s), c, "{s:?}");
    }
    codes.sort_unstable();
    codes.dedup();
    assert_eq!(codes.len(), all.len());
}

/// The paper's minimum-fuel transfer at kappa = 1.40, 4.38 days
/// (`fixtures/hybrid-min-fuel-k140-4p38d.toml`) as the C struct.
fn hybrid_problem() -> reconfig_capi::types_hybrid::ReconfigHybridProblem {
    use reconfig_capi::types_hybrid::*;
    ReconfigHybridProblem {
        kappa: 1.40,
        theta_rad: -2.0,
        duration_days: 4.38,
        thrust_n: 10.0,
        specific_impulse_s: 3000.0,
        chemical_specific_impulse_s: 300.0,
        parking_radius_km: 6778.0,
        arrival_r_lu: [0.823385182067, 0.0, -0.022277556273],
        arrival_v_vu: [0.0, 0.134184170262, 0.0],
        halo_period_tu: 2.746337,
        costates: [
            1.51293,
            7.36403,
            -0.122107,
            -0.0191786,
            0.014939,
            5.13983e-06,
            0.0596219,
        ],
        design_duration_days: 4.38,
        design_thrust_n: 10.0,
        objective: RECONFIG_HYBRID_OBJECTIVE_MIN_FUEL,
        ..Default::default()
    }
}

#[test]
fn hybrid_refusals_name_field_index_value_and_limit_and_a_solve_matches_the_core() {
    use reconfig_capi::hybrid::*;
    use reconfig_capi::names::RECONFIG_PLANNER_HYBRID;
    use reconfig_capi::types_hybrid::*;
    use reconfig_core::hybrid;
    let size = reconfig_hybrid_workspace_size();
    let mut mem = memory(size);
    let ws = mem.as_mut_ptr().cast::<c_void>();
    let mut settings = ReconfigHybridSettings::default();
    let mut out = ReconfigHybridSolution::default();
    let good = hybrid_problem();
    // SAFETY: valid pointers; `ws` has `size` bytes.
    unsafe {
        assert_eq!(reconfig_hybrid_default_settings(&mut settings), 0);
        assert_eq!(settings.work_budget, hybrid::DEFAULT_WORK_BUDGET);
        assert_eq!(
            reconfig_hybrid_solve(ws, &good, &settings, &mut out),
            RECONFIG_ERR_WORKSPACE_NOT_INITIALISED
        );
        assert_eq!(
            reconfig_hybrid_init(ws, size - 8),
            RECONFIG_ERR_WORKSPACE_TOO_SMALL
        );
        assert_eq!(reconfig_hybrid_init(ws, size), 0);
        // Null arguments.
        assert_eq!(
            reconfig_hybrid_solve(ws, core::ptr::null(), &settings, &mut out),
            RECONFIG_ERR_NULL_POINTER
        );
        assert_eq!(out.error.field, RECONFIG_FIELD_PROBLEM);
        // Codes a C struct can hold and the core's types cannot: named, the largest code.
        let mut p = good;
        p.objective = 3;
        assert_eq!(
            reconfig_hybrid_solve(ws, &p, &settings, &mut out),
            RECONFIG_ERR_INVALID_CODE
        );
        assert_eq!(
            (
                out.error.field,
                out.error.value,
                out.error.limit,
                out.usable
            ),
            (RECONFIG_FIELD_HYBRID_OBJECTIVE, 3.0, 2.0, 0)
        );
        let mut p = good;
        p.free_theta = 2;
        assert_eq!(
            reconfig_hybrid_solve(ws, &p, &settings, &mut out),
            RECONFIG_ERR_INVALID_CODE
        );
        assert_eq!(
            (out.error.field, out.error.value, out.error.limit),
            (RECONFIG_FIELD_HYBRID_FREE_THETA, 2.0, 1.0)
        );
        // A field out of range: named, value, the end broken (kappa's upper end is open).
        let mut p = good;
        p.kappa = core::f64::consts::SQRT_2;
        assert_eq!(
            reconfig_hybrid_solve(ws, &p, &settings, &mut out),
            RECONFIG_HYBRID_ERR_OUT_OF_RANGE
        );
        let e = out.error;
        assert_eq!(
            (e.field, e.index, e.detail, e.value, e.limit),
            (
                RECONFIG_FIELD_HYBRID_KAPPA,
                -1,
                1,
                core::f64::consts::SQRT_2,
                core::f64::consts::SQRT_2
            )
        );
        // An array's component: its index; not finite: detail 2, the upper end.
        let mut p = good;
        p.costates[3] = f64::NAN;
        assert_eq!(
            reconfig_hybrid_solve(ws, &p, &settings, &mut out),
            RECONFIG_HYBRID_ERR_OUT_OF_RANGE
        );
        let e = out.error;
        assert_eq!(
            (e.field, e.index, e.detail, e.limit),
            (RECONFIG_FIELD_HYBRID_COSTATES, 3, 2, hybrid::MAX_COSTATE)
        );
        assert!(e.value.is_nan());
        let mut p = good;
        p.departure_offset[1] = -0.02;
        assert_eq!(
            reconfig_hybrid_solve(ws, &p, &settings, &mut out),
            RECONFIG_HYBRID_ERR_OUT_OF_RANGE
        );
        let e = out.error;
        assert_eq!(
            (e.field, e.index, e.detail, e.value, e.limit),
            (RECONFIG_FIELD_HYBRID_DEPARTURE_OFFSET, 1, 0, -0.02, -1e-2)
        );
        // Minimum time has no free impulse: the flag named, 1 above its only value 0.
        let mut p = good;
        p.objective = RECONFIG_HYBRID_OBJECTIVE_MIN_TIME;
        p.free_kappa = 1;
        assert_eq!(
            reconfig_hybrid_solve(ws, &p, &settings, &mut out),
            RECONFIG_HYBRID_ERR_OUT_OF_RANGE
        );
        assert_eq!(
            (
                out.error.field,
                out.error.detail,
                out.error.value,
                out.error.limit
            ),
            (RECONFIG_FIELD_HYBRID_FREE_KAPPA, 1, 1.0, 0.0)
        );
        // An arrival point off the halo orbit: the miss and the tolerance.
        let mut p = good;
        p.arrival_v_vu[1] += 1e-3;
        assert_eq!(
            reconfig_hybrid_solve(ws, &p, &settings, &mut out),
            RECONFIG_HYBRID_ERR_NOT_ON_PERIODIC_ORBIT
        );
        let e = out.error;
        assert_eq!(
            (e.field, e.limit),
            (RECONFIG_FIELD_HYBRID_HALO_PERIOD, settings.halo_closure_tol)
        );
        assert!(e.value > settings.halo_closure_tol, "{e:?}");
        // A budget whose sixteenth cannot fly the halo period.
        let mut small = settings;
        small.work_budget = 100;
        assert_eq!(
            reconfig_hybrid_solve(ws, &good, &small, &mut out),
            RECONFIG_HYBRID_ERR_HALO_CHECK_UNFINISHED
        );
        assert_eq!(out.error.field, RECONFIG_FIELD_HYBRID_HALO_PERIOD);
        // A setting: NaN (not finite), and one past the built-in limits, named.
        let mut bad = settings;
        bad.flight_tol = f64::NAN;
        assert_eq!(
            reconfig_hybrid_solve(ws, &good, &bad, &mut out),
            RECONFIG_ERR_SETTING_OUT_OF_RANGE
        );
        assert_eq!(
            (out.error.field, out.error.index, out.error.detail),
            (
                RECONFIG_FIELD_SETTINGS,
                hybrid::SettingId::FlightTol as i32,
                2
            )
        );
        let mut bad = settings;
        bad.max_iterations = 31;
        assert_eq!(
            reconfig_hybrid_solve(ws, &good, &bad, &mut out),
            RECONFIG_ERR_LIMIT_EXCEEDED
        );
        assert_eq!(
            setting_name(RECONFIG_PLANNER_HYBRID, out.error.index).as_deref(),
            Some("max_iterations")
        );
        assert_eq!((out.error.value, out.error.limit), (31.0, 30.0));
        // A budget that runs out in the shooting (unverified, nothing flown) and the default
        // one (solved): the answer through the C structs, as through the core, bit for bit.
        for (budget, want) in [
            (1_200, RECONFIG_HYBRID_BUDGET_EXHAUSTED_UNVERIFIED),
            (hybrid::DEFAULT_WORK_BUDGET, RECONFIG_HYBRID_SOLVED),
        ] {
            let mut run = settings;
            run.work_budget = budget;
            let status = reconfig_hybrid_solve(ws, &good, &run, &mut out);
            assert_eq!(status, want, "budget {budget}");
            assert_eq!(out.error, ReconfigError::default());
            hybrid_matches_the_core(&good, budget, &out);
        }
    }
}

/// `out` is the core's answer to `c` with the default settings but `work_budget`, bit for bit.
fn hybrid_matches_the_core(
    c: &reconfig_capi::types_hybrid::ReconfigHybridProblem,
    work_budget: u64,
    out: &reconfig_capi::types_hybrid::ReconfigHybridSolution,
) {
    use reconfig_core::hybrid;
    let core_problem = hybrid::Problem {
        objective: hybrid::Objective::MinFuel,
        kappa: c.kappa,
        theta_rad: c.theta_rad,
        free_kappa: false,
        free_theta: false,
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
    let core_settings = hybrid::Settings {
        work_budget,
        ..Default::default()
    };
    let mut solution = hybrid::Solution::new();
    hybrid::solve(
        &core_problem,
        &core_settings,
        &mut hybrid::Workspace::new(),
        &mut solution,
    )
    .unwrap();
    let (code, stopped) = reconfig_capi::convert_hybrid::status_to_c(solution.info.status);
    assert_eq!((out.status, out.stopped), (code, stopped));
    assert_eq!(out.usable, u8::from(solution.info.status.is_usable()));
    assert_eq!(
        (out.work_units, out.evaluations, out.iterations),
        (
            solution.info.work_units,
            solution.info.evaluations,
            solution.info.iterations
        )
    );
    assert_eq!(out.walked_shootings, solution.info.walked.shootings);
    let pairs = [
        (out.walked_reached, solution.info.walked.reached),
        (out.kappa, solution.kappa),
        (out.theta_rad, solution.theta_rad),
        (out.duration_tu, solution.duration_tu),
        (out.cost_multiplier, solution.cost_multiplier),
        (out.mass_after_impulse, solution.mass_after_impulse),
        (out.residual, solution.residual.unwrap_or(0.0)),
    ];
    for (c, r) in pairs {
        assert_eq!(c.to_bits(), r.to_bits());
    }
    assert_eq!(out.has_residual, u8::from(solution.residual.is_some()));
    for (c, r) in out.costates.iter().zip(solution.costates) {
        assert_eq!(c.to_bits(), r.to_bits());
    }
    assert_eq!(out.has_flown, u8::from(solution.flown.is_some()));
    let flown = solution.flown.unwrap_or_default();
    let f = &out.flown;
    for (c, r) in [
        (f.final_mass, flown.final_mass),
        (f.end_miss, flown.end_miss),
        (f.hamiltonian_drift, flown.hamiltonian_drift),
    ] {
        assert_eq!(c.to_bits(), r.to_bits());
    }
    assert_eq!(
        (f.switches, f.thrust_arcs),
        (flown.switches, flown.thrust_arcs)
    );
    for (c, r) in f.switch_times_tu.iter().zip(flown.switch_times_tu) {
        assert_eq!(c.to_bits(), r.to_bits());
    }
}

#[test]
fn hybrid_status_codes_are_distinct_and_on_base_500() {
    use reconfig_capi::convert_hybrid::status_to_c;
    use reconfig_capi::types_hybrid::*;
    use reconfig_core::hybrid::{SolveStatus as H, Stopped};
    let all = [
        (H::Unsolved, RECONFIG_UNSOLVED),
        (H::Solved, RECONFIG_HYBRID_SOLVED),
        (
            H::BudgetExhausted { verified: true },
            RECONFIG_HYBRID_BUDGET_EXHAUSTED_VERIFIED,
        ),
        (H::IterationLimit, RECONFIG_HYBRID_ITERATION_LIMIT),
        (H::NoDescent, RECONFIG_HYBRID_NO_DESCENT),
        (H::Singular, RECONFIG_HYBRID_SINGULAR),
        (
            H::IntegrationStopped(Stopped::SwitchLimit),
            RECONFIG_HYBRID_INTEGRATION_STOPPED,
        ),
        (H::CheckFailed, RECONFIG_HYBRID_CHECK_FAILED),
        (
            H::BudgetExhausted { verified: false },
            RECONFIG_HYBRID_BUDGET_EXHAUSTED_UNVERIFIED,
        ),
    ];
    for (s, c) in all {
        assert_eq!(status_to_c(s).0, c, "{s:?}");
        // The core's own code on the planner's base (the wire's planner code 5, times 100),
        // but for the unverified budget stop, after the last status.
        if s != (H::BudgetExhausted { verified: false }) && s != H::Unsolved {
            assert_eq!(c, 500 + i32::from(s.code()), "{s:?}");
        }
    }
    let mut codes: Vec<i32> = all.iter().map(|(s, _)| status_to_c(*s).0).collect();
    codes.sort_unstable();
    codes.dedup();
    assert_eq!(codes.len(), all.len());
    for (why, code) in [
        (
            Stopped::StepTooSmall,
            RECONFIG_HYBRID_STOPPED_STEP_TOO_SMALL,
        ),
        (Stopped::NotFinite, RECONFIG_HYBRID_STOPPED_NOT_FINITE),
        (Stopped::SwitchLimit, RECONFIG_HYBRID_STOPPED_SWITCH_LIMIT),
    ] {
        assert_eq!(
            status_to_c(H::IntegrationStopped(why)),
            (RECONFIG_HYBRID_INTEGRATION_STOPPED, code)
        );
        assert_eq!(code, i32::from(why as u8));
    }
}
