//! The record of the truth-model check over planner B's fixtures
//! (`fixtures/golden/truth-planner-b.json`, written by `reconfig truth --record`) and the table
//! of `docs/truth-model.md` generated from it (`tests/tests/truth_docs.rs` fails when they
//! differ, and when a fresh check drifts from the record).

use super::plan_check::{PlanCheck, TruthSettings};
use anyhow::{bail, Context, Result};
use serde_json::{json, Value};

/// The record, relative to the repository's root.
pub const RECORD_FILE: &str = "fixtures/golden/truth-planner-b.json";
/// The document holding the generated table.
pub const DOCS_FILE: &str = "docs/truth-model.md";
/// Marker lines around the generated table.
pub const BEGIN: &str =
    "<!-- truth-planner-b table: generated from fixtures/golden/truth-planner-b.json -->";
/// End marker.
pub const END: &str = "<!-- end of the generated truth-planner-b table -->";
/// The command that rewrites the record (the fixtures: every planner-B fixture in `fixtures/`).
pub const RECORD_COMMAND: &str =
    "cargo run --release -p reconfig-host --bin reconfig -- truth --record fixtures/golden/truth-planner-b.json $(grep -l 'planner = \"impulsive\"' fixtures/*.toml)";
/// The command that rewrites the docs table from the record.
pub const UPDATE_DOCS_COMMAND: &str =
    "RECONFIG_UPDATE_DOCS=1 cargo test -p reconfig-tests --test truth_docs";

/// The record's JSON of `checks` made with `settings` and the model described by `model`.
pub fn to_record(settings: &TruthSettings, model: &str, checks: &[PlanCheck]) -> Value {
    json!({
        "_comment": "Truth-model check of planner B's plans: written by `reconfig truth --record`; \
                     docs/truth-model.md's table is generated from it. Times are host wall times \
                     (not compared by the drift test).",
        "command": RECORD_COMMAND,
        "epoch_jd_tt": settings.epoch_jd,
        "chief_ballistic_m2_kg": settings.chief_ballistic_m2_kg,
        "deputy_ballistic_m2_kg": settings.deputy_ballistic_m2_kg,
        "model": model,
        "checks": checks,
    })
}

fn f(v: &Value, key: &str) -> Result<f64> {
    v[key]
        .as_f64()
        .with_context(|| format!("record: {key} is not a number"))
}

fn triple(v: &Value) -> Result<[f64; 3]> {
    let a = v.as_array().context("record: expected an array of 3")?;
    if a.len() != 3 {
        bail!("record: expected an array of 3");
    }
    let mut out = [0.0; 3];
    for (o, x) in out.iter_mut().zip(a.iter()) {
        *o = x.as_f64().context("record: not a number")?;
    }
    Ok(out)
}

/// The markdown table of a record.
///
/// # Errors
/// A record without the fields [`to_record`] writes.
pub fn render(record: &Value) -> Result<String> {
    let checks = record["checks"].as_array().context("record: no checks")?;
    let mut out = String::new();
    out.push_str(&format!(
        "Model: {}; epoch JD {} TT; Cd A/m {} (chief) / {} (deputy) m^2/kg.\n\n",
        record["model"].as_str().context("record: model")?,
        f(record, "epoch_jd_tt")?,
        f(record, "chief_ballistic_m2_kg")?,
        f(record, "deputy_ballistic_m2_kg")?,
    ));
    out.push_str(
        "| fixture | status | dv [m/s] | flight [h] | miss vs target, full model [m] (R, T, N) | velocity miss [mm/s] | miss vs target, J2 only [m] | truth - planner's J2 model, relative position [m] (full / J2 only) | deputy full - J2 only, absolute [km] | host ms per day of flight, chief / deputy (full) |\n",
    );
    out.push_str("| --- | --- | ---: | ---: | --- | ---: | ---: | ---: | ---: | ---: |\n");
    for c in checks {
        let full = &c["full"];
        let j2 = &c["j2_only"];
        let r = triple(&full["target_rtn_m"])?;
        let v = triple(&full["target_vel_rtn_mm_s"])?;
        let t = triple(
            &[
                full["time_s"][0].clone(),
                full["time_s"][1].clone(),
                json!(0.0),
            ]
            .into(),
        )?;
        let days = f(c, "final_time_s")? / 86_400.0;
        out.push_str(&format!(
            "| `{}` | {} | {:.5} | {:.2} | {:.1} ({:.1}, {:.1}, {:.1}) | {:.1} | {:.2} | {:.1} / {:.2} | {:.3} | {:.0} / {:.0} |\n",
            c["name"].as_str().context("record: name")?,
            c["status"].as_str().context("record: status")?,
            f(c, "total_dv_mps")?,
            f(c, "final_time_s")? / 3600.0,
            f(full, "target_m")?,
            r[0],
            r[1],
            r[2],
            (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt(),
            f(j2, "target_m")?,
            f(full, "j2_model_m")?,
            f(j2, "j2_model_m")?,
            f(c, "deputy_full_minus_j2_only_m")? / 1e3,
            t[0] * 1e3 / days,
            t[1] * 1e3 / days,
        ));
    }
    Ok(out)
}

/// `docs` with the text between [`BEGIN`] and [`END`] replaced by `table`.
///
/// # Errors
/// The markers are missing or out of order.
pub fn splice(docs: &str, table: &str) -> Result<String> {
    let begin = docs.find(BEGIN).context("docs: no begin marker")?;
    let after_begin = begin + BEGIN.len();
    let end = docs[after_begin..]
        .find(END)
        .map(|k| k + after_begin)
        .context("docs: no end marker after the begin marker")?;
    Ok(format!(
        "{}\n{}{}",
        &docs[..after_begin],
        table,
        &docs[end..]
    ))
}
