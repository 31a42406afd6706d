//! Planner-B input forms through the flight service (issue 10 item 2): the form fixtures go on
//! the wire in their own forms (`Request::ImpulsiveForm`), the service converts them with the
//! core's `impulsive::forms`, and every answer equals the in-process solve bit for bit, with
//! the end state in the form the fixture gave its target in. A form outside the limits is
//! refused naming the field, its value and the limit.

mod harness_common;

use harness_common::*;
use reconfig_core::contract::Rule;
use reconfig_core::impulsive::{self, end_state, EndState, OrbitForm, RelativeForm};
use reconfig_core::limits::Setting;
use reconfig_core::wire::{self, Outcome, Request};
use reconfig_host::fixture;
use reconfig_host::harness::worker::Worker;

const FORM_FIXTURES: [&str; 2] = [
    "wang2018-gco-to-pco-2imp-roe.toml",
    "sso-leo-pair-e0-2imp-state.toml",
];

fn fixture_path(name: &str) -> String {
    format!("{}/../fixtures/{name}", env!("CARGO_MANIFEST_DIR"))
}

fn load(name: &str) -> reconfig_host::fixture::impulsive::ImpulsiveFixture {
    fixture::load_as(std::path::Path::new(&fixture_path(name))).expect("a planner-B fixture")
}

/// The fixture's one request (`Fixture::requests`).
fn request(name: &str) -> Request {
    let f = fixture::load(std::path::Path::new(&fixture_path(name))).expect("fixture loads");
    f.requests().expect("requests").remove(0).request
}

/// The worker's outcome for `request` (the code the service runs, in process).
fn answer(worker: &mut Worker, request: &Request) -> Outcome {
    let mut frame = vec![0u8; wire::REQUEST_MAX_BYTES];
    let n = wire::encode_request(1, request, &mut frame).expect("encode");
    let mut out = vec![0u8; wire::RESPONSE_MAX_BYTES];
    let m = worker.handle(&frame[..n], &mut out);
    wire::decode_response(&out[..m]).expect("decode").outcome
}

#[test]
fn the_worker_converts_in_the_core_and_answers_in_the_users_form() {
    let mut worker = Worker::new();
    for name in FORM_FIXTURES {
        let f = load(name);
        let request = request(name);
        assert!(
            matches!(request, Request::ImpulsiveForm { .. }),
            "{name} goes on the wire in its own forms"
        );
        // The in-process solve of the same forms (the CLI's path), and the end state of the
        // problem the CLI converted.
        let Some(form_problem) = &f.form else {
            panic!("{name} has no form")
        };
        let mut ws = Box::new(impulsive::Workspace::new());
        let mut local = Box::new(impulsive::Solution::new());
        impulsive::solve_form(form_problem, &f.settings, &mut ws, &mut local).expect("solves");
        let local_end = end_state(&f.problem.chief, &f.problem.target, &local, f.end_form);
        // The conversion is charged to the work meter on top of the plan's own units.
        let mut plain = Box::new(impulsive::Solution::new());
        impulsive::solve(&f.problem, &f.settings, &mut ws, &mut plain).expect("solves");
        assert_eq!(plain.impulses, local.impulses, "{name}: same plan");
        assert!(
            local.info.work_units >= plain.info.work_units,
            "{name}: conversion charged ({} < {})",
            local.info.work_units,
            plain.info.work_units
        );
        match answer(&mut worker, &request) {
            Outcome::ImpulsiveForm {
                solution,
                end_state,
            } => {
                // Bit for bit: the same conversion and the same solve.
                assert_eq!(solution, *local, "{name}");
                assert_eq!(end_state, local_end, "{name}");
                assert!(solution.info.status.is_usable(), "{name}");
                let Some(form) = &f.form else {
                    panic!("{name} has no form")
                };
                // The end state is the target in the user's form, to the plan's miss.
                match (end_state, &form.relative) {
                    (EndState::Roe(end), RelativeForm::Roe { target, .. }) => {
                        for (e, t) in [
                            (end.da_m, target.da_m),
                            (end.dlambda_m, target.dlambda_m),
                            (end.dex_m, target.dex_m),
                            (end.dey_m, target.dey_m),
                            (end.dix_m, target.dix_m),
                            (end.diy_m, target.diy_m),
                        ] {
                            assert!((e - t).abs() < 1e-3, "{name}: ROE {e} vs {t} m");
                        }
                    }
                    (
                        EndState::DeputyState(end),
                        RelativeForm::Deputy {
                            target: OrbitForm::State(target),
                            ..
                        },
                    ) => {
                        for k in 0..3 {
                            assert!((end.pos_km[k] - target.pos_km[k]).abs() < 1e-5, "{name}");
                            assert!(
                                (end.vel_km_s[k] - target.vel_km_s[k]).abs() < 1e-8,
                                "{name}"
                            );
                        }
                    }
                    (end, _) => panic!("{name}: end state {end:?} not in the target's form"),
                }
            }
            other => panic!("{name}: {other:?}"),
        }
    }
}

#[test]
fn a_hyperbolic_state_is_refused_by_the_service_naming_the_field() {
    let f = load("sso-leo-pair-e0-2imp-state.toml");
    let Some(mut form) = f.form.clone() else {
        panic!("no form")
    };
    if let RelativeForm::Deputy { target, .. } = &mut form.relative {
        *target = OrbitForm::State(impulsive::CartesianState {
            pos_km: [7078.137, 0.0, 0.0],
            vel_km_s: [0.0, 0.0, 12.0],
        });
    }
    let request = Request::ImpulsiveForm {
        problem: form,
        settings: f.settings,
    };
    match answer(&mut Worker::new(), &request) {
        Outcome::LimitExceeded(v) => {
            assert_eq!(
                (v.setting, v.limit, v.rule),
                (
                    Setting::Problem(reconfig_core::limits::ProblemLimit::DeputyTargetEccentricity),
                    1.0,
                    Rule::Below
                )
            );
            let e = 7078.137 * 144.0 / reconfig_core::astro::EARTH_MU_KM3_S2 - 1.0;
            assert!((v.value - e).abs() < 1e-12, "{v}");
            assert!(
                v.to_string()
                    .starts_with("deputy.target.eccentricity = 1.55"),
                "{v}"
            );
        }
        other => panic!("{other:?}"),
    }
}

#[test]
fn form_fixtures_go_through_shared_memory_and_match_the_local_solve() {
    let inst = instance("forms");
    let service = serve(&inst, &[]);
    let json = temp("forms", "report.json");
    let paths: Vec<String> = FORM_FIXTURES.iter().map(|n| fixture_path(n)).collect();
    let mut args = Vec::new();
    for p in &paths {
        args.push("--fixture");
        args.push(p.as_str());
    }
    let (code, report) = feed(&inst, &args, &json);
    // 0: every answer decoded and equals the local solve of the same frame byte for byte.
    assert_eq!(code, Some(0), "{report}");
    let results = report["results"].as_array().expect("results");
    assert_eq!(results.len(), 2, "{report}");
    for r in results {
        assert_eq!(r["status"], "Solved", "{report}");
        assert_eq!(r["correct"], true, "{report}");
    }
    let _ = std::fs::remove_file(&json);
    stop_and_check_clean(service, &inst);
}
