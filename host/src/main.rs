//! `reconfig`: the command-line entry point.

use clap::{Parser, Subcommand};
use std::process::ExitCode;

#[global_allocator]
static ALLOCATOR: reconfig_host::harness::alloc_count::CountingAllocator =
    reconfig_host::harness::alloc_count::CountingAllocator;

#[derive(Parser)]
#[command(
    name = "reconfig",
    version,
    about = "On-board formation reconfiguration planner: host tools"
)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand)]
enum Command {
    /// Solve one fixture and print a report (or JSON).
    Solve(reconfig_host::cli::solve::Args),
    /// A Monte Carlo campaign of one fixture: dispersed cases answered in parallel on every
    /// core, a CSV row per case.
    Campaign(reconfig_host::cli::campaign::Args),
    /// Reproduce Huang 2012 Table 2: random initial guesses, with and without test points.
    Montecarlo(reconfig_host::cli::montecarlo::Args),
    /// The main job: start the flight service, feed it every fixture, the fault set and
    /// generated scenarios, check every answer, print results and timing, stop the service.
    Demo(reconfig_host::cli::demo::Args),
    /// Run the flight service (iceoryx2) until SIGTERM / SIGINT.
    Serve(reconfig_host::cli::serve::Args),
    /// Feed a running flight service and report answers and timing.
    Feed(reconfig_host::cli::feed::Args),
    /// Draw a plan (SVG): trajectories, separations and controls, or relative motion.
    Plot(reconfig_host::cli::plot::Args),
    /// Two feeders at once (expensive + cheap, then two alike) against one flight service.
    Fairness(reconfig_host::cli::fairness::Args),
    /// Where the service's workers and the feeder should sit: round trips per placement.
    Placement(reconfig_host::cli::placement::Args),
    /// Planner A over seeded generated problems: the six families (default) or the tuning or
    /// held-out set of the kinds, a table row per family or kind.
    Sweep(reconfig_host::cli::sweep::Args),
    /// Planner-B fixtures: fly the plan in the high-fidelity truth model and report the miss.
    Truth(reconfig_host::cli::truth::Args),
    /// The hybrid transfer's on-board re-convergence over families of perturbations of a
    /// ground design (navigation updates, times of flight, derated engines).
    Reconverge(reconfig_host::cli::reconverge::Args),
    /// The hybrid transfer's continuation from a fixture's design: walk t_f or kappa, print
    /// each point and draw the (t_f, m_f) curve.
    Pareto(reconfig_host::cli::pareto::Args),
}

/// A report command whose reader stops early (`reconfig solve … | head`) ends quietly, as Unix
/// tools do, instead of panicking on the broken pipe (exit 101): SIGPIPE gets its default
/// action back (Rust's runtime ignores it). Not for the flight service, its feeders and the
/// demo, which must outlive a peer that goes away.
fn end_quietly_on_a_closed_pipe() {
    // SAFETY: `signal` with a valid signal number and the default action, before any thread
    // of ours starts; no handler runs Rust code.
    unsafe {
        libc::signal(libc::SIGPIPE, libc::SIG_DFL);
    }
}

fn main() -> ExitCode {
    let cli = Cli::parse();
    if matches!(
        cli.command,
        Command::Solve(_)
            | Command::Campaign(_)
            | Command::Montecarlo(_)
            | Command::Plot(_)
            | Command::Sweep(_)
            | Command::Truth(_)
            | Command::Reconverge(_)
            | Command::Pareto(_)
    ) {
        end_quietly_on_a_closed_pipe();
    }
    // iceoryx2 logs warnings such as "no config file was loaded" (none is needed); keep the
    // output for errors unless RUST_LOG-style IOX2_LOG_LEVEL asks for more.
    iceoryx2::prelude::set_log_level_from_env_or(iceoryx2::prelude::LogLevel::Error);
    let result = match cli.command {
        Command::Solve(args) => reconfig_host::cli::solve::run(&args),
        Command::Montecarlo(args) => reconfig_host::cli::montecarlo::run(&args),
        Command::Campaign(args) => reconfig_host::cli::campaign::run(&args),
        Command::Demo(args) => reconfig_host::cli::demo::run(&args),
        Command::Serve(args) => reconfig_host::cli::serve::run(&args),
        Command::Feed(args) => reconfig_host::cli::feed::run(&args),
        Command::Plot(args) => reconfig_host::cli::plot::run(&args),
        Command::Fairness(args) => reconfig_host::cli::fairness::run(&args),
        Command::Placement(args) => reconfig_host::cli::placement::run(&args),
        Command::Sweep(args) => reconfig_host::cli::sweep::run(&args),
        Command::Truth(args) => reconfig_host::cli::truth::run(&args),
        Command::Reconverge(args) => reconfig_host::cli::reconverge::run(&args),
        Command::Pareto(args) => reconfig_host::cli::pareto::run(&args),
    };
    match result {
        Ok(code) => code,
        Err(err) => {
            eprintln!("error: {err:#}");
            ExitCode::from(2)
        }
    }
}
