//! The work budget (`Settings::work_budget`, `reconfig_core::work`): a budget too small for a
//! solve stops it with `BudgetExhausted { verified }`, the answer returned is usable exactly
//! when it passed the planner's checks, the units used stay within the budget, and the stop is
//! deterministic (same input, same units, bit-identical answer).

use reconfig_core::{impulsive, pseudospectral};
use reconfig_tests::{impulsive_fixture, pseudospectral_fixture, solve_pseudospectral};

fn solve_impulsive(
    problem: &impulsive::Problem,
    settings: &impulsive::Settings,
) -> impulsive::Solution {
    let mut workspace = Box::new(impulsive::Workspace::new());
    let mut out = impulsive::Solution::new();
    impulsive::solve(problem, settings, &mut workspace, &mut out).expect("accepted");
    out
}

/// Planner A's usability, checked from the returned trajectory's own measures: continuous
/// separation at least d (within the verification tolerance) and no control above Umax.
fn a_is_feasible(problem: &pseudospectral::Problem, s: &pseudospectral::Solution) -> bool {
    let settings = pseudospectral::Settings::default();
    let nodes = usize::from(problem.degree) + 1;
    let controls_ok = s
        .controls_fu
        .iter()
        .take(problem.spacecraft.len())
        .flat_map(|sc| sc.iter().take(nodes))
        .flatten()
        .all(|u| u.abs() <= problem.max_control_fu * (1.0 + 1e-9));
    controls_ok && s.min_separation_lu.unwrap() >= problem.keep_out_lu - settings.verify_tol_lu
}

#[test]
fn planner_a_stops_at_its_budget_with_a_truthful_status() {
    let problem = pseudospectral_fixture("square-swap-4-sats-n16");
    let full = solve_pseudospectral(&problem, &pseudospectral::Settings::default()).unwrap();
    assert_eq!(full.info.status, pseudospectral::SolveStatus::Solved);
    let needed = full.info.work_units;
    assert!(needed > 0 && needed <= pseudospectral::Settings::default().work_budget);
    // No budget at all still pays the set-up and the check of the returned guess: the floor.
    let floor = solve_pseudospectral(
        &problem,
        &pseudospectral::Settings {
            work_budget: 0,
            ..pseudospectral::Settings::default()
        },
    )
    .unwrap()
    .info
    .work_units;
    assert!(floor > 0 && floor < needed / 2, "{floor} of {needed}");
    let mut usable = 0;
    let mut unusable = 0;
    let mut complete = 0;
    // Budgets from the floor to six times the units a full solve uses (a saddle escape's reserve
    // holds two answers' checks and certificates with every Lanczos step, so a full solve needs
    // more than it uses).
    for percent in (0u64..=100).step_by(4) {
        let settings = pseudospectral::Settings {
            work_budget: floor + (6 * needed - floor) * percent / 100,
            ..pseudospectral::Settings::default()
        };
        let cut = solve_pseudospectral(&problem, &settings).unwrap();
        let again = solve_pseudospectral(&problem, &settings).unwrap();
        let pseudospectral::SolveStatus::BudgetExhausted { verified } = cut.info.status else {
            // Not stopped: the meter changed nothing.
            assert_eq!(*cut, *full, "{percent} %");
            complete += 1;
            continue;
        };
        println!(
            "A {percent} %: verified {verified}, units {} of {}, J {}",
            cut.info.work_units, settings.work_budget, cut.cost
        );
        assert_eq!(cut.info.status.is_usable(), verified);
        assert!(!cut.info.status.is_certified());
        assert_eq!(verified, a_is_feasible(&problem, &cut), "{percent} %");
        assert!(
            cut.info.work_units <= settings.work_budget,
            "{percent} %: {} units over a budget of {}",
            cut.info.work_units,
            settings.work_budget
        );
        // Deterministic: the same units and the same bits.
        assert_eq!(cut.info.work_units, again.info.work_units);
        assert_eq!(
            postcard::to_allocvec(&*cut).unwrap(),
            postcard::to_allocvec(&*again).unwrap()
        );
        if verified {
            usable += 1;
            // A verified answer costs at least the optimum.
            assert!(cut.cost >= full.cost - 1e-9 * full.cost, "{percent} %");
        } else {
            unusable += 1;
        }
    }
    // The smallest budget stops before any QP solution; larger ones return a verified one.
    assert!(
        unusable >= 1 && usable >= 1 && complete >= 1,
        "{unusable} / {usable} / {complete}"
    );
}

