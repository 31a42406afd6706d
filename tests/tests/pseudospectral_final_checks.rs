//! Planner A's final checks and their reserve (`solver::finish`, `work_units::reserve`): an
//! answer that fails its checks, or whose QP state is not its own (the kept answer), takes no
//! certificate, so the first run keeps one certificate in reserve, not two; a saddle escape or
//! a flat probe keeps two. The units a solve uses stay within its budget at every budget.

use reconfig_core::pseudospectral::{Settings, SolveStatus};
use reconfig_host::families::sets::{self, Set};
use reconfig_tests::solve_pseudospectral;

/// Tuning #202, seven spacecraft swapping through the centre of a cube: `Solved` on board
/// (37.77 M units); with two certificates in the first run's reserve it stopped at
/// `BudgetExhausted { verified: true }` after 38.72 M units, J the same to 1e-6 (measured 29
/// Nov).
#[test]
fn the_first_run_keeps_one_certificate_in_reserve() {
    let (kind, problem) = sets::problem(Set::Tuning, 9, 202);
    assert_eq!(kind, "antipodal-cube");
    let settings = Settings::default();
    let s = solve_pseudospectral(&problem, &settings).expect("accepted");
    assert_eq!(s.info.status, SolveStatus::Solved, "{:?}", s.certificate);
    assert!(s.certificate.certifies_local_optimum());
    assert!((s.cost - 12.247_935).abs() < 1e-5, "{}", s.cost);
    assert!(s.min_separation_lu.unwrap() >= problem.keep_out_lu - settings.verify_tol_lu);
    assert!(s.info.work_units <= settings.work_budget);
}

/// The same problem at budgets from a tenth of the default to the default: every solve stays
/// within its budget; a cut solve is never certified, and its certificate is taken only where
/// its answer passed its checks (`verified`).
#[test]
fn every_budget_holds_with_the_final_checks_inside_it() {
    let (_, problem) = sets::problem(Set::Tuning, 9, 202);
    let default = Settings::default().work_budget;
    let mut verified_cuts = 0;
    for tenth in 1..=10u64 {
        let settings = Settings {
            work_budget: default * tenth / 10,
            ..Settings::default()
        };
        let s = solve_pseudospectral(&problem, &settings).expect("accepted");
        println!(
            "{tenth}/10: {:?}, {} units, J {}",
            s.info.status, s.info.work_units, s.cost
        );
        assert!(
            s.info.work_units <= settings.work_budget,
            "{tenth}/10: {} units over {}",
            s.info.work_units,
            settings.work_budget
        );
        if let SolveStatus::BudgetExhausted { verified } = s.info.status {
            assert!(!s.info.status.is_certified(), "{tenth}/10");
            if !verified {
                assert!(!s.certificate.first_order_evaluated, "{tenth}/10");
                assert_eq!(s.certificate.stationarity, 0.0, "{tenth}/10");
            } else {
                verified_cuts += 1;
                assert!(
                    s.min_separation_lu.unwrap() >= problem.keep_out_lu - settings.verify_tol_lu
                );
            }
        }
    }
    assert!(verified_cuts >= 1);
}
