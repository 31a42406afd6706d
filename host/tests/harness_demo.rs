//! `reconfig demo` end to end (with fewer generated scenarios): it starts its own flight
//! service, checks every answer, stops the service, exits 0 and leaves nothing behind.

use std::process::Command;

#[test]
fn the_demo_passes_and_cleans_up() {
    let out = Command::new(env!("CARGO_BIN_EXE_reconfig"))
        .args([
            "demo", "--random", "30", "--cpus", "0", "--no-pin", "--rows", "5",
        ])
        .current_dir(concat!(env!("CARGO_MANIFEST_DIR"), "/.."))
        .output()
        .expect("run demo");
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert!(
        out.status.success(),
        "demo failed:\n{stdout}\n{}",
        String::from_utf8_lossy(&out.stderr)
    );
    assert!(stdout.contains("every answer correct"), "{stdout}");
    assert!(
        stdout.contains("flight service stopped cleanly"),
        "{stdout}"
    );
    // The demo's instance prefix is reconfig_demo_<its pid>_; nothing of it may be left.
    let pid = out_pid(&stdout);
    assert_ne!(pid, "?", "{stdout}");
    let left: Vec<_> = std::fs::read_dir("/dev/shm")
        .map(|d| {
            d.flatten()
                .map(|e| e.file_name().to_string_lossy().to_string())
                .filter(|n| n.starts_with("reconfig_demo_"))
                .filter(|n| n.starts_with(&format!("reconfig_demo_{pid}_")))
                .collect()
        })
        .unwrap_or_default();
    assert!(left.is_empty(), "left behind: {left:?}");
}

/// The demo process's pid, from the prefix in the service's ready line.
fn out_pid(stdout: &str) -> String {
    stdout
        .lines()
        .find_map(|l| l.split("prefix reconfig_demo_").nth(1))
        .and_then(|l| l.split('_').next())
        .unwrap_or("?")
        .to_string()
}
