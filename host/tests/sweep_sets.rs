//! `reconfig sweep --set held-out`: one table row per kind, the problem and answer files in the
//! families' line formats (the oracle reads the problems), the same problems from the same
//! arguments, a `--record` equal to `SetRecord::measure`'s; `--count` is refused with the
//! families.

use reconfig_core::pseudospectral::Settings;
use reconfig_host::drivers::set_record::SetRecord;
use reconfig_host::drivers::sweep_oracle;
use reconfig_host::families::{kinds, sets};
use std::path::PathBuf;
use std::process::Command;

fn sweep(args: &[&str]) -> std::process::Output {
    Command::new(env!("CARGO_BIN_EXE_reconfig"))
        .arg("sweep")
        .args(args)
        .output()
        .expect("run reconfig sweep")
}

fn scratch(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("reconfig-sweep-sets-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("test io");
    dir.join(name)
}

#[test]
fn a_held_out_sweep_writes_every_kind_in_the_families_formats() {
    let count = kinds::KINDS.len();
    let (problems, answers) = (scratch("problems.jsonl"), scratch("answers.jsonl"));
    let out = sweep(&[
        "--set",
        "held-out",
        "--count",
        &count.to_string(),
        "--write",
        problems.to_str().expect("path"),
        "--write-answers",
        answers.to_str().expect("path"),
    ]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let table = String::from_utf8_lossy(&out.stdout);
    assert!(
        table.contains("| kind | problems | Solved | Feasible | usable (`is_usable()`) |"),
        "{table}"
    );
    assert!(table.contains(&format!("\n| all | {count} |")), "{table}");
    for kind in kinds::names() {
        assert!(
            table.contains(&format!("\n| {kind} | 1 |")),
            "{kind}: {table}"
        );
    }
    // The problem file reads back as the set's problems, each named by its kind.
    let written = sweep_oracle::load_problems(&problems).expect("problem file");
    let expected = sets::generate_set(sets::Set::HeldOut, 9, count);
    assert_eq!(written.len(), count);
    for ((f, p), (kind, q)) in written.iter().zip(&expected) {
        assert_eq!(f, kind);
        assert!(sweep_oracle::same_problem(p, q), "{kind}");
    }
    let lines = std::fs::read_to_string(&answers).expect("answer file");
    for (i, line) in lines.lines().enumerate() {
        let v: serde_json::Value = serde_json::from_str(line).expect("answer line");
        assert_eq!(v["index"], i);
        assert_eq!(v["family"], expected[i].0);
        assert!(v["status"].is_string());
    }
    assert_eq!(lines.lines().count(), count);
    // Same arguments, same problems, bit for bit; the record the sweep builds from its tallies
    // is the one `SetRecord::measure` (the golden records' test) counts.
    let (again, record) = (scratch("again.jsonl"), scratch("record.toml"));
    let out = sweep(&[
        "--set",
        "held-out",
        "--count",
        &count.to_string(),
        "--write",
        again.to_str().expect("path"),
        "--record",
        record.to_str().expect("path"),
    ]);
    assert!(out.status.success());
    assert_eq!(
        std::fs::read(&problems).expect("test io"),
        std::fs::read(&again).expect("test io")
    );
    let written: SetRecord =
        toml::from_str(&std::fs::read_to_string(&record).expect("test io")).expect("record");
    let measured = SetRecord::measure(
        sets::Set::HeldOut,
        9,
        count,
        Settings::default().work_budget,
    );
    assert_eq!(written, measured);
    assert_eq!(written.all.problems, count);
    let _ = std::fs::remove_dir_all(problems.parent().expect("dir"));
}

#[test]
fn count_is_for_the_kinds_sets() {
    let out = sweep(&["--count", "3"]);
    assert_eq!(out.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&out.stderr).contains("--count"));
}
