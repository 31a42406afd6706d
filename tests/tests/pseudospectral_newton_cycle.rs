//! Planner A ends a loop of Newton points at its first return (`newton_cycle.rs`): a run whose
//! Newton answers repeat their costs takes plain steps from there, instead of paying one
//! rejected Newton point per loop until `MAX_NEWTON_REJECTIONS`.

use reconfig_core::pseudospectral::{Settings, SolveStatus};
use reconfig_host::families::sets::{self, Set};
use reconfig_tests::solve_pseudospectral;

/// Tuning #33, a collinear reversal: its Newton points loop with period 7 (one check entering
/// and leaving an active set of 8 rows) from about the 7th subproblem on. Paying the loops, the
/// on-board budget ran out after 84 subproblems at `BudgetExhausted { verified: true }`
/// (measured 29 Nov; `Solved` only with the budget lifted, after 131); ended at the first
/// return it is `Solved` on board after 94.
#[test]
fn a_loop_of_newton_points_is_left_at_its_first_return() {
    let (kind, problem) = sets::problem(Set::Tuning, 9, 33);
    assert_eq!(kind, "collinear-reversal");
    let s = solve_pseudospectral(&problem, &Settings::default()).expect("accepted");
    assert_eq!(s.info.status, SolveStatus::Solved, "{:?}", s.certificate);
    assert!((s.cost - 14.602_08).abs() < 2e-5, "{}", s.cost);
    assert!(s.min_separation_lu.unwrap() >= problem.keep_out_lu - 1e-7);
    assert!(
        s.info.sqp_iterations <= 100,
        "subproblems: {}",
        s.info.sqp_iterations
    );
}
