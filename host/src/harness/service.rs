//! `reconfig serve`: the flight service.
//!
//! One dispatcher thread owns every iceoryx2 port. It blocks in a `WaitSet` on the
//! `to-service` event (no busy spinning), or until the earliest queued deadline. On a wake-up it
//! hands finished jobs' responses back over iceoryx2, moves every new request into its
//! per-client queues ([`Scheduler`]), answers the requests past their deadline `Expired`
//! unsolved, and hands the next requests to the free workers, clients in turn (round-robin).
//!
//! Each worker is a thread pinned to one CPU of the set, with its own [`Worker`] (workspaces)
//! and one job buffer that travels dispatcher -> worker -> dispatcher over bounded channels;
//! the request path allocates nothing after start-up. A worker wakes the dispatcher through
//! its own notifier on `to-service`.
//!
//! SIGTERM / SIGINT end the `WaitSet` wait; the service then finishes jobs in progress, answers
//! them, drops its ports and node (which removes its shared memory) and exits 0.

use super::schedule::Scheduler;
use super::worker::{Worker, WORKER_STACK_BYTES};
use super::{affinity, Instance, MAX_CLIENTS, MAX_IN_FLIGHT};
use anyhow::{anyhow, Context, Result};
use iceoryx2::active_request::ActiveRequest;
use iceoryx2::identifiers::UniqueClientId;
use iceoryx2::prelude::*;
use iceoryx2::waitset::WaitSetRunResult;
use reconfig_core::limits::Limits;
use reconfig_core::wire::{Expiry, OutcomeRef};
use reconfig_core::wire::{REQUEST_MAX_BYTES, RESPONSE_MAX_BYTES};
use std::sync::mpsc::{sync_channel, Receiver, SyncSender, TryRecvError};
use std::time::Duration;
use std::time::Instant;

/// Options of the flight service.
#[derive(Clone, Debug)]
pub struct ServiceOptions {
    /// Where the service lives.
    pub instance: Instance,
    /// One worker per CPU, pinned to it.
    pub cpus: Vec<usize>,
    /// Do not pin (for machines where affinity is not allowed).
    pub no_pin: bool,
    /// Test hook: each worker sleeps this long per request.
    pub delay: Duration,
    /// Limits every request is checked against before it is solved.
    pub limits: Limits,
    /// Deadline of a request that does not carry its own (counted from its receipt).
    pub default_deadline: Duration,
}

/// A request travelling to a worker and its response travelling back. Built once per worker.
pub struct Job {
    /// Which worker owns this buffer.
    pub worker: usize,
    /// Request frame bytes.
    pub request: [u8; REQUEST_MAX_BYTES],
    /// Used length of `request`.
    pub request_len: usize,
    /// Response frame bytes.
    pub response: [u8; RESPONSE_MAX_BYTES],
    /// Used length of `response`.
    pub response_len: usize,
}

impl Job {
    /// A job buffer for worker `worker` (allocated once, at start-up).
    pub fn boxed(worker: usize) -> Box<Self> {
        Box::new(Self {
            worker,
            request: [0; REQUEST_MAX_BYTES],
            request_len: 0,
            response: [0; RESPONSE_MAX_BYTES],
            response_len: 0,
        })
    }
}

/// Start-up for a thread that will block on `rx`: the first blocking receive on a std channel
/// builds the thread's channel context and waker entry (a few allocations, once). Doing it here,
/// before any request exists, keeps them off the request path. `rx` must be empty.
pub fn warm_up<T>(rx: &Receiver<T>) {
    let _ = rx.recv_timeout(Duration::from_millis(1));
}

/// The worker loop: take a job, answer it, hand it back, wake the dispatcher. Returns when the
/// dispatcher hangs up. `wake` is called after each job (the service passes an iceoryx2
/// notifier; tests pass a no-op).
pub fn worker_loop(
    worker: &mut Worker,
    jobs: &Receiver<Box<Job>>,
    done: &SyncSender<Box<Job>>,
    mut wake: impl FnMut(),
) {
    while let Ok(mut job) = jobs.recv() {
        let Job {
            request,
            request_len,
            response,
            response_len,
            ..
        } = &mut *job;
        let request = request.get(..*request_len).unwrap_or(&[]);
        *response_len = worker.handle(request, response);
        if done.send(job).is_err() {
            return;
        }
        wake();
    }
}

type Active = ActiveRequest<ipc::Service, [u8], RequestHeader, [u8], ()>;

type Rpc = iceoryx2::service::port_factory::request_response::PortFactory<
    ipc::Service,
    [u8],
    RequestHeader,
    [u8],
    (),
>;

