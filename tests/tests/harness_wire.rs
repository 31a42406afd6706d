//! Wire types: maximum encoded sizes at capacity, round trips, and decoding arbitrary bytes
//! never panics.

use proptest::prelude::*;
use reconfig_core::capacity::{MAX_IMPULSES, MAX_SPACECRAFT};
use reconfig_core::wire::*;

use reconfig_core::{impulsive, pseudospectral};

/// Planner-A request at capacity with every varint at its longest.
fn worst_pseudospectral_request() -> Request {
    let craft = pseudospectral::Spacecraft {
        mass_mu: f64::MAX,
        initial_state: [f64::MIN; 6],
        final_state: [f64::MAX; 6],
    };
    let mut spacecraft = heapless::Vec::new();
    for _ in 0..MAX_SPACECRAFT {
        spacecraft.push(craft).unwrap();
    }
    Request::Pseudospectral {
        problem: pseudospectral::Problem {
            horizon_tu: 1.0,
            max_control_fu: 1.0,
            keep_out_lu: 1.0,
            degree: u16::MAX,
            test_points: true,
            spacecraft,
        },
        settings: pseudospectral::Settings {
            sqp_max_iter: u16::MAX,
            qp_max_iter: u16::MAX,
            verify_max_rounds: u8::MAX,
            newton_max_iter: u16::MAX,
            refine_max_iter: u16::MAX,
            ..pseudospectral::Settings::default()
        },
    }
}

fn elements() -> impulsive::RelativeElements {
    impulsive::RelativeElements {
        dsma_km: 1.0,
        decc: 1.0,
        dinc_rad: 1.0,
        draan_rad: 1.0,
        dargp_rad: 1.0,
        dmean_anomaly_rad: 1.0,
    }
}

fn worst_impulsive_request() -> Request {
    let mut points = heapless::Vec::new();
    for _ in 0..MAX_IMPULSES {
        points
            .push(impulsive::ImpulsePoint {
                arg_latitude_rad: 1.0,
                revolutions: i32::MIN,
            })
            .unwrap();
    }
    Request::Impulsive {
        problem: impulsive::Problem {
            chief: impulsive::MeanElements {
                sma_km: 7000.0,
                ecc: 0.1,
                inc_rad: 1.0,
                raan_rad: 1.0,
                argp_rad: 1.0,
                mean_anomaly_rad: 1.0,
            },
            initial: elements(),
            target: elements(),
            plan: impulsive::ImpulsePlan::Fixed(points),
        },
        settings: impulsive::Settings::default(),
    }
}

fn worst_pseudospectral_solution() -> pseudospectral::Solution {
    let mut s = pseudospectral::Solution::new();
    s.degree = u16::MAX;
    s.spacecraft_count = u8::MAX;
    s.min_separation_pair = (u8::MAX, u8::MAX);
    s.info.status = pseudospectral::SolveStatus::NumericalFailure(pseudospectral::Stage::QpFactor);
    s.info.sqp_iterations = u16::MAX;
    s.info.qp_iterations = u32::MAX;
    s.info.verify_rounds = u8::MAX;
    s.info.verify_points_added = u16::MAX;
    s.info.keep_out_checks = u16::MAX;
    // A certificate listing every multiplier it can hold, each at its longest encoding.
    while s
        .certificate
        .multipliers
        .push(pseudospectral::Multiplier {
            constraint: pseudospectral::ActiveConstraint::KeepOut {
                pair: (u8::MAX, u8::MAX),
                time_tu: f64::MAX,
            },
            value: f64::MAX,
        })
        .is_ok()
    {}
    s
}

#[test]
fn worst_case_request_fits_the_stated_maximum() {
    let mut buf = vec![0u8; 4 * REQUEST_MAX_BYTES];
    for req in [worst_pseudospectral_request(), worst_impulsive_request()] {
        let body = postcard::to_allocvec(&req).unwrap().len();
        assert!(body <= REQUEST_BODY_MAX_BYTES, "body {body}");
        let n = encode_request(u64::MAX, &req, &mut buf).unwrap();
        assert!(n <= REQUEST_MAX_BYTES);
        assert_eq!(decode_request(&buf[..n]).unwrap().request, req);
    }
    // Planner A at capacity is the largest request (915 body bytes when this was written);
    // headroom stays for planner-B settings.
    let body = postcard::to_allocvec(&worst_pseudospectral_request())
        .unwrap()
        .len();
    println!("planner-A request body at capacity: {body} bytes");
    assert!(body + 64 <= REQUEST_BODY_MAX_BYTES, "{body}");
}

