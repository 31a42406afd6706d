//! Write the README's timing figures from criterion's last measurements.
//!
//! Run the benches first, then this, on the machine the figures describe:
//! ```text
//! cargo bench -p reconfig-host --bench pseudospectral --bench impulsive --bench geo_tour
//! cargo run --release -p reconfig-host --example record_timings
//! ```
//! Each figure is the median of criterion's samples (`target/criterion/GROUP/ID/new/
//! estimates.json`), written to `fixtures/golden/figures/` (timings are never written by a
//! test: machines are shared and loaded).

use anyhow::{anyhow, Context, Result};
use reconfig_host::figure_record::{root, write, Figure};

/// Criterion's median of benchmark `id` (its folder under `target/criterion`), seconds.
fn median_s(id: &str) -> Result<f64> {
    let path = root()
        .join("target/criterion")
        .join(id)
        .join("new/estimates.json");
    let text = std::fs::read_to_string(&path)
        .with_context(|| format!("{}: run the benches first", path.display()))?;
    let json: serde_json::Value = serde_json::from_str(&text)?;
    json["median"]["point_estimate"]
        .as_f64()
        .map(|ns| ns * 1e-9)
        .ok_or_else(|| anyhow!("{}: no median", path.display()))
}

fn main() -> Result<()> {
    let bench = |name: &str| format!("cargo bench -p reconfig-host --bench {name}");

    let paper = median_s("pseudospectral/huang2012-three-sats-n10")?;
    write(
        "a-wall-time",
        &Figure {
            what: "A: wall time, paper case (criterion median)".into(),
            target: "≤ 0.35 ms".into(),
            measured: format!("{:.3} ms", paper * 1e3),
            met: paper <= 0.35e-3,
            doc: "planner-a".into(),
            command: bench("pseudospectral"),
        },
    )
    .map_err(|e| anyhow!(e))?;

    let fixed = median_s("fixed_point_3imp_min_norm")?;
    let search = median_s("search/4imp")?;
    write(
        "b-timing",
        &Figure {
            what: "B: fixed-point minimum-norm solve / search at 4 impulses (criterion median)"
                .into(),
            target: "< 20 µs / < 1 s".into(),
            measured: format!("{:.1} µs / {:.1} ms", fixed * 1e6, search * 1e3),
            met: fixed < 20e-6 && search < 1.0,
            doc: "planner-b".into(),
            command: bench("impulsive"),
        },
    )
    .map_err(|e| anyhow!(e))?;

    let geo = median_s("geo_tour/geo-servicing-16-targets_as-given")?;
    write(
        "geo-timing",
        &Figure {
            what: "GEO: solve time, 16 clients (criterion median)".into(),
            target: "≤ 2 ms (issue 31; 1 ms before)".into(),
            measured: format!("{:.3} ms", geo * 1e3),
            met: geo <= 2e-3,
            doc: "geo-tour".into(),
            command: bench("geo_tour"),
        },
    )
    .map_err(|e| anyhow!(e))?;
    println!(
        "timing figures written to {}",
        reconfig_host::figure_record::DIR
    );
    Ok(())
}
