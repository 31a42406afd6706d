//! Planner B over the paper's fixtures: minimum-norm totals against the independent numpy
//! oracle (fixtures/golden/wang2018-min-norm.json) and the issue's figures, min-fuel and
//! nonlinear correction, the search against the paper's Table 3 bests, determinism.

use reconfig_core::impulsive::{
    solve, ElementSet, Problem, Settings, Solution, SolveStatus, Workspace,
};
use reconfig_host::fixture::{impulsive::ImpulsiveFixture, load_as};
use reconfig_tests::fixtures_dir;

fn problem(name: &str) -> Problem {
    load_as::<ImpulsiveFixture>(&fixtures_dir().join(format!("{name}.toml")))
        .unwrap()
        .problem
}

fn run(problem: &Problem, settings: &Settings) -> Solution {
    let mut ws = Workspace::new();
    let mut out = Solution::new();
    solve(problem, settings, &mut ws, &mut out).unwrap();
    out
}

fn golden() -> serde_json::Value {
    let text =
        std::fs::read_to_string(fixtures_dir().join("golden/wang2018-min-norm.json")).unwrap();
    serde_json::from_str(&text).unwrap()
}

/// The paper-reproduction mode: the minimum-norm fixed point in the paper's classical elements.
fn min_norm_only() -> Settings {
    Settings {
        min_fuel: false,
        nonlinear_correction: false,
        ..Settings::paper_classical()
    }
}

/// The issue's figures: 8.2207 / 8.2367 / 8.2174 m/s within 0.001.
const PAPER_POINTS: [(&str, f64); 3] = [
    ("wang2018-gco-to-pco-3imp", 8.2207),
    ("wang2018-gco-to-pco-2imp", 8.2367),
    ("wang2018-gco-to-pco-4imp", 8.2174),
];

/// The paper's tables of the three points and their printed totals, m/s.
const PAPER_TABLES: [(&str, f64); 3] = [
    ("Table 2, 3 imp", 8.220),
    ("Table 4, 2 imp", 8.240),
    ("Table 5, 4 imp", 8.219),
];

/// The linear plan's miss when flown with exact impulses (docs/planner-b.md), m.
const PAPER_MISS_M: [f64; 3] = [152.5, 56.9, 117.0];

