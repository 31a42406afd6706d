//! `docs/truth-model.md`'s table of the truth-model check of planner B's plans is generated from
//! the record `fixtures/golden/truth-planner-b.json` (written by `reconfig truth --record`):
//! this fails when the docs differ from the record, and when a fresh check of every fixture in
//! the record drifts from it (the check is deterministic: same input, same numbers).

use reconfig_host::fixture::{self, Fixture};
use reconfig_host::truth::plan_check::{check, TruthSettings};
use reconfig_host::truth::record::{
    render, splice, DOCS_FILE, RECORD_COMMAND, RECORD_FILE, UPDATE_DOCS_COMMAND,
};
use serde_json::Value;
use std::path::PathBuf;

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("..")
}

fn record() -> Value {
    let text = std::fs::read_to_string(root().join(RECORD_FILE)).expect("record");
    serde_json::from_str(&text).expect("record JSON")
}

#[test]
fn the_docs_table_is_the_record() {
    let docs_path = root().join(DOCS_FILE);
    let docs = std::fs::read_to_string(&docs_path).expect("docs");
    let table = render(&record()).expect("render");
    let expected = splice(&docs, &table).expect("markers");
    if std::env::var("RECONFIG_UPDATE_DOCS").as_deref() == Ok("1") && expected != docs {
        std::fs::write(&docs_path, &expected).expect("write the docs");
        return;
    }
    assert!(
        expected == docs,
        "{DOCS_FILE} differs from what {RECORD_FILE} generates; regenerate with\n  {UPDATE_DOCS_COMMAND}"
    );
}

fn close(what: &str, name: &str, got: f64, want: f64) {
    // Same machine, same bits; 1 micrometre (and 1e-9 relative) leaves room for another libm.
    assert!(
        (got - want).abs() <= 1e-6 + 1e-9 * want.abs(),
        "{name} {what}: checked {got}, recorded {want}; if the change is meant, rewrite the record:\n  {RECORD_COMMAND}"
    );
}

#[test]
fn a_fresh_check_is_the_record() {
    let rec = record();
    let settings = TruthSettings {
        epoch_jd: rec["epoch_jd_tt"].as_f64().expect("epoch"),
        chief_ballistic_m2_kg: rec["chief_ballistic_m2_kg"].as_f64().expect("chief B"),
        deputy_ballistic_m2_kg: rec["deputy_ballistic_m2_kg"].as_f64().expect("deputy B"),
    };
    let checks = rec["checks"].as_array().expect("checks");
    assert!(
        checks.len() >= 12,
        "every planner-B fixture is in the record"
    );
    for recorded in checks {
        let name = recorded["name"].as_str().expect("name");
        let path = root().join("fixtures").join(format!("{name}.toml"));
        let Fixture::Impulsive(f) = fixture::load(&path).expect("fixture") else {
            panic!("{name}: not a planner-B fixture");
        };
        let fresh = serde_json::to_value(check(&f, &settings).expect("check")).expect("json");
        assert_eq!(fresh["status"], recorded["status"], "{name} status");
        for key in [
            "total_dv_mps",
            "final_time_s",
            "deputy_full_minus_j2_only_m",
        ] {
            close(
                key,
                name,
                fresh[key].as_f64().unwrap(),
                recorded[key].as_f64().unwrap(),
            );
        }
        for model in ["full", "j2_only"] {
            for key in [
                "target_rtn_m",
                "target_vel_rtn_mm_s",
                "j2_model_rtn_m",
                "steps",
            ] {
                let (a, b) = (&fresh[model][key], &recorded[model][key]);
                for k in 0..a.as_array().expect("array").len() {
                    close(
                        &format!("{model}.{key}[{k}]"),
                        name,
                        a[k].as_f64().unwrap(),
                        b[k].as_f64().unwrap(),
                    );
                }
            }
        }
    }
}
