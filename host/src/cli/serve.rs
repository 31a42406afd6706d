//! `reconfig serve --cpus 0,1`: the flight service (runs until SIGTERM / SIGINT).

use crate::harness::{self, service, Instance};
use anyhow::Result;
use std::process::ExitCode;
use std::time::Duration;

/// Arguments of `reconfig serve`.
#[derive(clap::Args, Debug)]
pub struct Args {
    /// CPUs to run on: one solver worker per CPU, pinned to it (e.g. `0,1` or `0-3`).
    #[arg(long, default_value = "0,1")]
    pub cpus: String,
    /// Do not pin the workers (where affinity is not permitted).
    #[arg(long)]
    pub no_pin: bool,
    #[command(flatten)]
    pub instance: Instance,
    #[command(flatten)]
    pub limits: crate::limits::LimitsArg,
    /// Deadline of a request that carries none, ms after the service receives it: a request
    /// still queued then is answered `Expired` without being solved.
    #[arg(long, default_value_t = 5000)]
    pub deadline_ms: u64,
    /// Print the limits in force (the built-in ones, or `--limits FILE` over them) as a limits
    /// file and exit.
    #[arg(long)]
    pub print_limits: bool,
}

/// Run `reconfig serve`.
pub fn run(args: &Args) -> Result<ExitCode> {
    if args.print_limits {
        print!("{}", toml::to_string(&args.limits.load()?)?);
        return Ok(ExitCode::SUCCESS);
    }
    let opts = service::ServiceOptions {
        instance: args.instance.clone(),
        cpus: harness::parse_cpus(&args.cpus)?,
        no_pin: args.no_pin,
        limits: args.limits.load()?,
        default_deadline: Duration::from_millis(args.deadline_ms),
    };
    service::run(&opts)?;
    Ok(ExitCode::SUCCESS)
}