/// The iceoryx2 user header of a request: its deadline in microseconds after the service
/// receives it; 0 asks for the service's default (`serve --deadline-ms`).
pub type RequestHeader = u64;

/// Longest blocking wait of the dispatcher when nothing is queued (it wakes on every event).
const IDLE_WAIT: Duration = Duration::from_secs(3600);

/// A request's deadline after receipt: its own, else the service's default.
fn request_deadline(header_us: RequestHeader, default: Duration) -> Duration {
    if header_us == 0 {
        default
    } else {
        Duration::from_micros(header_us)
    }
}

/// Run the flight service until SIGTERM / SIGINT. Prints one `ready` line on stdout when it
/// accepts requests.
pub fn run(opts: &ServiceOptions) -> Result<()> {
    let inst = &opts.instance;
    let node = inst.node("reconfig-serve")?;
    let (dead, cleaned) = super::cleanup_dead_nodes(&node);
    if dead > 0 {
        eprintln!("serve: found {dead} dead node(s), cleaned up {cleaned}");
    }
    let workers = opts.cpus.len();
    let rpc: Rpc = node
        .service_builder(&inst.service_name("rpc")?)
        .request_response::<[u8], [u8]>()
        .request_user_header::<RequestHeader>()
        .max_clients(MAX_CLIENTS)
        .max_servers(2)
        .max_active_requests_per_client(MAX_IN_FLIGHT)
        .max_response_buffer_size(2)
        .max_loaned_requests(MAX_IN_FLIGHT)
        .max_nodes(MAX_CLIENTS + 4)
        .enable_safe_overflow_for_requests(false)
        .enable_safe_overflow_for_responses(false)
        .open_or_create()
        .map_err(|e| anyhow!("cannot open service rpc: {e:?}"))?;
    let to_service = node
        .service_builder(&inst.service_name("to-service")?)
        .event()
        .max_notifiers(MAX_CLIENTS + 64)
        .max_listeners(4)
        .max_nodes(MAX_CLIENTS + 64)
        .open_or_create()
        .map_err(|e| anyhow!("cannot open event to-service: {e:?}"))?;
    let to_feeder = node
        .service_builder(&inst.service_name("to-feeder")?)
        .event()
        .max_notifiers(4)
        .max_listeners(MAX_CLIENTS + 4)
        .max_nodes(MAX_CLIENTS + 4)
        .open_or_create()
        .map_err(|e| anyhow!("cannot open event to-feeder: {e:?}"))?;
    let server = rpc
        .server_builder()
        .initial_max_slice_len(RESPONSE_MAX_BYTES)
        .allocation_strategy(AllocationStrategy::Static)
        .max_loaned_responses_per_request(1)
        .create()
        .map_err(|e| anyhow!("cannot create server: {e:?}"))?;
    let listener = to_service
        .listener_builder()
        .create()
        .map_err(|e| anyhow!("cannot create listener: {e:?}"))?;
    let notifier = to_feeder
        .notifier_builder()
        .create()
        .map_err(|e| anyhow!("cannot create notifier: {e:?}"))?;

    // Workers: one per CPU, each with its job channel and its own notifier.
    let (done_tx, done_rx) = sync_channel::<Box<Job>>(workers);
    let mut job_txs = Vec::with_capacity(workers);
    let mut free: Vec<Option<Box<Job>>> = Vec::with_capacity(workers);
    let mut handles = Vec::with_capacity(workers);
    for (index, &cpu) in opts.cpus.iter().enumerate() {
        let (tx, rx) = sync_channel::<Box<Job>>(1);
        job_txs.push(tx);
        free.push(Some(Job::boxed(index)));
        let done = done_tx.clone();
        let worker_instance = inst.clone();
        let no_pin = opts.no_pin;
        let delay = opts.delay;
        let limits = opts.limits;
        let (ready_tx, ready_rx) = sync_channel::<Result<(), String>>(1);
        let handle = std::thread::Builder::new()
            .name(format!("worker-{index}-cpu{cpu}"))
            .stack_size(WORKER_STACK_BYTES)
            .spawn(move || {
                let pinned = if no_pin {
                    Ok(())
                } else {
                    affinity::pin_current_thread(cpu).map_err(|e| e.to_string())
                };
                // iceoryx2 ports are not Send: each worker opens its own node and notifier.
                let wake = pinned.and_then(|()| {
                    worker_notifier(&worker_instance, index).map_err(|e| format!("{e:#}"))
                });
                let mut worker = Worker::new();
                worker.delay = delay;
                worker.limits = limits;
                warm_up(&rx);
                let (wake, pinned) = match wake {
                    Ok(w) => (Some(w), Ok(())),
                    Err(e) => (None, Err(e)),
                };
                let failed = pinned.is_err();
                let _ = ready_tx.send(pinned);
                if failed {
                    return;
                }
                let Some((_node, wake)) = wake else { return };
                worker_loop(&mut worker, &rx, &done, || {
                    let _ = wake.notify();
                });
            })
            .context("cannot spawn worker")?;
        ready_rx
            .recv()
            .context("worker died at start-up")?
            .map_err(|e| anyhow!(e))?;
        handles.push(handle);
    }
    drop(done_tx);

    let waitset = WaitSetBuilder::new()
        .create::<ipc::Service>()
        .map_err(|e| anyhow!("cannot create waitset: {e:?}"))?;
    let guard = waitset
        .attach_notification(&listener)
        .map_err(|e| anyhow!("cannot attach listener: {e:?}"))?;

    let default_deadline = opts.default_deadline;
    let mut in_flight: Vec<Option<Active>> = (0..workers).map(|_| None).collect();
    let mut queue: Scheduler<UniqueClientId, Active> = Scheduler::new(MAX_CLIENTS, MAX_IN_FLIGHT);
    let mut answered: u64 = 0;
    let mut expired: u64 = 0;
    println!(
        "ready: service {} prefix {} workers {} cpus {:?}",
        inst.service, inst.prefix, workers, opts.cpus
    );
    use std::io::Write;
    let _ = std::io::stdout().flush();
    let allocations_at_start = super::alloc_count::allocations();

    let mut pump = |in_flight: &mut Vec<Option<Active>>,
                    free: &mut Vec<Option<Box<Job>>>,
                    queue: &mut Scheduler<UniqueClientId, Active>|
     -> Result<()> {
        // 1. Finished jobs: send their responses, free their workers.
        loop {
            match done_rx.try_recv() {
                Ok(job) => {
                    let index = job.worker;
                    if let Some(active) = in_flight.get_mut(index).and_then(Option::take) {
                        send_response(&active, &job);
                        answered += 1;
                        let _ = notifier.notify();
                    }
                    if let Some(slot) = free.get_mut(index) {
                        *slot = Some(job);
                    }
                }
                Err(TryRecvError::Empty) => break,
                Err(TryRecvError::Disconnected) => return Err(anyhow!("a worker has died")),
            }
        }
        // 2. Everything iceoryx2 holds moves to the per-client queues (bounded by iceoryx2's
        // MAX_CLIENTS x MAX_IN_FLIGHT), so clients can be served in turn.
        loop {
            let active = match server.receive() {
                Ok(Some(active)) => active,
                Ok(None) => break,
                Err(e) => {
                    // A broken connection to one feeder must not stop the service.
                    eprintln!("serve: receive failed: {e:?}");
                    break;
                }
            };
            let len = active.payload().len();
            if len > REQUEST_MAX_BYTES {
                oversized_answer(&active, len);
                answered += 1;
                let _ = notifier.notify();
                continue;
            }
            let now = Instant::now();
            let deadline = now + request_deadline(*active.user_header(), default_deadline);
            queue.push(active.origin(), active, now, deadline);
        }
        // 3. Requests past their deadline are answered without being solved.
        let now = Instant::now();
        queue.take_expired(now, |q| {
            expired_answer(&q, now);
            answered += 1;
            expired += 1;
            let _ = notifier.notify();
        });
        // 4. Free workers take the next request, clients in turn.
        for index in 0..free.len() {
            let Some(slot) = free.get_mut(index) else {
                break;
            };
            if slot.is_none() {
                continue;
            }
            let Some(q) = queue.pop() else { break };
            let Some(mut job) = slot.take() else { break };
            let bytes = q.item.payload();
            let len = bytes.len().min(job.request.len());
            if let (Some(dst), Some(src)) = (job.request.get_mut(..len), bytes.get(..len)) {
                dst.copy_from_slice(src);
            }
            job.request_len = len;
            if let Some(tx) = job_txs.get(index) {
                tx.send(job)
                    .map_err(|_| anyhow!("worker {index} has died"))?;
            }
            if let Some(f) = in_flight.get_mut(index) {
                *f = Some(q.item);
            }
        }
        Ok(())
    };

    // Wait for a wake-up or the next queued deadline, whichever comes first; then pump.
    let mut failed: Option<anyhow::Error> = None;
    let outcome = loop {
        let timeout = queue
            .next_deadline()
            .map_or(IDLE_WAIT, |d| d.saturating_duration_since(Instant::now()))
            .min(IDLE_WAIT);
        let result = waitset.wait_and_process_once_with_timeout(
            |id| {
                if id.has_event_from(&guard) {
                    // Consume the notifications; the pump below serves everything there is.
                    let _ = listener.try_wait(|_| {});
                }
                CallbackProgression::Continue
            },
            timeout,
        );
        match result {
            Ok(WaitSetRunResult::TerminationRequest | WaitSetRunResult::Interrupt) => break result,
            Ok(_) => {}
            Err(_) => break result,
        }
        if let Err(e) = pump(&mut in_flight, &mut free, &mut queue) {
            failed = Some(e);
            break Ok(WaitSetRunResult::StopRequest);
        }
    };
    if let Some(e) = failed {
        return Err(e);
    }
    let outcome = outcome.map_err(|e| anyhow!("waitset failed: {e:?}"))?;
    let allocations = super::alloc_count::allocations() - allocations_at_start;
    eprintln!(
        "serve: stopping ({outcome:?}); finishing jobs in progress, {} queued requests are \
         not answered",
        queue.len()
    );
    // Queued requests are dropped unanswered (their clients see them lost, as on a crash);
    // what the workers hold is finished and answered.
    queue.drain(drop);
    let deadline = Instant::now() + Duration::from_secs(10);
    while in_flight.iter().any(Option::is_some) && Instant::now() < deadline {
        let _ = listener.timed_wait(|_| {}, Duration::from_millis(50));
        while let Ok(job) = done_rx.try_recv() {
            if let Some(active) = in_flight.get_mut(job.worker).and_then(Option::take) {
                send_response(&active, &job);
                answered += 1;
                let _ = notifier.notify();
            }
        }
    }
    drop(job_txs);
    for h in handles {
        let _ = h.join();
    }
    eprintln!(
        "serve: answered {answered} requests ({expired} expired in the queue); heap allocations in the process after start-up: \
         {allocations} (iceoryx2 and WaitSet on the dispatcher; the workers make none)"
    );
    Ok(())
}

