//! Planner A against the independent CasADi + IPOPT oracle (`tests/oracle/planner_a_ipopt.py`)
//! on the checked-in generated families (`fixtures/generated/planner-a-families.jsonl`, written
//! by `reconfig sweep --write`; answers in `fixtures/golden/planner-a-oracle.jsonl`).
//!
//! Per problem the oracle solved: our status is usable (Solved or Feasible) unless the problem is
//! a recorded exception (`fixtures/golden/planner-a-oracle-bars.toml`, with the reason, so a
//! regression shows as a NEW exception), and our cost is never below the oracle's best by more
//! than a valid answer's tolerance plus what the oracle's keep-out margin costs it (our keep-out
//! multipliers times the margin; a lower cost would mean an infeasible answer). In aggregate:
//! the Solved and usable rates and the share of Solved answers more than 0.5 % above the oracle
//! are held at the recorded floors and ceiling (all in the bars file: tighten them there).
//!
//! The oracle's best includes IPOPT restarted from our answers of the time, so it is at or below
//! those; a solver change that finds a lower optimum legitimately trips the below-check, and the
//! golden file is then regenerated with a restart from the new answers.
//!
//! CI runtime: by default every `ci_stride`-th problem of the golden file runs (a fixed,
//! representative subset across the six families); `RECONFIG_ORACLE_ALL=1` runs all of them
//! against the `[all]` bars.

use reconfig_core::pseudospectral::{
    solve_with_alternative_starts, AlternativeStarts, Settings, Solution, SolveStatus, Workspace,
};
use reconfig_host::drivers::sweep_oracle::{self, relative_gap, GAP_REPORT_REL};
use reconfig_tests::{below_oracle_allowance_rel, fixtures_dir, solve_pseudospectral};
use std::collections::BTreeMap;

struct Bars {
    min_solved_rate: f64,
    min_usable_rate: f64,
    max_solved_above_rate: f64,
}

struct Config {
    /// Planner A's work budget for this comparison (`Settings::work_budget`).
    work_budget: u64,
    below_tolerance_rel: f64,
    /// The oracle's largest keep-out raise per pair, as a fraction of d (see the bars file).
    oracle_margin_rel: f64,
    ci_stride: usize,
    ci: Bars,
    all: Bars,
    /// The bars with one alternative start (`solve_with_alternative_starts`), over every problem.
    alternative: Bars,
    /// Known exceptions: problem index -> (status we return, reason).
    exceptions: BTreeMap<usize, (String, String)>,
    /// The same with one alternative start.
    alternative_exceptions: BTreeMap<usize, (String, String)>,
}

fn bars(table: &toml::Table, key: &str) -> Bars {
    let t = table[key].as_table().expect("bars table");
    Bars {
        min_solved_rate: t["min_solved_rate"].as_float().expect("float"),
        min_usable_rate: t["min_usable_rate"].as_float().expect("float"),
        max_solved_above_rate: t["max_solved_above_rate"].as_float().expect("float"),
    }
}

fn exceptions(table: &toml::Table, key: &str) -> BTreeMap<usize, (String, String)> {
    let mut exceptions = BTreeMap::new();
    if let Some(list) = table.get(key).and_then(toml::Value::as_array) {
        for e in list {
            let index = usize::try_from(e["index"].as_integer().expect("index")).expect("index");
            exceptions.insert(
                index,
                (
                    e["status"].as_str().expect("status").to_string(),
                    e["reason"].as_str().expect("reason").to_string(),
                ),
            );
        }
    }
    exceptions
}

fn config() -> Config {
    let path = fixtures_dir()
        .join("golden")
        .join("planner-a-oracle-bars.toml");
    let text = std::fs::read_to_string(&path).expect("bars file");
    let table: toml::Table = toml::from_str(&text).expect("bars toml");
    Config {
        work_budget: u64::try_from(table["work_budget"].as_integer().expect("int"))
            .expect("budget"),
        below_tolerance_rel: table["below_tolerance_rel"].as_float().expect("float"),
        oracle_margin_rel: table["oracle_margin_rel"].as_float().expect("float"),
        ci_stride: usize::try_from(table["ci_stride"].as_integer().expect("int")).expect("stride"),
        ci: bars(&table, "ci"),
        all: bars(&table, "all"),
        alternative: bars(&table, "alternative_starts"),
        exceptions: exceptions(&table, "exception"),
        alternative_exceptions: exceptions(&table, "alternative_exception"),
    }
}

