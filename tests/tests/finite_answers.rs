//! Finite answers (issue 29, item 6): a value that does not exist in an answer is absent (an
//! `Option`, a `has_...` flag in C), never NaN or infinity. For every request kind, requests
//! built from the repository's fixtures and perturbed (random values, tiny budgets, tight
//! caps, degenerate and extreme inputs, NaN and infinities) are answered through the one
//! request path (`wire::answer`, default limits, one boxed `AllPlanners` reused), and every
//! number of the outcome, usable or not, is walked (`reconfig_tests::numbers`): none is NaN or
//! infinite. The one number allowed to be non-finite is a refusal's echo of the caller's own
//! non-finite input (`PlanError::NotFinite { value }`, `SettingError::value`: "as the caller
//! gave it"), and only when the request holds one. A request holding a NaN or an infinity is
//! refused, never planned. Each outcome encodes with postcard, decodes back equal and fits a
//! response frame; the C view of a plan (planners A, B, B's forms, the GEO tour) is finite too.
//!
//! The cases are deterministic (fixed seeds) and few per kind, on cheapened settings, so that
//! the whole file runs in seconds in a debug build. A local hunt for more may set
//! `FINITE_ANSWERS_SEED` (mixed into each kind's seed) and `FINITE_ANSWERS_CASES_X` (a case
//! multiplier); CI sets neither.

use proptest::prelude::*;
use proptest::sample::Index;
use proptest::test_runner::{Config, RngSeed, TestCaseError, TestRunner};
use reconfig_capi::{convert_a, convert_b, convert_b_form, convert_geo, convert_leo};
use reconfig_core::limits::Limits;
use reconfig_core::wire::{
    answer, encode_outcome, AllPlanners, Outcome, OutcomeRef, Request, RESPONSE_BODY_MAX_BYTES,
};
use reconfig_tests::numbers::{non_finite, Number};
use serde_json::Value;
use std::cell::RefCell;
use std::collections::BTreeMap;
use std::sync::OnceLock;

/// The request kinds of `wire::Request`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord)]
enum Kind {
    Pseudospectral,
    Impulsive,
    ImpulsiveForm,
    GeoTour,
    LeoArc,
    LeoSequence,
    Hybrid,
}

fn kind(request: &Request) -> Kind {
    match request {
        Request::Pseudospectral { .. } => Kind::Pseudospectral,
        Request::Impulsive { .. } => Kind::Impulsive,
        Request::ImpulsiveForm { .. } => Kind::ImpulsiveForm,
        Request::GeoTour { .. } => Kind::GeoTour,
        Request::LeoArc { .. } => Kind::LeoArc,
        Request::LeoSequence { .. } => Kind::LeoSequence,
        Request::Hybrid { .. } => Kind::Hybrid,
    }
}

/// Every fixture's requests (the top-level `fixtures/*.toml`), labelled, with cheapened
/// settings: loaded once.
fn bases() -> &'static [(String, Request)] {
    static BASES: OnceLock<Vec<(String, Request)>> = OnceLock::new();
    BASES.get_or_init(|| {
        let mut out = Vec::new();
        for path in reconfig_tests::fixture_paths() {
            let fixture = reconfig_host::fixture::load(&path).expect("fixture loads");
            for r in fixture.requests().expect("fixture requests") {
                out.push((r.label, cheapen(r.request)));
            }
        }
        out
    })
}

/// The requests of one kind, optionally only the cheap ones (`keep`).
fn bases_of(k: Kind, keep: impl Fn(&Request) -> bool) -> Vec<(String, Request)> {
    let v: Vec<_> = bases()
        .iter()
        .filter(|(_, r)| kind(r) == k && keep(r))
        .cloned()
        .collect();
    assert!(!v.is_empty(), "no fixture request of kind {k:?}");
    v
}

