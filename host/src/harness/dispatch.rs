//! What the flight service's dispatcher does on a wake-up, and the order of service it keeps.
//!
//! [`Dispatcher::pump`] (1) sends the responses of finished jobs and frees their workers,
//! (2) moves every request iceoryx2 holds into the per-client queues ([`Scheduler`]), judging
//! each frame on receipt (`wire::decode_request`: a bounded amount of work, at most
//! `REQUEST_MAX_BYTES` of CRC and decoding) and recording it in its client's conduct
//! ([`super::conduct`]), (3) answers the queued requests past their deadline `Expired`, and
//! (4) gives turns while a worker is free, clients in turn: a good request goes to the free
//! worker, a bad frame is answered `BadRequest` by the dispatcher in its turn (it takes the
//! turn but not the worker), a request its client no longer waits for is dropped in its turn.
//!
//! **Order of service.** Every turn has a number, counted from 0 over all clients. Each answer
//! carries, in its iceoryx2 response user header ([`ServiceOrder`]), its request's turn and the
//! number of turns given before the request was received; a client can tell from its own
//! answers how many turns went to others while its request waited. `Expired` answers are given
//! outside the turns ([`NO_TURN`]).

use super::conduct::{Conducts, Standing};
use super::job::Job;
use super::schedule::{Queued, Scheduler, Share};
use super::{MAX_CLIENTS, MAX_IN_FLIGHT};
use anyhow::{anyhow, Result};
use iceoryx2::active_request::ActiveRequest;
use iceoryx2::identifiers::UniqueClientId;
use iceoryx2::port::ReceiveError;
use iceoryx2::prelude::*;
use reconfig_core::wire::{self, Expiry, FrameError, OutcomeRef};
use std::sync::mpsc::SyncSender;
use std::time::{Duration, Instant};

/// The iceoryx2 user header of a response: where its request stood in the order of service.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, ZeroCopySend)]
#[repr(C)]
pub struct ServiceOrder {
    /// The request's turn: how many turns the service had given (to any client) before it.
    /// [`NO_TURN`] for an answer given outside the turns (`Expired`).
    pub turn: u64,
    /// How many turns the service had given when it received the request.
    pub received_at_turn: u64,
}

/// [`ServiceOrder::turn`] of an answer given outside the turns.
pub const NO_TURN: u64 = u64::MAX;

/// The iceoryx2 user header of a request: its deadline in microseconds after the service
/// receives it; 0 asks for the service's default (`serve --deadline-ms`).
pub type RequestHeader = u64;

/// A request received by the service.
pub type Active = ActiveRequest<ipc::Service, [u8], RequestHeader, [u8], ServiceOrder>;

/// The service's server port.
pub type Server =
    iceoryx2::port::server::Server<ipc::Service, [u8], RequestHeader, [u8], ServiceOrder>;

/// Most frames one pump receives before it gives turns (iceoryx2 holds at most
/// `MAX_CLIENTS x MAX_IN_FLIGHT` requests the service has not received, and as many of clients
/// that have already dropped them).
const RECEIVE_PER_PUMP: usize = 2 * MAX_CLIENTS * MAX_IN_FLIGHT;

/// A received request waiting for its turn.
pub struct Entry {
    active: Active,
    /// Why `wire::decode_request` refused the frame; `None` for a good frame.
    bad: Option<FrameError>,
    received_at_turn: u64,
}

/// What the dispatcher did, since start-up.
#[derive(Clone, Debug, Default)]
pub struct Counters {
    /// Frames received.
    pub received: u64,
    /// Of them, bad frames (refused by `wire::decode_request`).
    pub bad: u64,
    /// Turns given.
    pub turns: u64,
    /// Responses sent (solved, refused, `BadRequest` and `Expired`).
    pub answered: u64,
    /// Requests answered `Expired` in the queue.
    pub expired: u64,
    /// Requests dropped in their turn, unsolved, because their client no longer waited.
    pub abandoned: u64,
    /// Frames of dropped clients, held unanswered.
    pub ignored: u64,
    /// Clients dropped for bad frames.
    pub clients_dropped: u64,
    /// Clients that went away while they had requests queued or held.
    pub clients_departed: u64,
    /// `Server::receive` failures other than every connection being at its borrow limit.
    pub receive_errors: u64,
}

/// The dispatcher's state: queues, conduct, workers, order of service.
pub struct Dispatcher {
    queue: Scheduler<UniqueClientId, Entry>,
    conduct: Conducts<UniqueClientId>,
    /// What each worker is solving, with its place in the order.
    in_flight: Vec<Option<(Active, ServiceOrder)>>,
    /// Each worker's job buffer while the worker is free.
    free: Vec<Option<Box<Job>>>,
    default_deadline: Duration,
    /// What happened.
    pub counters: Counters,
}

/// What one pump did.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Pumped {
    /// Finished jobs taken back from the workers.
    pub finished: usize,
    /// Frames received.
    pub received: usize,
    /// Responses sent.
    pub answered: usize,
}