#[test]
fn minimum_norm_matches_the_oracle_and_the_issue() {
    let g = golden();
    let mut totals = Vec::new();
    let mut table = String::from(
        "| case | minimum norm (ours) | oracle | issue | paper | min fuel (linear) | corrected, returned | linear-model miss |\n\
         | --- | --- | --- | --- | --- | --- | --- | --- |\n",
    );
    for (((name, issue_total), miss), (label, paper)) in
        PAPER_POINTS.into_iter().zip(PAPER_MISS_M).zip(PAPER_TABLES)
    {
        let p = problem(name);
        let s = run(&p, &min_norm_only());
        totals.push((issue_total, s.total_dv_mps));
        // The paper's own pipeline in full (classical elements, least fuel, correction).
        let full = run(&p, &Settings::paper_classical());
        let linear = full.linear_total_dv_mps.expect("finite");
        table.push_str(&format!(
            "| {label} | {:.5} | {:.7} | {issue_total:.4} | {paper:.3} | {linear:.5}{} | {:.5} | {:.0} m |\n",
            s.total_dv_mps,
            g[name]["min_norm_total_dv_mps"].as_f64().unwrap(),
            if s.impulses.len() * 3 == 6 { " (square)" } else { "" },
            full.total_dv_mps,
            s.terminal_error.expect("nonlinear check flown").position_m,
        ));
        // The linear model's fixed point is not a flyable plan: `Linearised` with its miss.
        match s.info.status {
            SolveStatus::Linearised { miss_m } => {
                assert_eq!(
                    miss_m,
                    s.terminal_error.expect("nonlinear check flown").position_m,
                    "{name}"
                );
                assert!((miss_m - miss).abs() < 1.0, "{name}: miss {miss_m} m");
            }
            other => panic!("{name}: {other:?}"),
        }
        assert!(!s.info.status.is_usable());
        assert!(
            (s.total_dv_mps - issue_total).abs() < 1e-3,
            "{name}: {}",
            s.total_dv_mps
        );
        assert!(
            s.info.iterations <= 10,
            "{name}: {} iterations",
            s.info.iterations
        );
        assert_eq!(s.info.rank, 6);
        let cond = s.info.condition_number.expect("full rank");
        assert!(cond > 1e3 && cond < 1e6);
        assert!(!s.info.min_fuel_used && !s.info.correction_used);
        let o = &g[name];
        let oracle_total = o["min_norm_total_dv_mps"].as_f64().unwrap();
        assert!(
            (s.total_dv_mps - oracle_total).abs() < 1e-6,
            "{name}: {} vs oracle {oracle_total}",
            s.total_dv_mps
        );
        assert_eq!(s.total_dv_mps, s.min_norm_total_dv_mps.expect("finite"));
        for (k, imp) in s.impulses.iter().enumerate() {
            let t = o["times_s"][k].as_f64().unwrap();
            assert!(
                (imp.time_s - t).abs() < 1e-3,
                "{name} impulse {k}: t {} vs {t}",
                imp.time_s
            );
            for axis in 0..3 {
                let v = o["dv_rtn_mps"][k][axis].as_f64().unwrap();
                assert!(
                    (imp.dv_rtn_mps[axis] - v).abs() < 1e-5,
                    "{name} impulse {k} axis {axis}: {} vs {v}",
                    imp.dv_rtn_mps[axis]
                );
            }
        }
    }
    reconfig_tests::doc_blocks::hold(
        "docs/planner-b.md",
        "planner-b-min-norm",
        "impulsive_fixtures",
        &table,
    )
    .unwrap();
    reconfig_host::figure_record::hold(
        "b-min-norm",
        &reconfig_host::figure_record::Figure {
            what: "B: minimum-norm totals, paper's points".into(),
            target: format!(
                "{} ± 0.001 m/s",
                totals
                    .iter()
                    .map(|(issue, _)| format!("{issue:.4}"))
                    .collect::<Vec<_>>()
                    .join(" / ")
            ),
            measured: totals
                .iter()
                .map(|(_, ours)| format!("{ours:.5}"))
                .collect::<Vec<_>>()
                .join(" / "),
            met: totals
                .iter()
                .all(|(issue, ours)| (ours - issue).abs() < 1e-3),
            doc: "planner-b".into(),
            command: "cargo test -p reconfig-tests --test impulsive_fixtures".into(),
        },
    )
    .unwrap();
}

#[test]
fn paper_times_are_reproduced() {
    // Table 2 and Table 4 (second time printed as an interval: 89376.765 + 5199.311).
    let cases: [(&str, &[f64]); 3] = [
        (
            "wang2018-gco-to-pco-3imp",
            &[16718.356, 82723.319, 95614.302],
        ),
        ("wang2018-gco-to-pco-2imp", &[89376.765, 94576.076]),
        (
            "wang2018-gco-to-pco-4imp",
            &[16592.786, 41054.099, 76629.552, 89593.915],
        ),
    ];
    for (name, times) in cases {
        let s = run(&problem(name), &min_norm_only());
        for (imp, t) in s.impulses.iter().zip(times.iter()) {
            assert!(
                (imp.time_s - t).abs() < 1.0,
                "{name}: {} vs {t}",
                imp.time_s
            );
        }
    }
    // Reading Table 5's true-latitude column as mean latitude moves the impulses by ~129 s.
    let s = run(
        &problem("wang2018-gco-to-pco-4imp-printed-u"),
        &min_norm_only(),
    );
    let shift = 16592.786 - s.impulses[0].time_s;
    assert!((100.0..160.0).contains(&shift), "{shift}");
}

