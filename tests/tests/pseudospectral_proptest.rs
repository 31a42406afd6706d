//! Arbitrary planner-A problems, including NaN, infinities, zeros and coincident spacecraft:
//! the solver never panics, and returns either an error or a solution with a status.

use proptest::prelude::*;
use reconfig_core::pseudospectral::{Problem, Settings, SolveStatus, Spacecraft};
use reconfig_tests::solve_pseudospectral;

fn number() -> impl Strategy<Value = f64> {
    prop_oneof![
        // Special values rare per number, so whole problems are often valid and reach the solver.
        120 => -20.0f64..20.0,
        1 => Just(0.0),
        1 => Just(f64::NAN),
        1 => Just(f64::INFINITY),
        1 => Just(-f64::INFINITY),
        1 => Just(1e300),
        1 => Just(-1e-300),
    ]
}

fn spacecraft() -> impl Strategy<Value = Spacecraft> {
    (
        prop_oneof![4 => 0.2f64..5.0, 1 => number()],
        prop::array::uniform6(number()),
        prop::array::uniform6(number()),
    )
        .prop_map(|(mass_mu, initial_state, final_state)| Spacecraft {
            mass_mu,
            initial_state,
            final_state,
        })
}

fn problem() -> impl Strategy<Value = Problem> {
    (
        prop_oneof![4 => 5.0f64..30.0, 1 => number()],
        prop_oneof![4 => 0.5f64..20.0, 1 => number()],
        prop_oneof![4 => 0.1f64..3.0, 1 => number()],
        0u16..30,
        any::<bool>(),
        prop::collection::vec(spacecraft(), 0..5),
    )
        .prop_map(
            |(horizon_tu, max_control_fu, keep_out_lu, degree, test_points, crafts)| {
                let mut spacecraft = heapless::Vec::new();
                for c in crafts {
                    let _ = spacecraft.push(c);
                }
                Problem {
                    horizon_tu,
                    max_control_fu,
                    keep_out_lu,
                    degree,
                    test_points,
                    spacecraft,
                }
            },
        )
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 96, rng_seed: proptest::test_runner::RngSeed::Fixed(2012), ..ProptestConfig::default() })]
    #[test]
    fn never_panics(problem in problem()) {
        let settings = Settings { sqp_max_iter: 8, ..Settings::default() };
        match solve_pseudospectral(&problem, &settings) {
            Ok(solution) => {
                // A produced solution carries a real status and finite numbers; only a failure
                // while setting up (before any subproblem) may report no iteration.
                prop_assert!(solution.cost.is_finite());
                let set_up_failed = matches!(
                    solution.info.status,
                    reconfig_core::pseudospectral::SolveStatus::NumericalFailure(_)
                );
                prop_assert!(solution.info.sqp_iterations >= 1 || set_up_failed);
                // Only `Infeasible` names unmet constraints, and it always names one, each
                // finite and missed.
                let infeasible = solution.info.status == SolveStatus::Infeasible;
                prop_assert_eq!(infeasible, solution.unmet.count > 0);
                for unmet in solution.unmet.named() {
                    prop_assert!(unmet.shortfall.is_finite() && unmet.shortfall > 0.0);
                    prop_assert!(unmet.shortfall_rel.is_finite() && unmet.shortfall_rel > 0.0);
                }
            }
            Err(error) => {
                // Errors render a message.
                let message = error.to_string();
                prop_assert!(!message.is_empty());
            }
        }
    }
}

/// Valid random reconfigurations: spacecraft on a well-separated grid swap to a shuffled grid,
/// with random masses, horizons and degrees.
fn valid_problem() -> impl Strategy<Value = Problem> {
    (
        2usize..5,
        4u16..17,
        any::<bool>(),
        prop::collection::vec(0.5f64..2.0, 4),
        prop::collection::vec(-1.0f64..1.0, 24),
        Just(()).prop_perturb(|_, mut rng| {
            let mut order: Vec<usize> = (0..4).collect();
            for i in (1..order.len()).rev() {
                let j = (rng.next_u32() as usize) % (i + 1);
                order.swap(i, j);
            }
            order
        }),
    )
        .prop_map(|(m, degree, test_points, masses, jitter, order)| {
            let slot = |k: usize, j: &[f64]| [6.0 * k as f64 + 0.5 * j[0], 0.5 * j[1], 0.5 * j[2]];
            let mut spacecraft = heapless::Vec::new();
            for i in 0..m {
                let a = slot(i, &jitter[3 * i..]);
                let b = slot(order[i], &jitter[12 + 3 * i..]);
                let b = [b[0], b[1] + 4.0, b[2]];
                let craft = Spacecraft {
                    mass_mu: masses[i],
                    initial_state: [a[0], a[1], a[2], 0.0, 0.0, 0.0],
                    final_state: [b[0], b[1], b[2], 0.0, 0.0, 0.0],
                };
                let _ = spacecraft.push(craft);
            }
            Problem {
                horizon_tu: 20.0,
                max_control_fu: 1.0,
                keep_out_lu: 2.0,
                degree,
                test_points,
                spacecraft,
            }
        })
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 48, rng_seed: proptest::test_runner::RngSeed::Fixed(2013), ..ProptestConfig::default() })]
    #[test]
    fn valid_problems_are_solved_or_say_why(problem in valid_problem()) {
        let solution = solve_pseudospectral(&problem, &Settings::default())
            .expect("a valid problem is accepted");
        let status = solution.info.status;
        if status.is_usable() {
            // Solved and Feasible mean verified: continuous separation, control bound and
            // boundary conditions hold.
            for sc in solution.controls_fu.iter().take(problem.spacecraft.len()) {
                for u in sc.iter().take(usize::from(problem.degree) + 1) {
                    prop_assert!(u.iter().all(|c| c.abs() <= problem.max_control_fu * (1.0 + 1e-9)));
                }
            }
            if status.is_certified() {
                prop_assert!(solution.certificate.certifies_local_optimum());
            }
            prop_assert!(solution.min_separation_lu.unwrap() >= 2.0 - 1e-6, "{:?}", solution.min_separation_lu);
            let n = usize::from(problem.degree);
            for (i, craft) in problem.spacecraft.iter().enumerate() {
                for k in 0..6 {
                    prop_assert!((solution.states[i][0][k] - craft.initial_state[k]).abs() < 1e-8);
                    prop_assert!((solution.states[i][n][k] - craft.final_state[k]).abs() < 1e-8);
                }
            }
        } else {
            // Anything else must not be flown; an infeasible answer says what it cannot meet.
            prop_assert!(!status.is_usable());
            prop_assert_eq!(status == SolveStatus::Infeasible, solution.unmet.count > 0);
        }
    }
}