#[test]
fn planner_b_search_stops_at_its_budget_and_still_returns_a_verified_plan() {
    let problem = impulsive_fixture("wang2018-gco-to-pco-search-3imp");
    // The whole search needs more than the default budget (it stops there, verified: issue 33),
    // so the full run has the budget lifted.
    let defaults = impulsive::Settings {
        work_budget: 100_000_000,
        ..impulsive::Settings::default()
    };
    let full = solve_impulsive(&problem, &defaults);
    assert_eq!(full.info.status, impulsive::SolveStatus::Solved);
    let needed = full.info.work_units;
    assert!(needed > impulsive::DEFAULT_WORK_BUDGET && needed <= defaults.work_budget);
    for percent in [30u64, 60, 90] {
        let settings = impulsive::Settings {
            work_budget: needed * percent / 100,
            ..defaults
        };
        let cut = solve_impulsive(&problem, &settings);
        let again = solve_impulsive(&problem, &settings);
        println!(
            "B {percent} %: {:?}, units {} of {}, evaluations {}, total {} m/s",
            cut.info.status,
            cut.info.work_units,
            settings.work_budget,
            cut.info.evaluations,
            cut.total_dv_mps
        );
        // The search stops early; the final solve at its best points has the budget kept for
        // it, and its plan reaches the target.
        assert_eq!(
            cut.info.status,
            impulsive::SolveStatus::BudgetExhausted { verified: true },
            "{percent} %"
        );
        assert!(cut.info.status.is_usable());
        assert!(
            cut.terminal_error
                .expect("nonlinear check flown")
                .position_m
                .abs()
                < 1e-3,
            "{percent} %"
        );
        assert!(cut.info.work_units <= settings.work_budget);
        assert!(cut.total_dv_mps >= full.total_dv_mps - 1e-6, "{percent} %");
        assert_eq!(cut.info.work_units, again.info.work_units);
        assert_eq!(
            postcard::to_allocvec(&cut).unwrap(),
            postcard::to_allocvec(&again).unwrap()
        );
    }
}

#[test]
fn planner_b_fixed_point_cut_short_is_not_usable() {
    let problem = impulsive_fixture("wang2018-gco-to-pco-3imp");
    let defaults = impulsive::Settings::default();
    let full = solve_impulsive(&problem, &defaults);
    assert_eq!(full.info.status, impulsive::SolveStatus::Solved);
    // No budget at all still pays the checks of the returned plan: the floor.
    let floor = solve_impulsive(
        &problem,
        &impulsive::Settings {
            work_budget: 0,
            ..defaults
        },
    )
    .info
    .work_units;
    assert!(floor > 0 && floor < full.info.work_units / 2);
    // Room for the checks and a tenth of the rest: a few fixed-point iterations, no correction.
    let settings = impulsive::Settings {
        work_budget: floor + (full.info.work_units - floor) / 10,
        ..defaults
    };
    let cut = solve_impulsive(&problem, &settings);
    println!(
        "B fixed point: {:?}, units {} of {}, miss {} m",
        cut.info.status,
        cut.info.work_units,
        settings.work_budget,
        cut.terminal_error
            .expect("nonlinear check flown")
            .position_m
    );
    assert_eq!(
        cut.info.status,
        impulsive::SolveStatus::BudgetExhausted { verified: false }
    );
    assert!(!cut.info.status.is_usable());
    // Not usable because it is not there: the linear plan misses the target by metres.
    assert!(
        cut.terminal_error
            .expect("nonlinear check flown")
            .position_m
            .abs()
            > 1.0
    );
    assert!(cut.info.work_units <= settings.work_budget);
    assert_eq!(solve_impulsive(&problem, &settings), cut);
}

