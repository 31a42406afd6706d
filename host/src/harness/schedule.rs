//! The dispatcher's queue: round-robin over clients, with a deadline per request.
//!
//! iceoryx2 hands a server its requests client by client, so a dispatcher that takes them in
//! that order serves one busy client's queue before another's (the starvation the two-feeder
//! runs showed). The dispatcher instead moves every request it receives into this queue at
//! once, one FIFO per client, and dispatches from the clients in turn: a client with a queue
//! never waits for more than one request of each other client. A request still queued when its
//! deadline passes is taken out by [`Scheduler::take_expired`] and answered `Expired`, unsolved.
//!
//! Each client's queue has a [`Share`]: `Full` (one turn per round), `Throttled` (one turn in
//! [`THROTTLED_ROUNDS`] rounds while another client has a request queued; alone it is served)
//! or `Muted` (never served, never expired: what it holds stays held until the client is
//! [`Scheduler::remove`]d). The dispatcher sets the share from the client's conduct
//! (`harness::conduct`).
//!
//! Capacity: `slots` client queues of `per_client` requests, allocated at start-up. iceoryx2
//! bounds both (`MAX_CLIENTS` clients of `MAX_IN_FLIGHT` active requests each), so the
//! request path does not allocate; a client beyond the slots (only possible while dead clients'
//! requests are still queued) gets a new slot, which allocates once.

use std::collections::VecDeque;
use std::time::Instant;

/// A queued request.
#[derive(Debug)]
pub struct Queued<T> {
    /// What was received (the iceoryx2 active request).
    pub item: T,
    /// When the dispatcher received it.
    pub received: Instant,
    /// When it expires if still queued.
    pub deadline: Instant,
}

/// How much of the round-robin a client's queue gets.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Share {
    /// One turn per round.
    Full,
    /// One turn in [`THROTTLED_ROUNDS`] rounds while another client has a request queued.
    Throttled,
    /// No turn: the queue is held, neither served nor expired.
    Muted,
}

/// A throttled client gets one turn in this many rounds (while others wait).
pub const THROTTLED_ROUNDS: u8 = 4;

struct Slot<K, T> {
    client: Option<K>,
    queue: VecDeque<Queued<T>>,
    share: Share,
    /// Rounds a throttled queue still sits out before its next turn.
    sit_out: u8,
}

impl<K, T> Slot<K, T> {
    fn new(per_client: usize) -> Self {
        Self {
            client: None,
            queue: VecDeque::with_capacity(per_client),
            share: Share::Full,
            sit_out: 0,
        }
    }

    /// Has a request that may be served.
    fn ready(&self) -> bool {
        self.share != Share::Muted && !self.queue.is_empty()
    }
}

/// Round-robin queues per client `K`.
pub struct Scheduler<K, T> {
    slots: Vec<Slot<K, T>>,
    per_client: usize,
    /// The slot to look at first on the next pop.
    cursor: usize,
    len: usize,
}

impl<K: Copy + Eq, T> Scheduler<K, T> {
    /// Queues for `slots` clients of `per_client` requests each.
    pub fn new(slots: usize, per_client: usize) -> Self {
        Self {
            slots: (0..slots.max(1)).map(|_| Slot::new(per_client)).collect(),
            per_client,
            cursor: 0,
            len: 0,
        }
    }

    /// Requests queued (muted queues included).
    pub fn len(&self) -> usize {
        self.len
    }

    /// Requests of muted queues.
    pub fn held(&self) -> usize {
        self.slots
            .iter()
            .filter(|s| s.share == Share::Muted)
            .map(|s| s.queue.len())
            .sum()
    }

    /// Nothing queued.
    pub fn is_empty(&self) -> bool {
        self.len == 0
    }

    /// Queue a request of `client`.
    pub fn push(&mut self, client: K, item: T, received: Instant, deadline: Instant) {
        let index = match self.slots.iter().position(|s| s.client == Some(client)) {
            Some(i) => i,
            // An idle slot (its client has nothing queued) is reused for a new client.
            None => match self.slots.iter().position(|s| s.queue.is_empty()) {
                Some(i) => {
                    if let Some(slot) = self.slots.get_mut(i) {
                        slot.share = Share::Full;
                        slot.sit_out = 0;
                    }
                    i
                }
                None => {
                    self.slots.push(Slot::new(self.per_client));
                    self.slots.len() - 1
                }
            },
        };
        if let Some(slot) = self.slots.get_mut(index) {
            slot.client = Some(client);
            slot.queue.push_back(Queued {
                item,
                received,
                deadline,
            });
            self.len += 1;
        }
    }

