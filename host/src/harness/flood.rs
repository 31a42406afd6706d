//! A hostile client for the fairness checks: it floods the flight service with garbage frames
//! (frames `wire::decode_request` refuses) and wake-ups as fast as it can, until it is killed
//! or has made `count` attempts.
//!
//! How it treats the answers is the [`FloodMode`]: it reads them, abandons each request as soon
//! as it is sent (drops the pending response unread), or keeps its requests open without ever
//! reading an answer (dropping the oldest when iceoryx2's limit of active requests is reached).
//! Its client port discards a request rather than wait when the service's buffer for it is
//! full, so it never blocks, and it notifies the service after every send.

use super::{Instance, Pending, MAX_IN_FLIGHT};
use anyhow::{anyhow, Result};
use iceoryx2::port::client::RequestSendError;
use iceoryx2::prelude::*;
use rand::{Rng, SeedableRng};
use reconfig_core::wire::{self, CRC_BYTES, PROTOCOL_VERSION, REQUEST_MAX_BYTES};
use std::collections::VecDeque;
use std::time::{Duration, Instant};

/// How the flooder treats the service's answers.
#[derive(Clone, Copy, Debug, PartialEq, Eq, clap::ValueEnum)]
pub enum FloodMode {
    /// Keeps up to 16 requests in flight and reads every answer.
    Read,
    /// Drops each request's pending response as soon as it is sent (never reads an answer).
    Abandon,
    /// Keeps its requests open and never reads an answer; drops the oldest when it has 16.
    Ignore,
}

/// The kinds of garbage sent, in turn.
pub const GARBAGE_KINDS: [&str; 6] = [
    "3 bytes (no readable header)",
    "bad magic",
    "wrong version",
    "bad CRC",
    "body length past the frame",
    "random bytes",
];

/// Garbage frame number `k` (its kind is `GARBAGE_KINDS[k % 6]`), with sequence number `seq`
/// where the header carries one. `wire::decode_request` refuses every one.
pub fn garbage_frame(k: u64, seq: u64, rng: &mut impl Rng) -> Vec<u8> {
    let mut header = Vec::with_capacity(REQUEST_MAX_BYTES);
    header.extend_from_slice(b"RQ");
    header.extend_from_slice(&PROTOCOL_VERSION.to_le_bytes());
    header.extend_from_slice(&seq.to_le_bytes());
    let body_len: usize = rng.random_range(1..200);
    header.extend_from_slice(&(body_len as u32).to_le_bytes());
    let mut frame = header;
    frame.extend((0..body_len).map(|_| rng.random::<u8>()));
    frame.extend_from_slice(&[0u8; CRC_BYTES]);
    match k % 6 {
        0 => frame.truncate(3),
        1 => frame[0] = b'X',
        2 => frame[2..4].copy_from_slice(&(PROTOCOL_VERSION ^ 0x40).to_le_bytes()),
        // The CRC field stays zero: wrong for any body but one in 2^32, checked below.
        3 => {}
        4 => frame[12..16].copy_from_slice(&(REQUEST_MAX_BYTES as u32).to_le_bytes()),
        _ => {
            let len = rng.random_range(1..=REQUEST_MAX_BYTES);
            frame = (0..len).map(|_| rng.random::<u8>()).collect();
        }
    }
    if wire::decode_request(&frame).is_ok() {
        // Astronomically unlikely; keep the promise anyway.
        frame.truncate(3);
    }
    frame
}

/// Options of a flood.
#[derive(Clone, Debug)]
pub struct FloodOptions {
    /// Where the service lives.
    pub instance: Instance,
    /// How answers are treated.
    pub mode: FloodMode,
    /// Stop after this many attempts (None: until killed).
    pub count: Option<u64>,
    /// Print a `flooding: N attempts, ...` line on stdout every this many attempts (0: never).
    pub report_every: u64,
    /// How long to wait for a flight service.
    pub wait_service: Duration,
    /// Seed of the garbage.
    pub seed: u64,
}

/// What a flood did.
#[derive(Clone, Debug, Default)]
pub struct FloodStats {
    /// Times round its loop: a send tried, or (mode `Read`, 16 unanswered) a wake-up sent.
    pub attempts: u64,
    /// Frames sent.
    pub sent: u64,
    /// Answers read (mode `Read` only).
    pub answered: u64,
    /// Sends iceoryx2 refused (too many active requests, no request memory left).
    pub refused: u64,
}

