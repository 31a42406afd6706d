//! Property tests: planner B never panics on arbitrary input (NaN, inf, huge, degenerate),
//! answers every request with an error or a status, and no accepted input yields a non-finite
//! number anywhere in its output, in any input form (`solve_form`: the plan and the end state).

use proptest::prelude::*;
use reconfig_core::astro::EARTH_MU_KM3_S2;
use reconfig_core::capacity::MAX_IMPULSES;
use reconfig_core::impulsive::{
    solve, solve_form, CartesianState, EndState, EquinoctialElements, FormProblem, ImpulsePlan,
    ImpulsePoint, MeanElements, OrbitForm, Problem, RelativeElements, RelativeForm, Roe, Settings,
    Solution, SolveStatus, Workspace,
};

fn any_f64() -> impl Strategy<Value = f64> {
    prop_oneof![
        4 => -10.0f64..10.0,
        1 => Just(f64::NAN),
        1 => Just(f64::INFINITY),
        1 => Just(f64::NEG_INFINITY),
        1 => Just(0.0),
        1 => any::<f64>(),
    ]
}

fn rel(v: [f64; 6]) -> RelativeElements {
    RelativeElements {
        dsma_km: v[0],
        decc: v[1],
        dinc_rad: v[2],
        draan_rad: v[3],
        dargp_rad: v[4],
        dmean_anomaly_rad: v[5],
    }
}

fn quick() -> Settings {
    Settings {
        search_samples: 20,
        search_starts: 2,
        search_max_evaluations: 60,
        fixed_point_max_iter: 20,
        ..Settings::default()
    }
}

/// Every number of a solution (and of its status).
fn numbers(out: &Solution) -> Vec<f64> {
    let mut v = Vec::new();
    for i in &out.impulses {
        v.extend([i.time_s, i.arg_latitude_rad, i.true_arg_latitude_rad]);
        v.extend(i.dv_rtn_mps);
    }
    v.extend([
        out.total_dv_mps,
        out.final_time_s,
        out.info.min_fuel_gap_mps,
    ]);
    // Absent values carry no number; present ones must be finite.
    v.extend(out.min_norm_total_dv_mps);
    v.extend(out.linear_total_dv_mps);
    v.extend(out.info.condition_number);
    if let Some(t) = &out.terminal_error {
        v.extend([t.along_track_m, t.position_m]);
        v.extend(t.elements.as_array());
        v.extend(t.equinoctial.as_array());
    }
    match out.info.status {
        SolveStatus::Linearised { miss_m } => v.push(miss_m),
        SolveStatus::UnsafePerigee {
            perigee_altitude_km,
            ..
        } => v.push(perigee_altitude_km),
        _ => {}
    }
    v
}

fn check_with(problem: &Problem, settings: &Settings) {
    let mut ws = Workspace::new();
    let mut out = Solution::new();
    match solve(problem, settings, &mut ws, &mut out) {
        Ok(()) => {
            assert_ne!(out.info.status, SolveStatus::Unsolved);
            assert!(!out.impulses.is_empty());
            let bad: Vec<f64> = numbers(&out)
                .into_iter()
                .filter(|x| !x.is_finite())
                .collect();
            assert!(
                bad.is_empty(),
                "accepted input gave non-finite output {bad:?}: {problem:?} -> {out:?}"
            );
        }
        Err(e) => assert!(!e.to_string().is_empty()),
    }
}

