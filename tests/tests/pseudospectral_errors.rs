//! Every class of bad planner-A input gets its own error (or status), never a panic.

use reconfig_core::pseudospectral::{
    Boundary, Capacity, PlanError, Problem, Quantity, SettingId, Settings, SolveStatus, Spacecraft,
    MAX_MAGNITUDE, MIN_POSITIVE,
};
use reconfig_tests::{pseudospectral_fixture, solve_pseudospectral};

fn paper() -> Problem {
    pseudospectral_fixture("huang2012-three-sats-n10")
}

fn rejected(problem: &Problem) -> PlanError {
    solve_pseudospectral(problem, &Settings::default()).expect_err("must be rejected")
}

/// The refused quantity, spacecraft and value (as bits: a NaN is named as given).
fn not_finite(e: PlanError) -> (Quantity, u8, u64) {
    match e {
        PlanError::NotFinite {
            what,
            spacecraft,
            value,
        } => (what, spacecraft, value.to_bits()),
        other => panic!("expected NotFinite, got {other:?}"),
    }
}

#[test]
fn nan_and_infinity_anywhere() {
    let mut p = paper();
    p.horizon_tu = f64::NAN;
    assert_eq!(
        not_finite(rejected(&p)),
        (Quantity::Horizon, 0, f64::NAN.to_bits())
    );
    let mut p = paper();
    p.max_control_fu = f64::INFINITY;
    assert_eq!(
        not_finite(rejected(&p)),
        (Quantity::MaxControl, 0, f64::INFINITY.to_bits())
    );
    let mut p = paper();
    p.keep_out_lu = f64::NEG_INFINITY;
    assert_eq!(
        not_finite(rejected(&p)),
        (Quantity::KeepOut, 0, f64::NEG_INFINITY.to_bits())
    );
    let mut p = paper();
    p.spacecraft[1].mass_mu = f64::NAN;
    assert_eq!(
        not_finite(rejected(&p)),
        (Quantity::Mass, 1, f64::NAN.to_bits())
    );
    let mut p = paper();
    p.spacecraft[2].final_state[4] = f64::NAN;
    assert_eq!(
        not_finite(rejected(&p)),
        (Quantity::BoundaryState, 2, f64::NAN.to_bits())
    );
}

#[test]
fn non_positive_horizon_keep_out_bound_and_mass() {
    for (edit, what) in [
        (0usize, Quantity::Horizon),
        (1, Quantity::MaxControl),
        (2, Quantity::KeepOut),
        (3, Quantity::Mass),
    ] {
        for value in [0.0, -1.0] {
            let mut p = paper();
            let spacecraft = if edit == 3 { 1 } else { 0 };
            match edit {
                0 => p.horizon_tu = value,
                1 => p.max_control_fu = value,
                2 => p.keep_out_lu = value,
                _ => p.spacecraft[1].mass_mu = value,
            }
            assert_eq!(
                rejected(&p),
                PlanError::NotPositive {
                    what,
                    spacecraft,
                    value
                }
            );
        }
    }
}

#[test]
fn degree_below_four_or_above_capacity() {
    let mut p = paper();
    p.degree = 3;
    assert_eq!(rejected(&p), PlanError::DegreeTooLow { requested: 3 });
    p.degree = 25;
    assert_eq!(
        rejected(&p),
        PlanError::CapacityExceeded {
            what: Capacity::Degree,
            requested: 25,
            capacity: 24
        }
    );
}

#[test]
fn no_spacecraft() {
    let mut p = paper();
    p.spacecraft.clear();
    assert_eq!(rejected(&p), PlanError::NoSpacecraft);
}

#[test]
fn more_spacecraft_than_capacity_cannot_be_built() {
    // The capacity is in the type: a ninth push fails, and a fixture with nine is refused.
    let mut p = paper();
    while p.spacecraft.len() < 8 {
        let k = p.spacecraft.len() as f64;
        let craft = Spacecraft {
            mass_mu: 1.0,
            initial_state: [50.0 + 5.0 * k, 0.0, 0.0, 0.0, 0.0, 0.0],
            final_state: [50.0 + 5.0 * k, 5.0, 0.0, 0.0, 0.0, 0.0],
        };
        p.spacecraft.push(craft).expect("room");
    }
    assert!(p.spacecraft.push(p.spacecraft[0]).is_err());
    let mut text =
        std::fs::read_to_string(reconfig_tests::fixtures_dir().join("crossing-8-sats-n16.toml"))
            .unwrap();
    text.push_str("\n[[spacecraft]]\ninitial = [90, 0, 0, 0, 0, 0]\nfinal = [90, 9, 0, 0, 0, 0]\n");
    let err = reconfig_host::fixture::parse(&text).expect_err("nine spacecraft");
    assert!(format!("{err:#}").contains("capacity of 8"), "{err:#}");
}

#[test]
fn spacecraft_starting_or_ending_too_close() {
    let mut p = paper();
    p.spacecraft[2].initial_state[0] = 8.0;
    p.spacecraft[2].initial_state[2] = 1.0; // 1 from spacecraft 2 at the start
    assert_eq!(
        rejected(&p),
        PlanError::BoundaryTooClose {
            first: 1,
            second: 2,
            boundary: Boundary::Initial
        }
    );
    let mut p = paper();
    p.spacecraft[1].final_state = p.spacecraft[0].final_state; // same end point
    assert_eq!(
        rejected(&p),
        PlanError::BoundaryTooClose {
            first: 0,
            second: 1,
            boundary: Boundary::Final
        }
    );
}