/// Settings that keep one solve short in a debug build (still within the default limits:
/// every cap lowered, none raised).
fn cheapen(mut request: Request) -> Request {
    match &mut request {
        Request::Pseudospectral { settings, .. } => {
            settings.sqp_max_iter = settings.sqp_max_iter.min(20);
            settings.verify_max_rounds = settings.verify_max_rounds.min(2);
            settings.work_budget = settings.work_budget.min(10_000_000);
        }
        Request::Impulsive { settings, .. } | Request::ImpulsiveForm { settings, .. } => {
            settings.search_samples = settings.search_samples.min(20);
            settings.search_starts = settings.search_starts.min(2);
            settings.search_max_evaluations = settings.search_max_evaluations.min(60);
            settings.fixed_point_max_iter = settings.fixed_point_max_iter.min(20);
            settings.work_budget = settings.work_budget.min(2_000_000);
        }
        Request::GeoTour { settings, .. } => {
            settings.work_budget = settings.work_budget.min(2_000_000);
        }
        Request::LeoArc { settings, .. } => cheapen_leo(settings),
        Request::LeoSequence {
            settings,
            arc_settings,
            ..
        } => {
            settings.max_arcs = settings.max_arcs.min(120);
            cheapen_leo(arc_settings);
        }
        Request::Hybrid { settings, .. } => {
            settings.max_iterations = settings.max_iterations.min(8);
            settings.max_halvings = settings.max_halvings.min(6);
        }
    }
    request
}

fn cheapen_leo(s: &mut reconfig_core::leo_tour::Settings) {
    s.grid_points = s.grid_points.min(24);
    s.candidates = s.candidates.min(2);
    s.hop_rounds = s.hop_rounds.min(1);
    s.search_max_evals = s.search_max_evals.min(150);
    s.polish_max_evals = s.polish_max_evals.min(40);
    s.work_budget = s.work_budget.min(2_000_000);
}

// ---------------------------------------------------------------------------------------------
// Perturbations: edits of the request's serde tree (its `serde_json::Value`: an f64 is kept
// exactly), one leaf at a time. A non-finite value goes in as a finite marker that is swapped
// for NaN or an infinity in the request's postcard bytes (JSON has no NaN). An edit whose
// result does not decode as a request (a negative count, a fixed array cut short) is skipped.
// ---------------------------------------------------------------------------------------------

/// What an edit does to the leaf it picks.
#[derive(Clone, Debug)]
enum Change {
    /// Times a factor.
    Scale(f64),
    /// Plus this times the leaf's magnitude (at least 1).
    Shift(f64),
    Zero,
    One,
    Negate,
    /// A tiny positive value (integers: 1).
    Tiny(f64),
    /// A huge value (integers: the same, capped at 2^53).
    Huge(f64),
    /// NaN, +inf or -inf (0, 1, 2).
    NonFinite(u8),
    /// Another leaf's value (degenerate inputs: equal positions, equal slots).
    Copy(Index),
    /// Drop the last element of an array (fewer spacecraft, targets, clients, impulses).
    Truncate,
}

/// One edit: which leaf (among all, or among the settings' only) and what to do to it.
#[derive(Clone, Debug)]
struct Edit {
    settings_only: bool,
    at: Index,
    change: Change,
}

fn change() -> impl Strategy<Value = Change> {
    prop_oneof![
        4 => (0.3f64..3.0).prop_map(Change::Scale),
        3 => (-1.0f64..1.0).prop_map(Change::Shift),
        1 => Just(Change::Zero),
        1 => Just(Change::One),
        1 => Just(Change::Negate),
        1 => prop::sample::select(vec![5e-324, 1e-300, 1e-12]).prop_map(Change::Tiny),
        1 => prop::sample::select(vec![1e6, 1e12, 1e300, f64::MAX]).prop_map(Change::Huge),
        2 => (0u8..3).prop_map(Change::NonFinite),
        1 => any::<Index>().prop_map(Change::Copy),
        1 => Just(Change::Truncate),
    ]
}

fn edit() -> impl Strategy<Value = Edit> {
    (prop::bool::weighted(0.3), any::<Index>(), change()).prop_map(|(settings_only, at, change)| {
        Edit {
            settings_only,
            at,
            change,
        }
    })
}

/// A case: a base request, up to three edits, and maybe a tiny work budget.
#[derive(Clone, Debug)]
struct Case {
    base: Index,
    edits: Vec<Edit>,
    budget: Option<u64>,
}

fn case() -> impl Strategy<Value = Case> {
    (
        any::<Index>(),
        prop::collection::vec(edit(), 0..=3),
        prop::option::weighted(
            0.25,
            prop::sample::select(vec![0u64, 1, 100, 10_000, 200_000]),
        ),
    )
        .prop_map(|(base, edits, budget)| Case {
            base,
            edits,
            budget,
        })
}

