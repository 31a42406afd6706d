//! Fixed-size wire types shared by the flight service, the feeder and the firmware.
//!
//! A frame is a fixed little-endian header, a postcard body and a CRC-32 trailer:
//!
//! ```text
//! request : magic "RQ" | version u16 | seq u64 | body_len u32                   | body | crc32
//! response: magic "RS" | version u16 | seq u64 | solve_time_ns u64 | body_len u32 | body | crc32
//! ```
//!
//! The CRC is CRC-32/ISO-HDLC (the zlib/Ethernet CRC) over everything before it. The body of a
//! request is a postcard [`Request`]; the body of a response is a postcard [`Outcome`]. Keeping
//! the sequence number and the service-measured solve time in the header leaves the body equal
//! to the bytes of the outcome alone, so two solves of one request can be compared byte for byte
//! (the harness's determinism check).
//!
//! Decoding checks, in order: size ([`FrameError::Oversized`], [`FrameError::Truncated`]),
//! magic, version, declared body length, CRC, then the body. Every failure is a [`FrameError`]
//! value naming what was wrong; no byte string makes a decode panic (proptested in `tests/`).
//! Nothing here allocates.
//!
//! Layout: `messages` holds what a frame carries (requests and outcomes), `error` why a frame
//! is refused, `frame` the encoding and decoding, `answer` the one request path every front end
//! answers a request through.

mod answer;
mod error;
mod frame;
mod messages;

pub use answer::{answer, AllPlanners, Buffers, Lent, Slot};
pub use error::{EncodeError, FrameError, MalformedKind};
pub use frame::{
    decode_request, decode_response, encode_outcome, encode_request, encode_response,
    peek_request_seq, view_response, RequestFrame, ResponseFrame, ResponseView,
};
pub use messages::{Expiry, Outcome, OutcomeRef, Rejection, Request};

/// Protocol version carried in every frame; a frame of another version is refused.
/// 2: planner A's solution carries its certificate, planner B's settings and solve info
/// changed, the GEO tour joined, and the `LimitExceeded` / `Expired` outcomes were added.
/// 3: planner B's settings gained `element_set` and its solution `terminal_error_equinoctial`;
///    planners A and B gained `work_budget`, `SolveInfo::work_units` and `BudgetExhausted`.
/// 4: planner A's certificate gained `flat_direction_probed`; planner-B requests in the user's
///    input forms (`Request::ImpulsiveForm`, answered by `Outcome::ImpulsiveForm` with the end
///    state in the same form), `PlanError::InputForm`, and the limits' form checks (`Rule::Below`).
/// 5: the LEO tour's arcs (`Request::LeoArc`, answered by `Outcome::LeoArc` or
///    `Outcome::LeoArcRejected`) and order (`Request::LeoSequence`, answered by
///    `Outcome::LeoSequence` or `Outcome::LeoSequenceRejected`), `Planner::LeoArc` and
///    `Planner::LeoSequence`, and their limits (`Setting::Leo*`).
/// 6: one contract and one request path (issue 29): every refused setting is named by its
///    planner's settings id with its value and range (`SettingError`) or limit; limits name
///    settings by id (`limits::Setting`); the LEO sequencing's request carries a
///    `SequenceProblem`; `Outcome::Unsupported` answers a request for a planner the front end
///    does not carry.
/// 7: no answer carries a NaN or an infinity: planner A's `min_separation_lu` is an `Option`
///    (absent with one spacecraft, where it was infinite).
/// 8: a planner's refusal of a setting names it by that planner's own settings id
///    (`SettingError<SettingId>`, no planner tag: the planner is the outcome's), so the planners
///    no longer depend on the request path's `limits::Setting`; the LEO sequencing refuses an
///    arc setting as `SequenceError::InvalidArcSetting`; the planner kinds are
///    `contract::PlannerKind` (same codes).
/// 9: the LEO sequencing's settings gained `full_plans` (orders ranked by each arc's full plan,
///    a ground design the built-in limits keep off; issue 31).
/// 10: the hybrid transfer joins (`Request::Hybrid`, `Outcome::Hybrid`, `Outcome::HybridRejected`,
///    `PlannerKind::Hybrid` = 5, `limits::Setting::Hybrid`; issue 30).
/// 11: planner A's certificate gained `symmetry_directions` (issue 28).
pub const PROTOCOL_VERSION: u16 = 11;
/// First two bytes of a request frame.
pub const REQUEST_MAGIC: [u8; 2] = *b"RQ";
/// First two bytes of a response frame.
pub const RESPONSE_MAGIC: [u8; 2] = *b"RS";
/// Bytes of the request header: magic, version, sequence number, body length.
pub const REQUEST_HEADER_BYTES: usize = 16;
/// Bytes of the response header: magic, version, sequence number, solve time, body length.
pub const RESPONSE_HEADER_BYTES: usize = 24;
/// Bytes of the CRC-32 trailer.
pub const CRC_BYTES: usize = 4;
/// Largest request frame, in bytes. A request body at capacity (8 spacecraft, every varint at
/// its longest) takes 915 bytes; the rest is headroom for planner-B settings.
pub const REQUEST_MAX_BYTES: usize = 1024;
/// Largest request body, in bytes.
pub const REQUEST_BODY_MAX_BYTES: usize = REQUEST_MAX_BYTES - REQUEST_HEADER_BYTES - CRC_BYTES;
/// Largest response frame, in bytes. A planner-A solution at capacity takes 17 558 body bytes
/// (16 241 before its optimality certificate, which lists up to 56 multipliers).
pub const RESPONSE_MAX_BYTES: usize = 18 * 1024;
/// Largest response body, in bytes.
pub const RESPONSE_BODY_MAX_BYTES: usize = RESPONSE_MAX_BYTES - RESPONSE_HEADER_BYTES - CRC_BYTES;

#[cfg(test)]
mod tests;
