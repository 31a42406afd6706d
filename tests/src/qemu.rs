//! One way to run a Cortex-M7 image under QEMU for the tests: the runner of
//! `.cargo/config.toml` (the `mps2-an500` board, semihosting, one instruction per virtual
//! nanosecond), extra arguments (the instruction-counting plugin), the output in files beside
//! the image, and a time limit (`RECONFIG_QEMU_TIMEOUT_S`, default 600 s) after which QEMU is
//! killed, so a hung image fails its test instead of hanging the run. Used by the firmware
//! images' tests (`tests/tests/qemu_firmware/image.rs`) and the C interface's M7 image
//! (`tests/tests/c_api.rs`).

use std::path::Path;
use std::process::{Command, ExitStatus, Stdio};
use std::time::{Duration, Instant};

/// QEMU's arguments before the image, as the runner of `.cargo/config.toml` has them.
pub const M7_ARGS: [&str; 10] = [
    "-cpu",
    "cortex-m7",
    "-machine",
    "mps2-an500",
    "-nographic",
    "-semihosting-config",
    "enable=on,target=native",
    "-icount",
    "shift=0",
    "-kernel",
];

/// What a run of an image printed, and how it ended.
pub struct Output {
    pub status: ExitStatus,
    pub stdout: String,
    pub stderr: String,
}

/// The time limit of one run: `RECONFIG_QEMU_TIMEOUT_S`, else 600 s.
fn limit() -> Duration {
    Duration::from_secs(
        std::env::var("RECONFIG_QEMU_TIMEOUT_S")
            .ok()
            .and_then(|s| s.parse().ok())
            .unwrap_or(600),
    )
}

/// Run `elf` with `qemu` (a path or `qemu-system-arm`) and `extra` arguments after the image;
/// its output goes to `<elf>.qemu-stdout.txt` / `.qemu-stderr.txt`.
///
/// # Errors
/// QEMU does not start, the files cannot be written or read, or the run passes the time
/// limit (QEMU is then killed).
pub fn run_m7(qemu: &Path, elf: &Path, extra: &[String]) -> Result<Output, String> {
    let out_dir = elf.parent().ok_or("odd image path")?;
    let stdout_path = out_dir.join("qemu-stdout.txt");
    let stderr_path = out_dir.join("qemu-stderr.txt");
    let file = |p: &Path| std::fs::File::create(p).map_err(|e| format!("{}: {e}", p.display()));
    let mut child = Command::new(qemu)
        .args(M7_ARGS)
        .arg(elf)
        .args(extra)
        .stdin(Stdio::null())
        .stdout(file(&stdout_path)?)
        .stderr(file(&stderr_path)?)
        .spawn()
        .map_err(|e| format!("cannot start {}: {e}", qemu.display()))?;
    let limit = limit();
    let started = Instant::now();
    let status = loop {
        if let Some(status) = child.try_wait().map_err(|e| e.to_string())? {
            break status;
        }
        if started.elapsed() > limit {
            let _ = child.kill();
            let _ = child.wait();
            return Err(format!(
                "{} did not finish within {} s (RECONFIG_QEMU_TIMEOUT_S)",
                elf.display(),
                limit.as_secs()
            ));
        }
        std::thread::sleep(Duration::from_millis(20));
    };
    let read = |p: &Path| std::fs::read_to_string(p).map_err(|e| format!("{}: {e}", p.display()));
    Ok(Output {
        status,
        stdout: read(&stdout_path)?,
        stderr: read(&stderr_path)?,
    })
}
