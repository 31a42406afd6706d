//! Fault injection: request frames that are wrong on the wire, and well-formed requests whose
//! problems are invalid. Each must come back as an error response naming what was wrong.

use super::feeder::{Item, Payload};
use crate::scenario;
use reconfig_core::contract::PlannerKind;
use reconfig_core::wire::{self, Request, CRC_BYTES, REQUEST_HEADER_BYTES};
use reconfig_core::{impulsive, pseudospectral};

fn valid_frame(seq: u64) -> Vec<u8> {
    crossing_frame(seq, 3)
}

/// The frame of a planner-A crossing of `spacecraft` spacecraft (N = 10, seeded by `seq`).
fn crossing_frame(seq: u64, spacecraft: usize) -> Vec<u8> {
    let mut rng = <rand_chacha::ChaCha8Rng as rand::SeedableRng>::seed_from_u64(seq);
    let request = Request::Pseudospectral {
        problem: scenario::crossing(&mut rng, spacecraft, 10),
        settings: pseudospectral::Settings::default(),
    };
    let mut buf = vec![0u8; wire::REQUEST_MAX_BYTES];
    let n = wire::encode_request(seq, &request, &mut buf).unwrap_or(0);
    buf.truncate(n);
    buf
}

fn recrc(frame: &mut [u8]) {
    let n = frame.len() - CRC_BYTES;
    let crc = crc::Crc::<u32>::new(&crc::CRC_32_ISO_HDLC).checksum(&frame[..n]);
    frame[n..].copy_from_slice(&crc.to_le_bytes());
}

fn raw(label: &str, bytes: Vec<u8>) -> Item {
    Item {
        label: label.into(),
        planner: None,
        size: "fault".into(),
        payload: Payload::Raw(bytes),
    }
}

fn request(label: &str, request: Request) -> Item {
    Item {
        label: label.into(),
        planner: Some(request.planner()),
        size: "invalid".into(),
        payload: Payload::Request(Box::new(request)),
    }
}

/// A frame that is valid except that its spacecraft count says 9, one more than the capacity
/// (a `Request` cannot hold that, so it is built by hand; a ninth spacecraft's 104 bytes would
/// also make the frame longer than `REQUEST_MAX_BYTES`, so the count alone is raised). Body
/// layout: variant (1), three f64 (24), degree varint (1 for N = 10), test_points (1), then the
/// spacecraft count.
fn nine_spacecraft(seq: u64) -> Vec<u8> {
    let mut buf = crossing_frame(seq, 8);
    let count_at = REQUEST_HEADER_BYTES + 27;
    if buf.get(count_at) != Some(&8) {
        return buf;
    }
    buf[count_at] = 9;
    recrc(&mut buf);
    buf
}

/// The fault set: six wire faults and four invalid problems. Labels say what each is.
pub fn items(first_seq: u64) -> Vec<Item> {
    let mut out = Vec::new();
    // Malformed: header and CRC right, body not a Request (an unknown variant).
    let mut f = valid_frame(first_seq);
    f[REQUEST_HEADER_BYTES] = 0x7f;
    recrc(&mut f);
    out.push(raw("fault: malformed body", f));
    // Truncated: the last 10 bytes cut off.
    let mut f = valid_frame(first_seq + 1);
    f.truncate(f.len() - 10);
    out.push(raw("fault: truncated", f));
    // Oversized: longer than the largest request frame.
    let mut f = valid_frame(first_seq + 2);
    f.resize(wire::REQUEST_MAX_BYTES + 100, 0xAA);
    out.push(raw("fault: oversized", f));
    // Wrong version.
    let mut f = valid_frame(first_seq + 3);
    f[2..4].copy_from_slice(&(wire::PROTOCOL_VERSION + 1).to_le_bytes());
    recrc(&mut f);
    out.push(raw("fault: wrong version", f));
    // Wrong CRC.
    let mut f = valid_frame(first_seq + 4);
    let last = f.len() - 1;
    f[last] ^= 0x5a;
    out.push(raw("fault: wrong CRC", f));

    out.push(raw(
        "fault: spacecraft count 9 (over capacity)",
        nine_spacecraft(first_seq + 5),
    ));

    let mut rng = <rand_chacha::ChaCha8Rng as rand::SeedableRng>::seed_from_u64(first_seq);
    let settings = pseudospectral::Settings::default();
    let mut p = scenario::crossing(&mut rng, 3, 10);
    p.horizon_tu = f64::NAN;
    out.push(request(
        "invalid: NaN horizon",
        Request::Pseudospectral {
            problem: p,
            settings,
        },
    ));
    let mut p = scenario::crossing(&mut rng, 3, 10);
    p.degree = 200;
    out.push(request(
        "invalid: degree over capacity",
        Request::Pseudospectral {
            problem: p,
            settings,
        },
    ));
    // Infeasible: a 1000 LU move in T = 10 at Umax = 1 is beyond bang-bang reach (25 LU).
    let mut p = scenario::crossing(&mut rng, 2, 10);
    if let Some(c) = p.spacecraft.get_mut(0) {
        c.final_state[0] += 1000.0;
    }
    out.push(request(
        "invalid: manoeuvre infeasible",
        Request::Pseudospectral {
            problem: p,
            settings,
        },
    ));
    let mut p = scenario::wang2018_published();
    p.chief.ecc = f64::NAN;
    out.push(request(
        "invalid: NaN eccentricity (planner B)",
        Request::Impulsive {
            problem: p,
            settings: impulsive::Settings::default(),
        },
    ));
    let _ = PlannerKind::Pseudospectral;
    out
}
