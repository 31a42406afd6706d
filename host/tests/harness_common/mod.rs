//! Helpers for the harness tests that run real processes: a unique iceoryx2 prefix and
//! service name per test, child processes stopped on drop, and a check that nothing with the
//! test's prefix is left in shared memory.

#![allow(dead_code)]

use reconfig_host::harness::Instance;
use std::io::{BufRead, BufReader};
use std::path::{Path, PathBuf};
use std::process::{Child, ChildStdout, Command, ExitStatus, Stdio};
use std::sync::mpsc::{channel, Receiver, RecvTimeoutError};
use std::time::{Duration, Instant};

/// The `reconfig` binary under test.
pub fn exe() -> &'static str {
    env!("CARGO_BIN_EXE_reconfig")
}

/// A per-test instance: prefix and service name unique to this test and process.
pub fn instance(test: &str) -> Instance {
    Instance {
        prefix: format!("rcfgt_{test}_{}_", std::process::id()),
        service: format!("t-{test}-{}", std::process::id()),
    }
}

/// Arguments naming the instance.
pub fn instance_args(inst: &Instance) -> Vec<String> {
    vec![
        "--prefix".into(),
        inst.prefix.clone(),
        "--service".into(),
        inst.service.clone(),
    ]
}

/// A child process killed on drop, with its stdout lines on a channel.
pub struct Proc {
    pub child: Child,
    pub lines: Receiver<String>,
    /// Every stdout line read so far, in order (for failure messages).
    pub seen: std::cell::RefCell<Vec<String>>,
}

impl Proc {
    pub fn pid(&self) -> i32 {
        self.child.id() as i32
    }

    pub fn signal(&self, sig: i32) {
        // SAFETY: kill(2) on our own child's pid.
        unsafe {
            libc::kill(self.pid(), sig);
        }
    }

    /// Wait for a stdout line starting with `prefix` (bounded).
    pub fn wait_line(&self, prefix: &str, limit: Duration) -> Option<String> {
        let start = Instant::now();
        while start.elapsed() < limit {
            match self.lines.recv_timeout(Duration::from_millis(100)) {
                Ok(line) => {
                    self.seen.borrow_mut().push(line.clone());
                    if line.starts_with(prefix) {
                        return Some(line);
                    }
                }
                Err(RecvTimeoutError::Timeout) => {}
                Err(RecvTimeoutError::Disconnected) => return None,
            }
        }
        None
    }

    /// Wait for exit (bounded); kills it when the limit passes.
    pub fn wait(&mut self, limit: Duration) -> Option<ExitStatus> {
        let start = Instant::now();
        while start.elapsed() < limit {
            if let Ok(Some(status)) = self.child.try_wait() {
                return Some(status);
            }
            std::thread::sleep(Duration::from_millis(20));
        }
        let _ = self.child.kill();
        let _ = self.child.wait();
        None
    }

    /// Every stdout line: those read so far and, after a bounded wait, the rest.
    pub fn all_lines(&self) -> Vec<String> {
        while let Ok(line) = self.lines.recv_timeout(Duration::from_millis(200)) {
            self.seen.borrow_mut().push(line);
        }
        self.seen.borrow().clone()
    }

    pub fn running(&mut self) -> bool {
        matches!(self.child.try_wait(), Ok(None))
    }
}

impl Drop for Proc {
    fn drop(&mut self) {
        if self.running() {
            let _ = self.child.kill();
            let _ = self.child.wait();
        }
    }
}

fn lines_of(stdout: ChildStdout) -> Receiver<String> {
    let (tx, rx) = channel();
    std::thread::spawn(move || {
        for line in BufReader::new(stdout).lines().map_while(Result::ok) {
            if tx.send(line).is_err() {
                break;
            }
        }
    });
    rx
}

/// Start `reconfig ARGS...`.
pub fn spawn(args: &[String]) -> Proc {
    let mut child = Command::new(exe())
        .args(args)
        .stdin(Stdio::null())
        .stdout(Stdio::piped())
        .spawn()
        .expect("cannot start reconfig");
    let lines = lines_of(child.stdout.take().expect("stdout"));
    Proc {
        child,
        lines,
        seen: Default::default(),
    }
}

