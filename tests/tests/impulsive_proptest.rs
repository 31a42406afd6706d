//! Property tests: planner B never panics on arbitrary input (NaN, inf, huge, degenerate),
//! answers every request with an error or a status, and no accepted input yields a non-finite
//! number anywhere in its output.

use proptest::prelude::*;
use reconfig_core::capacity::MAX_IMPULSES;
use reconfig_core::impulsive::{
    solve, ImpulsePlan, ImpulsePoint, MeanElements, Problem, RelativeElements, Settings, Solution,
    SolveStatus, Workspace,
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
    let e = &out.terminal_error_elements;
    v.extend([
        out.total_dv_mps,
        out.min_norm_total_dv_mps,
        out.linear_total_dv_mps,
        out.final_time_s,
        out.terminal_error_m,
        out.terminal_position_error_m,
        e.dsma_km,
        e.decc,
        e.dinc_rad,
        e.draan_rad,
        e.dargp_rad,
        e.dmean_anomaly_rad,
        out.info.condition_number,
    ]);
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