#[test]
fn min_fuel_is_never_worse_and_the_correction_closes_the_nonlinear_error() {
    for (name, _) in PAPER_POINTS {
        let p = problem(name);
        let plain = run(&p, &Settings::fixed_point_only());
        let s = run(&p, &Settings::default());
        assert_eq!(s.info.status, SolveStatus::Solved, "{name}");
        assert!(
            s.min_norm_total_dv_mps.expect("finite") == plain.total_dv_mps,
            "{name}"
        );
        assert!(
            s.linear_total_dv_mps.expect("finite")
                <= s.min_norm_total_dv_mps.expect("finite") + 1e-12,
            "{name}"
        );
        assert!(s.info.correction_used);
        let e = &s.terminal_error.expect("nonlinear check flown").elements;
        for v in [
            e.decc,
            e.dinc_rad,
            e.draan_rad,
            e.dargp_rad,
            e.dmean_anomaly_rad,
            e.dsma_km / 7178.137,
        ] {
            assert!(v.abs() <= 1e-12, "{name}: {e:?}");
        }
        assert!(
            s.terminal_error
                .expect("nonlinear check flown")
                .along_track_m
                .abs()
                < 1e-3
                && s.terminal_error.expect("nonlinear check flown").position_m < 1e-3,
            "{name}"
        );
        // Without the correction the linear model misses the nonlinear target by metres.
        assert!(
            plain
                .terminal_error
                .expect("nonlinear check flown")
                .position_m
                > 1.0,
            "{name}: {}",
            plain
                .terminal_error
                .expect("nonlinear check flown")
                .position_m
        );
    }
    // Three and four impulses leave a null space: min fuel is strictly lower there.
    let s = run(&problem("wang2018-gco-to-pco-3imp"), &Settings::default());
    assert!(
        s.info.min_fuel_used
            && s.linear_total_dv_mps.expect("finite")
                < s.min_norm_total_dv_mps.expect("finite") - 1e-3
    );
}

/// Corrected least-fuel totals at the printed points before the nonsingular core (classical
/// elements; docs/planner-b.md), m/s.
const CORRECTED_TOTALS_MPS: [f64; 3] = [8.216_298_706, 8.236_121_815, 8.214_725_280];

#[test]
fn corrected_plans_do_not_depend_on_the_element_set() {
    // The linearised fixed point depends on the coordinates at second order (about 2e-3 m/s
    // here); the plans corrected to the exact end condition do not (within 1e-5 m/s).
    for ((name, _), before) in PAPER_POINTS.into_iter().zip(CORRECTED_TOTALS_MPS) {
        let p = problem(name);
        let eq = run(&p, &Settings::default());
        let cl = run(&p, &Settings::paper_classical());
        for s in [&eq, &cl] {
            assert_eq!(s.info.status, SolveStatus::Solved, "{name}");
            assert!(
                (s.total_dv_mps - before).abs() < 1e-5,
                "{name}: {} vs {before}",
                s.total_dv_mps
            );
        }
        assert!((eq.total_dv_mps - cl.total_dv_mps).abs() < 1e-5, "{name}");
        let shift =
            eq.min_norm_total_dv_mps.expect("finite") - cl.min_norm_total_dv_mps.expect("finite");
        assert!(shift.abs() > 1e-5 && shift.abs() < 1e-2, "{name}: {shift}");
        println!(
            "{name}: corrected {:.9} (equinoctial) {:.9} (classical); min-norm shift {shift:+.2e} m/s",
            eq.total_dv_mps, cl.total_dv_mps
        );
    }
}

