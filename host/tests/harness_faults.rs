//! Faults the harness survives, with real processes. Each test has its own iceoryx2 prefix and
//! service names and removes what it creates; every wait is bounded.

mod harness_common;

use harness_common::*;
use std::time::Duration;

fn counters(report: &serde_json::Value) -> &serde_json::Value {
    &report["reports"][0]["counters"]
}

#[test]
fn bad_frames_and_invalid_problems_get_error_responses_and_the_service_keeps_running() {
    let inst = instance("frames");
    let service = serve(&inst, &[]);
    let json = temp("frames", "report.json");
    let (code, report) = feed(&inst, &["--faults"], &json);
    assert_eq!(code, Some(0), "feed --faults failed: {report}");
    let results = report["results"].as_array().expect("results");
    let status_of = |label: &str| -> String {
        results
            .iter()
            .find(|r| r["label"] == label)
            .map(|r| {
                assert_eq!(r["correct"], true, "{label}: {r}");
                r["status"].as_str().unwrap_or_default().to_string()
            })
            .unwrap_or_else(|| panic!("no result for {label}"))
    };
    assert!(status_of("fault: malformed body").contains("malformed body"));
    assert!(status_of("fault: truncated").contains("truncated frame"));
    assert!(status_of("fault: oversized").contains("oversized frame"));
    assert!(status_of("fault: wrong version").contains("wrong protocol version"));
    assert!(status_of("fault: wrong CRC").contains("bad CRC"));
    assert!(status_of("fault: spacecraft count 9 (over capacity)").contains("malformed body"));
    // The core's own error comes back as a response, naming what was wrong.
    for (label, names) in [
        ("invalid: NaN horizon", "Horizon = NaN is NaN or infinite"),
        ("invalid: degree over capacity", "exceeds capacity 24"),
        (
            "invalid: manoeuvre infeasible",
            "cannot meet its boundary conditions",
        ),
        ("invalid: NaN eccentricity (planner B)", "NaN"),
    ] {
        let status = status_of(label);
        assert!(status.starts_with("rejected"), "{label}: {status}");
        assert!(status.contains(names), "{label}: {status}");
    }
    assert_eq!(counters(&report)["lost"], 0);

    // Still serving.
    let (code, report) = feed(&inst, &["--random", "5", "--seed", "3"], &json);
    assert_eq!(code, Some(0), "{report}");
    let _ = std::fs::remove_file(&json);
    stop_and_check_clean(service, &inst);
}

#[test]
fn a_killed_feeder_does_not_stop_the_service_and_the_next_feeder_is_served() {
    let inst = instance("feedkill");
    let service = serve(&inst, &[]);
    let mut args: Vec<String> = [
        "feed",
        "--quiet",
        "--verbose",
        "--random",
        "400",
        "--rate",
        "40",
    ]
    .iter()
    .map(|s| s.to_string())
    .collect();
    args.extend(instance_args(&inst));
    let first = spawn(&args);
    assert!(
        first
            .wait_line("answered", Duration::from_secs(60))
            .is_some(),
        "the first feeder got no answer"
    );
    first.signal(libc::SIGKILL);
    drop(first);

    let json = temp("feedkill", "report.json");
    let (code, report) = feed(&inst, &["--random", "10", "--seed", "9"], &json);
    assert_eq!(code, Some(0), "second feeder: {report}");
    assert_eq!(counters(&report)["answered"], 10);
    let _ = std::fs::remove_file(&json);
    stop_and_check_clean(service, &inst);
}

#[test]
fn a_killed_service_loses_the_requests_in_flight_and_the_feeder_goes_on_with_a_new_one() {
    let inst = instance("servkill");
    // One worker and genuinely slow requests (a planner-B search over 10 000 samples, 0.7 s
    // each here under load, allowed by a limits file), so requests are surely in flight at each kill.
    let (slow, limits) = slow_search("servkill", 10_000);
    let (slow, limits) = (slow.display().to_string(), limits.display().to_string());
    let mut service = serve(&inst, &["--limits", &limits]);
    let json = temp("servkill", "report.json");
    let total = 24;
    let mut args: Vec<String> = [
        "feed",
        "--verbose",
        "--limits",
        &limits,
        "--window",
        "2",
        "--timeout-ms",
        // Long enough that a live but loaded service (a restarted one's first answers, CI
        // running the other fault tests beside this one) is never declared lost: only the
        // kills may lose requests, which is what the bound below counts. At 1500 ms a CI run
        // lost 7 (one slow answer taken for a loss); a search here takes up to 0.7 s, and a
        // request may wait for one before its own.
        "8000",
        "--wait-service-ms",
        "60000",
        "--json",
    ]
    .iter()
    .map(|s| s.to_string())
    .collect();
    args.push(json.display().to_string());
    for _ in 0..total {
        args.extend(["--fixture".to_string(), slow.clone()]);
    }
    args.extend(instance_args(&inst));
    let started = std::time::Instant::now();
    let mut events: Vec<String> = Vec::new();
    let mut feeder = spawn(&args);
    // Three SIGKILL / restart cycles mid-load.
    let cycles = 3;
    for cycle in 0..cycles {
        assert!(
            feeder
                .wait_line("answered", Duration::from_secs(60))
                .is_some(),
            "cycle {cycle}: no answer before the kill"
        );
        // Window 2, one slow worker: two requests are in flight now.
        service.signal(libc::SIGKILL);
        events.push(format!("{} kill", started.elapsed().as_millis()));
        let _ = service.wait(Duration::from_secs(10));
        drop(service);
        assert!(
            feeder.wait_line("lost", Duration::from_secs(30)).is_some(),
            "cycle {cycle}: the feeder did not notice the loss"
        );
        events.push(format!("{} restart", started.elapsed().as_millis()));
        service = serve(&inst, &["--limits", &limits]);
        events.push(format!("{} ready", started.elapsed().as_millis()));
    }
    let status = feeder.wait(Duration::from_secs(120));
    // Not every request was answered, so the feeder reports failure.
    assert_eq!(status.and_then(|s| s.code()), Some(1));
    let report: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&json).expect("report")).expect("json");
    // On a failure the message carries the feeder's own account, line by line, and every
    // request's fate: what was lost, when, and between which kills.
    let c = counters(&report);
    let diagnosis = serde_json::json!({
        "counters": c,
        "events_ms": events,
        "feeder_lines": feeder.all_lines(),
        "results": report["results"],
    });
    // Shown with --nocapture: how many sends found no server connection and went again.
    eprintln!("counters: {c}");
    let lost = c["lost"].as_u64().expect("lost");
    let answered = c["answered"].as_u64().expect("answered");
    // At least one request in flight at each kill, at most the window (2): nothing else lost.
    assert!((cycles..=2 * cycles).contains(&lost), "{diagnosis:#}");
    assert_eq!(answered + lost, total, "{diagnosis:#}");
    assert_eq!(c["sent"], total, "{diagnosis:#}");
    assert_eq!(
        c["duplicated"], 0,
        "nothing is answered twice: {diagnosis:#}"
    );
    assert_eq!(c["late"], 0, "{diagnosis:#}");
    assert_eq!(c["malformed"], 0, "{diagnosis:#}");
    // Every answer, before and after each restart, is right.
    for r in report["results"].as_array().expect("results") {
        assert!(
            r["correct"] == true || r["status"] == "lost (timeout)",
            "{r}"
        );
    }
    for path in [json.display().to_string(), slow, limits] {
        let _ = std::fs::remove_file(path);
    }
    stop_and_check_clean(service, &inst);
}
