//! `reconfig sweep`: planner A over seeded generated problem families, one table per family.
//!
//! Six families (issue 9): `random` (2-8 spacecraft, random ends in a 20 LU box),
//! `symmetric` (2-8 spacecraft on a circle, each to the antipode, so all meet at the centre),
//! `tight` (random, with Umax 1.15 times the least that reaches every axis rest to rest),
//! `fly-through` (two files of spacecraft passing through each other with initial velocity),
//! `dense` (8 spacecraft on a 2.4 LU lattice, permuted), `mixed` (random with masses 0.5-2,
//! degrees 8-24). The generator is seeded (ChaCha8), so the same arguments give the same
//! problems; `--write` stores them as JSON (one problem per line) for other tools.
//!
//! Per family the table gives the statuses, the largest QP working set, the saddle escapes and
//! the solve time (median, worst). When the oracle's golden file is found (`--golden`, default
//! `fixtures/golden/planner-a-oracle.jsonl`) and the generated problems are the checked-in ones
//! (`fixtures/generated/planner-a-families.jsonl`, compared problem by problem), a second table
//! gives per family the cost gap to the oracle's best, the Solved / usable rates of the problems
//! the oracle solves and the time against IPOPT's (`sweep_oracle.rs`).

use crate::drivers::pseudospectral::solve_timed_with_starts;
use crate::drivers::sweep_oracle::{self, relative_gap, OracleAnswer, GAP_REPORT_REL};
use anyhow::{Context, Result};
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use reconfig_core::pseudospectral::{
    AlternativeStarts, Problem, Settings, SolveStatus, Spacecraft,
};
use std::collections::BTreeMap;
use std::io::Write;
use std::path::PathBuf;
use std::process::ExitCode;

/// Arguments of `reconfig sweep`.
#[derive(clap::Args, Debug)]
pub struct Args {
    /// Problems per family.
    #[arg(long, default_value_t = 42)]
    pub per_family: usize,
    /// Random seed.
    #[arg(long, default_value_t = 9)]
    pub seed: u64,
    /// Also write the generated problems here (JSON, one `{family, problem}` per line).
    #[arg(long)]
    pub write: Option<PathBuf>,
    /// Also write our answers here (JSON, one `{index, family, status, cost, time_ms, nodes}` per
    /// line; `nodes` = node positions per spacecraft, for the oracle's restart from ours).
    #[arg(long)]
    pub write_answers: Option<PathBuf>,
    /// The oracle's golden answers (`tests/oracle/planner_a_ipopt.py`); the default path is used
    /// when it exists.
    #[arg(long, default_value = sweep_oracle::GOLDEN_DEFAULT)]
    pub golden: PathBuf,
    /// The problems the golden answers belong to (`reconfig sweep --write`); a generated
    /// problem is compared with the oracle only when it equals the stored one.
    #[arg(long, default_value = sweep_oracle::PROBLEMS_DEFAULT)]
    pub problems: PathBuf,
    /// Planner A's work budget in work units (`Settings::work_budget`); default: the core's
    /// default, which bounds a solve to 400 M Cortex-M7 instructions. A larger budget measures
    /// the planner's answers without the on-board time bound.
    #[arg(long)]
    pub work_budget: Option<u64>,
    /// Alternative starts after the analytic guess's solve (0, 1 or 2): the guess lifted
    /// sideways (y, then z), the best answer kept
    /// (`pseudospectral::solve_with_alternative_starts`).
    #[arg(long, default_value_t = 0, value_parser = clap::value_parser!(u8).range(0..=2))]
    pub alternative_starts: u8,
}

/// One generated problem's outcome, for the oracle table.
struct Outcome {
    family: &'static str,
    /// Oracle's best cost when the problem is the stored one and the oracle solved it.
    oracle: Option<f64>,
    /// IPOPT's time for one solve, ms.
    ipopt_ms: Option<f64>,
    /// `Some(status)` when the planner accepted the problem.
    status: Option<SolveStatus>,
    cost: f64,
    time_ms: f64,
}

/// The family names, in table order.
pub const FAMILIES: [&str; 6] = [
    "random",
    "symmetric",
    "tight",
    "fly-through",
    "dense",
    "mixed",
];

