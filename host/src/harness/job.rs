//! The buffer a request travels to a worker in and its response travels back in: the
//! dispatcher fills and sends it, a worker answers into it (`service::worker_loop`).

use reconfig_core::wire::{REQUEST_MAX_BYTES, RESPONSE_MAX_BYTES};

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