fn check(problem: &Problem) {
    check_with(problem, &quick());
    // The linear plan alone (status `Linearised`) reports its miss: finite too.
    check_with(
        problem,
        &Settings {
            min_fuel: false,
            nonlinear_correction: false,
            ..quick()
        },
    );
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 160, rng_seed: proptest::test_runner::RngSeed::Fixed(2018), ..ProptestConfig::default() })]

    #[test]
    fn arbitrary_elements_and_points(
        a in prop_oneof![6000.0f64..50_000.0, 5e4f64..2e5, any_f64(), Just(1e308), Just(1e10)],
        e in prop_oneof![0.0f64..1.2, 0.85f64..0.95, any_f64()],
        i in prop_oneof![0.0f64..3.2, any_f64()],
        angles in prop::array::uniform3(any_f64()),
        initial in prop::array::uniform6(prop_oneof![-1e-3f64..1e-3, any_f64()]),
        target in prop::array::uniform6(prop_oneof![-1e-3f64..1e-3, any_f64()]),
        pts in prop::collection::vec((any_f64(), -2i32..20), 0..=MAX_IMPULSES),
    ) {
        let plan = ImpulsePlan::Fixed(pts.iter().map(|(u, n)| ImpulsePoint { arg_latitude_rad: *u, revolutions: *n }).collect());
        let problem = Problem {
            chief: MeanElements { sma_km: a, ecc: e, inc_rad: i, raan_rad: angles[0], argp_rad: angles[1], mean_anomaly_rad: angles[2] },
            initial: rel(initial),
            target: rel(target),
            plan,
        };
        check(&problem);
    }

    #[test]
    fn arbitrary_searches(
        e in 0.0f64..0.9,
        i in 0.0f64..3.2,
        target in prop::array::uniform6(-1e-2f64..1e-2),
        impulses in 0u8..9,
        max_revolutions in -3i32..30,
    ) {
        let problem = Problem {
            chief: MeanElements { sma_km: 7000.0, ecc: e, inc_rad: i, raan_rad: 1.0, argp_rad: 2.0, mean_anomaly_rad: 3.0 },
            initial: rel([0.0; 6]),
            target: rel(target),
            plan: ImpulsePlan::Search { impulses, max_revolutions },
        };
        check(&problem);
    }

    /// Orbits built to be accepted (chief perigee 100 km to 40 000 km, e and sin i above the
    /// thresholds, small differences): most solve; every number of every output is finite.
    #[test]
    fn accepted_orbits_give_finite_outputs(
        perigee_alt_km in 100.0f64..40_000.0,
        e in 1e-4f64..0.9,
        i in 0.002f64..3.1394,
        angles in prop::array::uniform3(-10.0f64..10.0),
        initial in prop::array::uniform6(-1e-2f64..1e-2),
        target in prop::array::uniform6(-1e-2f64..1e-2),
        pts in prop::collection::vec((0.0f64..6.3, 0i32..5), 1..=MAX_IMPULSES),
    ) {
        let a = (6378.137 + perigee_alt_km) / (1.0 - e);
        let plan = ImpulsePlan::Fixed(pts.iter().map(|(u, n)| ImpulsePoint { arg_latitude_rad: *u, revolutions: *n }).collect());
        // Relative elements: da up to 1e-5 a, de up to 1e-4, angles up to 0.01 rad.
        let scale = [a * 1e-3, 1e-2, 1.0, 1.0, 1.0, 1.0];
        let mut ini = initial;
        let mut tgt = target;
        for k in 0..6 {
            ini[k] *= scale[k];
            tgt[k] *= scale[k];
        }
        let problem = Problem {
            chief: MeanElements { sma_km: a, ecc: e, inc_rad: i, raan_rad: angles[0], argp_rad: angles[1], mean_anomaly_rad: angles[2] },
            initial: rel(ini),
            target: rel(tgt),
            plan,
        };
        check(&problem);
    }
}

/// Every number of an end state (`Unavailable` and `NotFlown` carry none).
fn end_numbers(end: &EndState) -> Vec<f64> {
    match end {
        EndState::NotFlown => vec![],
        EndState::Elements(r) => vec![
            r.dsma_km,
            r.decc,
            r.dinc_rad,
            r.draan_rad,
            r.dargp_rad,
            r.dmean_anomaly_rad,
        ],
        EndState::Roe(r) => vec![r.da_m, r.dlambda_m, r.dex_m, r.dey_m, r.dix_m, r.diy_m],
        EndState::DeputyClassical(d) => vec![
            d.sma_km,
            d.ecc,
            d.inc_rad,
            d.raan_rad,
            d.argp_rad,
            d.mean_anomaly_rad,
        ],
        EndState::DeputyEquinoctial(q) => {
            vec![q.sma_km, q.mean_longitude_rad, q.ex, q.ey, q.hx, q.hy]
        }
        EndState::DeputyState(s) => s.pos_km.iter().chain(s.vel_km_s.iter()).copied().collect(),
        EndState::Unavailable(_) => Vec::new(),
    }
}

/// A request in other forms: refused by the limits, rejected by the planner, or answered with
/// finite numbers only (solution and end state), with the correction on and off.
fn check_form(problem: &FormProblem) {
    for settings in [
        quick(),
        Settings {
            min_fuel: false,
            nonlinear_correction: false,
            ..quick()
        },
    ] {
        let limits = reconfig_core::limits::Limits {
            impulsive: reconfig_core::limits::impulsive::Limits {
                settings: Settings {
                    nonlinear_correction: false,
                    ..Settings::default()
                },
                ..Default::default()
            },
            ..Default::default()
        };
        if limits.impulsive.check_form(problem, &settings).is_err() {
            continue;
        }
        let mut ws = Workspace::new();
        let mut out = Solution::new();
        match solve_form(problem, &settings, &mut ws, &mut out) {
            Ok(end) => {
                assert_ne!(out.info.status, SolveStatus::Unsolved);
                let bad: Vec<f64> = numbers(&out)
                    .into_iter()
                    .chain(end_numbers(&end))
                    .filter(|x| !x.is_finite())
                    .collect();
                assert!(
                    bad.is_empty(),
                    "accepted form input gave non-finite output {bad:?}: {problem:?} -> {end:?} {out:?}"
                );
            }
            Err(e) => assert!(!e.to_string().is_empty()),
        }
    }
}