/// The kernel images run each planner's worst-case request whole at the default budget (their
/// `solve-cap-default` and `solve-search-n6-default` cases), so its M7 instructions are
/// measured in CI: the cases' problems are the worst-case fixtures' (planner A's to the
/// fixture's six printed decimals, planner B's exactly).
#[test]
fn the_kernel_images_solve_the_worst_case_requests() {
    use reconfig_core::impulsive::kernels as kb;
    use reconfig_core::pseudospectral::kernels as ka;
    let index_a = ka::CASES
        .iter()
        .position(|c| c.name == "solve-cap-default")
        .expect("planner A's whole worst-case solve");
    let case_a = ka::case_problem(index_a).expect("a whole-solve case");
    let fixture_a = pseudospectral_fixture("worst-case/crossing-8-sats-n24");
    assert_eq!(
        (case_a.degree, case_a.test_points, case_a.spacecraft.len()),
        (
            fixture_a.degree,
            fixture_a.test_points,
            fixture_a.spacecraft.len()
        )
    );
    let scalars = |p: &pseudospectral::Problem| [p.horizon_tu, p.max_control_fu, p.keep_out_lu];
    assert_eq!(scalars(&case_a), scalars(&fixture_a));
    for (a, b) in case_a.spacecraft.iter().zip(&fixture_a.spacecraft) {
        assert_eq!(a.mass_mu, b.mass_mu);
        for (x, y) in a
            .initial_state
            .iter()
            .chain(&a.final_state)
            .zip(b.initial_state.iter().chain(&b.final_state))
        {
            assert!((x - y).abs() <= 5e-7, "{x} vs {y}");
        }
    }
    let index_b = kb::CASES
        .iter()
        .position(|c| c.name == "solve-search-n6-default")
        .expect("planner B's whole worst-case solve");
    let case_b = kb::case_problem(index_b).expect("a whole-solve case");
    assert_eq!(case_b, impulsive_fixture("worst-case/wang2018-search-6imp"));
    assert_eq!(ka::case_problem(0), None);
    // The LEO arc's: the single-arc fixture's request, searched in the planning model (the
    // dearest search) at the default budget, which it spends: the search all but the final
    // check's reserve (eight aim-point iterations of the arc's length, 6 %), the check some
    // of that.
    use reconfig_core::leo_tour::kernels as kl;
    let index_l = kl::CASES
        .iter()
        .position(|c| c.name == "solve-planning-model-default")
        .expect("the LEO arc's whole solve at the default budget");
    let case_l = kl::case_problem(index_l).expect("a whole-solve case");
    let fixture = reconfig_host::fixture::leo_tour::load(
        &reconfig_tests::fixtures_dir().join("leo-tour-example1-single-arc.toml"),
    )
    .expect("the single-arc fixture");
    let requests = fixture.requests().expect("its request");
    let [request] = requests.as_slice() else {
        panic!("one arc request");
    };
    let reconfig_core::wire::Request::LeoArc { problem, .. } = request.request else {
        panic!("an arc request");
    };
    assert_eq!(
        (case_l.duration_s, case_l.impulses),
        (problem.duration_s, problem.impulses)
    );
    for (x, y) in case_l
        .from
        .iter()
        .chain(&case_l.to)
        .zip(problem.from.iter().chain(&problem.to))
    {
        assert!((x - y).abs() <= 1e-9 * (1.0 + y.abs()), "{x} vs {y}");
    }
    let settings = reconfig_core::leo_tour::Settings {
        search_model: reconfig_core::leo_tour::flight::Model::Planning,
        ..Default::default()
    };
    let mut ws = Box::new(reconfig_core::leo_tour::Workspace::new());
    let mut out = reconfig_core::leo_tour::ArcSolution::new();
    reconfig_core::leo_tour::solve_arc(&case_l, &settings, &mut ws, &mut out).expect("planned");
    let budget = settings.work_budget;
    assert!(
        out.info.work_units * 100 >= budget * 90 && out.info.work_units <= budget,
        "the case spends the default budget: {} of {budget} units",
        out.info.work_units
    );
}
