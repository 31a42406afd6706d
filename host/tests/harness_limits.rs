//! Service-side limits and fair scheduling, with real processes: a request outside the limits
//! is answered `LimitExceeded` naming the setting (never solved); a `--limits` file tightens
//! them; a request queued past its deadline is answered `Expired`; two feeders at once are
//! served in turn.

mod harness_common;

use harness_common::*;
use std::path::Path;

fn result<'a>(report: &'a serde_json::Value, label: &str) -> &'a serde_json::Value {
    report["results"]
        .as_array()
        .expect("results")
        .iter()
        .find(|r| r["label"] == label)
        .unwrap_or_else(|| panic!("no result for {label}: {report}"))
}

fn fixture(path: &str) -> String {
    format!("{}/../fixtures/{path}", env!("CARGO_MANIFEST_DIR"))
}

#[test]
fn requests_outside_the_limits_are_refused_by_name_and_a_limits_file_tightens_them() {
    let inst = instance("limits");
    let limits = temp("limits", "limits.toml");
    // Tighter than the built-in limits: planner A at most 2 spacecraft.
    std::fs::write(&limits, "[pseudospectral]\nspacecraft = 2\n").expect("write limits");
    let limits_arg = limits.display().to_string();
    let service = serve(&inst, &["--limits", &limits_arg]);
    let json = temp("limits", "report.json");
    let search = fixture("over-limits/wang2018-search-3imp-2m-samples.toml");
    let unsafe_a = fixture("over-limits/huang2012-n10-no-continuous-verification.toml");
    let three = fixture("huang2012-three-sats-n10.toml");
    let fixed = fixture("wang2018-gco-to-pco-3imp.toml");
    let (code, report) = feed(
        &inst,
        &[
            "--fixture",
            &search,
            "--fixture",
            &unsafe_a,
            "--fixture",
            &three,
            "--fixture",
            &fixed,
            "--limits",
            &limits_arg,
        ],
        &json,
    );
    // Every answer equals the local check under the same limits.
    assert_eq!(code, Some(0), "{report}");
    let status = |label: &str| {
        result(&report, label)["status"]
            .as_str()
            .unwrap_or("")
            .to_string()
    };
    assert_eq!(
        status("wang2018-search-3imp-2m-samples"),
        "limit exceeded: search_samples = 2000000 is above the limit 400"
    );
    assert_eq!(
        status("huang2012-three-sats-n10-no-continuous-verification"),
        "limit exceeded: spacecraft = 3 is above the limit 2"
    );
    assert_eq!(
        status("huang2012-three-sats-n10"),
        "limit exceeded: spacecraft = 3 is above the limit 2"
    );
    // Within the limits: solved.
    assert_eq!(status("wang2018-gco-to-pco-3imp"), "Solved");
    // Refused without solving: the round trip is the harness's alone, far below a search's.
    let rtt = result(&report, "wang2018-search-3imp-2m-samples")["rtt_us"]
        .as_f64()
        .expect("rtt");
    // A solve of 2 M samples would take minutes; 1 s leaves room for a loaded CI machine (the
    // refusal itself takes well under a millisecond of the round trip).
    assert!(rtt < 1_000_000.0, "refusal took {rtt} us");
    let _ = std::fs::remove_file(&json);
    let _ = std::fs::remove_file(&limits);
    stop_and_check_clean(service, &inst);
}

#[test]
fn a_request_queued_past_its_deadline_is_answered_expired_unsolved() {
    let inst = instance("expire");
    // One worker and four genuinely slow requests (a planner-B search over 60 000 samples,
    // 1.9 s here under load, allowed by a limits file) sent at once with a 100 ms deadline: the first
    // one occupies the worker, the three behind it wait past their deadline. The feeder's
    // timeout is a safety net for a loaded machine, not a bound.
    let (slow, limits) = slow_search("expire", 60_000);
    let (slow, limits) = (slow.display().to_string(), limits.display().to_string());
    let service = serve(&inst, &["--limits", &limits]);
    let json = temp("expire", "report.json");
    let mut args = vec![
        "--window",
        "4",
        "--deadline-ms",
        "100",
        "--timeout-ms",
        "120000",
        "--limits",
        &limits,
    ];
    for _ in 0..4 {
        args.extend(["--fixture", slow.as_str()]);
    }
    let (code, report) = feed(&inst, &args, &json);
    // Expired answers are truthful but not plans, so the feed does not pass.
    assert_eq!(code, Some(1), "{report}");
    let results = report["results"].as_array().expect("results");
    let expired: Vec<_> = results
        .iter()
        .filter(|r| {
            r["status"]
                .as_str()
                .is_some_and(|s| s.starts_with("expired"))
        })
        .collect();
    let solved: Vec<_> = results.iter().filter(|r| r["correct"] == true).collect();
    assert_eq!(
        solved.len(),
        1,
        "only the first request reaches the worker: {report}"
    );
    assert_eq!(expired.len(), 3, "{report}");
    // The solved one had a turn; the expired ones were answered outside the turns.
    assert!(solved[0]["turn"].is_u64(), "{report}");
    let solved_rtt = solved[0]["rtt_us"].as_f64().expect("rtt");
    for r in expired {
        assert!(r["turn"].is_null(), "{r}");
        // Answered at its deadline, not after the worker got round to it: no sooner than the
        // deadline, and while the worker was still solving the first request (an order, on
        // any machine on which the search takes longer than 100 ms).
        let rtt = r["rtt_us"].as_f64().expect("rtt");
        assert!(rtt >= 100_000.0, "{r}");
        assert!(
            rtt < solved_rtt,
            "{r} answered after the solve ({solved_rtt} us)"
        );
        assert!(
            r["status"]
                .as_str()
                .unwrap_or("")
                .contains("deadline 100.0 ms"),
            "{r}"
        );
    }
    assert_eq!(report["reports"][0]["counters"]["lost"], 0);
    for path in [&json, Path::new(&slow), Path::new(&limits)] {
        let _ = std::fs::remove_file(path);
    }
    stop_and_check_clean(service, &inst);
}