impl Pumped {
    /// Anything at all.
    pub fn any(&self) -> bool {
        self.finished + self.received + self.answered > 0
    }
}

impl Dispatcher {
    /// A dispatcher for workers whose job buffers are `jobs` (index = worker).
    pub fn new(jobs: Vec<Box<Job>>, default_deadline: Duration) -> Self {
        Self {
            queue: Scheduler::new(MAX_CLIENTS, MAX_IN_FLIGHT),
            conduct: Conducts::new(2 * MAX_CLIENTS),
            in_flight: jobs.iter().map(|_| None).collect(),
            free: jobs.into_iter().map(Some).collect(),
            default_deadline,
            counters: Counters::default(),
        }
    }

    /// One wake-up's work: finished jobs, new frames, expiries, turns. `done` yields the
    /// workers' finished jobs; `jobs` are the workers' job channels.
    ///
    /// # Errors
    /// A worker that has died.
    pub fn pump(
        &mut self,
        server: &Server,
        mut done: impl FnMut() -> Result<Option<Box<Job>>>,
        jobs: &[SyncSender<Box<Job>>],
    ) -> Result<Pumped> {
        let answered_before = self.counters.answered;
        let mut pumped = Pumped::default();
        while let Some(job) = done()? {
            self.finish(job);
            pumped.finished += 1;
        }
        pumped.received = self.receive(server);
        self.expire(Instant::now());
        self.give_turns(jobs)?;
        pumped.answered = usize::try_from(self.counters.answered - answered_before).unwrap_or(0);
        Ok(pumped)
    }

    /// A worker's finished job: send its response, free the worker.
    pub fn finish(&mut self, job: Box<Job>) {
        let index = job.worker;
        if let Some((active, order)) = self.in_flight.get_mut(index).and_then(Option::take) {
            send_bytes(
                &active,
                order,
                job.response.get(..job.response_len).unwrap_or(&[]),
            );
            self.counters.answered += 1;
        }
        if let Some(slot) = self.free.get_mut(index) {
            *slot = Some(job);
        }
    }

    /// Move what iceoryx2 holds into the queues, judging each frame; returns how many.
    fn receive(&mut self, server: &Server) -> usize {
        let mut received = 0;
        while received < RECEIVE_PER_PUMP {
            let active = match server.receive() {
                Ok(Some(active)) => active,
                Ok(None) => break,
                // Every connection with requests waiting is at its limit of requests the
                // service holds (e.g. a dropped client's held frames): nothing to take now.
                Err(ReceiveError::ExceedsMaxBorrows) => break,
                Err(e) => {
                    // A broken connection to one client must not stop the service.
                    if self.counters.receive_errors == 0 {
                        eprintln!("serve: receive failed: {e:?} (counted from now on)");
                    }
                    self.counters.receive_errors += 1;
                    break;
                }
            };
            received += 1;
            self.admit(active);
        }
        received
    }

    /// Judge one frame and queue it in its client's queue.
    fn admit(&mut self, active: Active) {
        self.counters.received += 1;
        let client = active.origin();
        let now = Instant::now();
        let deadline = now + request_deadline(*active.user_header(), self.default_deadline);
        let received_at_turn = self.counters.turns;
        if self.conduct.standing(client) == Standing::Dropped {
            // Held unanswered in the muted queue (not even judged).
            self.counters.ignored += 1;
            let entry = Entry {
                active,
                bad: None,
                received_at_turn,
            };
            self.queue.push(client, entry, now, deadline);
            self.queue.set_share(client, Share::Muted);
            return;
        }
        let bad = wire::decode_request(active.payload()).err();
        if bad.is_some() {
            self.counters.bad += 1;
        }
        let standing = self.conduct.record(client, bad.is_some());
        let entry = Entry {
            active,
            bad,
            received_at_turn,
        };
        self.queue.push(client, entry, now, deadline);
        let share = match standing {
            Standing::Good => Share::Full,
            Standing::Throttled => Share::Throttled,
            Standing::Dropped => {
                self.counters.clients_dropped += 1;
                eprintln!(
                    "serve: client {client:?} dropped: {} bad frames among its last {}",
                    super::conduct::DROP_AT,
                    super::conduct::WINDOW
                );
                Share::Muted
            }
        };
        self.queue.set_share(client, share);
        if share == Share::Muted {
            self.counters.ignored += self.queue.len_of(client) as u64;
        }
    }

    /// Answer the queued requests past their deadline `Expired`, unsolved.
    fn expire(&mut self, now: Instant) {
        let mut answered = 0;
        self.queue.take_expired(now, |q| {
            expired_answer(&q, now);
            answered += 1;
        });
        self.counters.answered += answered;
        self.counters.expired += answered;
    }

