//! `reconfig plot FILE -o out.svg`: solve a fixture and draw the plan.

use crate::drivers::pseudospectral::least_separation;
use crate::fixture::{self, Fixture};
use crate::plot;
use anyhow::{bail, Result};
use reconfig_core::{impulsive, pseudospectral};
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
    /// GEO tour: draw total dv against mission time (20-120 d) instead of the tour.
    #[arg(long)]
    pub pareto: bool,
}

/// Run `reconfig plot`.
pub fn run(args: &Args) -> Result<ExitCode> {
    if args.file.as_os_str() == "wang2018" {
        let p = crate::scenario::wang2018_table2();
        impulsive_plot(
            &p,
            "Wang 2018 published case (Table 2 impulse points)",
            &args.output,
        )?;
        println!("wrote {}", args.output.display());
        return Ok(ExitCode::SUCCESS);
    }
    match fixture::load(&args.file)? {
        Fixture::Hybrid(f) => {
            let s = crate::plot_hybrid::transfer_svg(&f, &args.output)?;
            println!(
                "{}: {:?}, {} thrust arcs",
                f.name,
                s.info.status,
                s.flown.map_or(0, |p| p.thrust_arcs)
            );
        }
        Fixture::GeoTour(f) => {
            if args.pareto {
                let days: Vec<f64> = (10..=60).map(|k| f64::from(k) * 2.0).collect();
                for (d, by_cost, by_rule) in crate::plot_geo::pareto_svg(&f, &days, &args.output)? {
                    println!("{d:6.1} d  by cost {by_cost:?}  by rule {by_rule:?}");
                }
            } else {
                crate::plot_geo::tour_svg(&f, &args.output)?;
            }
        }
        Fixture::LeoTour(f) => {
            let drawn = crate::plot_leo::tour_svg(&f, &args.output)?;
            for a in &drawn.arcs {
                println!(
                    "arc {} -> {}: {:?}, {:.3} m/s",
                    a.from + 1,
                    a.to + 1,
                    a.solution.info.status,
                    a.solution.total_dv_mps
                );
            }
        }
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
                        "{}: {:?}, J = {:.4}, min separation {}",
                        f.name,
                        solution.info.status,
                        solution.cost,
                        least_separation(&solution)
                    );
                    (solution, what)
                }
                Err(e) if args.guess => {
                    let g = Box::new(plot::unconstrained_guess(&f.problem));
                    let what = format!(
                        "{}: unconstrained guess (solver: {e}), J = {:.4}, min separation {}",
                        f.name,
                        g.cost,
                        least_separation(&g)
                    );
                    (g, what)
                }
                Err(e) => bail!("{}: the solver rejected the problem: {e} (--guess draws the unconstrained guess)", f.name),
            };
            plot::pseudospectral_svg(&f.problem, &solution, &what, &args.output)?;
        }
        Fixture::Impulsive(f) => impulsive_plot(&f.problem, &f.name, &args.output)?,
    }
    println!("wrote {}", args.output.display());
    Ok(ExitCode::SUCCESS)
}

/// Solve a planner-B problem with the default settings and draw the plan.
fn impulsive_plot(problem: &impulsive::Problem, name: &str, out: &std::path::Path) -> Result<()> {
    let settings = impulsive::Settings::default();
    let mut workspace = Box::new(impulsive::Workspace::new());
    let mut solution = Box::new(impulsive::Solution::new());
    if let Err(e) = impulsive::solve(problem, &settings, &mut workspace, &mut solution) {
        bail!("{name}: the planner rejected the problem: {e}");
    }
    let period_s = std::f64::consts::TAU
        * (problem.chief.sma_km.powi(3) / reconfig_core::astro::EARTH_MU_KM3_S2).sqrt();
    let title = format!(
        "{name}: {:?}, total dv {:.4} m/s, {} impulses, last at {:.2} orbits, terminal position error {}",
        solution.info.status,
        solution.total_dv_mps,
        solution.impulses.len(),
        solution.final_time_s / period_s,
        solution
            .terminal_error
            .map_or_else(|| "absent".to_string(), |t| format!("{:.1e} m", t.position_m)),
    );
    plot::impulsive_svg(problem, &settings, &solution, &title, out)
}