/// For each of one client's answers `[received_at_turn, turn]`: (turns of its own earlier
/// requests, turns of other clients) between the request's receipt and its turn.
fn waits(served: &[(u64, u64)]) -> Vec<(u64, u64)> {
    served
        .iter()
        .map(|&(received, turn)| {
            let own = served
                .iter()
                .filter(|(_, t)| (received..turn).contains(t))
                .count() as u64;
            (own, turn - received - own)
        })
        .collect()
}

#[test]
fn two_feeders_are_served_in_turn() {
    // `reconfig fairness` starts its own service (one worker here) and two feeders per phase:
    // expensive (crossings, 2 in flight) + cheap (planner-B fixed points, one at a time), then
    // two alike (crossings, 2 in flight each); every answer is checked against a local solve.
    // This test asserts the order of service, not a speed (issue 29: a count of the cheap
    // client's answers in a 2 s window failed once on a loaded machine): every answer carries
    // its request's turn (counted over all clients) and the number of turns given when the
    // request arrived. Round-robin means that while a request waits, the other client gets at
    // most one turn more than the waiting client's own earlier requests. The command's own
    // verdict also holds latency and throughput, which a loaded machine may miss; they are not
    // asserted here (`reconfig fairness --seconds 60` measures them, docs/harness.md).
    let json = temp("fair", "fair.json");
    let out = std::process::Command::new(exe())
        .args([
            "fairness",
            "--seconds",
            "2",
            "--window",
            "2",
            "--cpus",
            "0",
            "--no-pin",
            "--json",
        ])
        .arg(&json)
        .output()
        .expect("run fairness");
    let stdout = String::from_utf8_lossy(&out.stdout);
    let report: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&json).unwrap_or_default())
            .unwrap_or(serde_json::Value::Null);
    let checks = &report["checks"];
    assert_eq!(checks["all_correct"], true, "{stdout}\n{report}");
    assert_eq!(checks["stopped_cleanly"], true, "{stdout}\n{report}");
    for phase in ["mixed", "same_kind"] {
        let clients = report[phase].as_array().expect("clients");
        assert_eq!(clients.len(), 2, "{report}");
        let mut all_turns = Vec::new();
        for c in clients {
            let served: Vec<(u64, u64)> = c["served"]
                .as_array()
                .expect("served")
                .iter()
                .map(|p| (p[0].as_u64().expect("turn"), p[1].as_u64().expect("turn")))
                .collect();
            // Every answer was given in a turn (none expired), and there was one.
            assert_eq!(Some(served.len() as u64), c["correct"].as_u64(), "{c}");
            assert!(!served.is_empty(), "{phase}: {c}");
            for (k, (own, others)) in waits(&served).into_iter().enumerate() {
                assert!(
                    others <= own + 1,
                    "{phase}, {}: request {k} waited for {others} turns of the other client \
                     and {own} of its own: {c}",
                    c["client"]
                );
            }
            all_turns.extend(served.iter().map(|(_, t)| *t));
        }
        // Each turn served one request of one client.
        let n = all_turns.len();
        all_turns.sort_unstable();
        all_turns.dedup();
        assert_eq!(all_turns.len(), n, "{phase}: a turn given twice: {report}");
    }
    // Both clients of the second phase keep two requests in flight on one worker, so each of
    // them has requests that waited for a turn of the other: the clients took turns.
    for c in report["same_kind"].as_array().expect("clients") {
        let served: Vec<(u64, u64)> = c["served"]
            .as_array()
            .expect("served")
            .iter()
            .map(|p| (p[0].as_u64().unwrap_or(0), p[1].as_u64().unwrap_or(0)))
            .collect();
        assert!(
            waits(&served).iter().any(|(_, others)| *others >= 1),
            "{}: never waited for the other client: {report}",
            c["client"]
        );
    }
    let _ = std::fs::remove_file(&json);
}
