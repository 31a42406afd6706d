#![allow(clippy::unwrap_used, clippy::indexing_slicing, clippy::expect_used)]

use super::*;
use crate::impulsive;

fn request() -> Request {
    Request::Impulsive {
        problem: impulsive::Problem {
            chief: impulsive::MeanElements {
                sma_km: 7178.137,
                ecc: 0.0678,
                inc_rad: 1.1,
                raan_rad: 1.9,
                argp_rad: 0.0,
                mean_anomaly_rad: 0.0,
            },
            initial: impulsive::RelativeElements {
                dsma_km: 1e-4,
                decc: 1e-4,
                dinc_rad: 1e-4,
                draan_rad: 1e-4,
                dargp_rad: 1e-4,
                dmean_anomaly_rad: 1e-4,
            },
            target: impulsive::RelativeElements {
                dsma_km: 2e-4,
                decc: 2e-4,
                dinc_rad: 2e-4,
                draan_rad: 2e-4,
                dargp_rad: 2e-4,
                dmean_anomaly_rad: 2e-4,
            },
            plan: impulsive::ImpulsePlan::Search {
                impulses: 3,
                max_revolutions: 14,
            },
        },
        settings: impulsive::Settings::default(),
    }
}

#[test]
fn request_round_trips_and_each_check_names_its_failure() {
    let mut buf = [0u8; REQUEST_MAX_BYTES];
    let n = encode_request(42, &request(), &mut buf).unwrap();
    let frame = decode_request(&buf[..n]).unwrap();
    assert_eq!(frame.seq, 42);
    assert_eq!(frame.request, request());
    assert_eq!(peek_request_seq(&buf[..n]), Some(42));
    assert!(matches!(
        decode_request(&buf[..n - 1]),
        Err(FrameError::Truncated { .. })
    ));
    assert!(matches!(
        decode_request(&buf[..3]),
        Err(FrameError::Truncated { .. })
    ));
    let mut bad = buf;
    bad[n - 1] ^= 1;
    assert!(matches!(
        decode_request(&bad[..n]),
        Err(FrameError::BadCrc { .. })
    ));
    // A version that is not this build's, whatever this build's is.
    let wrong = PROTOCOL_VERSION.wrapping_add(1);
    let mut bad = buf;
    bad[2..4].copy_from_slice(&wrong.to_le_bytes());
    assert!(matches!(
        decode_request(&bad[..n]),
        Err(FrameError::WrongVersion { got, .. }) if got == wrong
    ));
    let mut bad = buf;
    bad[0] = b'X';
    assert!(matches!(
        decode_request(&bad[..n]),
        Err(FrameError::BadMagic { .. })
    ));
    let big = [0u8; REQUEST_MAX_BYTES + 1];
    assert!(matches!(
        decode_request(&big),
        Err(FrameError::Oversized { .. })
    ));
}

#[test]
#[allow(clippy::unreachable)]
fn impulsive_form_requests_and_outcomes_round_trip_in_every_form() {
    use impulsive::{
        CartesianState, EndState, EquinoctialElements, FormProblem, OrbitForm, RelativeForm, Roe,
    };
    let Request::Impulsive { problem, settings } = request() else {
        unreachable!()
    };
    let classical = OrbitForm::Classical(problem.chief);
    let equinoctial = OrbitForm::Equinoctial(EquinoctialElements {
        sma_km: 7078.1,
        mean_longitude_rad: -1.25,
        ex: 1e-3,
        ey: -2e-3,
        hx: 0.7,
        hy: -1.1,
    });
    let state = OrbitForm::State(CartesianState {
        pos_km: [505.3, -875.2, 7008.5],
        vel_km_s: [-6.49, -3.75, -1.4e-14],
    });
    let roe = Roe {
        da_m: 0.4,
        dlambda_m: -9.3e-3,
        dex_m: -996.9,
        dey_m: -136.8,
        dix_m: -135.7,
        diy_m: 1726.7,
    };
    let relatives = [
        RelativeForm::Elements {
            initial: problem.initial,
            target: problem.target,
        },
        RelativeForm::Roe {
            initial: roe,
            target: roe,
        },
        RelativeForm::Deputy {
            initial: state,
            target: equinoctial,
        },
        RelativeForm::Deputy {
            initial: classical,
            target: state,
        },
    ];
    let mut buf = [0u8; REQUEST_MAX_BYTES];
    for chief in [classical, equinoctial, state] {
        for relative in relatives {
            let req = Request::ImpulsiveForm {
                problem: FormProblem {
                    chief,
                    relative,
                    plan: problem.plan.clone(),
                },
                settings,
            };
            let n = encode_request(7, &req, &mut buf).unwrap();
            let frame = decode_request(&buf[..n]).unwrap();
            assert_eq!(frame.request, req);
            assert_eq!(
                frame.request.planner(),
                crate::contract::PlannerKind::Impulsive
            );
        }
    }
    let solution = impulsive::Solution::new();
    let mut out = [0u8; RESPONSE_MAX_BYTES];
    for end_state in [
        EndState::Elements(problem.target),
        EndState::Roe(roe),
        EndState::DeputyEquinoctial(EquinoctialElements {
            sma_km: 7078.1,
            mean_longitude_rad: 0.5,
            ex: 0.0,
            ey: 0.0,
            hx: 0.0,
            hy: 0.0,
        }),
        EndState::DeputyClassical(problem.chief),
        EndState::DeputyState(CartesianState {
            pos_km: [1.0, 2.0, 3.0],
            vel_km_s: [4.0, 5.0, 6.0],
        }),
        EndState::Unavailable(impulsive::FormError::Kepler),
    ] {
        let outcome = Outcome::ImpulsiveForm {
            solution: solution.clone(),
            end_state,
        };
        let n = encode_response(3, 9, &outcome.as_ref(), &mut out).unwrap();
        assert_eq!(decode_response(&out[..n]).unwrap().outcome, outcome);
    }
    let rejected = Outcome::ImpulsiveRejected(impulsive::PlanError::InputForm {
        part: impulsive::FormPart::Target,
        error: impulsive::FormError::RoeEquatorialChief {
            sin_inc: 1e-5,
            min: 1e-3,
        },
    });
    let n = encode_response(4, 0, &rejected.as_ref(), &mut out).unwrap();
    assert_eq!(decode_response(&out[..n]).unwrap().outcome, rejected);
}
