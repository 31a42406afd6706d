//! The stored oracle answers for `reconfig sweep` and the regression test: the independent
//! CasADi + IPOPT solves of `tests/oracle/planner_a_ipopt.py` (golden file
//! `fixtures/golden/planner-a-oracle.jsonl`) over the checked-in generated problems
//! (`fixtures/generated/planner-a-families.jsonl`), and the cost-gap statistics against them.

use anyhow::{bail, Context, Result};
use reconfig_core::pseudospectral::Problem;
use std::collections::BTreeMap;
use std::path::Path;

/// Default golden file, relative to the repository root.
pub const GOLDEN_DEFAULT: &str = "fixtures/golden/planner-a-oracle.jsonl";
/// Default problem file (written by `reconfig sweep --write`), relative to the repository root.
pub const PROBLEMS_DEFAULT: &str = "fixtures/generated/planner-a-families.jsonl";
/// A Solved answer more than this above the oracle's best (relative) counts as a worse optimum.
pub const GAP_REPORT_REL: f64 = 5e-3;

/// One problem's oracle answer.
#[derive(Clone, Debug, PartialEq)]
pub struct OracleAnswer {
    /// Position in the problem file (0-based).
    pub index: usize,
    /// Family name.
    pub family: String,
    /// Best feasible cost over all starts (restart from ours included), `None` when no start
    /// ended feasible: the problem is then excluded from the "of the problems the oracle solves"
    /// rates.
    pub cost: Option<f64>,
    /// Best feasible cost over the oracle's own starts only (restart from ours excluded).
    pub cost_own_starts: Option<f64>,
    /// The cost IPOPT reached when restarted from our answer, when that restart ended feasible.
    pub cost_from_ours: Option<f64>,
    /// IPOPT's wall time for one solve (all keep-out rounds) from the analytic guess, in ms.
    pub ipopt_time_ms: Option<f64>,
    /// Whether IPOPT converged at the best answer (`Solve_Succeeded` or
    /// `Solved_To_Acceptable_Level`): an answer checked feasible after IPOPT gave up is no
    /// optimum to compare with.
    pub converged: bool,
}

/// Relative cost gap of ours above the oracle's (negative: ours is lower).
pub fn relative_gap(ours: f64, oracle: f64) -> f64 {
    (ours - oracle) / oracle.abs().max(1e-9)
}

fn opt_f64(v: &serde_json::Value, key: &str) -> Option<f64> {
    v.get(key).and_then(serde_json::Value::as_f64)
}

/// Read the golden file: a header line, then one JSON object per problem.
///
/// # Errors
/// The file cannot be read, or a line is not the oracle's JSON.
pub fn load_golden(path: &Path) -> Result<BTreeMap<usize, OracleAnswer>> {
    let mut out = BTreeMap::new();
    for (at, v) in json_lines::<serde_json::Value>(path)? {
        if v.get("header").is_some() {
            continue;
        }
        let Some(index) = v.get("index").and_then(serde_json::Value::as_u64) else {
            bail!("{at}: no index");
        };
        let solved = v
            .get("solved")
            .and_then(serde_json::Value::as_bool)
            .unwrap_or(false);
        let from_ours = v.get("ours_restart").and_then(|r| {
            if r.get("feasible").and_then(serde_json::Value::as_bool) == Some(true) {
                opt_f64(r, "cost")
            } else {
                None
            }
        });
        let index = usize::try_from(index).context("index")?;
        out.insert(
            index,
            OracleAnswer {
                index,
                family: v
                    .get("family")
                    .and_then(serde_json::Value::as_str)
                    .unwrap_or_default()
                    .to_string(),
                cost: if solved { opt_f64(&v, "cost") } else { None },
                cost_own_starts: opt_f64(&v, "best_without_ours"),
                cost_from_ours: from_ours,
                ipopt_time_ms: opt_f64(&v, "ipopt_time_ms"),
                converged: matches!(
                    v.get("ipopt_status").and_then(serde_json::Value::as_str),
                    Some("Solve_Succeeded" | "Solved_To_Acceptable_Level")
                ),
            },
        );
    }
    Ok(out)
}