#[test]
fn planner_a_meets_the_oracle_on_the_generated_families() {
    let cfg = config();
    let all = std::env::var("RECONFIG_ORACLE_ALL").is_ok_and(|v| v == "1");
    let bars = if all { &cfg.all } else { &cfg.ci };
    let stride = if all { 1 } else { cfg.ci_stride };
    let tally = compare(&cfg, bars, &cfg.exceptions, stride, None);
    if stride == 1 {
        let percent = |k: usize, of: usize| 100.0 * k as f64 / of as f64;
        let (solved, above) = (
            percent(tally.solved, tally.count),
            percent(tally.above, tally.solved),
        );
        reconfig_host::figure_record::hold(
            "a-oracle-families",
            &reconfig_host::figure_record::Figure {
                what: format!(
                    "A: the {} generated problems IPOPT solves, budget lifted",
                    tally.count
                ),
                target: "≥ 97 % `Solved`, ≤ 2 % of them > 0.5 % above".into(),
                measured: format!("{solved:.1} % `Solved`, {above:.1} % above"),
                met: solved >= 97.0 && above <= 2.0,
                doc: "planner-a".into(),
                command: "cargo test -p reconfig-tests --test pseudospectral_oracle".into(),
            },
        )
        .unwrap();
    }
}

/// What [`compare`] counted.
struct Tally {
    count: usize,
    solved: usize,
    above: usize,
}

/// Issue 9 item 6: with one alternative start (the guess lifted along y) every bar of the
/// issue holds on the generated families; the bars file records the measured rates.
#[test]
fn with_one_alternative_start_planner_a_meets_the_issue_bars() {
    let cfg = config();
    let bars = &cfg.alternative;
    assert!(bars.min_solved_rate >= 0.97 && bars.min_usable_rate >= 0.99);
    assert!(bars.max_solved_above_rate <= 0.02);
    let _ = compare(
        &cfg,
        bars,
        &cfg.alternative_exceptions,
        cfg.ci_stride,
        Some(AlternativeStarts::One),
    );
}

fn solve_with(
    problem: &reconfig_core::pseudospectral::Problem,
    settings: &Settings,
    starts: Option<AlternativeStarts>,
) -> Result<Box<Solution>, reconfig_core::pseudospectral::PlanError> {
    let Some(starts) = starts else {
        return solve_pseudospectral(problem, settings);
    };
    let mut workspace = Box::new(Workspace::new());
    let mut spare = Box::new(Solution::new());
    let mut out = Box::new(Solution::new());
    solve_with_alternative_starts(
        problem,
        settings,
        starts,
        &mut workspace,
        &mut spare,
        &mut out,
    )?;
    Ok(out)
}

