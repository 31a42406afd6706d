//! A flight service as a child process of this executable (`reconfig serve`), started and
//! stopped by the commands that run their own service (`demo`, `fairness`).

use super::Instance;
use anyhow::{anyhow, bail, Context, Result};
use std::io::{BufRead, BufReader};
use std::process::{Child, Command, Stdio};
use std::time::{Duration, Instant};

/// A flight service child process; stopped with SIGTERM when dropped.
pub struct ServiceChild {
    child: Option<Child>,
}

impl ServiceChild {
    /// Start `reconfig serve` (this executable) and wait for its `ready` line.
    pub fn start(instance: &Instance, cpus: &str, no_pin: bool, extra: &[&str]) -> Result<Self> {
        let exe = std::env::current_exe().context("cannot find this executable")?;
        let mut cmd = Command::new(exe);
        cmd.arg("serve")
            .args([
                "--cpus",
                cpus,
                "--prefix",
                &instance.prefix,
                "--service",
                &instance.service,
            ])
            .args(extra)
            .stdout(Stdio::piped())
            .stdin(Stdio::null());
        if no_pin {
            cmd.arg("--no-pin");
        }
        let mut child = cmd.spawn().context("cannot start the flight service")?;
        let stdout = child.stdout.take().ok_or_else(|| anyhow!("no stdout"))?;
        let (tx, rx) = std::sync::mpsc::channel();
        std::thread::spawn(move || {
            let mut lines = BufReader::new(stdout).lines();
            if let Some(Ok(line)) = lines.next() {
                let _ = tx.send(line);
            }
            for _ in lines {}
        });
        let mut me = Self { child: Some(child) };
        match rx.recv_timeout(Duration::from_secs(60)) {
            Ok(line) if line.starts_with("ready") => {
                println!("flight service started (pid {}): {line}", me.pid());
                Ok(me)
            }
            Ok(line) => {
                me.kill();
                bail!("flight service said {line:?} instead of ready")
            }
            Err(_) => {
                let status = me.child.as_mut().and_then(|c| c.try_wait().ok().flatten());
                me.kill();
                bail!("flight service did not become ready (exit status {status:?})")
            }
        }
    }

    /// Process id.
    pub fn pid(&self) -> u32 {
        self.child.as_ref().map_or(0, Child::id)
    }

    /// SIGTERM, then wait (10 s at most, then SIGKILL). True when it exited with status 0.
    pub fn stop(mut self) -> Result<bool> {
        let Some(mut child) = self.child.take() else {
            return Ok(false);
        };
        // SAFETY: kill(2) on our own child's pid.
        unsafe {
            libc::kill(child.id() as libc::pid_t, libc::SIGTERM);
        }
        let start = Instant::now();
        loop {
            if let Some(status) = child.try_wait()? {
                return Ok(status.success());
            }
            if start.elapsed() > Duration::from_secs(10) {
                let _ = child.kill();
                let _ = child.wait();
                return Ok(false);
            }
            std::thread::sleep(Duration::from_millis(20));
        }
    }

    fn kill(&mut self) {
        if let Some(mut child) = self.child.take() {
            let _ = child.kill();
            let _ = child.wait();
        }
    }
}

impl Drop for ServiceChild {
    fn drop(&mut self) {
        if let Some(child) = &self.child {
            // SAFETY: kill(2) on our own child's pid.
            unsafe {
                libc::kill(child.id() as libc::pid_t, libc::SIGTERM);
            }
        }
        if let Some(mut child) = self.child.take() {
            let _ = child.wait();
        }
    }
}