/// A worker's own node and its notifier on `to-service`.
fn worker_notifier(
    inst: &Instance,
    index: usize,
) -> Result<(
    Node<ipc::Service>,
    iceoryx2::port::notifier::Notifier<ipc::Service>,
)> {
    let node = inst.node(&format!("reconfig-worker-{index}"))?;
    let event = node
        .service_builder(&inst.service_name("to-service")?)
        .event()
        .open()
        .map_err(|e| anyhow!("worker {index} cannot open event to-service: {e:?}"))?;
    let notifier = event
        .notifier_builder()
        .create()
        .map_err(|e| anyhow!("worker {index} cannot create notifier: {e:?}"))?;
    Ok((node, notifier))
}

/// Send a job's response. A failure (a feeder that went away, a full response pool) loses this
/// one response, which the feeder reports as lost; it must not stop the service.
fn send_response(active: &Active, job: &Job) {
    send_bytes(active, job.response.get(..job.response_len).unwrap_or(&[]));
}

fn send_bytes(active: &Active, bytes: &[u8]) {
    match active.loan_slice_uninit(bytes.len()) {
        Ok(response) => {
            if let Err(e) = response.write_from_slice(bytes).send() {
                eprintln!("serve: cannot send a response: {e:?}");
            }
        }
        Err(e) => eprintln!("serve: cannot loan a response: {e:?}"),
    }
}