/// Every `stride`-th golden problem against `bars` and `exceptions`.
fn compare(
    cfg: &Config,
    bars: &Bars,
    exceptions: &BTreeMap<usize, (String, String)>,
    stride: usize,
    starts: Option<AlternativeStarts>,
) -> Tally {
    let golden =
        sweep_oracle::load_golden(&fixtures_dir().join("golden").join("planner-a-oracle.jsonl"))
            .expect("golden");
    let problems = sweep_oracle::load_problems(
        &fixtures_dir()
            .join("generated")
            .join("planner-a-families.jsonl"),
    )
    .expect("problems");
    let settings = Settings {
        work_budget: cfg.work_budget,
        ..Settings::default()
    };

    let (mut count, mut solved, mut usable, mut above) = (0usize, 0usize, 0usize, 0usize);
    let mut failures: Vec<String> = Vec::new();
    let mut seen_exceptions = 0usize;
    for (position, (index, answer)) in golden.iter().enumerate() {
        if position % stride != 0 {
            continue;
        }
        let Some(oracle_cost) = answer.cost else {
            continue; // the oracle found no feasible answer: not counted
        };
        let (family, problem) = &problems[*index];
        assert_eq!(family, &answer.family, "problem {index}: family mismatch");
        count += 1;
        let ours = match solve_with(problem, &settings, starts) {
            Ok(s) => s,
            Err(e) => {
                if !exceptions.contains_key(index) {
                    failures.push(format!(
                        "NEW exception: problem {index} ({family}) rejected ({e}) but the oracle solved it (J = {oracle_cost})"
                    ));
                } else {
                    seen_exceptions += 1;
                }
                continue;
            }
        };
        let status = ours.info.status;
        if status == SolveStatus::Solved {
            solved += 1;
        }
        if status.is_usable() {
            usable += 1;
            let gap = relative_gap(ours.cost, oracle_cost);
            let allowance = below_oracle_allowance_rel(
                &ours,
                problem.keep_out_lu,
                oracle_cost,
                cfg.below_tolerance_rel,
                cfg.oracle_margin_rel,
            );
            if gap < -allowance {
                failures.push(format!(
                    "problem {index} ({family}): our J = {} is below the oracle's best {oracle_cost} by {:.3e} (relative): an infeasible answer, or a better optimum than any the oracle found (then re-run the oracle restarted from our answers and say so in the golden file's commit)",
                    ours.cost, -gap
                ));
            }
            if status == SolveStatus::Solved && gap > GAP_REPORT_REL {
                above += 1;
            }
        }
        match exceptions.get(index) {
            Some((known, reason)) if !status.is_usable() => {
                seen_exceptions += 1;
                if *known != format!("{status:?}") {
                    failures.push(format!(
                        "problem {index} ({family}): known exception ({reason}) changed status: {known} -> {status:?}"
                    ));
                }
            }
            Some(_) => {} // an exception that now works: welcome; drop it from the list
            None if !status.is_usable() => failures.push(format!(
                "NEW exception: problem {index} ({family}) ends {status:?} (J = {}, min separation {:?}) but the oracle solved it (J = {oracle_cost})",
                ours.cost, ours.min_separation_lu
            )),
            None => {}
        }
    }
    assert!(count > 0, "no problem ran");
    let rate = |k: usize| k as f64 / count as f64;
    println!(
        "{starts:?}: {} problems the oracle solves: Solved {solved} ({:.3}), usable {usable} ({:.3}), Solved > 0.5 % above {above} ({:.3}), known exceptions seen {seen_exceptions}",
        count,
        rate(solved),
        rate(usable),
        rate(above)
    );
    assert!(failures.is_empty(), "{}", failures.join("\n"));
    assert!(
        rate(solved) >= bars.min_solved_rate,
        "Solved rate {} fell below the floor {}",
        rate(solved),
        bars.min_solved_rate
    );
    assert!(
        rate(usable) >= bars.min_usable_rate,
        "usable rate {} fell below the floor {}",
        rate(usable),
        bars.min_usable_rate
    );
    assert!(
        rate(above) <= bars.max_solved_above_rate,
        "share of Solved answers > 0.5 % above the oracle {} rose above {}",
        rate(above),
        bars.max_solved_above_rate
    );
    Tally {
        count,
        solved,
        above,
    }
}

/// Dense lattice #168: two minima of one pair's separation (tau = +-0.124) took turns under its
/// single moving check, the answer dipping below d at the one it had just left, and the cost
/// cycled by 1e-4 for all 300 subproblems (`MaxIterations`). With the check frozen where it
/// returns from, the iteration converges and certifies its local minimum.
#[test]
fn a_moving_check_cycling_between_two_minima_is_frozen_and_the_dense_case_converges() {
    let cfg = config();
    let problems = sweep_oracle::load_problems(
        &fixtures_dir()
            .join("generated")
            .join("planner-a-families.jsonl"),
    )
    .expect("problems");
    let (family, problem) = &problems[168];
    assert_eq!(family, "dense");
    let settings = Settings {
        work_budget: cfg.work_budget,
        ..Settings::default()
    };
    let ours = solve_pseudospectral(problem, &settings).expect("accepted");
    assert_eq!(
        ours.info.status,
        SolveStatus::Solved,
        "{:?}",
        ours.certificate
    );
    // 213 subproblems over 3 verification rounds; before, all 5 x 60 = 300.
    assert!(
        ours.info.sqp_iterations < 300,
        "{}",
        ours.info.sqp_iterations
    );
    assert!((ours.cost - 1.596418).abs() < 1e-5, "J = {}", ours.cost);
    assert!(ours.min_separation_lu.unwrap() >= problem.keep_out_lu - settings.verify_tol_lu);
    // That minimum is 14.6 % above the oracle's; the lifted start reaches the oracle's basin.
    let lifted = solve_with(problem, &settings, Some(AlternativeStarts::One)).expect("accepted");
    assert_eq!(lifted.info.status, SolveStatus::Solved);
    assert!((lifted.cost - 1.393162).abs() < 1e-5, "J = {}", lifted.cost);
}