/// Finite markers for the non-finite values (bit patterns no fixture or edit makes).
const MARKS: [(u64, f64); 3] = [
    (0x1357_9bdf_2468_ace1, f64::NAN),
    (0x1357_9bdf_2468_ace2, f64::INFINITY),
    (0x1357_9bdf_2468_ace3, f64::NEG_INFINITY),
];

/// JSON pointers of the tree's number and bool leaves, and of its arrays.
fn leaves(v: &Value, at: &str, out: &mut Vec<String>, arrays: &mut Vec<String>) {
    match v {
        Value::Number(_) | Value::Bool(_) => out.push(at.to_owned()),
        Value::Array(items) => {
            if !items.is_empty() {
                arrays.push(at.to_owned());
            }
            for (i, item) in items.iter().enumerate() {
                leaves(item, &format!("{at}/{i}"), out, arrays);
            }
        }
        Value::Object(map) => {
            for (k, item) in map {
                leaves(item, &format!("{at}/{k}"), out, arrays);
            }
        }
        _ => {}
    }
}

fn int_value(x: f64) -> Value {
    let x = x.round().clamp(-9.0e15, 9.0e15);
    if x < 0.0 {
        Value::from(x as i64)
    } else {
        Value::from(x as u64)
    }
}

/// The request with one edit, or `None` when the edit makes no request.
fn apply_edit(request: &Request, e: &Edit) -> Option<Request> {
    let mut tree = serde_json::to_value(request).ok()?;
    let (mut all, mut arrays) = (Vec::new(), Vec::new());
    leaves(&tree, "", &mut all, &mut arrays);
    let pool: Vec<String> = if e.settings_only {
        all.iter()
            .filter(|p| p.contains("settings"))
            .cloned()
            .collect()
    } else {
        all.clone()
    };
    if pool.is_empty() {
        return None;
    }
    if let Change::Truncate = e.change {
        if arrays.is_empty() {
            return None;
        }
        let at = e.at.get::<String>(&arrays);
        tree.pointer_mut(at)?.as_array_mut()?.pop();
    } else {
        let at = e.at.get::<String>(&pool);
        let old = tree.pointer(at)?.clone();
        let new = match (&old, &e.change) {
            (Value::Bool(b), _) => Value::Bool(!b),
            (_, Change::Copy(from)) => tree.pointer(from.get::<String>(&all))?.clone(),
            (Value::Number(n), change) => {
                let x = n.as_f64()?;
                let int = !n.is_f64();
                let y = match change {
                    Change::Scale(f) => x * f,
                    Change::Shift(d) => x + d * x.abs().max(1.0),
                    Change::Zero => 0.0,
                    Change::One => 1.0,
                    Change::Negate => -x,
                    Change::Tiny(t) if int => 1.0_f64.max(*t),
                    Change::Tiny(t) => *t,
                    Change::Huge(h) => *h,
                    Change::NonFinite(_) if int => return None,
                    Change::NonFinite(i) => f64::from_bits(MARKS[usize::from(*i)].0),
                    Change::Copy(_) | Change::Truncate => unreachable!(),
                };
                if int {
                    int_value(y)
                } else {
                    Value::from(y)
                }
            }
            _ => return None,
        };
        *tree.pointer_mut(at)? = new;
    }
    let edited: Request = serde_json::from_value(tree).ok()?;
    // The markers become the non-finite values they stand for.
    let mut bytes = postcard::to_allocvec(&edited).ok()?;
    for (bits, value) in MARKS {
        let mark = f64::from_bits(bits).to_le_bytes();
        let mut i = 0;
        while i + 8 <= bytes.len() {
            if bytes[i..i + 8] == mark {
                bytes[i..i + 8].copy_from_slice(&value.to_le_bytes());
                i += 8;
            } else {
                i += 1;
            }
        }
    }
    postcard::from_bytes(&bytes).ok()
}

fn set_budget(request: &mut Request, budget: u64) {
    match request {
        Request::Pseudospectral { settings, .. } => settings.work_budget = budget,
        Request::Impulsive { settings, .. } | Request::ImpulsiveForm { settings, .. } => {
            settings.work_budget = budget;
        }
        Request::GeoTour { settings, .. } => settings.work_budget = budget,
        Request::LeoArc { settings, .. } => settings.work_budget = budget,
        Request::LeoSequence { arc_settings, .. } => arc_settings.work_budget = budget,
        Request::Hybrid { settings, .. } => settings.work_budget = budget,
    }
}

