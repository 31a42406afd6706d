//! The LEO tour over the wire: an arc's request and plan round-trip byte for byte, the flight
//! service's worker answers an arc and a sequencing with what a direct solve gives, a setting
//! above the service's limits is refused by name before any solve, and a request outside the
//! planner's ranges is answered with the planner's error naming the field.
#![allow(clippy::unwrap_used, clippy::expect_used)]

use reconfig_core::contract::Rule;
use reconfig_core::leo_tour::{
    solve_arc, ArcProblem, ArcSolution, Field, PlanError, Settings, SolveStatus, Workspace,
};
use reconfig_core::limits::Limits;
use reconfig_core::limits::Setting;
use reconfig_core::wire::{
    decode_request, decode_response, encode_request, encode_response, Outcome, OutcomeRef, Request,
    REQUEST_MAX_BYTES, RESPONSE_MAX_BYTES,
};
use reconfig_host::drivers::leo_tour::choose_order;
use reconfig_host::fixture::leo_tour::{self, LeoTourFixture};
use reconfig_host::harness::worker::Worker;
use reconfig_tests::fixtures_dir;

/// The paper's single arc (client 1 -> 2, Example I) as the fixture gives it.
fn paper_arc() -> (ArcProblem, Settings) {
    let f = leo_tour::load(&fixtures_dir().join("leo-tour-example1-single-arc.toml")).unwrap();
    let mut requests = f.requests().unwrap();
    assert_eq!(requests.len(), 1);
    let Request::LeoArc { problem, settings } = requests.remove(0).request else {
        panic!("an arc request");
    };
    (problem, settings)
}

/// The sequencing request of a `[sequence]` fixture (`Fixture::requests`).
fn leo_sequence_request(f: &LeoTourFixture) -> Request {
    let mut requests = f.requests().unwrap();
    assert_eq!(requests.len(), 1);
    requests.remove(0).request
}

/// The outcome the worker answers to `request`.
fn answer(worker: &mut Worker, request: &Request) -> Outcome {
    let mut buf = vec![0u8; REQUEST_MAX_BYTES];
    let n = encode_request(11, request, &mut buf).unwrap();
    let mut out = vec![0u8; RESPONSE_MAX_BYTES];
    let m = worker.handle(&buf[..n], &mut out);
    let back = decode_response(&out[..m]).unwrap();
    assert_eq!(back.seq, 11);
    back.outcome
}

#[test]
fn the_paper_arc_round_trips_and_the_worker_answers_the_direct_solve() {
    let (problem, settings) = paper_arc();
    let request = Request::LeoArc { problem, settings };
    let mut buf = vec![0u8; REQUEST_MAX_BYTES];
    let n = encode_request(7, &request, &mut buf).unwrap();
    assert_eq!(decode_request(&buf[..n]).unwrap().request, request);

    let mut direct = ArcSolution::new();
    solve_arc(
        &problem,
        &settings,
        &mut Box::new(Workspace::new()),
        &mut direct,
    )
    .unwrap();
    // The on-board budget cuts the search; the plan it had is checked and arrives.
    assert_eq!(
        direct.info.status,
        SolveStatus::BudgetExhausted { verified: true }
    );
    // The published arc costs 418.445 m/s; ours is below it (docs/leo-tour.md).
    assert!(direct.total_dv_mps < 418.445, "{}", direct.total_dv_mps);
    let mut rbuf = vec![0u8; RESPONSE_MAX_BYTES];
    let m = encode_response(7, 1, &OutcomeRef::LeoArc(&direct), &mut rbuf).unwrap();
    println!("LEO arc: request {n} bytes, response {m} bytes");
    assert_eq!(
        decode_response(&rbuf[..m]).unwrap().outcome,
        Outcome::LeoArc(direct)
    );

    let mut worker = Worker::new();
    assert_eq!(answer(&mut worker, &request), Outcome::LeoArc(direct));
}

