//! `reconfig feed`: the feeder. Sends request frames to the flight service, sequentially or at
//! a rate with a window of requests in flight, with a per-request timeout; matches responses by
//! sequence number; counts lost, late, duplicated and malformed responses separately.
//!
//! iceoryx2 gives no error when the server process dies: a pending request simply never gets a
//! response. The feeder notices by its timeout, reports the request as lost, looks for dead
//! nodes (`Node::list`) and removes them (`try_cleanup_dead_nodes`), and waits (bounded) for a
//! server before it sends the next request.

use super::{affinity, Instance, Pending, MAX_IN_FLIGHT};
use anyhow::{anyhow, bail, Result};
use iceoryx2::prelude::*;
use reconfig_core::contract::PlannerKind;
use reconfig_core::wire::{self, Request, REQUEST_MAX_BYTES};
use std::time::{Duration, Instant};

/// What one feed item sends.
#[derive(Clone, Debug)]
pub enum Payload {
    /// A request; the feeder frames it with its sequence number.
    Request(Box<Request>),
    /// Raw bytes sent as they are (fault injection); the service answers with what was wrong.
    Raw(Vec<u8>),
}

/// One request to send.
#[derive(Clone, Debug)]
pub struct Item {
    /// Name for the results table.
    pub label: String,
    /// Planner (None for raw fault frames).
    pub planner: Option<PlannerKind>,
    /// Problem size class for the report, e.g. `M3 N10` or `K3`.
    pub size: String,
    /// What to send.
    pub payload: Payload,
}

/// Options of a feed run.
#[derive(Clone, Debug)]
pub struct FeedOptions {
    /// Where the service lives.
    pub instance: Instance,
    /// Per-request timeout: no response by then is a lost request.
    pub timeout: Duration,
    /// Most requests in flight (1 = sequential).
    pub window: usize,
    /// Requests per second (None: as fast as the window allows).
    pub rate: Option<f64>,
    /// How long to wait for a service (at start and after losing one) before giving up.
    pub wait_service: Duration,
    /// Pin the feeder's thread to this CPU.
    pub cpu: Option<usize>,
    /// First sequence number.
    pub first_seq: u64,
    /// Show a progress bar.
    pub progress: bool,
    /// Print `sent SEQ at T ms (N servers listed, delivered to K)`, `undelivered SEQ at T ms`,
    /// `answered SEQ at T ms` and `lost SEQ at T ms` lines on stdout as they happen (T from the
    /// feeder's start).
    pub verbose: bool,
    /// Each request's deadline in the service's queue (None: the service's default).
    pub deadline: Option<Duration>,
    /// Send nothing new after this long; items not sent by then are dropped from the run (for
    /// runs of a fixed duration over a long list of items).
    pub stop_after: Option<Duration>,
}

impl FeedOptions {
    /// Defaults for an instance.
    pub fn new(instance: Instance) -> Self {
        Self {
            instance,
            timeout: Duration::from_secs(5),
            window: 1,
            rate: None,
            wait_service: Duration::from_secs(10),
            cpu: None,
            first_seq: 1,
            progress: false,
            verbose: false,
            deadline: None,
            stop_after: None,
        }
    }
}

/// What became of one item.
#[derive(Clone, Debug)]
pub enum Fate {
    /// Never sent (no service appeared in time).
    NotSent,
    /// No response within the timeout.
    Lost,
    /// The response could not be decoded or answered another sequence number.
    Malformed(String),
    /// A valid response.
    Answered {
        /// Round trip, send to receive, ns.
        rtt_ns: u64,
        /// The solve's own time measured by the service, ns.
        solve_ns: u64,
        /// The response body (encoded outcome), for comparison with a local solve.
        body: Vec<u8>,
        /// Where the request stood in the service's order of service.
        order: super::dispatch::ServiceOrder,
    },
}

