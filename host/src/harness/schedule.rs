//! The dispatcher's queue: round-robin over clients, with a deadline per request.
//!
//! iceoryx2 hands a server its requests client by client, so a dispatcher that takes them in
//! that order serves one busy client's queue before another's (the starvation the two-feeder
//! runs showed). The dispatcher instead moves every request it receives into this queue at
//! once, one FIFO per client, and dispatches from the clients in turn: a client with a queue
//! never waits for more than one request of each other client. A request still queued when its
//! deadline passes is taken out by [`Scheduler::take_expired`] and answered `Expired`, unsolved.
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

struct Slot<K, T> {
    client: Option<K>,
    queue: VecDeque<Queued<T>>,
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
            slots: (0..slots.max(1))
                .map(|_| Slot {
                    client: None,
                    queue: VecDeque::with_capacity(per_client),
                })
                .collect(),
            per_client,
            cursor: 0,
            len: 0,
        }
    }

    /// Requests queued.
    pub fn len(&self) -> usize {
        self.len
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
                Some(i) => i,
                None => {
                    self.slots.push(Slot {
                        client: None,
                        queue: VecDeque::with_capacity(self.per_client),
                    });
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

    /// The next request in round-robin order over the clients with a queue.
    pub fn pop(&mut self) -> Option<Queued<T>> {
        let n = self.slots.len();
        for step in 0..n {
            let index = (self.cursor + step) % n;
            let Some(slot) = self.slots.get_mut(index) else {
                continue;
            };
            if let Some(q) = slot.queue.pop_front() {
                self.cursor = (index + 1) % n;
                self.len -= 1;
                return Some(q);
            }
        }
        None
    }

    /// Take out every request whose deadline is at or before `now`, in queue order.
    pub fn take_expired(&mut self, now: Instant, mut f: impl FnMut(Queued<T>)) {
        for slot in &mut self.slots {
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

    /// The earliest deadline queued.
    pub fn next_deadline(&self) -> Option<Instant> {
        self.slots
            .iter()
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
