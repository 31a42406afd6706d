//! `reconfig serve`: the flight service.
//!
//! One dispatcher thread owns every iceoryx2 port. It blocks in a `WaitSet` on the
//! `to-service` event (no busy spinning), until the earliest queued deadline, or for at most
//! [`HEARTBEAT`]. On every wake-up it resets the `to-service` listener and runs
//! [`Dispatcher::pump`] (finished jobs' responses, new requests into per-client queues, expiries,
//! turns to the free workers, clients in turn), again and again while a pump finds work.
//!
//! Why the heartbeat: iceoryx2's event (a unix datagram plus a notification state in shared
//! memory) can lose a wake-up for good. A listener that drains (`NOTIFIED -> IDLE`, then
//! empties the socket) while a notifier sends (`IDLE -> PENDING`, datagram, `PENDING ->
//! NOTIFIED`) reads that notifier's datagram yet leaves the state `NOTIFIED`; every later
//! `notify` then sees `NOTIFIED` and sends nothing, so a dispatcher that waits only for the
//! socket never wakes again. Under a client flooding notifications this happened within
//! seconds, and the service answered nobody until restarted. The heartbeat bounds such a stall
//! to one period, and the reset on every wake-up (`Listener::try_wait` moves `NOTIFIED` back
//! to `IDLE`) makes notifications wake the dispatcher again.
//!
//! Each worker is a thread pinned to one CPU of the set, with its own [`Worker`] (workspaces)
//! and one job buffer that travels dispatcher -> worker -> dispatcher over bounded channels;
//! the request path allocates nothing after start-up. A worker wakes the dispatcher through
//! its own notifier on `to-service`.
//!
//! SIGTERM / SIGINT end the `WaitSet` wait; the service then finishes jobs in progress, answers
//! them, drops its ports and node (which removes its shared memory) and exits 0.

use super::dispatch::{Dispatcher, RequestHeader, ServiceOrder};
use super::job::Job;
use super::worker::{Worker, WORKER_STACK_BYTES};
use super::{affinity, Instance, MAX_CLIENTS, MAX_IN_FLIGHT};
use anyhow::{anyhow, Context, Result};
use iceoryx2::identifiers::UniqueClientId;
use iceoryx2::prelude::*;
use iceoryx2::waitset::WaitSetRunResult;
use reconfig_core::limits::Limits;
use reconfig_core::wire::RESPONSE_MAX_BYTES;
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
    /// Limits every request is checked against before it is solved.
    pub limits: Limits,
    /// Deadline of a request that does not carry its own (counted from its receipt).
    pub default_deadline: Duration,
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

type Rpc = iceoryx2::service::port_factory::request_response::PortFactory<
    ipc::Service,
    [u8],
    RequestHeader,
    [u8],
    ServiceOrder,
>;

/// Longest wait of the dispatcher between two looks at its queues, events or not (see the
/// module's documentation: iceoryx2 can lose a wake-up).
pub const HEARTBEAT: Duration = Duration::from_millis(10);

/// Pumps per wake-up at most, before the dispatcher returns to its `WaitSet` (which reports
/// SIGTERM) and comes straight back.
const PUMPS_PER_WAKE: usize = 64;