#[test]
fn manoeuvre_impossible_within_the_bound() {
    // 30 LU rest to rest in T = 10 needs more than bang-bang at Umax = 1 reaches (25).
    let mut p = paper();
    p.spacecraft[0].final_state[1] = 30.0;
    assert_eq!(
        rejected(&p),
        PlanError::ManoeuvreInfeasible {
            spacecraft: 0,
            axis: 1
        }
    );
}

#[test]
fn invalid_settings_name_the_setting_the_value_and_the_range() {
    let p = paper();
    let zero = Settings {
        qp_max_iter: 0,
        ..Settings::default()
    };
    let PlanError::InvalidSetting(e) = solve_pseudospectral(&p, &zero).expect_err("zero limit")
    else {
        panic!("a setting refusal")
    };
    assert_eq!(
        (e.setting, e.value, e.range.min),
        (SettingId::QpMaxIter, 0.0, 1.0)
    );
    assert_eq!(e.setting.name(), "qp_max_iter");
    let nan = Settings {
        qp_tol_feas: f64::NAN,
        ..Settings::default()
    };
    let PlanError::InvalidSetting(e) = solve_pseudospectral(&p, &nan).expect_err("nan tolerance")
    else {
        panic!("a setting refusal")
    };
    assert_eq!(e.setting, SettingId::QpTolFeas);
    assert!(e.value.is_nan());
    assert!(
        e.to_string()
            .starts_with("setting qp_tol_feas = NaN is outside (0"),
        "{e}"
    );
}

#[test]
fn iteration_limit_returns_the_best_iterate_and_says_so() {
    let p = paper();
    let short = Settings {
        sqp_max_iter: 2,
        ..Settings::default()
    };
    let s = solve_pseudospectral(&p, &short).expect("accepted");
    // Two subproblems from the analytic guess give a QP solution that is verified feasible on
    // the continuous trajectory but is no certified optimum: `Feasible`, never `Solved`.
    assert_eq!(s.info.status, SolveStatus::Feasible);
    assert!(s.info.status.is_usable() && !s.info.status.is_certified());
    assert!(
        s.min_separation_lu.unwrap() >= 2.0 - 1e-7,
        "{:?}",
        s.min_separation_lu
    );
    assert!(s.certificate.max_violation <= 1e-7);
    // The returned iterate is a QP solution: it meets every checked keep-out.
    assert!(s.info.max_violation <= 1e-9, "{}", s.info.max_violation);
    assert!(s.cost.is_finite() && s.cost > 6.336);
    // One subproblem is not enough to clear the continuous keep-out: the iteration limit is
    // reported, and nothing promises feasibility.
    let one = Settings {
        sqp_max_iter: 1,
        ..Settings::default()
    };
    let s = solve_pseudospectral(&p, &one).expect("accepted");
    if s.info.status != SolveStatus::Feasible {
        assert_eq!(s.info.status, SolveStatus::MaxIterations);
        assert!(!s.info.status.is_usable());
    } else {
        assert!(s.min_separation_lu.unwrap() >= 2.0 - 1e-7);
    }
}

#[test]
fn qp_iteration_limit_is_a_status() {
    let p = paper();
    let tiny = Settings {
        qp_max_iter: 2,
        ..Settings::default()
    };
    let s = solve_pseudospectral(&p, &tiny).expect("accepted");
    assert_eq!(s.info.status, SolveStatus::QpLimit);
}

#[test]
fn warm_start_of_another_size_is_refused() {
    use reconfig_core::pseudospectral::{solve_warm, Solution, Workspace};
    let p = paper();
    let previous = solve_pseudospectral(
        &pseudospectral_fixture("huang2012-three-sats-n9"),
        &Settings::default(),
    )
    .unwrap();
    let mut ws = Box::new(Workspace::new());
    let mut out = Box::new(Solution::new());
    assert_eq!(
        solve_warm(&p, &Settings::default(), &mut ws, &previous, &mut out),
        Err(PlanError::WarmStartMismatch)
    );
}

#[test]
fn magnitudes_beyond_the_planners_range() {
    // Found by the property test: T = 1e300 underflows (2/T)^2 and states of 1e300 overflow the
    // cost. Both are refused before iterating.
    let mut p = paper();
    p.horizon_tu = 1e300;
    assert_eq!(
        rejected(&p),
        PlanError::OutOfRange {
            what: Quantity::Horizon,
            spacecraft: 0,
            value: 1e300,
            limit: MAX_MAGNITUDE
        }
    );
    let mut p = paper();
    p.max_control_fu = 1e-12;
    assert_eq!(
        rejected(&p),
        PlanError::OutOfRange {
            what: Quantity::MaxControl,
            spacecraft: 0,
            value: 1e-12,
            limit: MIN_POSITIVE
        }
    );
    let mut p = paper();
    p.spacecraft[0].initial_state[3] = 1e300;
    assert_eq!(
        rejected(&p),
        PlanError::OutOfRange {
            what: Quantity::BoundaryState,
            spacecraft: 0,
            value: 1e300,
            limit: MAX_MAGNITUDE
        }
    );
    let message = rejected(&p).to_string();
    assert!(message.contains("outside the accepted range"), "{message}");
}
