//! `reconfig reconverge [FIXTURE] [--cases N] [--record]`: the hybrid planner's on-board
//! re-convergence over families of perturbations of a ground design (issue 30): navigation
//! updates of the departure of four sizes, changed times of flight, derated engines. Each
//! family is a campaign of the fixture (`crate::campaign`: seeded, each case answered through
//! the one request path on one thread), and its row says how many cases ended `Solved`, the
//! statuses of the others, and the work units and times.

use crate::campaign::dispersion::Dispersion;
use crate::campaign::{progress_bar, Campaign, Row};
use crate::table_record::Table;
use anyhow::{bail, Context, Result};
use reconfig_core::limits::Limits;
use std::path::PathBuf;
use std::process::ExitCode;

/// Arguments of `reconfig reconverge`.
#[derive(clap::Args, Debug)]
pub struct Args {
    /// A hybrid fixture whose start is a ground design (with `[departure_offset]` zero).
    #[arg(default_value = "fixtures/hybrid-min-fuel-k140-4p38d.toml")]
    pub fixture: PathBuf,
    /// Cases per family.
    #[arg(long, default_value_t = 100)]
    pub cases: u64,
    /// Write the table as the record `fixtures/golden/tables/hybrid-reconvergence.md`
    /// (docs/hybrid.md shows it).
    #[arg(long)]
    pub record: bool,
    /// Added to every family's seed: other draws of the same families (the record is taken
    /// at 0; a change tuned on it is measured again at another shift).
    #[arg(long, default_value_t = 0)]
    pub seed_shift: u64,
}

/// One family: its name, its seed and its dispersions (`PATH=SIGMA`, or `PATH=LOW:HIGH`
/// uniform).
struct Family {
    name: String,
    seed: u64,
    gaussian: Vec<String>,
    uniform: Vec<String>,
}

/// The families: navigation updates of four sizes (a normal deviate per axis of position and
/// velocity), times of flight, and derated engines.
fn families() -> Vec<Family> {
    let mut out = Vec::new();
    for (position_km, velocity_mps) in [(0.1, 0.01), (1.0, 0.1), (3.0, 0.3), (10.0, 1.0)] {
        let mut gaussian = Vec::new();
        for axis in 0..3 {
            gaussian.push(format!(
                "departure_offset.position_km[{axis}]={position_km}"
            ));
        }
        for axis in 0..3 {
            gaussian.push(format!(
                "departure_offset.velocity_mps[{axis}]={velocity_mps}"
            ));
        }
        out.push(Family {
            name: format!("navigation: {position_km} km and {velocity_mps} m/s (sigma per axis)"),
            seed: 30,
            gaussian,
            uniform: Vec::new(),
        });
    }
    for sigma_days in [0.05, 0.2, 0.5] {
        out.push(Family {
            name: format!("time of flight: sigma {sigma_days} d"),
            seed: 31,
            gaussian: vec![format!("duration_days={sigma_days}")],
            uniform: Vec::new(),
        });
    }
    for low_n in [9.5, 9.0, 8.0] {
        out.push(Family {
            name: format!("thrust derated: uniform {low_n} to 10 N"),
            seed: 32,
            gaussian: Vec::new(),
            uniform: vec![format!("thrust_n={low_n}:10.0")],
        });
    }
    out
}

/// The median and the largest of `values` (sorted in place); `(0, 0)` when empty.
fn median_max(values: &mut [f64]) -> (f64, f64) {
    values.sort_by(f64::total_cmp);
    let median = values.get(values.len() / 2).copied();
    let max = values.last().copied();
    (median.unwrap_or_default(), max.unwrap_or_default())
}

/// A family's row.
fn row(name: &str, rows: &[Row]) -> Vec<String> {
    let solved = rows.iter().filter(|r| r.status == "Solved").count();
    let mut others = std::collections::BTreeMap::<&str, usize>::new();
    for r in rows.iter().filter(|r| r.status != "Solved") {
        *others.entry(r.status.as_str()).or_default() += 1;
    }
    let others = if others.is_empty() {
        "—".to_owned()
    } else {
        others
            .iter()
            .map(|(k, n)| format!("{n} {k}"))
            .collect::<Vec<_>>()
            .join(", ")
    };
    let mut work: Vec<f64> = rows
        .iter()
        .filter_map(|r| r.work_units.map(|w| w as f64))
        .collect();
    let (work_median, work_max) = median_max(&mut work);
    let mut times: Vec<f64> = rows.iter().map(|r| r.solve_time_s * 1e3).collect();
    let (time_median, time_max) = median_max(&mut times);
    vec![
        name.to_owned(),
        format!("{solved} / {}", rows.len()),
        others,
        format!("{work_median:.0} / {work_max:.0}"),
        format!("{time_median:.1} / {time_max:.1}"),
    ]
}

/// Run `reconfig reconverge`.
///
/// # Errors
/// The fixture cannot be read or is not a single-request fixture; a record cannot be written.
pub fn run(args: &Args) -> Result<ExitCode> {
    let text = std::fs::read_to_string(&args.fixture)
        .with_context(|| format!("cannot read {}", args.fixture.display()))?;
    if args.record && args.seed_shift != 0 {
        bail!("--record: the record is the families' own seeds (--seed-shift 0)");
    }
    let name = args.fixture.display().to_string();
    let mut table = Table::new(
        &[
            "family",
            "Solved",
            "other statuses",
            "work units, median / max",
            "solve time (ms), median / max",
        ],
        "lrlrr",
    );
    for family in families() {
        let mut dispersions = Vec::new();
        for g in &family.gaussian {
            dispersions.push(Dispersion::gaussian(g)?);
        }
        for u in &family.uniform {
            dispersions.push(Dispersion::uniform(u)?);
        }
        let campaign = Campaign::new(
            &name,
            &text,
            dispersions,
            family.seed.saturating_add(args.seed_shift),
            args.cases,
            Limits::default(),
        )?;
        let rows = campaign.run(1, &progress_bar(args.cases, false))?;
        let cells = row(&family.name, &rows);
        println!("{}", cells.join(" | "));
        table.push(cells);
    }
    if args.record {
        crate::table_record::write_reconfig(
            "hybrid-reconvergence",
            &format!(
                "reconverge {} --cases {} --record",
                args.fixture.display(),
                args.cases
            ),
            "The hybrid planner re-converging a ground design on board: each family a seeded \
             campaign of the fixture (seed 30 navigation, 31 time of flight, 32 thrust), every \
             case answered through the one request path with the default settings (work \
             budget 100,000 step trials, a walk of at most 32 shootings from the design) on \
             one thread; `Solved` is checked (residual and H drift within 1e-10, the check \
             flight within 1e-9).",
            &[&table],
        )?;
    }
    Ok(ExitCode::SUCCESS)
}