#[test]
fn search_reaches_the_paper_bests_deterministically() {
    let bests = [(2, 8.23922), (3, 8.21364), (4, 8.16153)];
    // The best known least-fuel plans (issue 10): the search must come within 0.1 %.
    let least_fuel = [(2, 8.23660), (3, 8.16873), (4, 8.14159)];
    let settings = Settings::default();
    let mut excess = Vec::new();
    let mut table = String::from(
        "| impulses | status | returned total | linear least fuel | best known least fuel (issue 10) | above it | linear min-norm at those points | evaluations |\n\
         | --- | --- | --- | --- | --- | --- | --- | --- |\n",
    );
    for (n, best) in bests {
        let p = problem(&format!("wang2018-gco-to-pco-search-{n}imp"));
        let a = run(&p, &settings);
        // The 3- and 4-impulse searches stop at the default budget (issue 33: the units hold
        // every step to 21 M7 instructions), their plans verified (usable) and still within
        // 0.1 % of the best known; with the budget lifted they finish Solved.
        let status = a.info.status;
        assert!(
            status == SolveStatus::Solved
                || (n > 2 && status == SolveStatus::BudgetExhausted { verified: true }),
            "{n}: {status:?}"
        );
        assert!(status.is_usable());
        if n > 2 {
            let lifted = Settings {
                work_budget: 100_000_000,
                ..settings
            };
            assert_eq!(run(&p, &lifted).info.status, SolveStatus::Solved, "{n}");
        }
        assert_eq!(a.impulses.len(), n);
        assert!(
            a.total_dv_mps <= best,
            "{n} impulses: {} > {best}",
            a.total_dv_mps
        );
        assert!(a.info.evaluations <= settings.search_max_evaluations + 1);
        let known = least_fuel.iter().find(|(m, _)| *m == n).unwrap().1;
        excess.push(100.0 * (a.total_dv_mps / known - 1.0));
        table.push_str(&format!(
            "| {n} | `{:?}` | {:.5} | {:.5} | {known:.5} | {:+.3} % | {:.5} | {} |\n",
            a.info.status,
            a.total_dv_mps,
            a.linear_total_dv_mps.expect("finite"),
            100.0 * (a.total_dv_mps / known - 1.0),
            a.min_norm_total_dv_mps.expect("finite"),
            a.info.evaluations,
        ));
        assert!(
            a.total_dv_mps <= known * 1.001,
            "{n} impulses: {} more than 0.1 % above {known}",
            a.total_dv_mps
        );
        let revs: i32 = a.impulses.iter().map(|i| i.revolutions).sum();
        assert!((0..=14).contains(&revs));
        let b = run(&p, &settings);
        assert_eq!(a, b);
        assert_eq!(
            postcard::to_allocvec(&a).unwrap(),
            postcard::to_allocvec(&b).unwrap()
        );
    }
    reconfig_tests::doc_blocks::hold(
        "docs/planner-b.md",
        "planner-b-search",
        "impulsive_fixtures",
        &table,
    )
    .unwrap();
    let list = |v: Vec<String>| v.join(" / ");
    reconfig_host::figure_record::hold(
        "b-least-fuel-search",
        &reconfig_host::figure_record::Figure {
            what: "B: least-fuel search at the on-board budget, 2 / 3 / 4 impulses".into(),
            target: format!(
                "within 0.1 % of {}",
                list(least_fuel.iter().map(|(_, k)| format!("{k:.5}")).collect())
            ),
            measured: list(excess.iter().map(|e| format!("{e:+.3} %")).collect()),
            met: excess.iter().all(|e| *e <= 0.1),
            doc: "planner-b".into(),
            command: "cargo test -p reconfig-tests --test impulsive_fixtures".into(),
        },
    )
    .unwrap();
}

#[test]
fn fixed_solve_is_bit_identical_and_workspace_reuse_is_clean() {
    let p = problem("wang2018-gco-to-pco-4imp");
    let settings = Settings::default();
    let mut ws = Workspace::new();
    let mut first = Solution::new();
    solve(&p, &settings, &mut ws, &mut first).unwrap();
    // A different problem through the same workspace, then the first again.
    let mut other = Solution::new();
    solve(
        &problem("wang2018-gco-to-pco-2imp"),
        &settings,
        &mut ws,
        &mut other,
    )
    .unwrap();
    let mut again = Solution::new();
    solve(&p, &settings, &mut ws, &mut again).unwrap();
    assert_eq!(first, again);
    let bits = |s: &Solution| {
        s.impulses
            .iter()
            .flat_map(|i| i.dv_rtn_mps.map(f64::to_bits))
            .collect::<Vec<_>>()
    };
    assert_eq!(bits(&first), bits(&again));
    assert_eq!(first.total_dv_mps.to_bits(), again.total_dv_mps.to_bits());
}