#[test]
fn a_setting_above_the_service_limits_is_refused_by_name_unsolved() {
    let (problem, settings) = paper_arc();
    let request = Request::LeoArc {
        problem,
        settings: Settings {
            search_max_evals: 1_000_000,
            ..settings
        },
    };
    let mut worker = Worker::new();
    match answer(&mut worker, &request) {
        Outcome::LimitExceeded(v) => {
            assert_eq!(
                (v.setting, v.value, v.limit, v.rule),
                (
                    Setting::LeoArc(reconfig_core::leo_tour::SettingId::SearchMaxEvals),
                    1e6,
                    f64::from(Settings::default().search_max_evals),
                    Rule::AtMost
                )
            );
            assert!(v.to_string().contains("search_max_evals"), "{v}");
        }
        other => panic!("expected LimitExceeded, got {other:?}"),
    }
}

#[test]
fn a_request_outside_the_planners_ranges_is_answered_with_the_field() {
    let (problem, settings) = paper_arc();
    let request = Request::LeoArc {
        problem: ArcProblem {
            duration_s: -5.0,
            ..problem
        },
        settings,
    };
    let mut worker = Worker::new();
    match answer(&mut worker, &request) {
        Outcome::LeoArcRejected(e) => {
            assert!(
                matches!(
                    e,
                    PlanError::OutOfRange {
                        field: Field::Duration,
                        ..
                    }
                ),
                "{e:?}"
            );
            assert!(e.to_string().starts_with("duration_s = -5"), "{e}");
        }
        other => panic!("expected LeoArcRejected, got {other:?}"),
    }
}

#[test]
fn the_sequencing_request_is_answered_with_the_hosts_order() {
    let f = leo_tour::load(&fixtures_dir().join("leo-tour-example1-sequence.toml")).unwrap();
    let request = leo_sequence_request(&f);
    let mut buf = vec![0u8; REQUEST_MAX_BYTES];
    let n = encode_request(3, &request, &mut buf).unwrap();
    println!("LEO sequencing request: {n} bytes");
    let (_, chosen) = choose_order(&f, &Limits::default()).unwrap().unwrap();
    let mut worker = Worker::new();
    let Outcome::LeoSequence(q) = answer(&mut worker, &request) else {
        panic!("expected LeoSequence");
    };
    // The one implementation: the service's answer is the host command's, bit for bit.
    assert_eq!(q, chosen.sequence);
    assert_eq!(&q.order[..5], &[3, 2, 0, 4, 1]);
    assert_eq!((q.info.arcs_planned, q.info.arcs_in_tree), (86, 320));
    // Within the sequencing's default budget, and the work the answer says it did.
    assert!(q.info.work_units > 0 && q.info.work_units <= settings_budget());
}

/// The sequencing's built-in limit on its work budget (its default).
fn settings_budget() -> u64 {
    reconfig_core::leo_tour::sequence::SequenceSettings::DEFAULT.work_budget
}

#[test]
fn a_sequencing_with_a_thinner_bound_margin_is_refused_by_name() {
    let f = leo_tour::load(&fixtures_dir().join("leo-tour-example1-sequence.toml")).unwrap();
    let Request::LeoSequence {
        problem,
        mut settings,
        arc_settings,
    } = leo_sequence_request(&f)
    else {
        panic!("a sequencing request");
    };
    settings.bound_margin = 0.0;
    let request = Request::LeoSequence {
        problem,
        settings,
        arc_settings,
    };
    let mut worker = Worker::new();
    match answer(&mut worker, &request) {
        Outcome::LimitExceeded(v) => {
            assert_eq!(
                (v.setting, v.value, v.limit, v.rule),
                (
                    Setting::LeoSequence(reconfig_core::leo_tour::sequence::SettingId::BoundMargin),
                    0.0,
                    0.05,
                    Rule::AtLeast
                )
            );
            assert!(v.to_string().contains("bound_margin"), "{v}");
        }
        other => panic!("expected LimitExceeded, got {other:?}"),
    }
}
