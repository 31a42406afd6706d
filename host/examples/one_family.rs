//! Solve one problem of the generated families (`reconfig sweep`'s file,
//! `fixtures/generated/planner-a-families.jsonl`) and print its status, cost, least separation
//! and, for an `Infeasible` answer, the constraints it names:
//! `cargo run --release -p reconfig-host --example one_family -- INDEX [WORK_BUDGET [QP_MAX_ITER]]`
//! (`PROBLEMS=FILE` for another file of the same form, e.g. `reconfig sweep --set tuning --write FILE`).
use reconfig_core::pseudospectral::{self, Settings, Solution, Workspace};
use reconfig_host::drivers::sweep_oracle;
use std::path::Path;

fn main() -> anyhow::Result<()> {
    let mut args = std::env::args().skip(1);
    let index: usize = args.next().unwrap_or_else(|| "0".into()).parse()?;
    // `PROBLEMS` names another file of the same form (`reconfig sweep --write`).
    let path = std::env::var("PROBLEMS").unwrap_or_else(|_| sweep_oracle::PROBLEMS_DEFAULT.into());
    let problems = sweep_oracle::load_problems(Path::new(&path))?;
    let (family, problem) = problems
        .get(index)
        .ok_or_else(|| anyhow::anyhow!("no problem {index}"))?;
    let mut settings = Settings::default();
    if let Some(budget) = args.next() {
        settings.work_budget = budget.parse()?;
    }
    if let Some(qp) = args.next() {
        settings.qp_max_iter = qp.parse()?;
    }
    let mut ws = Box::new(Workspace::new());
    let mut out = Box::new(Solution::new());
    pseudospectral::solve(problem, &settings, &mut ws, &mut out)
        .map_err(|e| anyhow::anyhow!("refused: {e:?}"))?;
    println!("#{index} ({family}): {:?} J = {:.6} min sep {:.6?} (pair {:?}, t {:.4}) subproblems {} elastic {}",
        out.info.status, out.cost, out.min_separation_lu, out.min_separation_pair, out.min_separation_time_tu,
        out.info.sqp_iterations, out.info.elastic_subproblems);
    for c in out.unmet.named() {
        println!("  unmet: {:?}, shortfall {:.3e}", c.constraint, c.shortfall);
    }
    Ok(())
}