#[test]
fn buffers_are_small_and_fixed() {
    let ws = std::mem::size_of::<Workspace>();
    let sol = std::mem::size_of::<Solution>();
    println!("Workspace {ws} B, Solution {sol} B");
    assert!(ws < 8 * 1024, "{ws}");
    assert!(sol < 1024, "{sol}");
}

#[test]
fn six_impulses_at_capacity() {
    use reconfig_core::impulsive::{ImpulsePlan, ImpulsePoint};
    let mut p = problem("wang2018-gco-to-pco-3imp");
    let pts = [
        (270.0, 1),
        (90.0, 2),
        (250.0, 3),
        (60.0, 2),
        (280.0, 3),
        (100.0, 1),
    ];
    p.plan = ImpulsePlan::Fixed(
        pts.iter()
            .map(|(u, n): &(f64, i32)| ImpulsePoint {
                arg_latitude_rad: u.to_radians(),
                revolutions: *n,
            })
            .collect(),
    );
    let s = run(&p, &Settings::default());
    assert_eq!(s.info.status, SolveStatus::Solved);
    assert_eq!(s.impulses.len(), 6);
    assert_eq!(s.info.rank, 6);
    assert!(
        s.linear_total_dv_mps.expect("finite") <= s.min_norm_total_dv_mps.expect("finite") + 1e-12
    );
    assert!(s.terminal_error.expect("nonlinear check flown").position_m < 1e-3);
    // Times increase and revolutions are carried through.
    for w in s.impulses.windows(2) {
        assert!(w[1].time_s > w[0].time_s);
    }
    assert_eq!(s.impulses[5].revolutions, 1);
}

#[test]
fn search_respects_a_small_budget() {
    let p = problem("wang2018-gco-to-pco-search-3imp");
    let settings = Settings {
        search_samples: 50,
        search_starts: 3,
        search_max_evaluations: 300,
        ..Settings::default()
    };
    let s = run(&p, &settings);
    assert!(
        s.info.evaluations <= 301 && s.info.evaluations >= 51,
        "{}",
        s.info.evaluations
    );
    assert_eq!(s.info.status, SolveStatus::Solved);
    assert!(s.total_dv_mps.is_finite() && s.total_dv_mps < 20.0);
}

#[test]
fn the_correction_converges_in_a_few_broyden_steps() {
    // The paper's points: 2 steps. A near-circular chief (e = 1e-3, where the linear-F defect
    // correction needed 10-11 steps): at most 5.
    for (name, _) in PAPER_POINTS {
        for (ecc, most) in [(None, 2), (Some(1e-3), 5)] {
            let mut p = problem(name);
            if let Some(e) = ecc {
                p.chief.ecc = e;
            }
            let s = run(&p, &Settings::default());
            assert_eq!(s.info.status, SolveStatus::Solved, "{name} {ecc:?}");
            assert!(
                s.info.correction_iterations <= most,
                "{name} {ecc:?}: {} steps",
                s.info.correction_iterations
            );
            assert!(
                s.terminal_error.expect("nonlinear check flown").position_m < 1e-3,
                "{name} {ecc:?}"
            );
        }
    }
}

/// Solve `name` with the default settings and check it against the oracle plan `oracle`: Solved,
/// nonlinear miss <= 1 mm, total and every impulse component within `tol` m/s, and (when
/// `check_times`) every impulse time within 1e-5 s. Returns the solution.
fn check_against_oracle(
    name: &str,
    oracle: &serde_json::Value,
    tol: f64,
    check_times: bool,
    settings: &Settings,
) -> Solution {
    let s = run(&problem(name), settings);
    assert_eq!(s.info.status, SolveStatus::Solved, "{name}");
    assert!(
        s.terminal_error.expect("nonlinear check flown").position_m <= 1e-3,
        "{name}"
    );
    let total = oracle["total_dv_mps"].as_f64().unwrap();
    assert!(
        (s.total_dv_mps - total).abs() < tol,
        "{name}: {} vs oracle {total}",
        s.total_dv_mps
    );
    for (k, imp) in s.impulses.iter().enumerate() {
        if check_times {
            let t = oracle["times_s"][k].as_f64().unwrap();
            assert!((imp.time_s - t).abs() < 1e-5, "{name} {k}: {}", imp.time_s);
        }
        for axis in 0..3 {
            let v = oracle["dv_rtn_mps"][k][axis].as_f64().unwrap();
            assert!(
                (imp.dv_rtn_mps[axis] - v).abs() < tol,
                "{name} impulse {k} axis {axis}: {} vs {v}",
                imp.dv_rtn_mps[axis]
            );
        }
    }
    s
}