/// Answer a request that waited in the queue past its deadline, without solving it.
fn expired_answer(q: &super::schedule::Queued<Active>, now: Instant) {
    let seq = reconfig_core::wire::peek_request_seq(q.item.payload()).unwrap_or(0);
    let micros = |d: Duration| u64::try_from(d.as_micros()).unwrap_or(u64::MAX);
    let expiry = Expiry {
        queued_us: micros(now.saturating_duration_since(q.received)),
        deadline_us: micros(q.deadline.saturating_duration_since(q.received)),
    };
    let mut buf = [0u8; 256];
    let n = reconfig_core::wire::encode_response(seq, 0, &OutcomeRef::Expired(expiry), &mut buf)
        .unwrap_or(0);
    send_bytes(&q.item, buf.get(..n).unwrap_or(&[]));
}

/// Answer a request longer than the largest frame without copying it to a worker.
fn oversized_answer(active: &Active, len: usize) {
    let seq = reconfig_core::wire::peek_request_seq(active.payload()).unwrap_or(0);
    let err = reconfig_core::wire::FrameError::Oversized {
        len: u32::try_from(len).unwrap_or(u32::MAX),
        max: REQUEST_MAX_BYTES as u32,
    };
    let mut buf = [0u8; 256];
    let n = reconfig_core::wire::encode_response(
        seq,
        0,
        &reconfig_core::wire::OutcomeRef::BadRequest(err),
        &mut buf,
    )
    .unwrap_or(0);
    send_bytes(active, buf.get(..n).unwrap_or(&[]));
}
