//! `reconfig truth FIXTURE...`: plan each planner-B fixture and fly the plan in the truth model
//! (`crate::truth`): the deputy's miss against the target formation and against the planner's
//! J2 model, in the full model and with J2 alone, and the propagation time.

use crate::fixture::{self, Fixture};
use crate::truth::epoch::parse_tt_jd;
use crate::truth::plan_check::{check, full_model, PlanCheck, TruthSettings};
use crate::truth::record::to_record;
use anyhow::{anyhow, bail, Context, Result};
use std::path::PathBuf;
use std::process::ExitCode;

/// Arguments of `reconfig truth`.
#[derive(clap::Args, Debug)]
pub struct Args {
    /// Planner-B fixture files (TOML).
    #[arg(required = true)]
    pub files: Vec<PathBuf>,
    /// Print one JSON object (the record) instead of the readable report.
    #[arg(long)]
    pub json: bool,
    /// The plan's epoch (t = 0), TT: YYYY-MM-DDTHH:MM:SS[.fff] (no zone).
    #[arg(long, default_value = "2025-01-01T00:00:00")]
    pub epoch: String,
    /// The chief's ballistic coefficient Cd A / m, m^2/kg.
    #[arg(long, default_value_t = 0.022)]
    pub chief_ballistic_m2_kg: f64,
    /// The deputy's ballistic coefficient Cd A / m, m^2/kg.
    #[arg(long, default_value_t = 0.022)]
    pub deputy_ballistic_m2_kg: f64,
    /// Also write the record (JSON) to this file.
    #[arg(long)]
    pub record: Option<PathBuf>,
}

/// Parse `--epoch` (TT, `YYYY-MM-DDTHH:MM:SS[.fff]`, `truth::epoch`) into a Julian date.
///
/// # Errors
/// Another form, or a field out of its range (named).
pub fn parse_epoch(text: &str) -> Result<f64> {
    parse_tt_jd(text).map_err(|e| anyhow!("--epoch {text:?} {e}"))
}

fn check_ballistic(name: &str, value: f64) -> Result<()> {
    // 0 (no drag) to 1 m^2/kg (a sheet of foil): outside is a typing error.
    if !(0.0..=1.0).contains(&value) {
        bail!("--{name} {value} m^2/kg outside [0, 1]");
    }
    Ok(())
}

/// Run `reconfig truth`. Exit 0 when every plan was checked, 2 on an input error.
pub fn run(args: &Args) -> Result<ExitCode> {
    check_ballistic("chief-ballistic-m2-kg", args.chief_ballistic_m2_kg)?;
    check_ballistic("deputy-ballistic-m2-kg", args.deputy_ballistic_m2_kg)?;
    let settings = TruthSettings {
        epoch_jd: parse_epoch(&args.epoch)?,
        chief_ballistic_m2_kg: args.chief_ballistic_m2_kg,
        deputy_ballistic_m2_kg: args.deputy_ballistic_m2_kg,
    };
    let mut checks: Vec<PlanCheck> = Vec::new();
    for path in &args.files {
        let Fixture::Impulsive(f) = fixture::load(path)? else {
            bail!("{}: not a planner-B fixture", path.display());
        };
        checks.push(check(&f, &settings)?);
    }
    let model = full_model(&settings, settings.chief_ballistic_m2_kg)?.describe();
    let model = format!("{model}; Dormand-Prince 5(4), relative tolerance 1e-12, absolute 1e-9 km");
    let record = to_record(&settings, &model, &checks);
    if let Some(path) = &args.record {
        std::fs::write(path, serde_json::to_string_pretty(&record)? + "\n")
            .with_context(|| format!("writing {}", path.display()))?;
    }
    if args.json {
        println!("{}", serde_json::to_string_pretty(&record)?);
        return Ok(ExitCode::SUCCESS);
    }
    println!("truth model: {model}");
    println!(
        "epoch JD {} TT, Cd A/m {} (chief) / {} (deputy) m^2/kg",
        settings.epoch_jd, settings.chief_ballistic_m2_kg, settings.deputy_ballistic_m2_kg
    );
    for c in &checks {
        println!(
            "{}: {} dv {:.5} m/s, last impulse at {:.1} s (planner's own miss {})",
            c.name,
            c.status,
            c.total_dv_mps,
            c.final_time_s,
            c.planner_terminal_error_m
                .map_or_else(|| "absent".to_string(), |m| format!("{m:.2e} m"))
        );
        for (label, m) in [("full model", &c.full), ("J2 only   ", &c.j2_only)] {
            println!(
                "  {label}: miss vs target {:.2} m (R {:.2}, T {:.2}, N {:.2}), velocity {:.2} mm/s; \
                 vs the planner's J2 model {:.2} m; chief {} steps {:.1} ms, deputy {} steps {:.1} ms",
                m.target_m,
                m.target_rtn_m[0],
                m.target_rtn_m[1],
                m.target_rtn_m[2],
                m.target_vel_rtn_mm_s.iter().map(|x| x * x).sum::<f64>().sqrt(),
                m.j2_model_m,
                m.steps[0],
                m.time_s[0] * 1e3,
                m.steps[1],
                m.time_s[1] * 1e3
            );
        }
    }
    Ok(ExitCode::SUCCESS)
}

#[cfg(test)]
#[allow(clippy::unwrap_used)]
mod tests {
    use super::*;

    #[test]
    fn epochs_parse_and_bad_ones_are_named() {
        assert_eq!(parse_epoch("2000-01-01T12:00:00").unwrap(), 2_451_545.0);
        let err = parse_epoch("2025-13-01T00:00:00").unwrap_err().to_string();
        assert!(err.contains("month 13"), "{err}");
        assert!(parse_epoch("2025-01-01").is_err());
        let err = parse_epoch("2025-02-29T00:00:00").unwrap_err().to_string();
        assert!(err.contains("day 29 outside [1, 28]"), "{err}");
        assert!(parse_epoch("2024-02-29T00:00:00").is_ok());
        let err = check_ballistic("deputy-ballistic-m2-kg", -1.0)
            .unwrap_err()
            .to_string();
        assert!(err.contains("deputy-ballistic-m2-kg -1"), "{err}");
    }
}