const KEEP_OUT_LU: f64 = 2.0;
const HORIZON_TU: f64 = 10.0;

fn craft(mass: f64, a: [f64; 6], b: [f64; 6]) -> Spacecraft {
    Spacecraft {
        mass_mu: mass,
        initial_state: a,
        final_state: b,
    }
}

fn at_rest(p: [f64; 3]) -> [f64; 6] {
    [p[0], p[1], p[2], 0.0, 0.0, 0.0]
}

/// `count` points in a cube of half-width `half`, pairwise at least `gap` apart.
fn spread(rng: &mut ChaCha8Rng, count: usize, half: f64, gap: f64) -> Vec<[f64; 3]> {
    let mut points: Vec<[f64; 3]> = Vec::new();
    // Bounded rejection sampling: the cube is large enough for 8 points at this gap.
    for _ in 0..10_000 {
        if points.len() == count {
            break;
        }
        let p = [
            rng.random_range(-half..half),
            rng.random_range(-half..half),
            rng.random_range(-half..half),
        ];
        let clear = points.iter().all(|q| {
            let d2: f64 = (0..3).map(|k| (p[k] - q[k]).powi(2)).sum();
            d2 >= gap * gap
        });
        if clear {
            points.push(p);
        }
    }
    points
}

fn problem(umax: f64, degree: u16, spacecraft: Vec<Spacecraft>) -> Problem {
    let mut list = heapless::Vec::new();
    for c in spacecraft.into_iter().take(8) {
        let _ = list.push(c);
    }
    Problem {
        horizon_tu: HORIZON_TU,
        max_control_fu: umax,
        keep_out_lu: KEEP_OUT_LU,
        degree,
        test_points: true,
        spacecraft: list,
    }
}

/// Spacecraft at rest at `starts`, each to rest at its end, with the masses `mass` gives (in
/// order: a generator's draws stay in the same sequence).
fn rest_to_rest(
    starts: &[[f64; 3]],
    ends: &[[f64; 3]],
    mut mass: impl FnMut() -> f64,
) -> Vec<Spacecraft> {
    starts
        .iter()
        .zip(ends)
        .map(|(a, b)| craft(mass(), at_rest(*a), at_rest(*b)))
        .collect()
}

/// Generate one problem of `family`.
pub fn generate(family: &str, rng: &mut ChaCha8Rng) -> Problem {
    let gap = KEEP_OUT_LU + 0.5;
    match family {
        "symmetric" => {
            let m = rng.random_range(2..=8usize);
            let radius = 6.0;
            let phase = rng.random_range(0.0..std::f64::consts::PI);
            let crafts = (0..m)
                .map(|k| {
                    let a = phase + 2.0 * std::f64::consts::PI * k as f64 / m as f64;
                    let p = [radius * a.cos(), radius * a.sin(), 0.0];
                    craft(1.0, at_rest(p), at_rest([-p[0], -p[1], 0.0]))
                })
                .collect();
            problem(1.0, 16, crafts)
        }
        "tight" => {
            let m = rng.random_range(2..=6usize);
            let (starts, ends) = (spread(rng, m, 8.0, gap), spread(rng, m, 8.0, gap));
            // Rest to rest along one axis needs 4 D / T^2 at least.
            let mut need = 0.0f64;
            for (a, b) in starts.iter().zip(ends.iter()) {
                for k in 0..3 {
                    need = need.max(4.0 * (b[k] - a[k]).abs() / (HORIZON_TU * HORIZON_TU));
                }
            }
            problem(
                1.15 * need.max(0.05),
                12,
                rest_to_rest(&starts, &ends, || 1.0),
            )
        }
        "fly-through" => {
            let per_side = rng.random_range(1..=4usize);
            let mut crafts = Vec::new();
            for k in 0..per_side {
                let y = 3.0 * k as f64 - 1.5 * (per_side - 1) as f64;
                let z = rng.random_range(-0.5..0.5);
                let speed = rng.random_range(0.5..1.5);
                crafts.push(craft(
                    1.0,
                    [-10.0, y, z, speed, 0.0, 0.0],
                    [10.0, y + rng.random_range(-1.0..1.0), z, speed, 0.0, 0.0],
                ));
                crafts.push(craft(
                    1.0,
                    [10.0, y + 0.5, -z, -speed, 0.0, 0.0],
                    [-10.0, y + 0.5, -z, -speed, 0.0, 0.0],
                ));
            }
            problem(1.0, 14, crafts)
        }
        "dense" => {
            let mut cells: Vec<[f64; 3]> = Vec::new();
            for i in 0..2 {
                for j in 0..2 {
                    for k in 0..2 {
                        cells.push([2.4 * i as f64, 2.4 * j as f64, 2.4 * k as f64]);
                    }
                }
            }
            let mut order: Vec<usize> = (0..8).collect();
            for i in (1..8).rev() {
                order.swap(i, rng.random_range(0..=i));
            }
            let crafts = (0..8)
                .map(|i| craft(1.0, at_rest(cells[i]), at_rest(cells[order[i]])))
                .collect();
            problem(1.0, 12, crafts)
        }
        "mixed" => {
            let m = rng.random_range(2..=8usize);
            let (starts, ends) = (spread(rng, m, 10.0, gap), spread(rng, m, 10.0, gap));
            let degree = rng.random_range(8..=24u16);
            let crafts = rest_to_rest(&starts, &ends, || rng.random_range(0.5..2.0));
            problem(1.0, degree, crafts)
        }
        _ => {
            let m = rng.random_range(2..=8usize);
            let (starts, ends) = (spread(rng, m, 10.0, gap), spread(rng, m, 10.0, gap));
            problem(1.0, 12, rest_to_rest(&starts, &ends, || 1.0))
        }
    }
}

