//! Arbitrary planner-A problems, including NaN, infinities, zeros and coincident spacecraft:
//! the solver never panics, and returns either an error or a solution with a status.

use proptest::prelude::*;
use reconfig_core::pseudospectral::{Problem, Settings, Spacecraft};
use reconfig_tests::solve_pseudospectral;

fn number() -> impl Strategy<Value = f64> {
    prop_oneof![
        8 => -20.0f64..20.0,
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
        prop_oneof![4 => 1.0f64..30.0, 1 => number()],
        prop_oneof![4 => 0.1f64..3.0, 1 => number()],
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
    #![proptest_config(ProptestConfig { cases: 96, ..ProptestConfig::default() })]
    #[test]
    fn never_panics(problem in problem()) {
        let settings = Settings { sqp_max_iter: 8, ..Settings::default() };
        match solve_pseudospectral(&problem, &settings) {
            Ok(solution) => {
                // A produced solution carries a real status and finite numbers.
                prop_assert!(solution.cost.is_finite());
                prop_assert!(solution.info.sqp_iterations >= 1);
            }
            Err(error) => {
                // Errors render a message.
                let message = error.to_string();
                prop_assert!(!message.is_empty());
            }
        }
    }
}
