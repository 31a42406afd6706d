//! `reconfig plot FILE -o out.svg`: solve a fixture and draw the plan.

use crate::fixture::{self, Fixture};
use crate::plot;
use anyhow::{bail, Result};
use reconfig_core::pseudospectral;
use std::path::PathBuf;
use std::process::ExitCode;

/// Arguments of `reconfig plot`.
#[derive(clap::Args, Debug)]
pub struct Args {
    /// Fixture file (TOML), or `wang2018` for the built-in published planner-B case.
    pub file: PathBuf,
    /// Output SVG file.
    #[arg(short, long, default_value = "plan.svg")]
    pub output: PathBuf,
    /// Planner A: draw the unconstrained minimum-energy guess (cubics, no keep-out) instead of
    /// failing when the solver rejects the problem or is not built.
    #[arg(long)]
    pub guess: bool,
}

/// Run `reconfig plot`.
pub fn run(args: &Args) -> Result<ExitCode> {
    if args.file.as_os_str() == "wang2018" {
        let p = crate::scenario::wang2018_table2();
        plot::impulsive_svg(
            &p,
            "Wang 2018 published case (Table 2 impulse points): formations in the chief's RTN frame",
            &args.output,
        )?;
        println!("wrote {}", args.output.display());
        return Ok(ExitCode::SUCCESS);
    }
    match fixture::load(&args.file)? {
        Fixture::Pseudospectral(f) => {
            let mut workspace = Box::new(pseudospectral::Workspace::new());
            let mut solution = Box::new(pseudospectral::Solution::new());
            let result = pseudospectral::solve(
                &f.problem,
                &pseudospectral::Settings::default(),
                &mut workspace,
                &mut solution,
            );
            let (solution, what) = match result {
                Ok(()) => {
                    let what = format!(
                        "{}: {:?}, J = {:.4}, min separation {:.4} (sats {}-{})",
                        f.name,
                        solution.info.status,
                        solution.cost,
                        solution.min_separation_lu,
                        solution.min_separation_pair.0 + 1,
                        solution.min_separation_pair.1 + 1
                    );
                    (solution, what)
                }
                Err(e) if args.guess => {
                    let g = Box::new(plot::unconstrained_guess(&f.problem));
                    let what = format!(
                        "{}: unconstrained guess (solver: {e}), J = {:.4}, min separation {:.4} (sats {}-{})",
                        f.name,
                        g.cost,
                        g.min_separation_lu,
                        g.min_separation_pair.0 + 1,
                        g.min_separation_pair.1 + 1
                    );
                    (g, what)
                }
                Err(e) => bail!("{}: the solver rejected the problem: {e} (--guess draws the unconstrained guess)", f.name),
            };
            plot::pseudospectral_svg(&f.problem, &solution, &what, &args.output)?;
        }
        Fixture::Impulsive(f) => plot::impulsive_svg(&f.problem, &f.name, &args.output)?,
    }
    println!("wrote {}", args.output.display());
    Ok(ExitCode::SUCCESS)
}
