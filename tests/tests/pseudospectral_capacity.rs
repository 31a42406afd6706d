//! Planner A within its documented capacities never stops on the QP's active-set size: a
//! subproblem whose working set outgrows the Gram factor (`MAX_ACTIVE` rows) continues with
//! the capacity-free dual fallback, and the answer is verified like any other.

use reconfig_core::capacity::MAX_ACTIVE;
use reconfig_core::pseudospectral::{Problem, Settings, SolveStatus, Spacecraft};
use reconfig_tests::solve_pseudospectral;

/// Eight spacecraft, N = 24, each moving 20 LU per axis in T = 10 with Umax = 1: close to
/// bang-bang (rest to rest needs 25 = Umax T^2 / 4 at most), so the first subproblem holds
/// control bounds at most nodes of every axis, far more than `MAX_ACTIVE` rows.
fn near_bang_bang() -> Problem {
    let mut spacecraft = heapless::Vec::new();
    for k in 0..8 {
        let x = 10.0 * f64::from(k);
        spacecraft
            .push(Spacecraft {
                mass_mu: 1.0,
                initial_state: [x, 0.0, 0.0, 0.0, 0.0, 0.0],
                final_state: [x + 20.0, 20.0, 20.0, 0.0, 0.0, 0.0],
            })
            .expect("capacity 8");
    }
    Problem {
        horizon_tu: 10.0,
        max_control_fu: 1.0,
        keep_out_lu: 2.0,
        degree: 24,
        test_points: true,
        spacecraft,
    }
}

#[test]
fn a_working_set_beyond_the_factor_capacity_is_no_failure() {
    let problem = near_bang_bang();
    // The dual fallback's sweeps cost 42.1 M work units here, past the default budget (40 M:
    // about 382 M M7 instructions; it was 25 M, when this case ended `BudgetExhausted { verified:
    // false }` with 14.6 M units used, the rest reserved for the final checks). What is tested is the QP's capacity, so the budget is raised.
    let settings = Settings {
        work_budget: 60_000_000,
        ..Settings::default()
    };
    let s = solve_pseudospectral(&problem, &settings).expect("accepted");
    assert!(
        usize::from(s.info.max_active) > MAX_ACTIVE,
        "the case must exceed the factor: {}",
        s.info.max_active
    );
    assert_ne!(s.info.status, SolveStatus::QpLimit);
    assert_eq!(s.info.status, SolveStatus::Solved, "{:?}", s.certificate);
    // Verified: control bound at every node, separation on the continuous trajectory.
    for sc in s.controls_fu.iter().take(8) {
        for u in sc.iter().take(25) {
            assert!(u.iter().all(|c| c.abs() <= 1.0 + 1e-9), "{u:?}");
        }
    }
    assert!(s.min_separation_lu.unwrap() >= 2.0 - 1e-7);
    assert!(s.certificate.stationarity <= 1e-6, "{:?}", s.certificate);
    // Per axis the optimum is the saturated law of eq. 24-26 (no keep-out is near): its cost is
    // the sum of 24 equal axes, each between the cubic's and Umax^2 T / 2.
    let cubic_axis = 6.0 * 20.0 * 20.0 / 1000.0; // 6 D^2 / T^3 per unit mass
    assert!(
        s.cost > 24.0 * cubic_axis && s.cost < 24.0 * 5.0,
        "{}",
        s.cost
    );
}