    /// Requests queued by `client`.
    pub fn len_of(&self, client: K) -> usize {
        self.slots
            .iter()
            .filter(|s| s.client == Some(client))
            .map(|s| s.queue.len())
            .sum()
    }

    /// Set the share of `client`'s queue (a client with nothing queued has none: its next
    /// request starts at `Full`, so set the share after [`Scheduler::push`]).
    pub fn set_share(&mut self, client: K, share: Share) {
        if let Some(slot) = self.slots.iter_mut().find(|s| s.client == Some(client)) {
            if slot.share != share {
                slot.share = share;
                slot.sit_out = 0;
            }
        }
    }

    /// The next request in round-robin order over the clients with a queue. A throttled queue
    /// sits out `THROTTLED_ROUNDS - 1` rounds after each turn while another queue is ready; a
    /// muted queue is never served.
    pub fn pop(&mut self) -> Option<Queued<T>> {
        let n = self.slots.len();
        let ready = self.slots.iter().filter(|s| s.ready()).count();
        if ready == 0 {
            return None;
        }
        // Each throttled queue sits out at most THROTTLED_ROUNDS - 1 passes, so the cursor
        // finds a queue to serve within THROTTLED_ROUNDS rounds.
        for step in 0..n * usize::from(THROTTLED_ROUNDS) {
            let index = (self.cursor + step) % n;
            let Some(slot) = self.slots.get_mut(index) else {
                continue;
            };
            if !slot.ready() {
                continue;
            }
            if slot.share == Share::Throttled && ready > 1 && slot.sit_out > 0 {
                slot.sit_out -= 1;
                continue;
            }
            if let Some(q) = slot.queue.pop_front() {
                if slot.share == Share::Throttled {
                    slot.sit_out = THROTTLED_ROUNDS - 1;
                }
                self.cursor = (index + 1) % n;
                self.len -= 1;
                return Some(q);
            }
        }
        None
    }

    /// Take out every request of `client` (a client that has gone), in queue order.
    pub fn remove(&mut self, client: K, mut f: impl FnMut(Queued<T>)) {
        for slot in self.slots.iter_mut().filter(|s| s.client == Some(client)) {
            while let Some(q) = slot.queue.pop_front() {
                self.len -= 1;
                f(q);
            }
            slot.client = None;
            slot.share = Share::Full;
            slot.sit_out = 0;
        }
    }

    /// Every client with a queue (muted ones included).
    pub fn clients(&self) -> impl Iterator<Item = K> + '_ {
        self.slots
            .iter()
            .filter(|s| !s.queue.is_empty())
            .filter_map(|s| s.client)
    }

    /// Take out every request whose deadline is at or before `now`, in queue order (muted
    /// queues keep theirs).
    pub fn take_expired(&mut self, now: Instant, mut f: impl FnMut(Queued<T>)) {
        for slot in self.slots.iter_mut().filter(|s| s.share != Share::Muted) {
            // Deadlines of one client need not be in order (each request carries its own).
            let mut i = 0;
            while i < slot.queue.len() {
                if slot.queue.get(i).is_some_and(|q| q.deadline <= now) {
                    if let Some(q) = slot.queue.remove(i) {
                        self.len -= 1;
                        f(q);
                    }
                } else {
                    i += 1;
                }
            }
        }
    }

    /// The earliest deadline queued (muted queues have none).
    pub fn next_deadline(&self) -> Option<Instant> {
        self.slots
            .iter()
            .filter(|s| s.share != Share::Muted)
            .flat_map(|s| s.queue.iter().map(|q| q.deadline))
            .min()
    }

    /// Take out everything (at shutdown).
    pub fn drain(&mut self, mut f: impl FnMut(Queued<T>)) {
        for slot in &mut self.slots {
            while let Some(q) = slot.queue.pop_front() {
                f(q);
            }
        }
        self.len = 0;
    }
}

#[cfg(test)]
#[allow(clippy::unwrap_used)]
mod tests {
    use super::*;
    use std::time::Duration;

