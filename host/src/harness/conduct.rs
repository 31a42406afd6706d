//! A client's conduct: how many of its last frames were garbage, and what that costs it.
//!
//! A *bad frame* is one `wire::decode_request` refuses (too short to hold a header, wrong
//! magic or version, a length that does not match, a wrong CRC, a body that is not a
//! `Request`, longer than `REQUEST_MAX_BYTES`). The service keeps, per client (iceoryx2 client
//! port), whether each of its last [`WINDOW`] frames was bad, counted in frames received, not
//! in time. From the number of bad frames among them:
//!
//! * fewer than [`THROTTLE_AT`]: [`Standing::Good`], a full share of the round-robin; a bad
//!   frame takes one turn like any request and is answered `BadRequest` in that turn;
//! * [`THROTTLE_AT`] or more: [`Standing::Throttled`], one turn in
//!   `schedule::THROTTLED_ROUNDS` rounds while another client has a request queued (bad frames
//!   still answered in turn); back to `Good` once fewer than [`THROTTLE_AT`] of its last
//!   [`WINDOW`] frames are bad;
//! * [`DROP_AT`] or more: [`Standing::Dropped`] for as long as its client port exists: nothing
//!   it sent or sends is answered or solved any more (its queue is muted and held).
//!
//! With these numbers a client that sends only garbage gets 3 answers at a full share, 12 more
//! frames at a quarter share, and is dropped at its 16th bad frame.

/// Frames remembered per client.
pub const WINDOW: u32 = 32;
/// Bad frames among the last [`WINDOW`] that throttle a client.
pub const THROTTLE_AT: u32 = 4;
/// Bad frames among the last [`WINDOW`] that drop a client.
pub const DROP_AT: u32 = 16;

/// What a client's conduct has earned it.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Standing {
    /// Served at a full share.
    Good,
    /// Served at a quarter share while others wait.
    Throttled,
    /// Not served any more (until its client port goes away).
    Dropped,
}

/// One client's last frames.
#[derive(Clone, Copy, Debug)]
pub struct Conduct {
    /// Bit k set: the frame k frames ago was bad (bit 0: the latest).
    history: u32,
    standing: Standing,
}

impl Default for Conduct {
    fn default() -> Self {
        Self {
            history: 0,
            standing: Standing::Good,
        }
    }
}

impl Conduct {
    /// Record one frame; returns the standing it leaves the client in.
    pub fn record(&mut self, bad: bool) -> Standing {
        // WINDOW = 32 = the bits of the history.
        self.history = (self.history << 1) | u32::from(bad);
        let bad_frames = self.history.count_ones();
        self.standing = match self.standing {
            Standing::Dropped => Standing::Dropped,
            _ if bad_frames >= DROP_AT => Standing::Dropped,
            _ if bad_frames >= THROTTLE_AT => Standing::Throttled,
            _ => Standing::Good,
        };
        self.standing
    }

    /// Bad frames among the last [`WINDOW`].
    pub fn bad_frames(&self) -> u32 {
        self.history.count_ones()
    }

    /// The current standing.
    pub fn standing(&self) -> Standing {
        self.standing
    }
}

/// The conduct of every client seen, by client id `K`. Capacity is allocated at start-up; a
/// client beyond it (only while departed clients have not been forgotten) allocates once.
pub struct Conducts<K> {
    entries: Vec<(K, Conduct)>,
}

impl<K: Copy + Eq> Conducts<K> {
    /// Room for `capacity` clients.
    pub fn new(capacity: usize) -> Self {
        Self {
            entries: Vec::with_capacity(capacity),
        }
    }

    /// The standing of `client` (`Good` when never seen).
    pub fn standing(&self, client: K) -> Standing {
        self.entries
            .iter()
            .find(|(k, _)| *k == client)
            .map_or(Standing::Good, |(_, c)| c.standing())
    }

    /// Record one frame of `client`; returns its standing after it.
    pub fn record(&mut self, client: K, bad: bool) -> Standing {
        if let Some((_, c)) = self.entries.iter_mut().find(|(k, _)| *k == client) {
            return c.record(bad);
        }
        let mut c = Conduct::default();
        let standing = c.record(bad);
        self.entries.push((client, c));
        standing
    }

    /// No room left without allocating.
    pub fn is_full(&self) -> bool {
        self.entries.len() >= self.entries.capacity()
    }

    /// Forget every client for which `keep` is false.
    pub fn retain(&mut self, mut keep: impl FnMut(K) -> bool) {
        self.entries.retain(|(k, _)| keep(*k));
    }

    /// Clients currently dropped.
    pub fn dropped(&self) -> usize {
        self.entries
            .iter()
            .filter(|(_, c)| c.standing() == Standing::Dropped)
            .count()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_garbage_only_client_is_throttled_at_its_fourth_bad_frame_and_dropped_at_its_sixteenth() {
        let mut c = Conduct::default();
        let standings: Vec<Standing> = (0..20).map(|_| c.record(true)).collect();
        assert!(standings[..3].iter().all(|s| *s == Standing::Good));
        assert!(standings[3..15].iter().all(|s| *s == Standing::Throttled));
        assert!(standings[15..].iter().all(|s| *s == Standing::Dropped));
        // Dropped stays dropped, whatever follows.
        for _ in 0..100 {
            assert_eq!(c.record(false), Standing::Dropped);
        }
    }

    #[test]
    fn a_throttled_client_recovers_after_enough_good_frames_counted_in_frames() {
        let mut c = Conduct::default();
        for _ in 0..5 {
            c.record(true);
        }
        assert_eq!(c.standing(), Standing::Throttled);
        // The bad frames leave the window of 32 one by one: after 27 good frames 5 bad are in
        // it, after 28 four, after 29 three.
        for _ in 0..28 {
            assert_eq!(c.record(false), Standing::Throttled);
        }
        assert_eq!(c.bad_frames(), 4);
        assert_eq!(c.record(false), Standing::Good);
        assert_eq!(c.bad_frames(), 3);
    }

    #[test]
    fn fifteen_bad_frames_in_any_thirty_two_never_drop_a_client() {
        let mut c = Conduct::default();
        for k in 0..1000 {
            assert_ne!(c.record(k % 32 < 15), Standing::Dropped);
        }
        // Sixteen bad frames in a row make 16 in the window, whatever came before.
        for _ in 0..16 {
            c.record(true);
        }
        assert_eq!(c.standing(), Standing::Dropped);
    }

    #[test]
    fn conducts_are_per_client_and_forgotten_when_the_client_goes() {
        let mut all = Conducts::<u32>::new(2);
        for _ in 0..16 {
            all.record(1, true);
        }
        all.record(2, false);
        assert_eq!(all.standing(1), Standing::Dropped);
        assert_eq!(all.standing(2), Standing::Good);
        assert_eq!(all.standing(3), Standing::Good);
        assert!(all.is_full());
        assert_eq!(all.dropped(), 1);
        all.retain(|k| k != 1);
        assert_eq!(all.standing(1), Standing::Good);
        assert!(!all.is_full());
    }
}