use sweep_oracle::percentile;

/// The oracle's answers by problem index, and the stored problems they belong to.
type OracleData = (BTreeMap<usize, OracleAnswer>, Vec<(String, Problem)>);

/// The golden answers and stored problems, when both are there.
fn load_oracle(args: &Args) -> Option<OracleData> {
    if !args.golden.exists() || !args.problems.exists() {
        return None;
    }
    match (
        sweep_oracle::load_golden(&args.golden),
        sweep_oracle::load_problems(&args.problems),
    ) {
        (Ok(g), Ok(p)) => Some((g, p)),
        (Err(e), _) | (_, Err(e)) => {
            eprintln!("oracle comparison skipped: {e:#}");
            None
        }
    }
}

fn pct(part: usize, whole: usize) -> String {
    if whole == 0 {
        "-".to_string()
    } else {
        format!("{:.1} %", 100.0 * part as f64 / whole as f64)
    }
}

/// The oracle table: per family and in all, over the problems the oracle solves.
fn print_oracle_table(outcomes: &[Outcome]) {
    println!();
    println!(
        "| family | oracle solves | Solved | usable (`is_usable()`) | gap median | gap p95 | gap worst | Solved > 0.5 % above | ours ms median / worst | IPOPT ms median | IPOPT / ours (medians) |"
    );
    println!("| --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- |");
    let mut rows: Vec<&str> = FAMILIES.to_vec();
    rows.push("all");
    for family in rows {
        let set: Vec<&Outcome> = outcomes
            .iter()
            .filter(|o| o.oracle.is_some() && (family == "all" || o.family == family))
            .collect();
        let solved = set
            .iter()
            .filter(|o| o.status == Some(SolveStatus::Solved))
            .count();
        let usable = set
            .iter()
            .filter(|o| o.status.is_some_and(|s| s.is_usable()))
            .count();
        let mut gaps: Vec<f64> = set
            .iter()
            .filter(|o| o.status.is_some_and(|s| s.is_usable()))
            .filter_map(|o| o.oracle.map(|j| relative_gap(o.cost, j)))
            .collect();
        gaps.sort_by(f64::total_cmp);
        let above = set
            .iter()
            .filter(|o| o.status == Some(SolveStatus::Solved))
            .filter(|o| {
                o.oracle
                    .is_some_and(|j| relative_gap(o.cost, j) > GAP_REPORT_REL)
            })
            .count();
        let mut ours: Vec<f64> = set
            .iter()
            .filter(|o| o.status.is_some())
            .map(|o| o.time_ms)
            .collect();
        ours.sort_by(f64::total_cmp);
        let mut ipopt: Vec<f64> = set.iter().filter_map(|o| o.ipopt_ms).collect();
        ipopt.sort_by(f64::total_cmp);
        let ours_median = percentile(&ours, 0.5);
        let ipopt_median = percentile(&ipopt, 0.5);
        println!(
            "| {family} | {} | {solved} ({}) | {usable} ({}) | {:.4} % | {:.4} % | {:.4} % | {above} of {solved} | {:.2} / {:.2} | {:.0} | {:.0}x |",
            set.len(),
            pct(solved, set.len()),
            pct(usable, set.len()),
            100.0 * percentile(&gaps, 0.5),
            100.0 * percentile(&gaps, 0.95),
            100.0 * gaps.last().copied().unwrap_or(f64::NAN),
            ours_median,
            ours.last().copied().unwrap_or(f64::NAN),
            ipopt_median,
            ipopt_median / ours_median,
        );
    }
}

