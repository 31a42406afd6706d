//! The GEO tour over the wire: a request and a solution at capacity (16 clients) round-trip
//! within the frame limits, byte for byte.
#![allow(clippy::unwrap_used, clippy::expect_used)]

use reconfig_core::geo_tour::{
    solve, MethodPolicy, Problem, Settings, Solution, SolveStatus, SweepChoice, Workspace,
};
use reconfig_core::wire::{
    decode_request, decode_response, encode_request, encode_response, Outcome, OutcomeRef, Request,
    REQUEST_MAX_BYTES, RESPONSE_MAX_BYTES,
};

fn capacity_problem() -> Problem {
    let mut t = heapless::Vec::new();
    for k in 0..16 {
        t.push((50.0 + 7.5 * f64::from(k)).to_radians()).unwrap();
    }
    Problem {
        start_lon_rad: 48f64.to_radians(),
        targets_lon_rad: t,
        mission_time_s: 120.0 * 86_400.0,
        max_burn_mps: 5.0,
        sweep: SweepChoice::Cheaper,
        policy: MethodPolicy::ByCost,
    }
}

#[test]
fn request_and_solution_at_capacity_round_trip() {
    let problem = capacity_problem();
    let settings = Settings::default();
    let request = Request::GeoTour {
        problem: problem.clone(),
        settings,
    };
    let mut buf = vec![0u8; REQUEST_MAX_BYTES];
    let n = encode_request(7, &request, &mut buf).unwrap();
    assert!(n <= REQUEST_MAX_BYTES);
    assert_eq!(decode_request(&buf[..n]).unwrap().request, request);

    let mut ws = Box::new(Workspace::new());
    let mut out = Box::new(Solution::new());
    solve(&problem, &settings, &mut ws, &mut out).unwrap();
    assert_eq!(out.info.status, SolveStatus::Solved);
    assert_eq!(out.legs.len(), 16);
    let mut rbuf = vec![0u8; RESPONSE_MAX_BYTES];
    let m = encode_response(7, 1, &OutcomeRef::GeoTour(&out), &mut rbuf).unwrap();
    println!("request {n} bytes, response {m} bytes (16 legs)");
    let back = decode_response(&rbuf[..m]).unwrap();
    assert_eq!(back.outcome, Outcome::GeoTour((*out).clone()));
}

#[test]
fn memory_sizes() {
    // Reported in docs/geo-tour.md (static memory an M7 build would add).
    println!(
        "Workspace {} B, Solution {} B",
        std::mem::size_of::<Workspace>(),
        std::mem::size_of::<Solution>()
    );
    assert!(std::mem::size_of::<Workspace>() < 32 * 1024);
}