    #[test]
    fn clients_take_turns_whatever_arrived_first() {
        let t0 = Instant::now();
        let far = t0 + Duration::from_secs(60);
        let mut s = Scheduler::<u32, (u32, u32)>::new(2, 8);
        // Client 1 queues five requests before client 2's two arrive.
        for k in 0..5 {
            s.push(1, (1, k), t0, far);
        }
        s.push(2, (2, 0), t0, far);
        s.push(2, (2, 1), t0, far);
        let order: Vec<_> = std::iter::from_fn(|| s.pop().map(|q| q.item)).collect();
        assert_eq!(
            order,
            [(1, 0), (2, 0), (1, 1), (2, 1), (1, 2), (1, 3), (1, 4)]
        );
        assert!(s.is_empty());
    }

    #[test]
    fn expired_requests_leave_the_queue_and_the_rest_keep_their_order() {
        let t0 = Instant::now();
        let mut s = Scheduler::<u32, u32>::new(2, 8);
        s.push(1, 10, t0, t0 + Duration::from_millis(50));
        s.push(1, 11, t0, t0 + Duration::from_millis(5));
        s.push(2, 20, t0, t0 + Duration::from_millis(5));
        s.push(1, 12, t0, t0 + Duration::from_millis(50));
        assert_eq!(s.next_deadline(), Some(t0 + Duration::from_millis(5)));
        let mut gone = Vec::new();
        s.take_expired(t0 + Duration::from_millis(5), |q| gone.push(q.item));
        assert_eq!(gone, [11, 20]);
        assert_eq!(s.len(), 2);
        assert_eq!(s.pop().unwrap().item, 10);
        assert_eq!(s.pop().unwrap().item, 12);
        assert_eq!(s.pop().map(|q| q.item), None);
    }

    #[test]
    fn a_throttled_client_gets_one_turn_in_four_rounds_while_others_wait() {
        let t0 = Instant::now();
        let far = t0 + Duration::from_secs(60);
        let mut s = Scheduler::<u32, (u32, u32)>::new(2, 16);
        for k in 0..8 {
            s.push(1, (1, k), t0, far);
            s.push(2, (2, k), t0, far);
        }
        s.set_share(1, Share::Throttled);
        let order: Vec<u32> = std::iter::from_fn(|| s.pop().map(|q| q.item.0)).collect();
        // Client 1 is served first (nothing sat out yet), then once in four rounds, in which
        // client 2 has four turns; when client 2 has nothing left, client 1 is served alone.
        assert_eq!(order, [1, 2, 2, 2, 2, 1, 2, 2, 2, 2, 1, 1, 1, 1, 1, 1]);
    }

    #[test]
    fn a_muted_client_is_neither_served_nor_expired_until_removed() {
        let t0 = Instant::now();
        let soon = t0 + Duration::from_millis(5);
        let mut s = Scheduler::<u32, u32>::new(2, 4);
        s.push(1, 10, t0, soon);
        s.push(1, 11, t0, soon);
        s.push(2, 20, t0, soon + Duration::from_secs(1));
        s.set_share(1, Share::Muted);
        assert_eq!(s.held(), 2);
        assert_eq!(s.next_deadline(), Some(soon + Duration::from_secs(1)));
        let mut gone = Vec::new();
        s.take_expired(soon, |q| gone.push(q.item));
        assert!(gone.is_empty());
        assert_eq!(s.pop().map(|q| q.item), Some(20));
        assert_eq!(s.pop().map(|q| q.item), None);
        assert_eq!(s.len(), 2);
        s.remove(1, |q| gone.push(q.item));
        assert_eq!(gone, [10, 11]);
        assert!(s.is_empty());
        // The slot is free again, at full share, for the next client.
        s.push(3, 30, t0, soon);
        assert_eq!(s.pop().map(|q| q.item), Some(30));
    }

    #[test]
    fn more_clients_than_slots_still_queue() {
        let t0 = Instant::now();
        let far = t0 + Duration::from_secs(1);
        let mut s = Scheduler::<u32, u32>::new(1, 2);
        for c in 0..3 {
            s.push(c, c, t0, far);
        }
        let mut got: Vec<_> = std::iter::from_fn(|| s.pop().map(|q| q.item)).collect();
        got.sort_unstable();
        assert_eq!(got, [0, 1, 2]);
    }
}