/// Read the problem file written by `reconfig sweep --write`: `(family, problem)` per line.
///
/// # Errors
/// The file cannot be read or a line is not a problem.
pub fn load_problems(path: &Path) -> Result<Vec<(String, Problem)>> {
    #[derive(serde::Deserialize)]
    struct Item {
        family: String,
        problem: Problem,
    }
    Ok(json_lines::<Item>(path)?
        .into_iter()
        .map(|(_, item)| (item.family, item.problem))
        .collect())
}

/// A JSON-lines file's non-empty lines, each read as `T`, with where it stands (`FILE line N`).
///
/// # Errors
/// The file cannot be read, or a line is not a `T` (named by its place).
fn json_lines<T: serde::de::DeserializeOwned>(path: &Path) -> Result<Vec<(String, T)>> {
    let text =
        std::fs::read_to_string(path).with_context(|| format!("reading {}", path.display()))?;
    let mut out = Vec::new();
    for (line_no, line) in text.lines().enumerate() {
        if line.trim().is_empty() {
            continue;
        }
        let at = format!("{} line {}", path.display(), line_no + 1);
        let value = serde_json::from_str(line).with_context(|| at.clone())?;
        out.push((at, value));
    }
    Ok(out)
}

/// The same problem up to the last bit or two of each number: the JSON text round trip may move
/// a float by an ulp (serde_json's default parser), which must not hide the oracle's answer.
pub fn same_problem(a: &Problem, b: &Problem) -> bool {
    let close = |x: f64, y: f64| (x - y).abs() <= 1e-12 * (1.0 + x.abs().max(y.abs()));
    a.degree == b.degree
        && a.test_points == b.test_points
        && close(a.horizon_tu, b.horizon_tu)
        && close(a.max_control_fu, b.max_control_fu)
        && close(a.keep_out_lu, b.keep_out_lu)
        && a.spacecraft.len() == b.spacecraft.len()
        && a.spacecraft.iter().zip(b.spacecraft.iter()).all(|(p, q)| {
            close(p.mass_mu, q.mass_mu)
                && p.initial_state
                    .iter()
                    .zip(q.initial_state.iter())
                    .chain(p.final_state.iter().zip(q.final_state.iter()))
                    .all(|(x, y)| close(*x, *y))
        })
}

/// The value at quantile `q` of sorted values (nearest rank), NaN when empty.
pub fn percentile(sorted: &[f64], q: f64) -> f64 {
    if sorted.is_empty() {
        return f64::NAN;
    }
    let last = sorted.len() - 1;
    let index = ((last as f64) * q).round() as usize;
    sorted[index.min(last)]
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn gap_is_relative_and_signed() {
        assert!((relative_gap(10.05, 10.0) - 5e-3).abs() < 1e-12);
        assert!(relative_gap(9.9, 10.0) < 0.0);
    }

    #[test]
    fn percentile_is_nearest_rank() {
        let v = [1.0, 2.0, 3.0, 4.0, 5.0];
        assert_eq!(percentile(&v, 0.5), 3.0);
        assert_eq!(percentile(&v, 1.0), 5.0);
        assert!(percentile(&[], 0.5).is_nan());
    }

    #[test]
    fn golden_lines_are_read_and_unsolved_ones_have_no_cost() {
        let dir = std::env::temp_dir().join(format!("sweep-oracle-{}", std::process::id()));
        std::fs::create_dir_all(&dir).expect("dir");
        let path = dir.join("g.jsonl");
        std::fs::write(
            &path,
            "{\"header\": {}}\n\
             {\"index\": 0, \"family\": \"random\", \"solved\": true, \"cost\": 5.0, \"best_without_ours\": 5.1, \"ours_restart\": {\"cost\": 5.0, \"feasible\": true}, \"ipopt_time_ms\": 40.0}\n\
             {\"index\": 1, \"family\": \"mixed\", \"solved\": false, \"cost\": null, \"best_without_ours\": null, \"ours_restart\": null, \"ipopt_time_ms\": 12.0}\n",
        )
        .expect("write");
        let g = load_golden(&path).expect("golden");
        assert_eq!(g[&0].cost, Some(5.0));
        assert_eq!(g[&0].cost_own_starts, Some(5.1));
        assert_eq!(g[&0].cost_from_ours, Some(5.0));
        assert_eq!(g[&1].cost, None);
        assert_eq!(g[&1].family, "mixed");
        std::fs::remove_dir_all(&dir).expect("cleanup");
    }
}