fn build(bases: &[(String, Request)], case: &Case) -> (String, Request) {
    let (label, base) = case.base.get(bases);
    let mut request = base.clone();
    for e in &case.edits {
        if let Some(r) = apply_edit(&request, e) {
            request = r;
        }
    }
    if let Some(b) = case.budget {
        set_budget(&mut request, b);
    }
    (label.clone(), request)
}

// ---------------------------------------------------------------------------------------------
// The check.
// ---------------------------------------------------------------------------------------------

/// How an outcome ended, for the coverage tally.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord)]
enum Ending {
    Usable,
    NotUsable,
    Refused,
    LimitExceeded,
}

/// The name of how an outcome ended: its variant and, for a plan, its status's variant
/// (`Pseudospectral/BudgetExhausted`), for the tally.
fn ending_name(o: &OutcomeRef<'_>) -> String {
    let status = reconfig_host::drivers::answer::status_text(o).unwrap_or_else(|| format!("{o:?}"));
    let word = |t: &str| {
        t.split(|c: char| !c.is_alphanumeric())
            .next()
            .unwrap_or("")
            .to_owned()
    };
    format!("{}/{}", word(&format!("{o:?}")), word(&status))
}

/// An owned copy of a borrowed outcome.
fn owned(o: &OutcomeRef<'_>) -> Outcome {
    match *o {
        OutcomeRef::Pseudospectral(s) => Outcome::Pseudospectral(s.clone()),
        OutcomeRef::PseudospectralRejected(e) => Outcome::PseudospectralRejected(e),
        OutcomeRef::Impulsive(s) => Outcome::Impulsive(s.clone()),
        OutcomeRef::ImpulsiveRejected(e) => Outcome::ImpulsiveRejected(e),
        OutcomeRef::BadRequest(e) => Outcome::BadRequest(e),
        OutcomeRef::LimitExceeded(v) => Outcome::LimitExceeded(v),
        OutcomeRef::Expired(x) => Outcome::Expired(x),
        OutcomeRef::GeoTour(s) => Outcome::GeoTour(s.clone()),
        OutcomeRef::GeoTourRejected(e) => Outcome::GeoTourRejected(e),
        OutcomeRef::ImpulsiveForm {
            solution,
            end_state,
        } => Outcome::ImpulsiveForm {
            solution: solution.clone(),
            end_state,
        },
        OutcomeRef::LeoArc(s) => Outcome::LeoArc(*s),
        OutcomeRef::LeoArcRejected(e) => Outcome::LeoArcRejected(e),
        OutcomeRef::LeoSequence(q) => Outcome::LeoSequence(*q),
        OutcomeRef::LeoSequenceRejected(e) => Outcome::LeoSequenceRejected(e),
        OutcomeRef::Unsupported(p) => Outcome::Unsupported(p),
        OutcomeRef::Hybrid(s) => Outcome::Hybrid(*s),
        OutcomeRef::HybridRejected(e) => Outcome::HybridRejected(e),
    }
}

/// The `NaN` / `inf` tokens of a C struct's `Debug` text (the C view has no serde).
fn debug_non_finite(text: &str) -> Vec<String> {
    let tokens: Vec<&str> = text
        .split(|c: char| !(c.is_alphanumeric() || c == '_'))
        .collect();
    let mut bad = Vec::new();
    for (i, t) in tokens.iter().enumerate() {
        if *t == "NaN" || *t == "inf" {
            // The nearest field name before it, for the report.
            let field = tokens[..i]
                .iter()
                .rev()
                .find(|t| t.chars().next().is_some_and(char::is_lowercase))
                .unwrap_or(&"?");
            bad.push(format!("{field}: {t}"));
        }
    }
    bad
}

