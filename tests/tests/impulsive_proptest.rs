//! Property tests: planner B never panics on arbitrary input (NaN, inf, huge, degenerate), and
//! answers every request with an error or a status.

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

fn check(problem: &Problem) {
    let mut ws = Workspace::new();
    let mut out = Solution::new();
    match solve(problem, &quick(), &mut ws, &mut out) {
        Ok(()) => {
            assert_ne!(out.info.status, SolveStatus::Unsolved);
            assert!(!out.impulses.is_empty());
            if out.info.status.is_usable() {
                assert!(out.total_dv_mps.is_finite());
            }
        }
        Err(e) => assert!(!e.to_string().is_empty()),
    }
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 160, rng_seed: proptest::test_runner::RngSeed::Fixed(2018), ..ProptestConfig::default() })]

    #[test]
    fn arbitrary_elements_and_points(
        a in prop_oneof![6000.0f64..50_000.0, any_f64()],
        e in prop_oneof![0.0f64..1.2, any_f64()],
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
}