/// Flood the service. Returns after `count` attempts (or never, when killed first).
pub fn run(opts: &FloodOptions) -> Result<FloodStats> {
    let inst = &opts.instance;
    let node = inst.node("reconfig-flood")?;
    let started = Instant::now();
    let rpc = loop {
        match node
            .service_builder(&inst.service_name("rpc")?)
            .request_response::<[u8], [u8]>()
            .request_user_header::<super::dispatch::RequestHeader>()
            .response_user_header::<super::dispatch::ServiceOrder>()
            .open()
        {
            Ok(rpc) => break rpc,
            Err(e) if started.elapsed() >= opts.wait_service => {
                return Err(anyhow!("no flight service {:?}: {e:?}", inst.service))
            }
            Err(_) => std::thread::sleep(Duration::from_millis(10)),
        }
    };
    let to_service = inst.open_event(&node, "to-service")?;
    let client = rpc
        .client_builder()
        .initial_max_slice_len(REQUEST_MAX_BYTES)
        .allocation_strategy(AllocationStrategy::PowerOfTwo)
        .backpressure_strategy(BackpressureStrategy::DiscardData)
        .create()
        .map_err(|e| anyhow!("cannot create client: {e:?}"))?;
    let wake = super::notifier(&to_service)?;
    let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(opts.seed);
    let mut stats = FloodStats::default();
    let mut open: VecDeque<Pending> = VecDeque::with_capacity(MAX_IN_FLIGHT);
    while opts.count.is_none_or(|n| stats.attempts < n) {
        stats.attempts += 1;
        if opts.report_every > 0 && stats.attempts % opts.report_every == 0 {
            println!(
                "flooding: {} attempts, {} frames sent, {} answers read, {} refused",
                stats.attempts, stats.sent, stats.answered, stats.refused
            );
            let _ = std::io::Write::flush(&mut std::io::stdout());
        }
        if opts.mode == FloodMode::Read {
            open.retain(|p| match p.receive() {
                Ok(Some(_)) => {
                    stats.answered += 1;
                    false
                }
                Ok(None) => true,
                Err(_) => false,
            });
            if open.len() >= MAX_IN_FLIGHT {
                // Nothing more may be sent before an answer: wake the service anyway.
                let _ = wake.notify();
                std::thread::yield_now();
                continue;
            }
        } else if open.len() >= MAX_IN_FLIGHT {
            open.pop_front();
        }
        let frame = garbage_frame(stats.attempts, 1_000_000_000 + stats.attempts, &mut rng);
        let Ok(request) = client.loan_slice_uninit(frame.len()) else {
            stats.refused += 1;
            open.pop_front();
            let _ = wake.notify();
            continue;
        };
        match request.write_from_slice(&frame).send() {
            Ok(pending) => {
                stats.sent += 1;
                if opts.mode != FloodMode::Abandon {
                    open.push_back(pending);
                }
            }
            Err(RequestSendError::ExceedsMaxActiveRequests) => {
                stats.refused += 1;
                open.pop_front();
            }
            Err(e) => return Err(anyhow!("cannot send: {e:?}")),
        }
        let _ = wake.notify();
    }
    Ok(stats)
}

/// A flooder in its own process (`reconfig feed --flood MODE`), killed with SIGKILL by
/// [`FlooderProcess::kill`] or on drop, as a hostile client dies: without cleaning up.
pub struct FlooderProcess {
    child: Option<std::process::Child>,
    lines: std::sync::mpsc::Receiver<String>,
    last: Option<String>,
}

impl FlooderProcess {
    /// Start `exe feed --flood MODE` against `instance` and wait (60 s at most) for its first
    /// `flooding:` line (1000 attempts made).
    ///
    /// # Errors
    /// The process cannot start, or says nothing in time.
    pub fn start(exe: &std::path::Path, instance: &Instance, mode: FloodMode) -> Result<Self> {
        use clap::ValueEnum;
        use std::io::BufRead;
        let name = mode
            .to_possible_value()
            .map(|v| v.get_name().to_string())
            .unwrap_or_default();
        let mut child = std::process::Command::new(exe)
            .args(["feed", "--flood", &name, "--prefix", &instance.prefix])
            .args(["--service", &instance.service])
            .stdin(std::process::Stdio::null())
            .stdout(std::process::Stdio::piped())
            .spawn()
            .map_err(|e| anyhow!("cannot start the flooder: {e}"))?;
        let stdout = child
            .stdout
            .take()
            .ok_or_else(|| anyhow!("flooder without stdout"))?;
        let (tx, lines) = std::sync::mpsc::channel();
        std::thread::spawn(move || {
            for line in std::io::BufReader::new(stdout)
                .lines()
                .map_while(Result::ok)
            {
                if tx.send(line).is_err() {
                    break;
                }
            }
        });
        let mut me = Self {
            child: Some(child),
            lines,
            last: None,
        };
        match me.lines.recv_timeout(Duration::from_secs(60)) {
            Ok(line) if line.starts_with("flooding") => {
                me.last = Some(line);
                Ok(me)
            }
            other => Err(anyhow!("the flooder did not start flooding: {other:?}")),
        }
    }

    /// Process id.
    pub fn pid(&self) -> u32 {
        self.child.as_ref().map_or(0, std::process::Child::id)
    }

    /// SIGKILL it; returns its last `flooding:` line.
    pub fn kill(mut self) -> String {
        self.stop();
        while let Ok(line) = self.lines.recv_timeout(Duration::from_millis(200)) {
            self.last = Some(line);
        }
        self.last.take().unwrap_or_default()
    }

    fn stop(&mut self) {
        if let Some(mut child) = self.child.take() {
            let _ = child.kill();
            let _ = child.wait();
        }
    }
}

impl Drop for FlooderProcess {
    fn drop(&mut self) {
        self.stop();
    }
}