/// The C view of a plan (the kinds with a C interface), as `Debug` text.
fn c_view(o: &OutcomeRef<'_>) -> Option<String> {
    match *o {
        OutcomeRef::Pseudospectral(s) => {
            // SAFETY: a `repr(C)` struct of integers, floats and arrays of them: all zero is
            // a valid value (the C caller's zeroed buffer); `solution_to_c` then writes it.
            let mut c: Box<reconfig_capi::types_a::ReconfigASolution> =
                Box::new(unsafe { std::mem::zeroed() });
            convert_a::solution_to_c(s, &mut c);
            Some(format!("{c:?}"))
        }
        OutcomeRef::Impulsive(s) => Some(format!("{:?}", convert_b::solution_to_c(s))),
        OutcomeRef::ImpulsiveForm {
            solution,
            end_state,
        } => Some(format!(
            "{:?} {:?}",
            convert_b::solution_to_c(solution),
            convert_b_form::end_state_to_c(&end_state)
        )),
        OutcomeRef::GeoTour(s) => {
            let mut c = Box::<reconfig_capi::types_geo::ReconfigGeoSolution>::default();
            convert_geo::solution_to_c(s, &mut c);
            Some(format!("{c:?}"))
        }
        OutcomeRef::LeoArc(s) => {
            let mut c = Box::<reconfig_capi::types_leo::ReconfigLeoArcSolution>::default();
            convert_leo::solution_to_c(s, &mut c);
            Some(format!("{c:?}"))
        }
        _ => None,
    }
}

/// The same non-finite value: both NaN, or the same infinity.
fn same(a: f64, b: f64) -> bool {
    (a.is_nan() && b.is_nan()) || a == b
}

/// Answer `request` and check every number of the answer; how it ended.
fn check(
    label: &str,
    request: &Request,
    buffers: &mut AllPlanners,
) -> Result<(Ending, String), TestCaseError> {
    let input_non_finite = !non_finite(request).is_empty();
    let outcome = answer(request, &Limits::default(), buffers);
    let ending = match outcome.usable() {
        Some(true) => Ending::Usable,
        Some(false) => Ending::NotUsable,
        None if matches!(outcome, OutcomeRef::LimitExceeded(_)) => Ending::LimitExceeded,
        None => Ending::Refused,
    };
    prop_assert!(
        !matches!(
            outcome,
            OutcomeRef::Unsupported(_) | OutcomeRef::BadRequest(_) | OutcomeRef::Expired(_)
        ),
        "{label}: {outcome:?}"
    );
    // A NaN or an infinity in the request is refused, never planned.
    prop_assert!(
        !(input_non_finite && outcome.usable().is_some()),
        "{label}: a request with a non-finite number was planned:\n{request:?}\n-> {outcome:?}"
    );
    // Every number of the answer is finite, but a refusal's echo of the caller's own
    // non-finite input.
    let given = non_finite(request);
    let echo = |n: &Number| {
        let field = n.path.rsplit('.').next().unwrap_or("");
        ending == Ending::Refused
            && field.starts_with("value")
            && given.iter().any(|g| same(g.value, n.value))
    };
    let bad: Vec<_> = non_finite(&outcome)
        .into_iter()
        .filter(|n| !echo(n))
        .collect();
    prop_assert!(
        bad.is_empty(),
        "{label}: non-finite answer numbers {bad:?}\nrequest {request:?}\n-> {outcome:?}"
    );
    // The C view of a plan is finite.
    if let Some(text) = c_view(&outcome) {
        let bad = debug_non_finite(&text);
        prop_assert!(
            bad.is_empty(),
            "{label}: non-finite C fields {bad:?}\nrequest {request:?}\n-> {outcome:?}"
        );
    }
    // The answer encodes, fits a response, and decodes back equal.
    let bytes = postcard::to_allocvec(&outcome).expect("outcome encodes");
    let mut frame = vec![0u8; RESPONSE_BODY_MAX_BYTES];
    let n = encode_outcome(&outcome, &mut frame).expect("outcome fits a response body");
    prop_assert_eq!(&frame[..n], &bytes[..]);
    let back: Outcome = postcard::from_bytes(&bytes).expect("outcome decodes");
    prop_assert_eq!(
        postcard::to_allocvec(&back.as_ref()).expect("re-encodes"),
        bytes
    );
    if non_finite(&outcome).is_empty() {
        prop_assert_eq!(back, owned(&outcome));
    }
    Ok((ending, ending_name(&outcome)))
}

