//! `reconfig solve FILE [--json] [--limits FILE]`: solve one fixture of either planner and
//! report. The fixture's `[settings]` (over the defaults) are checked against the same limits
//! as the flight service's (`reconfig_core::limits`) before anything is solved.

use crate::fixture::{self, Fixture};
use crate::limits::LimitsArg;
use anyhow::{Context, Result};
use reconfig_core::limits::LimitViolation;
use reconfig_core::wire::Request;
use serde_json::json;
use std::path::PathBuf;
use std::process::ExitCode;
use std::time::Instant;

/// Exit code: the plan is usable (its status is `Solved`).
pub const EXIT_USABLE: u8 = 0;
/// Exit code: the planner ran but the plan is not usable (any other status).
pub const EXIT_NOT_USABLE: u8 = 1;
/// Exit code: the input was rejected (unreadable fixture, or the planner's `PlanError`).
pub const EXIT_REJECTED: u8 = 2;

/// Arguments of `reconfig solve`.
#[derive(clap::Args, Debug)]
#[command(
    after_help = "Exit codes (every planner): 0 the plan is usable (status Solved); \
1 the planner ran and the plan is not usable (any other status: it is still printed); \
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
    /// GEO tour: override the fixture's mission time, days.
    #[arg(long)]
    pub mission_days: Option<f64>,
}

/// Run `reconfig solve`. Exit codes [`EXIT_USABLE`], [`EXIT_NOT_USABLE`], [`EXIT_REJECTED`]
/// (a fixture that does not load is an error, which `main` turns into 2 as well).
pub fn run(args: &Args) -> Result<ExitCode> {
    let limits = args.limits.load()?;
    let text = std::fs::read_to_string(&args.file)
        .with_context(|| format!("reading {}", args.file.display()))?;
    if fixture::geo_tour::is_geo_tour(&text) {
        let f = fixture::geo_tour::load(&args.file)?;
        let mut problem = f.problem.clone();
        if let Some(days) = args.mission_days {
            problem.mission_time_s = days * fixture::geo_tour::DAY_S;
        }
        let request = Request::GeoTour {
            problem,
            settings: f.settings,
        };
        if let Some(code) = refuse_outside(&limits, &request, &f.name, args.json) {
            return Ok(code);
        }
        return crate::cli::solve_geo_tour::run(&f, args.json, args.mission_days);
    }
    if fixture::leo_tour::is_leo_tour(&text) {
        let f = fixture::leo_tour::load(&args.file)?;
        // Every arc request the tour makes (and those of its sequencing and its schedule) has
        // the fixture's impulse count and settings: the service's check on those.
        let leo = &limits.leo_tour;
        let check = || {
            leo.check_impulses(f.impulses)
                .and_then(|()| leo.check_settings(&f.settings))
                .and_then(|()| {
                    f.sequence.as_ref().map_or(Ok(()), |s| {
                        f.sequence_problem().map_or(Ok(()), |problem| {
                            leo.check_sequence(&problem, &s.settings, &s.arc_settings)
                        })
                    })
                })
                // The schedule's estimates are arc searches too.
                .and_then(|()| {
                    f.schedule
                        .as_ref()
                        .map_or(Ok(()), |s| leo.check_settings(&s.arc_settings))
                })
        };
        if let Some(code) = refuse_if(check, &f.name, args.json) {
            return Ok(code);
        }
        return crate::cli::solve_leo_tour::run(&f, args.json);
    }
    let fixture = fixture::load(&args.file)?;
    // The very check the service's workers run, on the request the service would receive.
    let request = match &fixture {
        Fixture::Pseudospectral(f) => Request::Pseudospectral {
            problem: f.problem.clone(),
            settings: f.settings,
        },
        // In the fixture's own forms when it uses any: the limits check those too.
        Fixture::Impulsive(f) => f.request(),
    };
    if let Some(code) = refuse_outside(&limits, &request, fixture.name(), args.json) {
        return Ok(code);
    }
    match fixture {
        Fixture::Pseudospectral(f) => crate::cli::solve_pseudospectral::run(&f, args.json),
        Fixture::Impulsive(f) => crate::cli::solve_impulsive::run(&f, args.json),
    }
}

/// Report a planner's `PlanError` in the one shape every planner uses and return exit code
/// [`EXIT_REJECTED`].
pub fn report_rejection<E: core::fmt::Debug + core::fmt::Display>(
    name: &str,
    err: &E,
    json_output: bool,
) -> ExitCode {
    if json_output {
        println!(
            "{}",
            json!({ "name": name, "status": "Rejected", "error": format!("{err:?}"), "message": err.to_string() })
        );
    } else {
        println!("{name}: rejected: {err}");
    }
    ExitCode::from(EXIT_REJECTED)
}

/// The limits' verdict on `request`: `None` when it may be solved, else the refusal is
/// reported and its exit code returned (a rejected input).
fn refuse_outside(
    limits: &reconfig_core::limits::Limits,
    request: &Request,
    name: &str,
    json_output: bool,
) -> Option<ExitCode> {
    refuse_if(|| limits.check(request), name, json_output)
}

/// The verdict of a limits `check` (timed): `None` when it passes, else the refusal is
/// reported and its exit code returned.
fn refuse_if(
    check: impl FnOnce() -> Result<(), LimitViolation>,
    name: &str,
    json_output: bool,
) -> Option<ExitCode> {
    let started = Instant::now();
    let checked = check();
    let check_time_s = started.elapsed().as_secs_f64();
    let violation = checked.err()?;
    report_refusal(name, &violation, check_time_s, json_output);
    // A refusal by the limits is a rejected input: the one convention of every planner.
    Some(ExitCode::from(EXIT_REJECTED))
}

fn report_refusal(name: &str, v: &LimitViolation, check_time_s: f64, json_output: bool) {
    if json_output {
        println!(
            "{}",
            json!({
                "name": name,
                "status": "LimitExceeded",
                "setting": v.setting.name(),
                "value": v.value,
                "limit": v.limit,
                "rule": format!("{:?}", v.rule),
                "message": v.to_string(),
                "check_time_s": check_time_s,
            })
        );
    } else {
        println!("{name}: refused, limit exceeded: {v}");
        println!(
            "  nothing was solved; limit check took {:.1} us",
            check_time_s * 1e6
        );
    }
}
