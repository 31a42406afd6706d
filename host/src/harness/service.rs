//! `reconfig serve`: the flight service.
//!
//! One dispatcher thread owns every iceoryx2 port. It blocks in a `WaitSet` on the
//! `to-service` event (no busy spinning). On a wake-up it hands finished jobs' responses back
//! over iceoryx2, then takes new requests from the server port only while a worker is free, so
//! a request waits in iceoryx2's queue, not in ours, and each is dispatched to a free worker.
//!
//! Each worker is a thread pinned to one CPU of the set, with its own [`Worker`] (workspaces)
//! and one job buffer that travels dispatcher -> worker -> dispatcher over bounded channels;
//! the request path allocates nothing after start-up. A worker wakes the dispatcher through
//! its own notifier on `to-service`.
//!
//! SIGTERM / SIGINT end the `WaitSet` wait; the service then finishes jobs in progress, answers
//! them, drops its ports and node (which removes its shared memory) and exits 0.

use super::worker::{Worker, WORKER_STACK_BYTES};
use super::{affinity, Instance, MAX_CLIENTS, MAX_IN_FLIGHT};
use anyhow::{anyhow, Context, Result};
use iceoryx2::active_request::ActiveRequest;
use iceoryx2::prelude::*;
use reconfig_core::wire::{REQUEST_MAX_BYTES, RESPONSE_MAX_BYTES};
use std::sync::mpsc::{sync_channel, Receiver, SyncSender, TryRecvError};
use std::time::Duration;

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

type Active = ActiveRequest<ipc::Service, [u8], (), [u8], ()>;

type Rpc = iceoryx2::service::port_factory::request_response::PortFactory<
    ipc::Service,
    [u8],
    (),
    [u8],
    (),
>;

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

    let mut in_flight: Vec<Option<Active>> = (0..workers).map(|_| None).collect();
    let mut answered: u64 = 0;
    let mut failed: Option<anyhow::Error> = None;
    println!(
        "ready: service {} prefix {} workers {} cpus {:?}",
        inst.service, inst.prefix, workers, opts.cpus
    );
    use std::io::Write;
    let _ = std::io::stdout().flush();
    let allocations_at_start = super::alloc_count::allocations();

    let mut pump =
        |in_flight: &mut Vec<Option<_>>, free: &mut Vec<Option<Box<Job>>>| -> Result<()> {
            // Finished jobs first: send their responses, free their workers.
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
            // Then new requests, only while a worker is free.
            for index in 0..free.len() {
                let Some(slot) = free.get_mut(index) else {
                    break;
                };
                if slot.is_none() {
                    continue;
                }
                let active = match server.receive() {
                    Ok(Some(active)) => active,
                    Ok(None) => break,
                    Err(e) => {
                        // A broken connection to one feeder must not stop the service.
                        eprintln!("serve: receive failed: {e:?}");
                        break;
                    }
                };
                let Some(mut job) = slot.take() else { break };
                let bytes = active.payload();
                let len = bytes.len().min(job.request.len());
                if let (Some(dst), Some(src)) = (job.request.get_mut(..len), bytes.get(..len)) {
                    dst.copy_from_slice(src);
                }
                // A request longer than the largest frame keeps its true length, so the decoder
                // reports it as oversized rather than as a truncated frame.
                job.request_len = if bytes.len() > job.request.len() {
                    job.request.len() + 1
                } else {
                    len
                };
                if job.request_len > job.request.len() {
                    oversized_answer(&active, bytes.len());
                    answered += 1;
                    let _ = notifier.notify();
                    *slot = Some(job);
                    continue;
                }
                if let Some(tx) = job_txs.get(index) {
                    tx.send(job)
                        .map_err(|_| anyhow!("worker {index} has died"))?;
                }
                if let Some(f) = in_flight.get_mut(index) {
                    *f = Some(active);
                }
            }
            Ok(())
        };

    let outcome = waitset.wait_and_process(|id| {
        if id.has_event_from(&guard) {
            // Consume the notifications, then serve everything that is there.
            let _ = listener.try_wait(|_| {});
            if let Err(e) = pump(&mut in_flight, &mut free) {
                failed = Some(e);
                return CallbackProgression::Stop;
            }
        }
        CallbackProgression::Continue
    });
    if let Some(e) = failed {
        return Err(e);
    }
    let outcome = outcome.map_err(|e| anyhow!("waitset failed: {e:?}"))?;
    let allocations = super::alloc_count::allocations() - allocations_at_start;
    eprintln!("serve: stopping ({outcome:?}); finishing jobs in progress");
    // Finish what the workers hold; answer it.
    let deadline = std::time::Instant::now() + Duration::from_secs(10);
    while in_flight.iter().any(Option::is_some) && std::time::Instant::now() < deadline {
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
        "serve: answered {answered} requests; heap allocations in the process after start-up: \
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
