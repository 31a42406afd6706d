//! Zero heap allocations during a planner-B solve (fixed points, min fuel, correction, search),
//! counted by a global allocator. Its own test binary, so no other test allocates meanwhile.

use reconfig_core::impulsive::{solve, ImpulsePlan, Settings, Solution, SolveStatus, Workspace};
use reconfig_tests::alloc_count::{count, CountingAllocator};

#[global_allocator]
static GLOBAL: CountingAllocator = CountingAllocator;

#[test]
fn solve_does_not_allocate() {
    // Wang 2018 Table 2's impulse points.
    let mut problem = reconfig_tests::impulsive_fixture("wang2018-gco-to-pco-3imp");
    assert!(matches!(&problem.plan, ImpulsePlan::Fixed(points) if points.len() == 3));
    let settings = Settings::default();
    let small_search = Settings {
        search_samples: 200,
        search_starts: 4,
        search_max_evaluations: 1000,
        ..settings
    };
    let mut ws = Box::new(Workspace::new());
    let mut out = Box::new(Solution::new());

    let (fixed_result, allocations) = count(|| solve(&problem, &settings, &mut ws, &mut out));
    assert_eq!(allocations, 0, "fixed-point solve allocated");
    assert!(fixed_result.is_ok());
    assert_eq!(out.info.status, SolveStatus::Solved);

    problem.plan = ImpulsePlan::Search {
        impulses: 3,
        max_revolutions: 14,
    };
    let (search_result, allocations) = count(|| solve(&problem, &small_search, &mut ws, &mut out));
    assert_eq!(allocations, 0, "search allocated");
    assert!(search_result.is_ok());
    assert!(out.info.evaluations > 100);

    // A rejected request does not allocate either.
    problem.chief.ecc = f64::NAN;
    let (rejected, allocations) = count(|| solve(&problem, &settings, &mut ws, &mut out));
    assert_eq!(allocations, 0, "rejected solve allocated");
    assert!(rejected.is_err());
}