/// One answer as JSON: status, cost, time, the iteration counters and certificate measures, and
/// the node positions of every spacecraft.
fn answer_json(
    index: usize,
    family: &str,
    p: &Problem,
    s: &reconfig_core::pseudospectral::Solution,
    time_s: f64,
) -> serde_json::Value {
    let nodes = usize::from(s.degree) + 1;
    let positions: Vec<Vec<[f64; 3]>> = s
        .states
        .iter()
        .take(p.spacecraft.len())
        .map(|craft| {
            craft
                .iter()
                .take(nodes)
                .map(|x| [x[0], x[1], x[2]])
                .collect()
        })
        .collect();
    serde_json::json!({
        "index": index,
        "family": family,
        "status": format!("{:?}", s.info.status),
        "cost": s.cost,
        "min_separation_lu": s.min_separation_lu,
        "time_ms": time_s * 1e3,
        // Why an answer is not Solved (the diagnosis of issue 9): the iteration's counters and
        // the certificate's measures.
        "sqp_iterations": s.info.sqp_iterations,
        "max_active": s.info.max_active,
        "verify_rounds": s.info.verify_rounds,
        "saddle_escapes": s.info.saddle_escapes,
        "work_units": s.info.work_units,
        "stationarity": s.certificate.stationarity,
        "complementarity": s.certificate.complementarity,
        "min_reduced_eigenvalue": s.certificate.min_reduced_eigenvalue,
        "max_violation": s.certificate.max_violation,
        "first_order_evaluated": s.certificate.first_order_evaluated,
        "second_order_evaluated": s.certificate.second_order_evaluated,
        "flat_direction_probed": s.certificate.flat_direction_probed,
        "nodes": positions,
    })
}