fn state(pos_km: [f64; 3], vel_km_s: [f64; 3]) -> CartesianState {
    CartesianState { pos_km, vel_km_s }
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 96, rng_seed: proptest::test_runner::RngSeed::Fixed(2026), ..ProptestConfig::default() })]

    /// Chief as an osculating state or equinoctial elements (ellipses, hyperbolas, NaN, huge),
    /// relative state as ROE or the deputy's own state: no accepted request yields a
    /// non-finite number in its plan or its end state.
    #[test]
    fn forms_give_finite_outputs_or_named_refusals(
        r_km in prop_oneof![12 => 6700.0f64..45_000.0, 1 => any_f64()],
        dir in prop::array::uniform3(-1.0f64..1.0),
        speed_ratio in prop_oneof![12 => 0.97f64..1.1, 2 => 1.3f64..1.6, 1 => any_f64()],
        equinoctial in prop::array::uniform6(prop_oneof![30 => -0.02f64..0.02, 1 => any_f64()]),
        roe in prop::array::uniform6(prop_oneof![30 => -2000.0f64..2000.0, 1 => any_f64()]),
        dx in prop::array::uniform6(prop_oneof![30 => -1.0f64..1.0, 1 => any_f64()]),
        chief_kind in 0u8..2,
        relative_kind in 0u8..2,
        pts in prop::collection::vec((0.0f64..6.3, 0i32..4), 1..=3),
    ) {
        // A chief state at radius r, velocity across the radius scaled from circular speed.
        let n = (dir[0] * dir[0] + dir[1] * dir[1] + dir[2] * dir[2]).sqrt().max(1e-3);
        let u = [dir[0] / n, dir[1] / n, dir[2] / n];
        let pos = [r_km * u[0], r_km * u[1], r_km * u[2]];
        // Some vector not parallel to u, crossed with u: a direction across the radius.
        let w = if u[0].abs() < 0.9 { [1.0, 0.0, 0.0] } else { [0.0, 1.0, 0.0] };
        let c = [u[1] * w[2] - u[2] * w[1], u[2] * w[0] - u[0] * w[2], u[0] * w[1] - u[1] * w[0]];
        let cn = (c[0] * c[0] + c[1] * c[1] + c[2] * c[2]).sqrt();
        let v = speed_ratio * (EARTH_MU_KM3_S2 / r_km).sqrt();
        let vel = [v * c[0] / cn, v * c[1] / cn, v * c[2] / cn];
        let chief = if chief_kind == 0 {
            OrbitForm::State(state(pos, vel))
        } else {
            OrbitForm::Equinoctial(EquinoctialElements {
                sma_km: r_km,
                mean_longitude_rad: equinoctial[0] * 300.0,
                ex: equinoctial[1],
                ey: equinoctial[2],
                hx: equinoctial[3] * 50.0,
                hy: equinoctial[4] * 50.0,
            })
        };
        let relative = if relative_kind == 0 {
            let r = Roe { da_m: roe[0], dlambda_m: roe[1], dex_m: roe[2], dey_m: roe[3], dix_m: roe[4], diy_m: roe[5] };
            RelativeForm::Roe { initial: r, target: Roe { da_m: -roe[0], ..r } }
        } else {
            // The deputy: the chief's state moved by up to 1 km and 1 m/s.
            let d = |k: usize| dx[k];
            let deputy = state(
                [pos[0] + d(0), pos[1] + d(1), pos[2] + d(2)],
                [vel[0] + 1e-3 * d(3), vel[1] + 1e-3 * d(4), vel[2] + 1e-3 * d(5)],
            );
            RelativeForm::Deputy { initial: OrbitForm::State(deputy), target: chief }
        };
        let plan = ImpulsePlan::Fixed(pts.iter().map(|(u, n)| ImpulsePoint { arg_latitude_rad: *u, revolutions: *n }).collect());
        check_form(&FormProblem { chief, relative, plan });
    }
}
