//! `reconfig solve FILE [--json] [--limits FILE]`: answer one fixture of any planner and
//! report. The fixture's requests ([`Fixture::requests`]) go through the core's one request
//! path (`wire::answer`: the limits of `--limits` or the built-in ones, the flight service's
//! check, then the planner), and the report is printed from the outcome
//! (`crate::drivers`).

use crate::drivers::answer::{answer, buffers, report_other};
use crate::drivers::{geo_tour, hybrid, impulsive, leo_report, pseudospectral};
use crate::fixture::{self, Fixture};
use crate::limits::LimitsArg;
use anyhow::{bail, Result};
use std::path::PathBuf;
use std::process::ExitCode;

pub use crate::drivers::answer::{EXIT_NOT_USABLE, EXIT_REJECTED, EXIT_USABLE};

/// Arguments of `reconfig solve`.
#[derive(clap::Args, Debug)]
#[command(
    after_help = "Exit codes (every planner): 0 the plan is usable (status Solved, or one \
the planner's docs call usable such as BudgetExhausted { verified: true }; a LEO tour's arcs \
also confirmed by the truth model within 1 m after their re-plan); 1 the planner ran and the \
plan is not usable (any other status: it is still printed), or a LEO tour's truth-model check \
failed (status TruthMissed, naming the arc and the miss); \
2 the input was rejected (fixture unreadable or invalid, the planner's PlanError, or a setting \
outside the limits, which is named)."
)]
pub struct Args {
    /// Fixture file (TOML).
    pub file: PathBuf,
    /// Print one JSON object instead of the readable report.
    #[arg(long)]
    pub json: bool,
    #[command(flatten)]
    pub limits: LimitsArg,
    /// GEO tour: override the fixture's mission time, days (refused for other planners).
    #[arg(long)]
    pub mission_days: Option<f64>,
    #[command(flatten)]
    pub hybrid: HybridOverrides,
}

/// The hybrid transfer's overrides of its fixture (refused for other planners): one fixture
/// gives any case. The shooting still starts from the fixture's costates: far from their
/// design it may not converge, and says so.
#[derive(clap::Args, Debug, Default)]
pub struct HybridOverrides {
    /// Hybrid: the objective, `min-fuel`, `min-energy` or `min-time`.
    #[arg(long)]
    pub objective: Option<String>,
    /// Hybrid: the impulse ratio κ (its start value when free).
    #[arg(long)]
    pub kappa: Option<f64>,
    /// Hybrid: the impulse's phase θ, rad (its start value when free).
    #[arg(long)]
    pub theta_rad: Option<f64>,
    /// Hybrid: the time of flight, days (minimum time: its first guess).
    #[arg(long)]
    pub tf_days: Option<f64>,
    /// Hybrid: the free impulse parameters, comma-separated (`kappa`, `theta`, `kappa,theta`;
    /// `none` frees neither).
    #[arg(long)]
    pub free: Option<String>,
}

impl HybridOverrides {
    fn any(&self) -> bool {
        self.objective.is_some()
            || self.kappa.is_some()
            || self.theta_rad.is_some()
            || self.tf_days.is_some()
            || self.free.is_some()
    }

    /// Apply the overrides to a hybrid fixture.
    ///
    /// # Errors
    /// An unknown objective or free parameter.
    pub fn apply(&self, f: &mut fixture::hybrid::HybridFixture) -> Result<()> {
        let p = &mut f.problem;
        if let Some(o) = &self.objective {
            p.objective = fixture::hybrid::objective(o)?;
        }
        if let Some(k) = self.kappa {
            p.kappa = k;
        }
        if let Some(t) = self.theta_rad {
            p.theta_rad = t;
        }
        if let Some(d) = self.tf_days {
            p.duration_days = d;
        }
        if let Some(free) = &self.free {
            let names: Vec<String> = free
                .split(',')
                .map(|n| n.trim().to_owned())
                .filter(|n| n != "none")
                .collect();
            (p.free_kappa, p.free_theta) = fixture::hybrid::free(&names)?;
        }
        Ok(())
    }
}

/// Run `reconfig solve`. Exit codes [`EXIT_USABLE`], [`EXIT_NOT_USABLE`], [`EXIT_REJECTED`]
/// (a fixture that does not load is an error, which `main` turns into 2 as well).
pub fn run(args: &Args) -> Result<ExitCode> {
    let limits = args.limits.load()?;
    let mut fixture = fixture::load(&args.file)?;
    if let Some(days) = args.mission_days {
        // Only a GEO tour has a mission time; any other fixture refuses the flag rather than
        // plan as if it had been applied.
        let Fixture::GeoTour(f) = &mut fixture else {
            bail!(
                "--mission-days applies to geo-tour fixtures; {} is a {} fixture",
                fixture.name(),
                fixture.planner()
            );
        };
        f.problem.mission_time_s = days * fixture::geo_tour::DAY_S;
    }
    if args.hybrid.any() {
        let Fixture::Hybrid(f) = &mut fixture else {
            bail!(
                "--objective, --kappa, --theta-rad, --tf-days and --free apply to hybrid \
                 fixtures; {} is a {} fixture",
                fixture.name(),
                fixture.planner()
            );
        };
        args.hybrid.apply(f)?;
    }
    // A LEO tour stands for several requests, answered in turn by its driver.
    if let Fixture::LeoTour(f) = &fixture {
        return leo_report::run(f, &limits, args.json);
    }
    let requests = fixture.requests()?;
    let [request] = &requests[..] else {
        bail!(
            "{} stands for {} requests, not one",
            fixture.name(),
            requests.len()
        );
    };
    let mut buffers = buffers();
    let answered = answer(&request.request, &limits, &mut *buffers);
    // The planner's own report; a kind without one prints its outcome as the wire carries it.
    match &fixture {
        Fixture::Pseudospectral(f) => pseudospectral::report(f, &answered, args.json),
        Fixture::Impulsive(f) => impulsive::report(f, &answered, args.json),
        Fixture::GeoTour(f) => geo_tour::report(f, &answered, args.json),
        Fixture::Hybrid(f) => hybrid::report(f, &answered, args.json),
        _ => report_other(fixture.name(), &answered, args.json),
    }
}
