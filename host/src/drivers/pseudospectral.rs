//! Planner A's driver: the report of an answered planner-A fixture (readable, or one JSON
//! object) for `reconfig solve`, and the timed solve with alternative starts the sweep uses (a
//! study of the planner, not a request: alternative starts are not on the wire).

use super::answer::{exit_code, report_other, Answered};
use crate::fixture::pseudospectral::PseudospectralFixture;
use anyhow::{anyhow, Result};
use reconfig_core::pseudospectral::{
    self, ActiveConstraint, Settings, Solution, UnmetConstraint, Workspace,
};
use reconfig_core::wire::OutcomeRef;
use serde_json::json;
use std::process::ExitCode;
use std::time::Instant;

/// The outcome of one timed solve.
pub struct Timed {
    /// The solution (boxed: it is large).
    pub solution: Box<Solution>,
    /// Wall time of the core's solve alone, seconds.
    pub solve_time_s: f64,
}

/// A planner-A solve in a fresh boxed workspace from the analytic guess, followed by `starts`
/// alternative starts (0, 1 or 2; `pseudospectral::solve_with_alternative_starts`) when given,
/// the best answer kept; also returns which start it came from (0: the analytic guess). The
/// time covers every solve. The sweep's study of the planner (its work budget may be lifted
/// past the limits), not a request of a front end.
///
/// # Errors
/// The core's `PlanError`, as a message.
pub fn solve_timed_with_starts(
    problem: &pseudospectral::Problem,
    settings: &Settings,
    starts: Option<pseudospectral::AlternativeStarts>,
) -> Result<(Timed, u8)> {
    let mut workspace = Box::new(Workspace::new());
    let mut solution = Box::new(Solution::new());
    let start = Instant::now();
    let kept = match starts {
        None => pseudospectral::solve(problem, settings, &mut workspace, &mut solution).map(|()| 0),
        Some(starts) => {
            let mut spare = Box::new(Solution::new());
            pseudospectral::solve_with_alternative_starts(
                problem,
                settings,
                starts,
                &mut workspace,
                &mut spare,
                &mut solution,
            )
            .map(|outcome| outcome.kept)
        }
    }
    .map_err(|e| anyhow!("the planner rejected the problem: {e}"))?;
    Ok((
        Timed {
            solution,
            solve_time_s: start.elapsed().as_secs_f64(),
        },
        kept,
    ))
}

/// The JSON object `reconfig solve --json` prints for planner A.
pub fn to_json(name: &str, s: &Solution, solve_time_s: f64) -> serde_json::Value {
    let m = usize::from(s.spacecraft_count);
    let nodes = usize::from(s.degree) + 1;
    // Each spacecraft's values at the nodes in use.
    fn used<T: Copy, const N: usize>(rows: &[[T; N]], m: usize, nodes: usize) -> Vec<Vec<T>> {
        rows.iter().take(m).map(|sc| sc[..nodes].to_vec()).collect()
    }
    let states = used(&s.states, m, nodes);
    let controls = used(&s.controls_fu, m, nodes);
    json!({
        "name": name,
        "planner": "pseudospectral",
        "status": format!("{:?}", s.info.status),
        "cost": s.cost,
        "min_separation": s.min_separation_lu,
        "min_separation_pair": [s.min_separation_pair.0 + 1, s.min_separation_pair.1 + 1],
        "min_separation_time": s.min_separation_time_tu,
        "iterations": s.info.sqp_iterations,
        "qp_iterations": s.info.qp_iterations,
        "verify_rounds": s.info.verify_rounds,
        "verify_points_added": s.info.verify_points_added,
        "keep_out_checks": s.info.keep_out_checks,
        "max_active": s.info.max_active,
        "warm_start_used": s.info.warm_start_used,
        "max_violation": s.info.max_violation,
        "max_dynamics_error": s.max_dynamics_error,
        "certificate": &s.certificate,
        "unmet": s.unmet.named(),
        "unmet_truncated": s.unmet.truncated,
        "elastic_subproblems": s.info.elastic_subproblems,
        "solve_time_s": solve_time_s,
        "node_times": &s.node_times_tu[..nodes],
        "states": states,
        "controls": controls,
    })
}