/// How often, at most, the dispatcher looks for clients that have gone.
const DEPARTED_CHECK: Duration = Duration::from_secs(1);

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
        .response_user_header::<ServiceOrder>()
        .max_clients(MAX_CLIENTS)
        .max_servers(2)
        .max_active_requests_per_client(MAX_IN_FLIGHT)
        .max_response_buffer_size(2)
        .max_loaned_requests(MAX_IN_FLIGHT)
        .max_nodes(MAX_CLIENTS + 4)
        .enable_safe_overflow_for_requests(false)
        .enable_safe_overflow_for_responses(false)
        // Hand the dispatcher the requests their clients have already dropped too (iceoryx2's
        // default, stated here on purpose): it judges them and spends their turns. Without it,
        // `Server::receive` drops them in a loop of its own, which a client sending and dropping
        // requests as fast as it can could keep going.
        .enable_fire_and_forget_requests(true)
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
        // Never wait for a client: a response that finds the client's buffer for it full (a
        // client that does not read its answers) is dropped. iceoryx2's default would retry
        // until delivered, and a client that never reads could hold the dispatcher forever.
        .backpressure_strategy(BackpressureStrategy::DiscardData)
        .create()
        .map_err(|e| anyhow!("cannot create server: {e:?}"))?;
    let listener = super::listener(&to_service)?;
    let notifier = super::notifier(&to_feeder)?;

    // Workers: one per CPU, each with its job channel and its own notifier.
    let (done_tx, done_rx) = sync_channel::<Box<Job>>(workers);
    let mut job_txs = Vec::with_capacity(workers);
    let mut jobs: Vec<Box<Job>> = Vec::with_capacity(workers);
    let mut handles = Vec::with_capacity(workers);
    for (index, &cpu) in opts.cpus.iter().enumerate() {
        let (tx, rx) = sync_channel::<Box<Job>>(1);
        job_txs.push(tx);
        jobs.push(Job::boxed(index));
        let done = done_tx.clone();
        let worker_instance = inst.clone();
        let no_pin = opts.no_pin;
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

    let mut dispatcher = Dispatcher::new(jobs, opts.default_deadline);
    println!(
        "ready: service {} prefix {} workers {} cpus {:?}",
        inst.service, inst.prefix, workers, opts.cpus
    );
    use std::io::Write;
    let _ = std::io::stdout().flush();
    let allocations_at_start = super::alloc_count::allocations();

    let finished = || match done_rx.try_recv() {
        Ok(job) => Ok(Some(job)),
        Err(TryRecvError::Empty) => Ok(None),
        Err(TryRecvError::Disconnected) => Err(anyhow!("a worker has died")),
    };
    // Wake-ups by the heartbeat (no event) that found frames or finished jobs waiting: the
    // notifications iceoryx2 did not deliver.
    let mut missed_wakeups: u64 = 0;
    let mut departed_checked = Instant::now();
    let mut failed: Option<anyhow::Error> = None;
    let mut busy = false;
    let outcome = loop {
        let timeout = if busy {
            Duration::ZERO
        } else {
            dispatcher
                .next_deadline()
                .map_or(HEARTBEAT, |d| d.saturating_duration_since(Instant::now()))
                .min(HEARTBEAT)
        };
        let mut evented = false;
        let result = waitset.wait_and_process_once_with_timeout(
            |id| {
                evented |= id.has_event_from(&guard);
                CallbackProgression::Continue
            },
            timeout,
        );
        match result {
            Ok(WaitSetRunResult::TerminationRequest | WaitSetRunResult::Interrupt) => break result,
            Ok(_) => {}
            Err(_) => break result,
        }
        let mut first = true;
        let mut idle = true;
        busy = false;
        for round in 0..PUMPS_PER_WAKE {
            // Consume the notifications first (and move a lost wake-up's NOTIFIED state back
            // to IDLE): one sent after this wakes the next wait, so work this pump misses does
            // not wait for the heartbeat.
            let _ = listener.try_wait(|_| {});
            let pumped = match dispatcher.pump(&server, finished, &job_txs) {
                Ok(p) => p,
                Err(e) => {
                    failed = Some(e);
                    break;
                }
            };
            if pumped.answered > 0 {
                let _ = notifier.notify();
            }
            if first && !evented && pumped.received + pumped.finished > 0 {
                missed_wakeups += 1;
            }
            first = false;
            if !pumped.any() {
                break;
            }
            idle = false;
            // Still work after the last round: look again at once, after the WaitSet has had
            // its say (SIGTERM).
            busy = round + 1 == PUMPS_PER_WAKE;
        }
        if failed.is_some() {
            break Ok(WaitSetRunResult::StopRequest);
        }
        if idle && departed_checked.elapsed() >= DEPARTED_CHECK {
            departed_checked = Instant::now();
            let listed = listed_clients(&rpc);
            dispatcher.forget_departed(|c| listed.contains(&Some(c)));
        }
    };
    if let Some(e) = failed {
        return Err(e);
    }
    let outcome = outcome.map_err(|e| anyhow!("waitset failed: {e:?}"))?;
    let allocations = super::alloc_count::allocations() - allocations_at_start;
    let held = dispatcher.held();
    let queued = dispatcher.drop_queued();
    eprintln!(
        "serve: stopping ({outcome:?}); finishing jobs in progress, {} queued requests are \
         not answered ({held} of them held for dropped clients)",
        queued
    );
    // What the workers hold is finished and answered.
    let deadline = Instant::now() + Duration::from_secs(10);
    while dispatcher.busy() > 0 && Instant::now() < deadline {
        let _ = listener.timed_wait(|_| {}, Duration::from_millis(50));
        while let Ok(job) = done_rx.try_recv() {
            dispatcher.finish(job);
            let _ = notifier.notify();
        }
    }
    drop(job_txs);
    for h in handles {
        let _ = h.join();
    }
    let c = &dispatcher.counters;
    eprintln!(
        "serve: received {} frames ({} bad), gave {} turns, answered {} ({} expired in the queue), \
         dropped {} unsolved whose clients no longer waited; dropped {} client(s) for bad frames \
         ({} frames held unanswered), {} client(s) left with requests queued; {} wake-up(s) \
         came from the heartbeat, not from a notification; {} receive error(s)",
        c.received,
        c.bad,
        c.turns,
        c.answered,
        c.expired,
        c.abandoned,
        c.clients_dropped,
        c.ignored,
        c.clients_departed,
        missed_wakeups,
        c.receive_errors
    );
    eprintln!(
        "serve: heap allocations in the process after start-up: {allocations} (iceoryx2 and \
         WaitSet on the dispatcher; the workers make none)"
    );
    Ok(())
}

/// The ids of the clients iceoryx2 lists for the service (at most `MAX_CLIENTS`).
fn listed_clients(rpc: &Rpc) -> [Option<UniqueClientId>; MAX_CLIENTS] {
    let mut ids = [None; MAX_CLIENTS];
    let mut n = 0;
    rpc.dynamic_config().list_clients(|details| {
        if let Some(slot) = ids.get_mut(n) {
            *slot = Some(details.client_id);
        }
        n += 1;
        CallbackProgression::Continue
    });
    ids
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
    let event = inst
        .open_event(&node, "to-service")
        .with_context(|| format!("worker {index}"))?;
    let notifier = super::notifier(&event).with_context(|| format!("worker {index}"))?;
    Ok((node, notifier))
}
