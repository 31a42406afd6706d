//! One solver worker: decode a request frame, solve it in the worker's own workspace, encode
//! the response frame. After [`Worker::new`] nothing here allocates (see the counting-allocator
//! test `harness_alloc`).

use reconfig_core::limits::Limits;
use reconfig_core::wire::{self, Outcome, OutcomeRef, Request};
use reconfig_core::{geo_tour, impulsive, leo_tour, pseudospectral};
use std::time::Instant;

/// Stack size for threads that own a [`Worker`]: workspaces are boxed, but building them goes
/// through the stack in unoptimised builds.
pub const WORKER_STACK_BYTES: usize = 32 * 1024 * 1024;

/// A worker's workspaces and output buffers, each built once.
pub struct Worker {
    ps_workspace: Box<pseudospectral::Workspace>,
    ps_solution: Box<pseudospectral::Solution>,
    imp_workspace: Box<impulsive::Workspace>,
    imp_solution: Box<impulsive::Solution>,
    /// The service's limits: a request outside them is answered `LimitExceeded` unsolved.
    pub limits: Limits,
    geo_workspace: Box<geo_tour::Workspace>,
    geo_solution: Box<geo_tour::Solution>,
    leo_arc_workspace: Box<leo_tour::Workspace>,
    leo_arc_solution: Box<leo_tour::ArcSolution>,
    leo_sequence_workspace: Box<leo_tour::tour_order::SequenceWorkspace>,
    leo_sequence: Box<leo_tour::sequence::Sequence>,
    /// Test hook: sleep this long per request (a stand-in for a long solve in fault tests).
    pub delay: std::time::Duration,
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
            ps_workspace: Box::new(pseudospectral::Workspace::new()),
            ps_solution: Box::new(pseudospectral::Solution::new()),
            imp_workspace: Box::new(impulsive::Workspace::new()),
            imp_solution: Box::new(impulsive::Solution::new()),
            limits: Limits::default(),
            geo_workspace: Box::new(geo_tour::Workspace::new()),
            geo_solution: Box::new(geo_tour::Solution::new()),
            leo_arc_workspace: Box::new(leo_tour::Workspace::new()),
            leo_arc_solution: Box::new(leo_tour::ArcSolution::new()),
            leo_sequence_workspace: Box::new(leo_tour::tour_order::SequenceWorkspace::new()),
            leo_sequence: Box::new(leo_tour::sequence::Sequence::new()),
            delay: std::time::Duration::ZERO,
        }
    }

    /// Answer one request frame: writes the response frame into `out` (at least
    /// [`wire::RESPONSE_MAX_BYTES`] long) and returns its length.
    pub fn handle(&mut self, request: &[u8], out: &mut [u8]) -> usize {
        let seq = wire::peek_request_seq(request).unwrap_or(0);
        let frame = match wire::decode_request(request) {
            Ok(frame) => frame,
            Err(e) => return encode(seq, 0, &OutcomeRef::BadRequest(e), out),
        };
        if !self.delay.is_zero() {
            std::thread::sleep(self.delay);
        }
        let start = Instant::now();
        // Before any solve: a request outside the limits is refused, never clamped.
        if let Err(violation) = self.limits.check(&frame.request) {
            let ns = elapsed_ns(start);
            return encode(frame.seq, ns, &OutcomeRef::LimitExceeded(violation), out);
        }
        match &frame.request {
            Request::Pseudospectral { problem, settings } => {
                // A fresh output buffer per solve: a rejected request leaves `out` untouched,
                // and the answer must not depend on the previous request.
                *self.ps_solution = pseudospectral::Solution::new();
                let result = pseudospectral::solve(
                    problem,
                    settings,
                    &mut self.ps_workspace,
                    &mut self.ps_solution,
                );
                let ns = elapsed_ns(start);
                match result {
                    Ok(()) => encode(
                        frame.seq,
                        ns,
                        &OutcomeRef::Pseudospectral(&self.ps_solution),
                        out,
                    ),
                    Err(e) => encode(frame.seq, ns, &OutcomeRef::PseudospectralRejected(e), out),
                }
            }
            Request::Impulsive { problem, settings } => {
                *self.imp_solution = impulsive::Solution::new();
                let result = impulsive::solve(
                    problem,
                    settings,
                    &mut self.imp_workspace,
                    &mut self.imp_solution,
                );
                let ns = elapsed_ns(start);
                match result {
                    Ok(()) => encode(
                        frame.seq,
                        ns,
                        &OutcomeRef::Impulsive(&self.imp_solution),
                        out,
                    ),
                    Err(e) => encode(frame.seq, ns, &OutcomeRef::ImpulsiveRejected(e), out),
                }
            }
            Request::ImpulsiveForm { problem, settings } => {
                // Converted here by the core's `impulsive::forms`, the one implementation.
                *self.imp_solution = impulsive::Solution::new();
                let result = impulsive::solve_form(
                    problem,
                    settings,
                    &mut self.imp_workspace,
                    &mut self.imp_solution,
                );
                let ns = elapsed_ns(start);
                match result {
                    Ok(end_state) => encode(
                        frame.seq,
                        ns,
                        &OutcomeRef::ImpulsiveForm {
                            solution: &self.imp_solution,
                            end_state,
                        },
                        out,
                    ),
                    Err(e) => encode(frame.seq, ns, &OutcomeRef::ImpulsiveRejected(e), out),
                }
            }
            Request::GeoTour { problem, settings } => {
                *self.geo_solution = geo_tour::Solution::new();
                let result = geo_tour::solve(
                    problem,
                    settings,
                    &mut self.geo_workspace,
                    &mut self.geo_solution,
                );
                let ns = elapsed_ns(start);
                match result {
                    Ok(()) => encode(frame.seq, ns, &OutcomeRef::GeoTour(&self.geo_solution), out),
                    Err(e) => encode(frame.seq, ns, &OutcomeRef::GeoTourRejected(e), out),
                }
            }
            Request::LeoArc { problem, settings } => {
                self.leo_arc_solution.reset();
                let result = leo_tour::solve_arc(
                    problem,
                    settings,
                    &mut self.leo_arc_workspace,
                    &mut self.leo_arc_solution,
                );
                let ns = elapsed_ns(start);
                match result {
                    Ok(()) => encode(
                        frame.seq,
                        ns,
                        &OutcomeRef::LeoArc(&self.leo_arc_solution),
                        out,
                    ),
                    Err(e) => encode(frame.seq, ns, &OutcomeRef::LeoArcRejected(e), out),
                }
            }
            Request::LeoSequence {
                problem,
                settings,
                arc_settings,
            } => {
                self.leo_sequence.reset();
                let result = leo_tour::tour_order::solve_sequence(
                    problem,
                    settings,
                    arc_settings,
                    &mut self.leo_sequence_workspace,
                    &mut self.leo_sequence,
                );
                let ns = elapsed_ns(start);
                match result {
                    Ok(()) => encode(
                        frame.seq,
                        ns,
                        &OutcomeRef::LeoSequence(&self.leo_sequence),
                        out,
                    ),
                    Err(e) => encode(frame.seq, ns, &OutcomeRef::LeoSequenceRejected(e), out),
                }
            }
        }
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

/// A short human summary of an outcome: (status, cost or dv, min separation, iterations).
pub fn summarize(outcome: &Outcome) -> (String, String, String, String) {
    match outcome {
        Outcome::Pseudospectral(s) => (
            format!("{:?}", s.info.status),
            format!("J={:.4}", s.cost),
            format!(
                "{:.4} ({}-{})",
                s.min_separation_lu,
                s.min_separation_pair.0 + 1,
                s.min_separation_pair.1 + 1
            ),
            format!("{}", s.info.sqp_iterations),
        ),
        Outcome::Impulsive(s) => (
            format!("{:?}", s.info.status),
            format!("dv={:.4} m/s", s.total_dv_mps),
            "-".into(),
            format!("{}", s.info.iterations),
        ),
        Outcome::ImpulsiveForm { solution: s, .. } => (
            format!("{:?}", s.info.status),
            format!("dv={:.4} m/s", s.total_dv_mps),
            "-".into(),
            format!("{}", s.info.iterations),
        ),
        Outcome::PseudospectralRejected(e) => {
            (format!("rejected: {e}"), "-".into(), "-".into(), "-".into())
        }
        Outcome::ImpulsiveRejected(e) => {
            (format!("rejected: {e}"), "-".into(), "-".into(), "-".into())
        }
        Outcome::GeoTour(s) => (
            format!("{:?}", s.info.status),
            format!("dv={:.4} m/s", s.total_dv_mps),
            "-".into(),
            format!("{}", s.info.price_iterations),
        ),
        Outcome::GeoTourRejected(e) => {
            (format!("rejected: {e}"), "-".into(), "-".into(), "-".into())
        }
        Outcome::LeoArc(s) => (
            format!("{:?}", s.info.status),
            format!("dv={:.4} m/s", s.total_dv_mps),
            "-".into(),
            format!("{}", s.info.evaluations),
        ),
        Outcome::LeoArcRejected(e) => {
            (format!("rejected: {e}"), "-".into(), "-".into(), "-".into())
        }
        Outcome::LeoSequence(q) => (
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
            q.total_dv_mps
                .map_or("no order".into(), |t| format!("dv={t:.4} m/s")),
            "-".into(),
            format!("{}", q.info.arcs_planned),
        ),
        Outcome::LeoSequenceRejected(e) => {
            (format!("rejected: {e}"), "-".into(), "-".into(), "-".into())
        }
        Outcome::BadRequest(e) => (
            format!("bad request: {e}"),
            "-".into(),
            "-".into(),
            "-".into(),
        ),
        Outcome::LimitExceeded(v) => (
            format!("limit exceeded: {v}"),
            "-".into(),
            "-".into(),
            "-".into(),
        ),
        Outcome::Expired(x) => (
            format!(
                "expired: queued {:.1} ms, deadline {:.1} ms",
                x.queued_us as f64 / 1e3,
                x.deadline_us as f64 / 1e3
            ),
            "-".into(),
            "-".into(),
            "-".into(),
        ),
    }
}