/// Report a planner-A fixture's answer. Exit code 0 when the plan is usable, 1 when it is
/// not, 2 when the request was refused or rejected.
///
/// # Errors
/// An answer of another planner, or JSON that does not print.
pub fn report(
    fixture: &PseudospectralFixture,
    answered: &Answered,
    json_output: bool,
) -> Result<ExitCode> {
    let OutcomeRef::Pseudospectral(s) = answered.outcome else {
        return report_other(&fixture.name, answered, json_output);
    };
    let solve_time_s = answered.time_s;
    if json_output {
        println!(
            "{}",
            serde_json::to_string_pretty(&to_json(&fixture.name, s, solve_time_s))?
        );
    } else {
        let p = &fixture.problem;
        println!("{} (planner A, pseudospectral)", fixture.name);
        println!(
            "  M = {} spacecraft, N = {} ({} LGL nodes), T = {}, Umax = {}, d = {}, test points {}",
            p.spacecraft.len(),
            p.degree,
            p.degree + 1,
            p.horizon_tu,
            p.max_control_fu,
            p.keep_out_lu,
            if p.test_points { "on" } else { "off" }
        );
        println!("  status               {:?}", s.info.status);
        println!("  cost J               {:.6}", s.cost);
        match s.min_separation_lu {
            Some(d) => println!(
                "  min separation       {d:.6} (spacecraft {} and {}, t = {:.4}), continuous",
                s.min_separation_pair.0 + 1,
                s.min_separation_pair.1 + 1,
                s.min_separation_time_tu
            ),
            None => println!("  min separation       none (one spacecraft)"),
        }
        println!(
            "  dynamics error       {:.3e} (eq. 29)",
            s.max_dynamics_error
        );
        println!(
            "  iterations           {} convex subproblems, {} active-set steps, {} verification rounds (+{} points)",
            s.info.sqp_iterations, s.info.qp_iterations, s.info.verify_rounds, s.info.verify_points_added
        );
        let c = &s.certificate;
        println!(
            "  certificate          stationarity {:.1e}, complementarity {:.1e}, max violation {:.1e}, reduced-Hessian min eigenvalue {}, {} active constraints{}",
            c.stationarity,
            c.complementarity,
            c.max_violation,
            if c.second_order_evaluated && c.flat_direction_probed {
                format!(
                    "{:.1e} (flat: probed both ways, no lower cost)",
                    c.min_reduced_eigenvalue
                )
            } else if c.second_order_evaluated && c.symmetry_directions > 0 {
                format!(
                    "{:.4} ({} exact turn symmetr{} deflated)",
                    c.min_reduced_eigenvalue,
                    c.symmetry_directions,
                    if c.symmetry_directions == 1 { "y" } else { "ies" }
                )
            } else if c.second_order_evaluated {
                format!("{:.4}", c.min_reduced_eigenvalue)
            } else {
                "not evaluated".to_string()
            },
            c.multipliers.len(),
            if c.multipliers_complete { "" } else { " (more than listed)" }
        );
        for unmet in s.unmet.named() {
            println!("  cannot be met        {}", describe_unmet(unmet));
        }
        if s.unmet.truncated {
            println!("  cannot be met        (more, with smaller shortfalls)");
        }
        println!("  solve time           {:.3} ms", solve_time_s * 1e3);
    }
    Ok(exit_code(s.info.status.is_usable()))
}

/// The least continuous separation and its pair (numbered from 1) for a one-line summary, or
/// "none" with one spacecraft: the CLI's plot titles and the harness's result lines.
pub fn least_separation(s: &Solution) -> String {
    s.min_separation_lu.map_or_else(
        || "none".to_owned(),
        |d| {
            format!(
                "{d:.4} (sats {}-{})",
                s.min_separation_pair.0 + 1,
                s.min_separation_pair.1 + 1
            )
        },
    )
}

/// One constraint an `Infeasible` answer names, for a person (spacecraft numbered from 1).
pub fn describe_unmet(unmet: &UnmetConstraint) -> String {
    match unmet.constraint {
        ActiveConstraint::KeepOut { pair, time_tu } => format!(
            "keep-out of spacecraft {} and {} at t = {:.4}: {:.3e} LU inside it",
            pair.0 + 1,
            pair.1 + 1,
            time_tu,
            unmet.shortfall
        ),
        ActiveConstraint::Control {
            spacecraft,
            axis,
            node,
            upper,
        } => format!(
            "control bound of spacecraft {}, axis {}, node {} ({}): {:.3e} FU beyond Umax",
            spacecraft + 1,
            ["x", "y", "z"]
                .get(usize::from(axis))
                .copied()
                .unwrap_or("?"),
            node,
            if upper { "upper" } else { "lower" },
            unmet.shortfall
        ),
    }
}