#[test]
fn worst_case_response_fits_the_stated_maximum() {
    let solution = worst_pseudospectral_solution();
    let mut buf = vec![0u8; 2 * RESPONSE_MAX_BYTES];
    let outcome = OutcomeRef::Pseudospectral(&solution);
    let n = encode_response(u64::MAX, u64::MAX, &outcome, &mut buf).unwrap();
    assert!(n <= RESPONSE_MAX_BYTES, "{n}");
    // 17 342 body bytes when this was written (with a full certificate); keep headroom for
    // solution fields.
    println!(
        "planner-A response body at capacity: {} bytes",
        n - RESPONSE_HEADER_BYTES - CRC_BYTES
    );
    assert!(n + 512 <= RESPONSE_MAX_BYTES, "{n}");
    let back = decode_response(&buf[..n]).unwrap();
    assert_eq!(back.seq, u64::MAX);
    assert_eq!(back.solve_time_ns, u64::MAX);
    assert_eq!(back.outcome, Outcome::Pseudospectral(solution.clone()));
    // The borrowed and the owned outcome encode to the same bytes.
    let owned = postcard::to_allocvec(&Outcome::Pseudospectral(solution)).unwrap();
    assert_eq!(owned, &buf[RESPONSE_HEADER_BYTES..n - CRC_BYTES]);

    let imp = impulsive::Solution::new();
    let n = encode_response(1, 2, &OutcomeRef::Impulsive(&imp), &mut buf).unwrap();
    assert!(n <= RESPONSE_MAX_BYTES);
    let worst_error = FrameError::BadCrc {
        computed: u32::MAX,
        received: u32::MAX,
    };
    let n = encode_response(1, 2, &OutcomeRef::BadRequest(worst_error), &mut buf).unwrap();
    assert!(n <= RESPONSE_MAX_BYTES);
}

#[test]
fn encoding_into_a_small_buffer_is_an_error() {
    let mut buf = [0u8; 100];
    assert_eq!(
        encode_request(1, &worst_pseudospectral_request(), &mut buf),
        Err(EncodeError::BufferTooSmall)
    );
    assert_eq!(
        encode_request(1, &worst_pseudospectral_request(), &mut [0u8; 3]),
        Err(EncodeError::BufferTooSmall)
    );
}

#[test]
fn each_request_fault_is_named() {
    let mut buf = vec![0u8; REQUEST_MAX_BYTES];
    let n = encode_request(7, &worst_impulsive_request(), &mut buf).unwrap();
    let good = buf[..n].to_vec();
    let err = |b: &[u8]| decode_request(b).unwrap_err();

    assert!(matches!(err(&good[..10]), FrameError::Truncated { .. }));
    assert!(matches!(err(&good[..n - 1]), FrameError::Truncated { .. }));
    let mut long = good.clone();
    long.push(0);
    assert!(matches!(err(&long), FrameError::TrailingBytes { .. }));
    assert!(matches!(
        err(&vec![0u8; REQUEST_MAX_BYTES + 1]),
        FrameError::Oversized { .. }
    ));
    let mut b = good.clone();
    b[2..4].copy_from_slice(&(PROTOCOL_VERSION + 1).to_le_bytes());
    assert_eq!(
        err(&b),
        FrameError::WrongVersion {
            got: PROTOCOL_VERSION + 1,
            expected: PROTOCOL_VERSION
        }
    );
    let mut b = good.clone();
    b[20] ^= 0x40;
    assert!(matches!(err(&b), FrameError::BadCrc { .. }));
    // A valid frame around a body that is not a Request.
    let mut b = vec![0u8; REQUEST_MAX_BYTES];
    let n = encode_request(7, &worst_impulsive_request(), &mut b).unwrap();
    b[REQUEST_HEADER_BYTES] = 9; // no such Request variant
    let crc = crc::Crc::<u32>::new(&crc::CRC_32_ISO_HDLC).checksum(&b[..n - CRC_BYTES]);
    b[n - CRC_BYTES..n].copy_from_slice(&crc.to_le_bytes());
    assert!(matches!(err(&b[..n]), FrameError::Malformed { .. }));
    assert_eq!(peek_request_seq(&b[..n]), Some(7));
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 2000, rng_seed: proptest::test_runner::RngSeed::Fixed(2026), ..ProptestConfig::default() })]

    #[test]
    fn decoding_any_bytes_never_panics(bytes in proptest::collection::vec(any::<u8>(), 0..2048)) {
        let _ = decode_request(&bytes);
        let _ = decode_response(&bytes);
        let _ = peek_request_seq(&bytes);
    }

    #[test]
    fn decoding_a_corrupted_frame_never_panics(
        flips in proptest::collection::vec((0usize..1024, any::<u8>()), 1..8),
        cut in 0usize..1100,
    ) {
        let mut buf = vec![0u8; REQUEST_MAX_BYTES];
        let n = encode_request(3, &worst_pseudospectral_request(), &mut buf).unwrap();
        buf.truncate(n);
        for (at, x) in flips {
            if let Some(b) = buf.get_mut(at % n) { *b ^= x; }
        }
        let _ = decode_request(&buf);
        let _ = decode_request(&buf[..cut.min(n)]);
    }

    #[test]
    fn frames_with_a_valid_crc_but_random_bodies_never_panic(
        body in proptest::collection::vec(any::<u8>(), 0..1000),
    ) {
        // Build a frame whose header and CRC are right, so the body reaches postcard.
        let mut f = Vec::new();
        f.extend_from_slice(&REQUEST_MAGIC);
        f.extend_from_slice(&PROTOCOL_VERSION.to_le_bytes());
        f.extend_from_slice(&5u64.to_le_bytes());
        f.extend_from_slice(&(body.len() as u32).to_le_bytes());
        f.extend_from_slice(&body);
        let crc = crc::Crc::<u32>::new(&crc::CRC_32_ISO_HDLC).checksum(&f);
        f.extend_from_slice(&crc.to_le_bytes());
        match decode_request(&f) {
            Ok(frame) => prop_assert_eq!(frame.seq, 5),
            Err(e) => {
                let malformed = matches!(e, FrameError::Malformed { .. });
                prop_assert!(malformed, "{:?}", e);
            }
        }
    }
}