/// Result of one item.
#[derive(Clone, Debug)]
pub struct Record {
    /// Index into the items.
    pub index: usize,
    /// Sequence number sent.
    pub seq: u64,
    /// The frame sent.
    pub frame: Vec<u8>,
    /// What happened.
    pub fate: Fate,
}

/// Counters of a feed run.
#[derive(Clone, Debug, Default, serde::Serialize)]
pub struct Counters {
    /// Requests sent.
    pub sent: u64,
    /// Valid responses to requests in time.
    pub answered: u64,
    /// Requests with no response within the timeout.
    pub lost: u64,
    /// Responses that arrived after their request was declared lost.
    pub late: u64,
    /// Second (or later) responses to one request.
    pub duplicated: u64,
    /// Responses that failed to decode or carried the wrong sequence number.
    pub malformed: u64,
    /// Items never sent because no service was there.
    pub not_sent: u64,
    /// Sends that iceoryx2 delivered to no server (a restarting service whose server port is
    /// listed before its connections exist) and that were sent again; not requests lost.
    pub undelivered: u64,
    /// Dead nodes found and cleaned up.
    pub dead_nodes_cleaned: u64,
}

/// Outcome of a feed run.
#[derive(Clone, Debug)]
pub struct FeedRun {
    /// One per item, in item order.
    pub records: Vec<Record>,
    /// Counters.
    pub counters: Counters,
    /// Wall time of the run.
    pub elapsed: Duration,
}

struct InFlight {
    index: usize,
    seq: u64,
    sent_at: Instant,
    pending: Pending,
}

enum Settled {
    Answered,
    Lost,
}

/// Encode an item's frame with its sequence number.
pub fn frame_of(item: &Item, seq: u64) -> Result<Vec<u8>> {
    match &item.payload {
        Payload::Raw(bytes) => Ok(bytes.clone()),
        Payload::Request(request) => {
            let mut buf = vec![0u8; REQUEST_MAX_BYTES];
            let n = wire::encode_request(seq, request, &mut buf)
                .map_err(|e| anyhow!("{}: cannot encode: {e:?}", item.label))?;
            buf.truncate(n);
            Ok(buf)
        }
    }
}

/// The sequence number a raw frame will be answered with (0 when its header is unreadable).
fn expected_seq(frame: &[u8], seq: u64, item: &Item) -> u64 {
    match item.payload {
        Payload::Request(_) => seq,
        Payload::Raw(_) => wire::peek_request_seq(frame).unwrap_or(0),
    }
}