    /// Give turns while a worker is free, clients in turn.
    fn give_turns(&mut self, jobs: &[SyncSender<Box<Job>>]) -> Result<()> {
        while let Some(index) = self.free.iter().position(Option::is_some) {
            let Some(q) = self.queue.pop() else { break };
            let order = ServiceOrder {
                turn: self.counters.turns,
                received_at_turn: q.item.received_at_turn,
            };
            self.counters.turns += 1;
            let Entry { active, bad, .. } = q.item;
            if !active.is_connected() {
                // Its client dropped it: the turn is spent, nothing is solved or answered.
                self.counters.abandoned += 1;
                continue;
            }
            if let Some(e) = bad {
                bad_answer(&active, order, e);
                self.counters.answered += 1;
                continue;
            }
            let Some(mut job) = self.free.get_mut(index).and_then(Option::take) else {
                break;
            };
            let bytes = active.payload();
            let len = bytes.len().min(job.request.len());
            if let (Some(dst), Some(src)) = (job.request.get_mut(..len), bytes.get(..len)) {
                dst.copy_from_slice(src);
            }
            job.request_len = len;
            if let Some(tx) = jobs.get(index) {
                tx.send(job)
                    .map_err(|_| anyhow!("worker {index} has died"))?;
            }
            if let Some(f) = self.in_flight.get_mut(index) {
                *f = Some((active, order));
            }
        }
        Ok(())
    }

    /// The earliest deadline of a queued request.
    pub fn next_deadline(&self) -> Option<Instant> {
        self.queue.next_deadline()
    }

    /// Forget the clients for which `listed` is false (their ports have gone): drop what of
    /// theirs is queued or held, unanswered, and their conduct.
    pub fn forget_departed(&mut self, listed: impl Fn(UniqueClientId) -> bool) {
        let mut gone = [None; MAX_CLIENTS];
        let mut n = 0;
        for client in self.queue.clients() {
            if !listed(client) && n < gone.len() {
                if let Some(g) = gone.get_mut(n) {
                    *g = Some(client);
                }
                n += 1;
            }
        }
        for client in gone.iter().flatten() {
            self.queue.remove(*client, drop);
            self.counters.clients_departed += 1;
        }
        if n > 0 || self.conduct.is_full() {
            self.conduct.retain(&listed);
        }
    }

    /// Requests queued, held ones included.
    pub fn queued(&self) -> usize {
        self.queue.len()
    }

    /// Requests held for dropped clients.
    pub fn held(&self) -> usize {
        self.queue.held()
    }

    /// Clients dropped and not yet gone.
    pub fn dropped_clients(&self) -> usize {
        self.conduct.dropped()
    }

    /// Workers solving a request.
    pub fn busy(&self) -> usize {
        self.in_flight.iter().filter(|f| f.is_some()).count()
    }

    /// At shutdown: drop every queued request unanswered (their clients see them lost, as
    /// after a crash); returns how many.
    pub fn drop_queued(&mut self) -> usize {
        let mut n = 0;
        self.queue.drain(|_| n += 1);
        n
    }
}

/// A request's deadline after receipt: its own, else the service's default.
fn request_deadline(header_us: RequestHeader, default: Duration) -> Duration {
    if header_us == 0 {
        default
    } else {
        Duration::from_micros(header_us)
    }
}

/// Send one response. A failure (a client that went away, a full response pool) loses this
/// one response, which the client reports as lost; it must not stop the service.
fn send_bytes(active: &Active, order: ServiceOrder, bytes: &[u8]) {
    match active.loan_slice_uninit(bytes.len()) {
        Ok(mut response) => {
            *response.user_header_mut() = order;
            if let Err(e) = response.write_from_slice(bytes).send() {
                eprintln!("serve: cannot send a response: {e:?}");
            }
        }
        Err(e) => eprintln!("serve: cannot loan a response: {e:?}"),
    }
}

/// Answer a bad frame `BadRequest` (the same bytes a worker's `wire::decode_request` gives).
fn bad_answer(active: &Active, order: ServiceOrder, e: FrameError) {
    let seq = wire::peek_request_seq(active.payload()).unwrap_or(0);
    let mut buf = [0u8; 256];
    let n = wire::encode_response(seq, 0, &OutcomeRef::BadRequest(e), &mut buf).unwrap_or(0);
    send_bytes(active, order, buf.get(..n).unwrap_or(&[]));
}

/// Answer a request that waited in the queue past its deadline, without solving it.
fn expired_answer(q: &Queued<Entry>, now: Instant) {
    let active = &q.item.active;
    let seq = wire::peek_request_seq(active.payload()).unwrap_or(0);
    let micros = |d: Duration| u64::try_from(d.as_micros()).unwrap_or(u64::MAX);
    let expiry = Expiry {
        queued_us: micros(now.saturating_duration_since(q.received)),
        deadline_us: micros(q.deadline.saturating_duration_since(q.received)),
    };
    let mut buf = [0u8; 256];
    let n = wire::encode_response(seq, 0, &OutcomeRef::Expired(expiry), &mut buf).unwrap_or(0);
    let order = ServiceOrder {
        turn: NO_TURN,
        received_at_turn: q.item.received_at_turn,
    };
    send_bytes(active, order, buf.get(..n).unwrap_or(&[]));
}
