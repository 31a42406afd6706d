//! A request answered through the core's one request path (`wire::answer`: the limits check,
//! then the planner), timed, and the reports every planner shares: the exit codes, a refusal
//! by the limits, a planner's rejection, and an answer with no report of its own.

use reconfig_core::limits::{LimitViolation, Limits};
use reconfig_core::wire::{self, AllPlanners, Buffers, Outcome, OutcomeRef, Rejection, Request};
use serde_json::{json, Value};
use std::process::ExitCode;
use std::time::Instant;

/// Exit code: the plan is usable (its status is `Solved`, or another the planner calls usable).
pub const EXIT_USABLE: u8 = 0;
/// Exit code: the planner ran but the plan is not usable (any other status).
pub const EXIT_NOT_USABLE: u8 = 1;
/// Exit code: the input was rejected (unreadable fixture, the planner's `PlanError`, or a
/// setting outside the limits).
pub const EXIT_REJECTED: u8 = 2;

/// One answered request: the outcome (borrowing the buffers it was written into) and the time
/// `wire::answer` took (the limits check and the solve), s.
#[derive(Debug, Clone, Copy)]
pub struct Answered<'a> {
    /// The outcome.
    pub outcome: OutcomeRef<'a>,
    /// Wall time of the answer, s.
    pub time_s: f64,
}

/// Every planner's buffers, boxed (about 240 KB), for a host front end that answers requests.
pub fn buffers() -> Box<AllPlanners> {
    Box::new(AllPlanners::new())
}

/// Answer `request` under `limits` into `buffers`, timed.
pub fn answer<'a, B: Buffers + ?Sized>(
    request: &Request,
    limits: &Limits,
    buffers: &'a mut B,
) -> Answered<'a> {
    let started = Instant::now();
    let outcome = wire::answer(request, limits, buffers);
    Answered {
        outcome,
        time_s: started.elapsed().as_secs_f64(),
    }
}

/// The planner's status as `{:?}` prints it (`BudgetExhausted { verified: true }`), for an
/// outcome with a plan; `None` when nothing was planned.
pub fn status_text(outcome: &OutcomeRef) -> Option<String> {
    match outcome {
        OutcomeRef::Pseudospectral(s) => Some(format!("{:?}", s.info.status)),
        OutcomeRef::Impulsive(s) | OutcomeRef::ImpulsiveForm { solution: s, .. } => {
            Some(format!("{:?}", s.info.status))
        }
        OutcomeRef::GeoTour(s) => Some(format!("{:?}", s.info.status)),
        OutcomeRef::LeoArc(s) => Some(format!("{:?}", s.info.status)),
        OutcomeRef::LeoSequence(q) => Some(format!("{:?}", q.info.status)),
        OutcomeRef::Hybrid(s) => Some(format!("{:?}", s.info.status)),
        _ => None,
    }
}

/// The exit code of a planned answer: [`EXIT_USABLE`] or [`EXIT_NOT_USABLE`].
pub fn exit_code(usable: bool) -> ExitCode {
    ExitCode::from(if usable { EXIT_USABLE } else { EXIT_NOT_USABLE })
}

/// A planner's `PlanError` as the JSON object `reconfig solve --json` prints.
pub fn rejection_json(name: &str, err: &dyn Rejection) -> Value {
    json!({ "name": name, "status": "Rejected", "error": format!("{err:?}"), "message": err.to_string() })
}

/// A refusal by the limits as the JSON object `reconfig solve --json` prints (nothing was
/// solved; `check_time_s` is the answer's time).
pub fn refusal_json(name: &str, v: &LimitViolation, check_time_s: f64) -> Value {
    json!({
        "name": name,
        "status": "LimitExceeded",
        "setting": v.setting.name(),
        "value": v.value,
        "limit": v.limit,
        "rule": format!("{:?}", v.rule),
        "message": v.to_string(),
        "check_time_s": check_time_s,
    })
}

/// Report a planner's `PlanError` in the one shape every planner uses and return exit code
/// [`EXIT_REJECTED`].
pub fn report_rejection(name: &str, err: &dyn Rejection, json_output: bool) -> ExitCode {
    if json_output {
        println!("{}", rejection_json(name, err));
    } else {
        println!("{name}: rejected: {err}");
    }
    ExitCode::from(EXIT_REJECTED)
}

/// Report a refusal by the limits (nothing was solved; `check_time_s` is the answer's time)
/// and return exit code [`EXIT_REJECTED`]: a refused request is a rejected input, the one
/// convention of every planner.
pub fn report_refusal(
    name: &str,
    v: &LimitViolation,
    check_time_s: f64,
    json_output: bool,
) -> ExitCode {
    if json_output {
        println!("{}", refusal_json(name, v, check_time_s));
    } else {
        println!("{name}: refused, limit exceeded: {v}");
        println!(
            "  nothing was solved; limit check took {:.1} us",
            check_time_s * 1e6
        );
    }
    ExitCode::from(EXIT_REJECTED)
}

