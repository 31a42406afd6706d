//! The hybrid planner through its contract: the published cases re-converged from ground
//! designs given to six digits, a navigation update, the work budget, and the refusals.

use super::*;
use crate::hybrid::units::days;
extern crate std;
use std::string::ToString;

/// Table 3's first case, κ = 1.40 and θ = −2 fixed, 4.38 d: the minimum-fuel costates the
/// ladder designs (`ladder` tests), to six significant digits.
pub(super) fn table_3_min_fuel() -> Problem {
    Problem {
        objective: Objective::MinFuel,
        kappa: 1.4,
        theta_rad: -2.0,
        free_kappa: false,
        free_theta: false,
        duration_days: 4.38,
        thrust_n: 10.0,
        specific_impulse_s: 3000.0,
        chemical_specific_impulse_s: 300.0,
        parking_radius_km: 6778.0,
        departure_offset: [0.0; 7],
        arrival_r_lu: [0.823_385_182_067, 0.0, -0.022_277_556_273],
        arrival_v_vu: [0.0, 0.134_184_170_262, 0.0],
        halo_period_tu: 2.746_337,
        costates: [
            1.512_93,
            7.364_03,
            -0.122_107,
            -0.019_178_6,
            0.014_939_0,
            5.139_83e-6,
            0.059_621_9,
        ],
        cost_multiplier: 0.0,
        design_duration_days: 4.38,
        design_thrust_n: 10.0,
    }
}

/// Table 2's κ = 1.40: minimum time, the multipliers to six digits, t_f from 3.4 d.
fn table_2_min_time() -> Problem {
    Problem {
        objective: Objective::MinTime,
        duration_days: 3.4,
        costates: [
            0.235_177,
            0.971_872,
            -0.006_433_37,
            -0.002_610_45,
            0.001_891_00,
            2.056_38e-6,
            0.007_616_55,
        ],
        cost_multiplier: 0.006_891_84,
        ..table_3_min_fuel()
    }
}

fn plan(problem: &Problem, settings: &Settings) -> Result<Solution, PlanError> {
    let mut out = Solution::new();
    solve(problem, settings, &mut Workspace::new(), &mut out)?;
    Ok(out)
}

#[test]
fn table_3s_first_case_reconverges_and_is_checked() {
    let settings = Settings::default();
    let out = plan(&table_3_min_fuel(), &settings).unwrap();
    assert_eq!(out.info.status, SolveStatus::Solved, "{out:?}");
    let flown = out.flown.unwrap();
    // The paper's 0.3365; ours 0.336551 (docs/hybrid.md).
    assert!((flown.final_mass - 0.336_551).abs() < 2e-6, "{flown:?}");
    assert!(out.residual.unwrap() <= 1e-10 && flown.end_miss <= 1e-10);
    assert!(flown.hamiltonian_drift <= 1e-10, "{flown:?}");
    // A bang-bang law that starts thrusting and switches: every switch inside the flight.
    assert!(flown.switches >= 2 && flown.thrust_arcs >= 2, "{flown:?}");
    let count = usize::try_from(flown.switches)
        .unwrap()
        .min(flown.switch_times_tu.len());
    let times = &flown.switch_times_tu[..count];
    assert!(times.windows(2).all(|w| w[0] < w[1]), "{times:?}");
    assert!(times.iter().all(|t| *t > 0.0 && *t < out.duration_tu));
    assert!(out.info.iterations >= 1 && out.info.work_units <= settings.work_budget);
    // The mass after the impulse is Table 2's for κ = 1.40 (0.3529, truncated as printed).
    assert!((out.mass_after_impulse - 0.3529).abs() < 1e-4);
    // Same input, same bits.
    let again = plan(&table_3_min_fuel(), &settings).unwrap();
    assert_eq!(again, out);
    assert_eq!(
        again.flown.unwrap().final_mass.to_bits(),
        flown.final_mass.to_bits()
    );
}