/// One row of the oracle tables of `docs/planner-b.md`: the fixture and its label, our total,
/// the oracle's, the Broyden steps, the nonlinear miss and the status.
fn oracle_row(label: &str, s: &Solution, oracle: &serde_json::Value, status: bool) -> String {
    let miss = s.terminal_error.expect("nonlinear check flown").position_m;
    let mut row = format!(
        "| {label} | {:.10} | {:.10} | {} | {miss:.1e} m |",
        s.total_dv_mps,
        oracle["total_dv_mps"].as_f64().unwrap(),
        s.info.correction_iterations
    );
    if status {
        row.push_str(&format!(" {:?} |", s.info.status));
    }
    row.push('\n');
    row
}

#[test]
fn corrected_two_impulse_plans_match_the_exact_model_oracle() {
    // Two impulses: the corrected plan is the unique root of the exact end condition, computed
    // independently by tests/oracle/planner_b_corrected.py (numpy Newton).
    let text =
        std::fs::read_to_string(fixtures_dir().join("golden/planner-b-corrected.json")).unwrap();
    let g: serde_json::Value = serde_json::from_str(&text).unwrap();
    for name in ["sso-leo-pair-e1e-3-2imp", "wang2018-gco-to-pco-2imp"] {
        check_against_oracle(name, &g[name], 1e-8, true, &Settings::default());
    }
    // The docs' table: the classical set, as the oracle writes its plans.
    let classical = Settings {
        element_set: ElementSet::Classical,
        ..Settings::default()
    };
    let mut table = String::from(
        "| fixture | ours (default settings, classical elements) | oracle | Broyden steps | nonlinear miss |\n\
         | --- | --- | --- | --- | --- |\n",
    );
    for (name, label) in [
        (
            "sso-leo-pair-e1e-3-2imp",
            "`sso-leo-pair-e1e-3-2imp` (a = 7078.137 km, e = 1e-3, i = 98.2°)",
        ),
        ("wang2018-gco-to-pco-2imp", "`wang2018-gco-to-pco-2imp`"),
    ] {
        let s = check_against_oracle(name, &g[name], 1e-8, true, &classical);
        table.push_str(&oracle_row(label, &s, &g[name], false));
    }
    reconfig_tests::doc_blocks::hold(
        "docs/planner-b.md",
        "planner-b-corrected-oracle",
        "impulsive_fixtures",
        &table,
    )
    .unwrap();
}