/// Report an answer that the planner's own report does not show: a refusal by the limits, a
/// rejection, or (a request kind without a report of its own) the outcome as the wire carries
/// it, with the exit code its verdict gives.
///
/// # Errors
/// An outcome that no request of a fixture can have (a bad frame, an expiry, an unsupported
/// planner: `reconfig solve` answers every planner).
pub fn report_other(
    name: &str,
    answered: &Answered,
    json_output: bool,
) -> anyhow::Result<ExitCode> {
    let outcome = &answered.outcome;
    if let OutcomeRef::LimitExceeded(v) = outcome {
        return Ok(report_refusal(name, v, answered.time_s, json_output));
    }
    if let Some(err) = outcome.rejection() {
        return Ok(report_rejection(name, err, json_output));
    }
    let Some(usable) = outcome.usable() else {
        anyhow::bail!("{name}: unexpected answer {outcome:?}");
    };
    if json_output {
        println!("{}", other_json(name, answered)?);
    } else {
        println!("{name}: {outcome:?}");
    }
    Ok(exit_code(usable))
}

/// The JSON object `reconfig solve --json` prints for an answer that the planner's own report
/// does not show ([`report_other`]): a refusal by the limits, a rejection, or the outcome as
/// the wire carries it.
///
/// # Errors
/// An outcome that no request of a fixture can have (as [`report_other`]).
pub fn other_json(name: &str, answered: &Answered) -> anyhow::Result<Value> {
    let outcome = &answered.outcome;
    if let OutcomeRef::LimitExceeded(v) = outcome {
        return Ok(refusal_json(name, v, answered.time_s));
    }
    if let Some(err) = outcome.rejection() {
        return Ok(rejection_json(name, err));
    }
    if outcome.usable().is_none() {
        anyhow::bail!("{name}: unexpected answer {outcome:?}");
    }
    Ok(json!({ "name": name, "outcome": outcome, "solve_time_s": answered.time_s }))
}

/// A request that got no plan (a refusal by the limits, a rejection by the planner), as the
/// error of a driver that answers several: the request's label and its outcome.
#[derive(Debug, Clone)]
pub struct NoPlan {
    /// Which request (`<fixture> arc 2 (3->1)`).
    pub label: String,
    /// Its outcome.
    pub outcome: Outcome,
    /// The answer's time, s.
    pub time_s: f64,
}

impl std::fmt::Display for NoPlan {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let outcome = self.outcome.as_ref();
        match (&outcome, outcome.rejection()) {
            (OutcomeRef::LimitExceeded(v), _) => write!(f, "{}: refused: {v}", self.label),
            (_, Some(e)) => write!(f, "{}: rejected: {e}", self.label),
            (other, None) => write!(f, "{}: unexpected answer {other:?}", self.label),
        }
    }
}

impl std::error::Error for NoPlan {}

/// Why `answered` is no plan, as an error naming the request ([`NoPlan`]).
pub fn no_plan(label: &str, answered: &Answered) -> anyhow::Error {
    // The outcome owned: its encoding decoded (a refusal or a rejection is a few bytes).
    let outcome = postcard::to_stdvec(&answered.outcome)
        .ok()
        .and_then(|bytes| postcard::from_bytes::<Outcome>(&bytes).ok());
    match outcome {
        Some(outcome) => anyhow::Error::new(NoPlan {
            label: label.to_owned(),
            outcome,
            time_s: answered.time_s,
        }),
        None => anyhow::anyhow!("{label}: an answer that does not encode"),
    }
}

/// A refusal by the limits of a host step that is no request (the LEO schedule's estimates),
/// as the error a refused request gives ([`NoPlan`]).
pub fn refused(label: &str, violation: LimitViolation) -> anyhow::Error {
    anyhow::Error::new(NoPlan {
        label: label.to_owned(),
        outcome: Outcome::LimitExceeded(violation),
        time_s: 0.0,
    })
}

/// Report the error of a driver that answers several requests under the fixture's `name`: a
/// request refused by the limits as a refusal, anything else (a rejection, named with its
/// request) as a rejection; both exit [`EXIT_REJECTED`].
pub fn report_error(name: &str, error: &anyhow::Error, json_output: bool) -> ExitCode {
    match error.downcast_ref::<NoPlan>() {
        Some(NoPlan {
            outcome: Outcome::LimitExceeded(v),
            time_s,
            ..
        }) => report_refusal(name, v, *time_s, json_output),
        _ => report_rejection(name, &Chain(error), json_output),
    }
}

/// The JSON object [`report_error`] prints, its status (`LimitExceeded` or `Rejected`) and
/// message.
pub fn error_json(name: &str, error: &anyhow::Error) -> (Value, &'static str, String) {
    match error.downcast_ref::<NoPlan>() {
        Some(NoPlan {
            outcome: Outcome::LimitExceeded(v),
            time_s,
            ..
        }) => (
            refusal_json(name, v, *time_s),
            "LimitExceeded",
            v.to_string(),
        ),
        _ => (
            rejection_json(name, &Chain(error)),
            "Rejected",
            error.to_string(),
        ),
    }
}

/// An `anyhow` error reported as a rejection: its Debug form (the JSON `error` field) is its
/// chain of causes, not anyhow's Debug, which appends a stack backtrace when
/// `RUST_BACKTRACE` is set.
struct Chain<'e>(&'e anyhow::Error);

impl core::fmt::Debug for Chain<'_> {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        write!(f, "{:#}", self.0)
    }
}

impl core::fmt::Display for Chain<'_> {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        write!(f, "{}", self.0)
    }
}