#[test]
fn table_2s_minimum_time_reconverges() {
    let out = plan(&table_2_min_time(), &Settings::default()).unwrap();
    assert_eq!(out.info.status, SolveStatus::Solved, "{out:?}");
    assert!((days(out.duration_tu) - 3.3692).abs() < 1e-3, "{out:?}");
    let flown = out.flown.unwrap();
    assert!((flown.final_mass - 0.3200).abs() < 1e-4, "{flown:?}");
    assert_eq!((flown.switches, flown.thrust_arcs), (0, 1));
    assert!(flown.hamiltonian_drift <= 1e-10);
}

#[test]
fn a_navigation_update_of_the_departure_reconverges() {
    // 1 km off in x and 0.1 m/s off in y after the impulse: the design's costates are a
    // neighbour's, and the shooting converges from them.
    let lu_km = crate::hybrid::units::LU_KM;
    let mut problem = table_3_min_fuel();
    problem.departure_offset[0] = 1.0 / lu_km;
    problem.departure_offset[4] = 1e-4 / crate::hybrid::units::vu_kmps();
    let out = plan(&problem, &Settings::default()).unwrap();
    assert_eq!(out.info.status, SolveStatus::Solved, "{out:?}");
    let nominal = plan(&table_3_min_fuel(), &Settings::default()).unwrap();
    // A different transfer: the costates moved.
    assert!((out.costates[0] - nominal.costates[0]).abs() > 1e-6);
}

#[test]
fn a_spent_budget_says_so_and_offers_nothing() {
    let settings = Settings {
        work_budget: 1_200,
        ..Settings::default()
    };
    let out = plan(&table_3_min_fuel(), &settings).unwrap();
    assert_eq!(
        out.info.status,
        SolveStatus::BudgetExhausted { verified: false },
        "{out:?}"
    );
    assert!(!out.info.status.is_usable());
    assert!(out.info.work_units <= 1_200, "{}", out.info.work_units);
    // Every number finite, whatever the status.
    assert!(out.costates.iter().all(|x| x.is_finite()));
}

#[test]
fn a_start_far_from_the_design_does_not_claim_a_plan() {
    let mut problem = table_3_min_fuel();
    problem.costates = [0.1, 0.1, 0.1, 0.1, 0.1, 0.1, 0.1];
    let settings = Settings {
        max_iterations: 5,
        ..Settings::default()
    };
    let out = plan(&problem, &settings).unwrap();
    assert!(!out.info.status.is_usable(), "{out:?}");
    assert!(out.info.iterations <= 5);
}

#[test]
fn bad_input_is_refused_naming_the_field_the_value_and_the_limit() {
    let refused = |problem: Problem| plan(&problem, &Settings::default()).unwrap_err();
    let out_of_range = |e: PlanError| match e {
        PlanError::OutOfRange { field, value, .. } => (field, value),
        other => panic!("{other:?}"),
    };
    let sqrt2 = core::f64::consts::SQRT_2;
    let e = refused(Problem {
        kappa: sqrt2,
        ..table_3_min_fuel()
    });
    assert_eq!(out_of_range(e), (Field::Kappa, sqrt2));
    assert!(e.to_string().contains("1.4142135623730951)"), "{e}");
    assert_eq!(
        out_of_range(refused(Problem {
            kappa: 0.99,
            ..table_3_min_fuel()
        })),
        (Field::Kappa, 0.99)
    );
    let e = refused(Problem {
        theta_rad: f64::NAN,
        ..table_3_min_fuel()
    });
    assert!(matches!(
        e,
        PlanError::OutOfRange {
            field: Field::Theta,
            ..
        }
    ));
    for (problem, field) in [
        (
            Problem {
                thrust_n: 0.0,
                ..table_3_min_fuel()
            },
            Field::Thrust,
        ),
        (
            Problem {
                specific_impulse_s: -1.0,
                ..table_3_min_fuel()
            },
            Field::SpecificImpulse,
        ),
        (
            Problem {
                free_kappa: true,
                ..table_2_min_time()
            },
            Field::FreeKappa,
        ),
    ] {
        assert_eq!(out_of_range(refused(problem)).0, field);
    }
    // A point 1e-4 LU off the halo orbit does not return to itself.
    let mut off = table_3_min_fuel();
    off.arrival_r_lu[0] += 1e-4;
    match refused(off) {
        PlanError::NotOnPeriodicOrbit { miss, limit } => {
            assert!(miss > limit && limit == 1e-6, "{miss} {limit}");
        }
        other => panic!("{other:?}"),
    }
    // A setting outside its range.
    let e = plan(
        &table_3_min_fuel(),
        &Settings {
            tolerance: 0.0,
            ..Settings::default()
        },
    )
    .unwrap_err();
    assert!(matches!(e, PlanError::InvalidSetting(_)), "{e:?}");
}