/// Run the sweep and print the tables.
///
/// # Errors
/// Writing the problem file.
pub fn run(args: &Args) -> Result<ExitCode> {
    let mut rng = ChaCha8Rng::seed_from_u64(args.seed);
    let mut file = match &args.write {
        Some(path) => Some(
            std::fs::File::create(path).with_context(|| format!("creating {}", path.display()))?,
        ),
        None => None,
    };
    let mut answers = match &args.write_answers {
        Some(path) => Some(
            std::fs::File::create(path).with_context(|| format!("creating {}", path.display()))?,
        ),
        None => None,
    };
    let mut index = 0usize;
    let oracle = load_oracle(args);
    let mut outcomes: Vec<Outcome> = Vec::new();
    let mut settings = Settings::default();
    if let Some(budget) = args.work_budget {
        settings.work_budget = budget;
    }
    let starts = match args.alternative_starts {
        0 => None,
        1 => Some(AlternativeStarts::One),
        _ => Some(AlternativeStarts::Two),
    };
    println!(
        "work budget: {} units; alternative starts: {}",
        settings.work_budget, args.alternative_starts
    );
    println!(
        "| family | problems | Solved | Feasible | other (status: count) | rejected | largest working set | saddle escapes (helped) | answers from an alternative start | J median / worst | ms median / worst |"
    );
    println!("| --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- |");
    for family in FAMILIES {
        let mut solved = 0usize;
        let mut feasible = 0usize;
        let mut rejected = 0usize;
        let mut reasons: std::collections::BTreeMap<String, usize> = Default::default();
        let mut other: std::collections::BTreeMap<String, usize> = Default::default();
        let mut times = Vec::new();
        let mut costs = Vec::new();
        let mut working = 0u16;
        let mut escapes = 0usize;
        let mut helped = 0usize;
        let mut from_alternative = 0usize;
        for _ in 0..args.per_family {
            let p = generate(family, &mut rng);
            let this = index;
            index += 1;
            // The oracle's answer counts only for the very problem it solved.
            let stored = oracle.as_ref().and_then(|(golden, problems)| {
                let same = problems
                    .get(this)
                    .is_some_and(|(f, q)| f == family && sweep_oracle::same_problem(q, &p));
                if same {
                    golden.get(&this)
                } else {
                    None
                }
            });
            let mut outcome = Outcome {
                family,
                oracle: stored.and_then(|a| a.cost),
                ipopt_ms: stored.and_then(|a| a.ipopt_time_ms),
                status: None,
                cost: f64::NAN,
                time_ms: f64::NAN,
            };
            if let Some(f) = file.as_mut() {
                writeln!(
                    f,
                    "{}",
                    serde_json::json!({ "family": family, "problem": &p })
                )?;
            }
            let timed = match solve_timed_with_starts(&p, &settings, starts) {
                Ok((timed, kept)) => {
                    if kept > 0 {
                        from_alternative += 1;
                    }
                    timed
                }
                Err(e) => {
                    if let Some(f) = answers.as_mut() {
                        writeln!(
                            f,
                            "{}",
                            serde_json::json!({ "index": this, "family": family, "status": "Rejected", "error": e.to_string() })
                        )?;
                    }
                    rejected += 1;
                    // Name the refusal class from the core's message.
                    let text = e.to_string();
                    let class = if text.contains("cannot meet its boundary conditions") {
                        "ManoeuvreInfeasible"
                    } else if text.contains("closer than") {
                        "BoundaryTooClose"
                    } else {
                        "other"
                    }
                    .to_string();
                    *reasons.entry(class).or_default() += 1;
                    outcomes.push(outcome);
                    continue;
                }
            };
            let s = &timed.solution;
            if let Some(f) = answers.as_mut() {
                writeln!(
                    f,
                    "{}",
                    answer_json(this, family, &p, s, timed.solve_time_s)
                )?;
            }
            times.push(timed.solve_time_s * 1e3);
            outcome.status = Some(s.info.status);
            outcome.cost = s.cost;
            outcome.time_ms = timed.solve_time_s * 1e3;
            outcomes.push(outcome);
            working = working.max(s.info.max_active);
            if s.info.saddle_escapes > 0 {
                escapes += 1;
                if s.info.status == SolveStatus::Solved {
                    helped += 1;
                }
            }
            match s.info.status {
                SolveStatus::Solved => {
                    solved += 1;
                    costs.push(s.cost);
                }
                SolveStatus::Feasible => {
                    feasible += 1;
                    costs.push(s.cost);
                }
                status => *other.entry(format!("{status:?}")).or_default() += 1,
            }
        }
        times.sort_by(f64::total_cmp);
        costs.sort_by(f64::total_cmp);
        let others: Vec<String> = other.iter().map(|(k, v)| format!("{k}: {v}")).collect();
        let reasons: Vec<String> = reasons.iter().map(|(k, v)| format!("{k}: {v}")).collect();
        println!(
            "| {family} | {} | {solved} | {feasible} | {} | {rejected}{} | {working} | {escapes} ({helped}) | {from_alternative} | {:.4} / {:.4} | {:.2} / {:.2} |",
            args.per_family,
            if others.is_empty() { "-".to_string() } else { others.join(", ") },
            if reasons.is_empty() { String::new() } else { format!(" ({})", reasons.join(", ")) },
            percentile(&costs, 0.5),
            costs.last().copied().unwrap_or(f64::NAN),
            percentile(&times, 0.5),
            times.last().copied().unwrap_or(f64::NAN),
        );
    }
    if oracle.is_some() {
        print_oracle_table(&outcomes);
    } else {
        eprintln!(
            "no oracle comparison: {} or {} not found",
            args.golden.display(),
            args.problems.display()
        );
    }
    Ok(ExitCode::SUCCESS)
}