#[test]
fn circular_and_equatorial_fixtures_match_the_equinoctial_oracle() {
    // Circular (e = 0) and circular equatorial (GEO, e = 0, i = 0) chiefs, which the classical
    // elements refuse: Solved by the default (equinoctial) core with a nonlinear miss <= 1 mm,
    // and equal to the root of the exact end condition computed independently in equinoctial
    // elements by tests/oracle/planner_b_nonsingular.py (which also reproduces the classical
    // oracle's plans for the e = 1e-3 and the paper's fixtures).
    let text =
        std::fs::read_to_string(fixtures_dir().join("golden/planner-b-nonsingular.json")).unwrap();
    let g: serde_json::Value = serde_json::from_str(&text).unwrap();
    let mut table = String::from(
        "| fixture | ours (default settings) | oracle | Broyden steps | nonlinear miss | status |\n\
         | --- | --- | --- | --- | --- | --- |\n",
    );
    for (name, label) in [
        (
            "sso-leo-pair-e0-2imp",
            "`sso-leo-pair-e0-2imp` (a = 7078.137 km, e = 0, i = 98.2°)",
        ),
        (
            "geo-colocation-e0-i0-2imp",
            "`geo-colocation-e0-i0-2imp` (a = 42164.17 km, e = 0, i = 0; e/i vectors turned 90°)",
        ),
        (
            "sso-leo-pair-e1e-3-2imp",
            "`sso-leo-pair-e1e-3-2imp` (equinoctial default)",
        ),
        (
            "wang2018-gco-to-pco-2imp",
            "`wang2018-gco-to-pco-2imp` (equinoctial default)",
        ),
    ] {
        let s = check_against_oracle(name, &g[name], 1e-8, true, &Settings::default());
        table.push_str(&oracle_row(label, &s, &g[name], true));
        let total = g[name]["total_dv_mps"].as_f64().unwrap();
        println!(
            "{name}: {:.10} m/s (oracle {total:.10}), miss {:.2e} m, {} correction steps",
            s.total_dv_mps,
            s.terminal_error.expect("nonlinear check flown").position_m,
            s.info.correction_iterations
        );
    }
    reconfig_tests::doc_blocks::hold(
        "docs/planner-b.md",
        "planner-b-nonsingular-oracle",
        "impulsive_fixtures",
        &table,
    )
    .unwrap();
}

#[test]
fn input_forms_give_the_plans_of_their_classical_twins() {
    // The published case in ROE form, and the e = 0 SSO pair with every orbit as an osculating
    // ECI state (tests/oracle/planner_b_forms.py wrote both inputs, independently): the plans
    // equal the classical fixtures' oracle plans.
    let text =
        std::fs::read_to_string(fixtures_dir().join("golden/planner-b-nonsingular.json")).unwrap();
    let g: serde_json::Value = serde_json::from_str(&text).unwrap();
    // The states carry 16 digits and the oracle's J2 rates come from central differences of
    // its own conversion (a agrees to ~1e-8 km, the rest to ~1e-14).
    for (name, twin, tol) in [
        (
            "wang2018-gco-to-pco-2imp-roe",
            "wang2018-gco-to-pco-2imp",
            1e-8,
        ),
        ("sso-leo-pair-e0-2imp-state", "sso-leo-pair-e0-2imp", 1e-8),
    ] {
        let s = check_against_oracle(name, &g[twin], tol, false, &Settings::default());
        let total = g[twin]["total_dv_mps"].as_f64().unwrap();
        println!(
            "{name}: {:.10} m/s (oracle {total:.10}), miss {:.2e} m",
            s.total_dv_mps,
            s.terminal_error.expect("nonlinear check flown").position_m
        );
    }
    // The osculating-to-mean conversion (core) inverts the oracle's mean-to-osculating one.
    let from_state = problem("sso-leo-pair-e0-2imp-state").chief;
    let classical = problem("sso-leo-pair-e0-2imp").chief;
    let (a, b) = (
        reconfig_core::impulsive::equinoctial_of(&from_state),
        reconfig_core::impulsive::equinoctial_of(&classical),
    );
    println!(
        "chief from the state minus the classical chief: a {:.2e} km, lambda {:.2e}, ex {:.2e}, ey {:.2e}, hx {:.2e}, hy {:.2e}",
        a.sma_km - b.sma_km,
        a.mean_longitude_rad - b.mean_longitude_rad,
        a.ex - b.ex,
        a.ey - b.ey,
        a.hx - b.hx,
        a.hy - b.hy
    );
    assert!(
        (a.sma_km - b.sma_km).abs() < 1e-7,
        "{} vs {}",
        a.sma_km,
        b.sma_km
    );
    for (x, y) in [(a.ex, b.ex), (a.ey, b.ey), (a.hx, b.hx), (a.hy, b.hy)] {
        assert!((x - y).abs() < 1e-13, "{x} vs {y}");
    }
    assert!((a.mean_longitude_rad - b.mean_longitude_rad).abs() < 1e-13);
}