/// Start the flight service (one unpinned worker) and wait until it is ready.
pub fn serve(inst: &Instance, extra: &[&str]) -> Proc {
    let mut args: Vec<String> = vec![
        "serve".into(),
        "--cpus".into(),
        "0".into(),
        "--no-pin".into(),
    ];
    args.extend(instance_args(inst));
    args.extend(extra.iter().map(|s| s.to_string()));
    let p = spawn(&args);
    assert!(
        p.wait_line("ready", Duration::from_secs(60)).is_some(),
        "flight service did not become ready"
    );
    p
}

/// Run `reconfig feed` with `extra` to completion (bounded); returns (exit code, JSON report).
pub fn feed(inst: &Instance, extra: &[&str], json: &Path) -> (Option<i32>, serde_json::Value) {
    let mut args: Vec<String> = vec!["feed".into(), "--quiet".into(), "--json".into()];
    args.push(json.display().to_string());
    args.extend(instance_args(inst));
    args.extend(extra.iter().map(|s| s.to_string()));
    let mut p = spawn(&args);
    let status = p.wait(Duration::from_secs(120));
    let text = std::fs::read_to_string(json).unwrap_or_default();
    let value = serde_json::from_str(&text).unwrap_or(serde_json::Value::Null);
    (status.and_then(|s| s.code()), value)
}

/// A temporary file path for this test.
pub fn temp(test: &str, name: &str) -> PathBuf {
    std::env::temp_dir().join(format!("rcfgt_{test}_{}_{name}", std::process::id()))
}

/// Files whose names contain the instance's prefix, in shared memory and iceoryx2's folder.
pub fn leftovers(inst: &Instance) -> Vec<PathBuf> {
    let mut found = Vec::new();
    let mut stack = vec![PathBuf::from("/dev/shm"), PathBuf::from("/tmp/iceoryx2")];
    while let Some(dir) = stack.pop() {
        let Ok(entries) = std::fs::read_dir(&dir) else {
            continue;
        };
        for e in entries.flatten() {
            let path = e.path();
            if path.is_dir() {
                stack.push(path.clone());
            }
            if e.file_name().to_string_lossy().contains(&inst.prefix) {
                found.push(path);
            }
        }
    }
    found
}

/// Stop the service with SIGTERM, expect a clean exit, remove the instance's global segment and
/// check nothing of the instance is left.
pub fn stop_and_check_clean(mut service: Proc, inst: &Instance) {
    service.signal(libc::SIGTERM);
    let status = service.wait(Duration::from_secs(20));
    assert!(
        status.is_some_and(|s| s.success()),
        "service did not stop cleanly on SIGTERM: {status:?}"
    );
    reconfig_host::harness::remove_instance_segment(inst).expect("remove global segment");
    let left = leftovers(inst);
    assert!(left.is_empty(), "left behind: {left:?}");
}

/// A genuinely slow request and the limits that allow it, written for this test: planner B's
/// impulse-point search (Wang 2018's published case, 3 impulses) over `samples` samples with a
/// work budget large enough to finish (the built-in limits allow 400 samples). Its solve time
/// grows with `samples` (`reconfig solve`, this 2-core VM under load: 10 000 in 0.71 s, 20 000 in
/// 0.51 s, 60 000 in 1.90 s, 100 000 in 1.90 s).
/// Returns (fixture, limits file); pass the limits file to both `serve` and `feed`.
pub fn slow_search(test: &str, samples: u64) -> (PathBuf, PathBuf) {
    let base = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../fixtures/over-limits/wang2018-search-3imp-2m-samples.toml");
    let text = std::fs::read_to_string(&base).expect("read the search fixture");
    let evaluations = samples + 1800;
    let text = text
        .replace(
            "name = \"wang2018-search-3imp-2m-samples\"",
            &format!("name = \"slow-search-{samples}\""),
        )
        .replace(
            "search_samples = 2000000",
            &format!("search_samples = {samples}"),
        )
        .replace(
            "search_max_evaluations = 2020000",
            &format!("search_max_evaluations = {evaluations}\nwork_budget = 100000000000"),
        );
    assert!(
        text.contains(&format!("search_samples = {samples}")),
        "{text}"
    );
    let fixture = temp(test, "slow-search.toml");
    std::fs::write(&fixture, text).expect("write the slow fixture");
    let limits = temp(test, "slow-limits.toml");
    std::fs::write(
        &limits,
        format!(
            "[impulsive]\nsearch_samples = {samples}\nsearch_max_evaluations = {evaluations}\n\
             work_budget = 100000000000\n"
        ),
    )
    .expect("write the limits");
    (fixture, limits)
}
