//! `reconfig truth`: a planner-B plan is flown and reported (exit 0); another planner's
//! fixture, a bad epoch or a bad ballistic coefficient is refused with exit 2 and the value named.

use std::path::{Path, PathBuf};
use std::process::Command;

fn root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("..")
}

fn truth(args: &[&str]) -> (i32, String, String) {
    let out = Command::new(env!("CARGO_BIN_EXE_reconfig"))
        .current_dir(root())
        .arg("truth")
        .args(args)
        .output()
        .expect("run reconfig truth");
    (
        out.status.code().expect("exit code"),
        String::from_utf8_lossy(&out.stdout).to_string(),
        String::from_utf8_lossy(&out.stderr).to_string(),
    )
}

#[test]
fn a_planner_b_plan_is_flown_and_the_same_input_gives_the_same_numbers() {
    let args = ["fixtures/sso-leo-pair-e0-2imp.toml", "--json"];
    let (code, first, err) = truth(&args);
    assert_eq!(code, 0, "{err}");
    let (_, second, _) = truth(&args);
    let strip = |text: &str| -> serde_json::Value {
        let mut v: serde_json::Value = serde_json::from_str(text).expect("json");
        for check in v["checks"].as_array_mut().expect("checks") {
            for model in ["full", "j2_only"] {
                check[model]["time_s"] = serde_json::Value::Null;
            }
        }
        v
    };
    let (a, b) = (strip(&first), strip(&second));
    assert_eq!(a, b, "two runs differ");
    let miss = a["checks"][0]["full"]["target_m"].as_f64().expect("miss");
    // Metres: the planner's J2 mean-element model against the truth over 10 h (docs table).
    assert!(miss > 1.0 && miss < 20.0, "{miss}");
    assert_eq!(a["checks"][0]["status"], "Solved");
}

#[test]
fn inputs_outside_their_range_are_refused_by_name() {
    let (code, _, err) = truth(&["fixtures/huang2012-three-sats-n10.toml"]);
    assert_eq!(code, 2);
    assert!(err.contains("not a planner-B fixture"), "{err}");
    let (code, _, err) = truth(&[
        "fixtures/sso-leo-pair-e0-2imp.toml",
        "--epoch",
        "2025-02-30T25:00:00",
    ]);
    assert_eq!(code, 2);
    assert!(err.contains("hour 25"), "{err}");
    let (code, _, err) = truth(&[
        "fixtures/sso-leo-pair-e0-2imp.toml",
        "--deputy-ballistic-m2-kg",
        "3",
    ]);
    assert_eq!(code, 2);
    assert!(err.contains("--deputy-ballistic-m2-kg 3"), "{err}");
}