/// Feed `items` to the service and collect the answers.
pub fn run(items: &[Item], opts: &FeedOptions) -> Result<FeedRun> {
    if let Some(cpu) = opts.cpu {
        affinity::pin_current_thread(cpu)?;
    }
    let inst = &opts.instance;
    let node = inst.node("reconfig-feed")?;
    let mut counters = Counters::default();
    let (_, cleaned) = super::cleanup_dead_nodes(&node);
    counters.dead_nodes_cleaned += cleaned;

    let started = Instant::now();
    let rpc = wait_for(opts.wait_service, || {
        node.service_builder(&inst.service_name("rpc")?)
            .request_response::<[u8], [u8]>()
            .request_user_header::<super::dispatch::RequestHeader>()
            .response_user_header::<super::dispatch::ServiceOrder>()
            .open()
            .map_err(|e| anyhow!("{e:?}"))
    })
    .map_err(|e| {
        anyhow!(
            "no flight service {:?} (prefix {}): {e}",
            inst.service,
            inst.prefix
        )
    })?;
    let to_service = inst.open_event(&node, "to-service")?;
    let to_feeder = inst.open_event(&node, "to-feeder")?;
    let client = rpc
        .client_builder()
        .initial_max_slice_len(REQUEST_MAX_BYTES)
        .allocation_strategy(AllocationStrategy::PowerOfTwo)
        .create()
        .map_err(|e| anyhow!("cannot create client: {e:?}"))?;
    let wake_service = super::notifier(&to_service)?;
    let listener = super::listener(&to_feeder)?;

    let window = opts.window.clamp(1, MAX_IN_FLIGHT / 2);
    let settled_cap = MAX_IN_FLIGHT - window;
    let mut records: Vec<Record> = Vec::with_capacity(items.len());
    let mut in_flight: Vec<InFlight> = Vec::with_capacity(window);
    let mut settled: std::collections::VecDeque<(Pending, Settled)> = Default::default();
    let mut next = 0usize;
    let mut seq = opts.first_seq;
    let period = opts
        .rate
        .filter(|r| *r > 0.0)
        .map(|r| Duration::from_secs_f64(1.0 / r));
    let mut next_send = Instant::now();
    // Since when the next item has found no server connection to deliver it to.
    let mut undelivered_since: Option<Instant> = None;
    // Set by a loss, cleared by an answer: while set, a server counts only if its node is alive.
    let mut suspect = false;
    let bar = opts.progress.then(|| {
        let bar = indicatif::ProgressBar::new(items.len() as u64);
        bar.set_style(
            indicatif::ProgressStyle::with_template("{bar:40} {pos}/{len} {msg}")
                .unwrap_or_else(|_| indicatif::ProgressStyle::default_bar()),
        );
        bar
    });

    for (index, item) in items.iter().enumerate() {
        let frame = frame_of(item, opts.first_seq + index as u64)?;
        records.push(Record {
            index,
            seq: opts.first_seq + index as u64,
            frame,
            fate: Fate::NotSent,
        });
    }

    while next < items.len() || !in_flight.is_empty() {
        // 1. Receive.
        let mut i = 0;
        while i < in_flight.len() {
            let f = &in_flight[i];
            let mut got = false;
            while let Some(response) = f
                .pending
                .receive()
                .map_err(|e| anyhow!("receive failed: {e:?}"))?
            {
                if got {
                    counters.duplicated += 1;
                    continue;
                }
                got = true;
                let rtt_ns = f.sent_at.elapsed().as_nanos() as u64;
                let record = &mut records[f.index];
                let want = expected_seq(&record.frame, f.seq, &items[f.index]);
                record.fate = match wire::view_response(response.payload()) {
                    Ok(view) if view.seq == want => {
                        counters.answered += 1;
                        suspect = false;
                        Fate::Answered {
                            rtt_ns,
                            solve_ns: view.solve_time_ns,
                            body: view.body.to_vec(),
                            order: *response.user_header(),
                        }
                    }
                    Ok(view) => {
                        counters.malformed += 1;
                        Fate::Malformed(format!("answered seq {} for seq {want}", view.seq))
                    }
                    Err(e) => {
                        counters.malformed += 1;
                        Fate::Malformed(e.to_string())
                    }
                };
                if let Some(bar) = &bar {
                    bar.inc(1);
                }
                if opts.verbose {
                    println!("answered {} at {} ms", f.seq, started.elapsed().as_millis());
                    let _ = std::io::Write::flush(&mut std::io::stdout());
                }
            }
            if got {
                let f = in_flight.swap_remove(i);
                settled.push_back((f.pending, Settled::Answered));
            } else {
                i += 1;
            }
        }
        for (pending, how) in &settled {
            while let Ok(Some(_)) = pending.receive() {
                match how {
                    Settled::Answered => counters.duplicated += 1,
                    Settled::Lost => counters.late += 1,
                }
            }
        }
        // 2. Time out.
        let mut lost_any = false;
        let mut i = 0;
        while i < in_flight.len() {
            if in_flight[i].sent_at.elapsed() >= opts.timeout {
                let f = in_flight.swap_remove(i);
                records[f.index].fate = Fate::Lost;
                counters.lost += 1;
                lost_any = true;
                if opts.verbose {
                    println!("lost {} at {} ms", f.seq, started.elapsed().as_millis());
                    let _ = std::io::Write::flush(&mut std::io::stdout());
                }
                if let Some(bar) = &bar {
                    bar.inc(1);
                }
                settled.push_back((f.pending, Settled::Lost));
            } else {
                i += 1;
            }
        }
        while settled.len() > settled_cap {
            settled.pop_front();
        }
        if lost_any {
            suspect = true;
            let (dead, cleaned) = super::cleanup_dead_nodes(&node);
            counters.dead_nodes_cleaned += cleaned;
            if dead > 0 {
                // The lost requests' pendings belong to a dead server: drop them.
                settled.retain(|(_, how)| matches!(how, Settled::Answered));
            }
            if let Some(bar) = &bar {
                bar.set_message(format!("lost {}", counters.lost));
            }
        }
        // 3. Send.
        if opts.stop_after.is_some_and(|d| started.elapsed() >= d) && next < items.len() {
            // Items are sent in order, so the unsent ones are the tail.
            records.truncate(next);
            next = items.len();
        }
        while in_flight.len() < window && next < items.len() {
            let now = Instant::now();
            if period.is_some() && now < next_send {
                break;
            }
            // After a loss, a listed server may be the dead one (listed until a cleanup removes
            // it; a node killed while starting may not show as dead at once): a request sent to
            // it would be lost too. So then only servers of live nodes count.
            let servers = |counters: &mut Counters| {
                if suspect {
                    let (_, cleaned) = super::cleanup_dead_nodes(&node);
                    counters.dead_nodes_cleaned += cleaned;
                    super::live_servers(&node, |f| rpc.dynamic_config().list_servers(f))
                } else {
                    rpc.dynamic_config().number_of_servers()
                }
            };
            if servers(&mut counters) == 0 {
                if !in_flight.is_empty() {
                    break;
                }
                let waited = wait_for(opts.wait_service, || {
                    if servers(&mut counters) > 0 {
                        Ok(())
                    } else {
                        Err(anyhow!("no server"))
                    }
                });
                if waited.is_err() {
                    // Give up on the rest: the run ends with them not sent.
                    counters.not_sent += (items.len() - next) as u64;
                    next = items.len();
                    break;
                }
            }
            let record = &records[next];
            let mut request = client
                .loan_slice_uninit(record.frame.len())
                .map_err(|e| anyhow!("cannot loan request: {e:?}"))?;
            // 0 asks for the service's default deadline.
            *request.user_header_mut() = opts.deadline.map_or(0, |d| {
                u64::try_from(d.as_micros()).unwrap_or(u64::MAX).max(1)
            });
            let sent_at = Instant::now();
            let pending = request
                .write_from_slice(&record.frame)
                .send()
                .map_err(|e| anyhow!("cannot send request: {e:?}"))?;
            let delivered = pending.number_of_server_connections();
            if delivered == 0 {
                // Listed servers, but none received it: a restarted service whose server port
                // is in the service's list before its connection to this client exists. Nobody
                // will answer it, so it is not in flight: send it again shortly, for at most
                // `wait_service` (then give up on the rest, as when no server is listed).
                drop(pending);
                counters.undelivered += 1;
                if opts.verbose {
                    println!(
                        "undelivered {} at {} ms",
                        record.seq,
                        started.elapsed().as_millis()
                    );
                    let _ = std::io::Write::flush(&mut std::io::stdout());
                }
                let since = *undelivered_since.get_or_insert_with(Instant::now);
                if since.elapsed() >= opts.wait_service {
                    counters.not_sent += (items.len() - next) as u64;
                    next = items.len();
                } else {
                    std::thread::sleep(Duration::from_millis(10));
                }
                break;
            }
            undelivered_since = None;
            let _ = wake_service.notify();
            counters.sent += 1;
            if opts.verbose {
                println!(
                    "sent {} at {} ms ({} servers listed, delivered to {})",
                    record.seq,
                    started.elapsed().as_millis(),
                    rpc.dynamic_config().number_of_servers(),
                    delivered
                );
                let _ = std::io::Write::flush(&mut std::io::stdout());
            }
            in_flight.push(InFlight {
                index: next,
                seq: record.seq,
                sent_at,
                pending,
            });
            seq = record.seq + 1;
            next += 1;
            if let Some(p) = period {
                next_send = next_send.max(now - p) + p;
            }
        }
        // 4. Wait for a response, a timeout, or the next send time.
        let mut wait = Duration::from_millis(100);
        for f in &in_flight {
            wait = wait.min(opts.timeout.saturating_sub(f.sent_at.elapsed()));
        }
        if period.is_some() && next < items.len() && in_flight.len() < window {
            wait = wait.min(next_send.saturating_duration_since(Instant::now()));
        }
        if in_flight.is_empty() && (next >= items.len()) {
            break;
        }
        wait_for_wake_up(&listener, wait);
    }
    let _ = seq;
    // A last look for duplicates and late answers.
    wait_for_wake_up(&listener, Duration::from_millis(5));
    for (pending, how) in &settled {
        while let Ok(Some(_)) = pending.receive() {
            match how {
                Settled::Answered => counters.duplicated += 1,
                Settled::Lost => counters.late += 1,
            }
        }
    }
    if let Some(bar) = bar {
        bar.finish_and_clear();
    }
    counters.not_sent = records
        .iter()
        .filter(|r| matches!(r.fate, Fate::NotSent))
        .count() as u64;
    Ok(FeedRun {
        records,
        counters,
        elapsed: started.elapsed(),
    })
}