/// Run `cases` deterministic cases over the requests of kind `k` (those `keep` takes); the
/// tally of how they ended.
fn run(k: Kind, cases: u32, seed: u64, keep: impl Fn(&Request) -> bool) -> BTreeMap<Ending, u32> {
    let bases = bases_of(k, keep);
    let buffers = RefCell::new(Box::new(AllPlanners::new()));
    let tally = RefCell::new(BTreeMap::new());
    let names = RefCell::new(BTreeMap::<String, u32>::new());
    // Every fixture request as it is (cheapened), then the perturbed cases.
    for (label, request) in &bases {
        let (ending, name) =
            check(label, request, &mut buffers.borrow_mut()).unwrap_or_else(|e| panic!("{e}"));
        *tally.borrow_mut().entry(ending).or_insert(0) += 1;
        *names.borrow_mut().entry(name).or_insert(0) += 1;
    }
    // A local hunt may vary the seeds and multiply the cases; unset (CI), the cases are fixed.
    let knob = |name: &str| std::env::var(name).ok().and_then(|s| s.parse::<u64>().ok());
    let seed = knob("FINITE_ANSWERS_SEED").map_or(seed, |x| seed ^ x);
    let cases = knob("FINITE_ANSWERS_CASES_X").map_or(cases, |m| cases * m as u32);
    let config = Config {
        cases,
        rng_seed: RngSeed::Fixed(seed),
        failure_persistence: None,
        // Shrinking re-solves: keep it short.
        max_shrink_iters: 64,
        ..Config::default()
    };
    let mut runner = TestRunner::new(config);
    let result = runner.run(&case(), |case| {
        let (label, request) = build(&bases, &case);
        let (ending, name) = check(&label, &request, &mut buffers.borrow_mut())?;
        *tally.borrow_mut().entry(ending).or_insert(0) += 1;
        *names.borrow_mut().entry(name).or_insert(0) += 1;
        Ok(())
    });
    if let Err(e) = result {
        panic!("{k:?}: {e}");
    }
    let tally = tally.into_inner();
    eprintln!("{k:?}: {tally:?}\n  {:?}", names.into_inner());
    tally
}

/// The kinds must reach plans and refusals, usable and not: the perturbations are not all
/// refused at the door.
fn assert_reached(k: Kind, tally: &BTreeMap<Ending, u32>, endings: &[Ending]) {
    for e in endings {
        assert!(tally.contains_key(e), "{k:?} never ended {e:?}: {tally:?}");
    }
}

const ALL: [Ending; 4] = [
    Ending::Usable,
    Ending::NotUsable,
    Ending::Refused,
    Ending::LimitExceeded,
];

#[test]
fn pseudospectral_answers_are_finite() {
    // The three-spacecraft fixtures: the eight-spacecraft ones cost too much per case here.
    let tally = run(Kind::Pseudospectral, 200, 0x29_06_01, |_| true);
    assert_reached(Kind::Pseudospectral, &tally, &ALL);
}

#[test]
fn impulsive_answers_are_finite() {
    let tally = run(Kind::Impulsive, 400, 0x29_06_02, |_| true);
    assert_reached(Kind::Impulsive, &tally, &ALL);
}

#[test]
fn impulsive_form_answers_are_finite() {
    let tally = run(Kind::ImpulsiveForm, 300, 0x29_06_03, |_| true);
    assert_reached(Kind::ImpulsiveForm, &tally, &ALL);
}

#[test]
fn geo_tour_answers_are_finite() {
    let tally = run(Kind::GeoTour, 400, 0x29_06_04, |_| true);
    assert_reached(Kind::GeoTour, &tally, &ALL);
}

#[test]
fn leo_arc_answers_are_finite() {
    let tally = run(Kind::LeoArc, 100, 0x29_06_05, |_| true);
    assert_reached(Kind::LeoArc, &tally, &[Ending::Usable, Ending::Refused]);
}

#[test]
fn hybrid_answers_are_finite() {
    let tally = run(Kind::Hybrid, 120, 0x30_06_07, |_| true);
    assert_reached(Kind::Hybrid, &tally, &ALL);
}

#[test]
fn leo_sequence_answers_are_finite() {
    let tally = run(Kind::LeoSequence, 40, 0x29_06_06, |_| true);
    assert_reached(Kind::LeoSequence, &tally, &[Ending::Usable]);
}
