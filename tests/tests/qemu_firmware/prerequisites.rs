//! What a QEMU run needs, and what a test does when it is missing: skip (say so and pass) or,
//! with `RECONFIG_REQUIRE_QEMU=1`, fail.

use std::io::Write as _;
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};

pub const TARGET: &str = "thumbv7em-none-eabihf";

pub fn root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .parent()
        .expect("tests/ sits in the workspace")
        .to_path_buf()
}

pub fn cargo() -> String {
    std::env::var("CARGO").unwrap_or_else(|_| "cargo".into())
}

/// Print to the real stderr, past the test harness's capture, so a skip is always seen.
pub fn notice(text: &str) {
    let _ = writeln!(std::io::stderr(), "{text}");
}

/// Skip (say so and pass) or, with `RECONFIG_REQUIRE_QEMU=1`, fail.
pub fn skip(test: &str, why: &str) {
    if std::env::var("RECONFIG_REQUIRE_QEMU").as_deref() == Ok("1") {
        panic!("{test}: {why}\n(RECONFIG_REQUIRE_QEMU=1, so this is a failure, not a skip)");
    }
    notice(&format!(
        "SKIPPED {test}: {why}\n  (set RECONFIG_REQUIRE_QEMU=1 to make this a failure)"
    ));
}

fn tool_runs(program: &str, arg: &str) -> bool {
    Command::new(program)
        .arg(arg)
        .stdout(Stdio::null())
        .stderr(Stdio::null())
        .status()
        .is_ok_and(|s| s.success())
}

/// What the QEMU run needs, or why it cannot happen here.
pub fn check_prerequisites() -> Result<(), String> {
    if !tool_runs("qemu-system-arm", "--version") {
        return Err("qemu-system-arm is not installed. Install it with \
                    `sudo apt-get install qemu-system-arm` (Debian/Ubuntu) or your system's \
                    QEMU package (it needs TCG plugin support, as Debian's has)."
            .into());
    }
    let rustc = std::env::var("RUSTC").unwrap_or_else(|_| "rustc".into());
    let sysroot = Command::new(&rustc)
        .args(["--print", "sysroot"])
        .output()
        .map_err(|e| format!("cannot run {rustc}: {e}"))?;
    let sysroot = String::from_utf8_lossy(&sysroot.stdout).trim().to_owned();
    if !Path::new(&sysroot)
        .join("lib/rustlib")
        .join(TARGET)
        .is_dir()
    {
        return Err(format!(
            "the Rust target {TARGET} is not installed. Install it with \
             `rustup target add {TARGET}`."
        ));
    }
    Ok(())
}
