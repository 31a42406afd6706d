//! A client flooding the flight service with garbage (issue 33), with real processes: a
//! flooder (`reconfig feed --flood MODE`: garbage frames and wake-ups as fast as it can) runs
//! while a good client sends real requests one at a time; the flooder is killed (SIGKILL)
//! half-way, and a new client comes after it. Asserted, from the order of service every answer
//! carries (its request's turn, and the turns given before the request arrived) and from a
//! local solve of every request, never from a speed:
//! * every good request is answered, correctly, during the flood and after the kill;
//! * the good client is served in turn: between a request's receipt and its turn the service
//!   gave at most one turn to another client (the flooder);
//! * the flooder got at most 15 turns while the good client was served (its 16th bad frame
//!   among 32 drops it: `harness::conduct`).
//!
//! Timeouts are safety nets only. Before the fix, the good client lost every request in most
//! runs, during the flood and after the flooder was gone: iceoryx2's event lost a wake-up under
//! the flood and the dispatcher slept for good (docs/harness.md, *Hostile clients*).

mod harness_common;

use harness_common::*;
use std::time::Duration;

/// Most turns a flooding client can get: it is dropped at its 16th bad frame among 32, and the
/// 16th is not served.
const FLOODER_TURNS: u64 = 15;

fn flood_case(mode: &str) {
    let test = format!("flood-{mode}");
    let inst = instance(&test);
    let service = serve(&inst, &[]);

    let mut flooder_args: Vec<String> = ["feed", "--flood", mode]
        .iter()
        .map(|s| s.to_string())
        .collect();
    flooder_args.extend(instance_args(&inst));
    let mut flooder = spawn(&flooder_args);
    // 1000 attempts made before the good client starts.
    assert!(
        flooder
            .wait_line("flooding", Duration::from_secs(60))
            .is_some(),
        "{mode}: the flooder did not flood"
    );

    let json = temp(&test, "good.json");
    let total = 30;
    let mut good_args: Vec<String> = [
        "feed",
        "--verbose",
        "--random",
        &total.to_string(),
        "--seed",
        "21",
        "--timeout-ms",
        "30000",
        "--json",
    ]
    .iter()
    .map(|s| s.to_string())
    .collect();
    good_args.push(json.display().to_string());
    good_args.extend(instance_args(&inst));
    let mut good = spawn(&good_args);
    for k in 0..total / 2 {
        assert!(
            good.wait_line("answered", Duration::from_secs(120))
                .is_some(),
            "{mode}: good request {k} not answered during the flood: {:?}",
            good.all_lines()
        );
    }
    // Still flooding when killed.
    assert!(flooder.running(), "{mode}: the flooder stopped by itself");
    flooder.signal(libc::SIGKILL);
    let _ = flooder.wait(Duration::from_secs(10));
    let status = good.wait(Duration::from_secs(300));
    let text = std::fs::read_to_string(&json).unwrap_or_default();
    let report: serde_json::Value = serde_json::from_str(&text).unwrap_or_default();
    assert_eq!(
        status.and_then(|s| s.code()),
        Some(0),
        "{mode}: {report}\n{:?}",
        good.all_lines()
    );
    let counters = &report["reports"][0]["counters"];
    assert_eq!(counters["answered"], total, "{mode}: {counters}");
    for what in ["lost", "late", "duplicated", "malformed", "not_sent"] {
        assert_eq!(counters[what], 0, "{mode}: {what}: {counters}");
    }
    let results = report["results"].as_array().expect("results");
    assert_eq!(results.len(), total);
    let mut turns = Vec::new();
    for r in results {
        assert_eq!(r["correct"], true, "{mode}: {r}");
        let turn = r["turn"].as_u64().expect("answered in a turn");
        let received = r["received_at_turn"].as_u64().expect("received");
        // One request at a time: every turn in between went to another client.
        assert!(
            turn - received <= 1,
            "{mode}: request waited for {} turns of the flooder: {r}",
            turn - received
        );
        turns.push((received, turn));
    }
    let first = turns.iter().map(|(r, _)| *r).min().unwrap_or(0);
    let last = turns.iter().map(|(_, t)| *t).max().unwrap_or(0);
    let others = last + 1 - first - total as u64;
    assert!(
        others <= FLOODER_TURNS,
        "{mode}: the flooder had {others} turns while the good client was served"
    );

    // A new client after the flood is served too (and removes the killed flooder's node).
    let json2 = temp(&test, "after.json");
    let (code, after) = feed(&inst, &["--random", "5", "--seed", "22"], &json2);
    assert_eq!(code, Some(0), "{mode}: {after}");
    for path in [&json, &json2] {
        let _ = std::fs::remove_file(path);
    }
    stop_and_check_clean(service, &inst);
}

#[test]
fn a_flooder_that_abandons_its_requests_starves_no_one() {
    flood_case("abandon");
}

#[test]
fn a_flooder_that_reads_its_answers_starves_no_one() {
    flood_case("read");
}

#[test]
fn a_flooder_that_never_reads_its_answers_starves_no_one() {
    flood_case("ignore");
}