/// Wait on `listener` for a wake-up, at most `wait` (not at all when it is zero). iceoryx2 hands
/// the wait to a unix socket as `SO_RCVTIMEO` in whole microseconds, and a zero `timeval` there
/// means "no timeout": a wait under 1 us would block until the next notification, which for a
/// client with nothing in flight may never come. So a wait is at least 1 us.
pub fn wait_for_wake_up(
    listener: &iceoryx2::port::listener::Listener<ipc::Service>,
    wait: Duration,
) {
    if !wait.is_zero() {
        let _ = listener.timed_wait(|_| {}, wait.max(Duration::from_micros(1)));
    }
}

/// Retry `f` every 10 ms until it succeeds or `limit` has passed.
fn wait_for<T>(limit: Duration, mut f: impl FnMut() -> Result<T>) -> Result<T> {
    let start = Instant::now();
    loop {
        match f() {
            Ok(v) => return Ok(v),
            Err(e) if start.elapsed() >= limit => bail!("gave up after {limit:?}: {e}"),
            Err(_) => std::thread::sleep(Duration::from_millis(10)),
        }
    }
}

#[cfg(test)]
#[allow(clippy::unwrap_used)]
mod tests {
    use super::*;

    /// Whether `f` returns within `limit` (a safety net: it either returns at once or never).
    fn returns_within(limit: Duration, f: impl FnOnce() + Send + 'static) -> bool {
        let (tx, rx) = std::sync::mpsc::channel();
        std::thread::spawn(move || {
            f();
            let _ = tx.send(());
        });
        rx.recv_timeout(limit).is_ok()
    }

    #[test]
    fn a_wait_under_a_microsecond_returns() {
        let instance = Instance {
            prefix: format!("rcfgu_wake_{}_", std::process::id()),
            service: "wake".into(),
        };
        let returned = returns_within(Duration::from_secs(30), move || {
            let node = instance.node("wake-test").unwrap();
            let event = node
                .service_builder(&instance.service_name("to-feeder").unwrap())
                .event()
                .open_or_create()
                .unwrap();
            let listener = event.listener_builder().create().unwrap();
            // Nothing will ever notify this listener.
            wait_for_wake_up(&listener, Duration::from_nanos(500));
            drop(listener);
            drop(event);
            drop(node);
            let _ = super::super::remove_instance_segment(&instance);
        });
        assert!(returned, "a 500 ns wait did not return");
    }
}