#[test]
fn the_walk_from_the_design_reaches_what_the_straight_shooting_does_not() {
    // 10 km off in x and 1 m/s off in y: the shooting from the design alone stops without
    // descent (no walk); the walk from the design reaches the request.
    let lu_km = crate::hybrid::units::LU_KM;
    let mut problem = table_3_min_fuel();
    problem.departure_offset[0] = 10.0 / lu_km;
    problem.departure_offset[4] = 1e-3 / crate::hybrid::units::vu_kmps();
    let straight = plan(
        &problem,
        &Settings {
            continuation_steps: 0,
            ..Settings::default()
        },
    )
    .unwrap();
    assert!(!straight.info.status.is_usable(), "{straight:?}");
    assert_eq!(straight.info.walked.shootings, 0);
    let walked = plan(&problem, &Settings::default()).unwrap();
    assert_eq!(walked.info.status, SolveStatus::Solved, "{walked:?}");
    assert!(walked.info.walked.shootings >= 1 && walked.info.walked.reached == 1.0);
    assert!(walked.info.work_units <= Settings::default().work_budget);
    // A changed time of flight (4.38 d designed, 4.20 d asked) and a derated engine (10 N
    // designed, 9.5 N available) from the same design.
    for changed in [
        Problem {
            duration_days: 4.2,
            ..table_3_min_fuel()
        },
        Problem {
            thrust_n: 9.5,
            ..table_3_min_fuel()
        },
    ] {
        let out = plan(&changed, &Settings::default()).unwrap();
        assert_eq!(out.info.status, SolveStatus::Solved, "{changed:?}: {out:?}");
        assert!(out.flown.unwrap().hamiltonian_drift <= 1e-10);
    }
}

#[test]
fn a_large_navigation_update_reconverges_by_the_predicted_walk() {
    // 30, −20, 15 km and 3, −2, 1.5 m/s off after the impulse (σ 10 km / 1 m/s is the
    // largest family of `reconfig reconverge`). Without the secant predictor and the straight
    // shooting's share (each step from the last converged costates, the straight shooting
    // free to spend the budget) this ran out of walk shootings (`IterationLimit`, 73,050
    // work units); with them it is `Solved` in about a third of that.
    let lu_km = crate::hybrid::units::LU_KM;
    let vu_mps = crate::hybrid::units::vu_kmps() * 1e3;
    let mut problem = table_3_min_fuel();
    for (slot, km) in problem.departure_offset.iter_mut().zip([30.0, -20.0, 15.0]) {
        *slot = km / lu_km;
    }
    for (slot, mps) in problem.departure_offset[3..]
        .iter_mut()
        .zip([3.0, -2.0, 1.5])
    {
        *slot = mps / vu_mps;
    }
    let out = plan(&problem, &Settings::default()).unwrap();
    assert_eq!(out.info.status, SolveStatus::Solved, "{out:?}");
    assert!(out.info.walked.shootings >= 1 && out.info.walked.reached == 1.0);
    assert!(out.info.work_units < 30_000, "{}", out.info.work_units);
}
