//! One solver worker: decode a request frame, solve it in the worker's own workspace, encode
//! the response frame. After [`Worker::new`] nothing here allocates (see the counting-allocator
//! test `harness_alloc`).

use reconfig_core::limits::Limits;
use reconfig_core::wire::{self, AllPlanners, Outcome, OutcomeRef};
use std::time::Instant;

/// Stack size for threads that own a [`Worker`]: workspaces are boxed, but building them goes
/// through the stack in unoptimised builds.
pub const WORKER_STACK_BYTES: usize = 32 * 1024 * 1024;

/// A worker's workspaces and output buffers, each built once.
pub struct Worker {
    /// Every planner's workspace and solution (the request path's buffers).
    buffers: Box<AllPlanners>,
    /// The service's limits: a request outside them is answered `LimitExceeded` unsolved.
    pub limits: Limits,
}

impl Default for Worker {
    fn default() -> Self {
        Self::new()
    }
}

impl Worker {
    /// Build the workspaces (the only allocations a worker makes).
    pub fn new() -> Self {
        Self {
            buffers: Box::new(AllPlanners::new()),
            limits: Limits::default(),
        }
    }

    /// Answer one request frame: writes the response frame into `out` (at least
    /// [`wire::RESPONSE_MAX_BYTES`] long) and returns its length. The request goes through the
    /// core's one request path ([`wire::answer`]): the limits check, then the planner.
    pub fn handle(&mut self, request: &[u8], out: &mut [u8]) -> usize {
        let seq = wire::peek_request_seq(request).unwrap_or(0);
        let frame = match wire::decode_request(request) {
            Ok(frame) => frame,
            Err(e) => return encode(seq, 0, &OutcomeRef::BadRequest(e), out),
        };
        let start = Instant::now();
        let outcome = wire::answer(&frame.request, &self.limits, &mut *self.buffers);
        let ns = elapsed_ns(start);
        encode(frame.seq, ns, &outcome, out)
    }
}

fn elapsed_ns(start: Instant) -> u64 {
    u64::try_from(start.elapsed().as_nanos()).unwrap_or(u64::MAX)
}

fn encode(seq: u64, ns: u64, outcome: &OutcomeRef<'_>, out: &mut [u8]) -> usize {
    // Every outcome fits RESPONSE_MAX_BYTES (tested in harness_wire); a too-short `out` is a
    // caller bug, answered with an empty frame that the feeder reports as malformed.
    wire::encode_response(seq, ns, outcome, out).unwrap_or(0)
}

/// The outcome a local solve gives for `request` (for checking the service's answers).
pub fn local_outcome(worker: &mut Worker, request: &[u8]) -> Vec<u8> {
    let mut out = vec![0u8; wire::RESPONSE_MAX_BYTES];
    let n = worker.handle(request, &mut out);
    match wire::view_response(out.get(..n).unwrap_or(&[])) {
        Ok(view) => view.body.to_vec(),
        Err(_) => Vec::new(),
    }
}

/// A short human summary of an outcome: (status, cost or dv, min separation, iterations). The
/// outcomes of the planners shown here have their figures; a refusal, a rejection or a bad
/// frame says what went wrong; any other outcome shows as it is.
pub fn summarize(outcome: &Outcome) -> (String, String, String, String) {
    let dash = || "-".to_owned();
    let figures =
        |status: String, cost: String, iterations: String| (status, cost, dash(), iterations);
    let dv = |mps: f64| format!("dv={mps:.4} m/s");
    match outcome {
        Outcome::Pseudospectral(s) => (
            format!("{:?}", s.info.status),
            format!("J={:.4}", s.cost),
            crate::drivers::pseudospectral::least_separation(s),
            format!("{}", s.info.sqp_iterations),
        ),
        Outcome::Impulsive(s) | Outcome::ImpulsiveForm { solution: s, .. } => figures(
            format!("{:?}", s.info.status),
            dv(s.total_dv_mps),
            format!("{}", s.info.iterations),
        ),
        Outcome::GeoTour(s) => figures(
            format!("{:?}", s.info.status),
            dv(s.total_dv_mps),
            format!("{}", s.info.price_iterations),
        ),
        Outcome::LeoArc(s) => figures(
            format!("{:?}", s.info.status),
            dv(s.total_dv_mps),
            format!("{}", s.info.evaluations),
        ),
        Outcome::LeoSequence(q) => figures(
            format!(
                "{:?} {}",
                q.info.status,
                q.order
                    .iter()
                    .take(usize::from(q.len))
                    .map(|k| (k + 1).to_string())
                    .collect::<Vec<_>>()
                    .join(">")
            ),
            q.total_dv_mps.map_or("no order".into(), dv),
            format!("{}", q.info.arcs_planned),
        ),
        Outcome::Hybrid(s) => figures(
            format!("{:?}", s.info.status),
            s.flown.map_or_else(
                || "not flown".to_owned(),
                |f| {
                    format!(
                        "m_f={:.6} t_f={:.4} d",
                        f.final_mass,
                        reconfig_core::hybrid::units::days(s.duration_tu)
                    )
                },
            ),
            format!("{}", s.info.iterations),
        ),
        Outcome::BadRequest(e) => figures(format!("bad request: {e}"), dash(), dash()),
        Outcome::LimitExceeded(v) => figures(format!("limit exceeded: {v}"), dash(), dash()),
        Outcome::Unsupported(p) => figures(format!("unsupported planner {p:?}"), dash(), dash()),
        Outcome::Expired(x) => figures(
            format!(
                "expired: queued {:.1} ms, deadline {:.1} ms",
                x.queued_us as f64 / 1e3,
                x.deadline_us as f64 / 1e3
            ),
            dash(),
            dash(),
        ),
        other => match other.as_ref().rejection() {
            Some(e) => figures(format!("rejected: {e}"), dash(), dash()),
            None => figures(format!("{other:?}"), dash(), dash()),
        },
    }
}
