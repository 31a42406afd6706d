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

use crate::{geo_tour, impulsive, pseudospectral};
use serde::{Deserialize, Serialize};

/// Protocol version carried in every frame; a frame of another version is refused.
/// 2: planner A's solution carries its certificate, planner B's settings and solve info
/// changed, the GEO tour joined, and the `LimitExceeded` / `Expired` outcomes were added.
/// 3: planner B's settings gained `element_set` and its solution `terminal_error_equinoctial`;
///    planners A and B gained `work_budget`, `SolveInfo::work_units` and `BudgetExhausted`.
/// 4: planner A's certificate gained `flat_direction_probed`; planner-B requests in the user's
///    input forms (`Request::ImpulsiveForm`, answered by `Outcome::ImpulsiveForm` with the end
///    state in the same form), `PlanError::InputForm`, and the limits' form checks (`Rule::Below`).
pub const PROTOCOL_VERSION: u16 = 4;
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
/// Largest response frame, in bytes. A planner-A solution at capacity takes 17 345 body bytes
/// (16 241 before its optimality certificate, which lists up to 56 multipliers).
pub const RESPONSE_MAX_BYTES: usize = 18 * 1024;
/// Largest response body, in bytes.
pub const RESPONSE_BODY_MAX_BYTES: usize = RESPONSE_MAX_BYTES - RESPONSE_HEADER_BYTES - CRC_BYTES;

const CRC32: crc::Crc<u32> = crc::Crc::<u32>::new(&crc::CRC_32_ISO_HDLC);

/// A planning request for either planner.
// No heap in the core: the variants stay inline, sized by the capacities.
#[allow(clippy::large_enum_variant)]
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub enum Request {
    /// Planner A.
    Pseudospectral {
        /// The problem.
        problem: pseudospectral::Problem,
        /// Loop bounds and tolerances.
        settings: pseudospectral::Settings,
    },
    /// Planner B.
    Impulsive {
        /// The problem.
        problem: impulsive::Problem,
        /// Loop bounds and tolerances.
        settings: impulsive::Settings,
    },
    /// The GEO servicing tour.
    GeoTour {
        /// The problem.
        problem: geo_tour::Problem,
        /// Loop bounds, tolerances and the paper's rule.
        settings: geo_tour::Settings,
    },
    /// Planner B with its orbits in the forms the user gave (equinoctial elements, osculating
    /// ECI states, ROE, the deputy's own orbits), converted in the service by the core's
    /// `impulsive::forms`.
    ImpulsiveForm {
        /// The problem, in the user's forms.
        problem: impulsive::FormProblem,
        /// Loop bounds and tolerances.
        settings: impulsive::Settings,
    },
}

impl Request {
    /// Which planner the request is for.
    pub fn planner(&self) -> Planner {
        match self {
            Self::Pseudospectral { .. } => Planner::Pseudospectral,
            Self::Impulsive { .. } | Self::ImpulsiveForm { .. } => Planner::Impulsive,
            Self::GeoTour { .. } => Planner::GeoTour,
        }
    }
}

/// The planners.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash, Serialize, Deserialize)]
#[repr(u8)]
pub enum Planner {
    /// Planner A.
    Pseudospectral = 0,
    /// Planner B.
    Impulsive = 1,
    /// The GEO servicing tour.
    GeoTour = 2,
}

/// What the service answers to one request.
// No heap in the core: the solution stays inline (about 16 KB at capacity).
#[allow(clippy::large_enum_variant)]
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub enum Outcome {
    /// Planner A iterated; the solution's `info.status` says how it ended.
    Pseudospectral(pseudospectral::Solution),
    /// Planner A rejected the request before iterating.
    PseudospectralRejected(pseudospectral::PlanError),
    /// Planner B iterated; the solution's `info.status` says how it ended.
    Impulsive(impulsive::Solution),
    /// Planner B rejected the request before iterating.
    ImpulsiveRejected(impulsive::PlanError),
    /// The request frame could not be decoded; says what was wrong.
    BadRequest(FrameError),
    /// The request asks for more work or less safety than the service's limits allow; nothing
    /// was solved (see [`crate::limits`]).
    LimitExceeded(crate::limits::LimitViolation),
    /// The request waited in the service's queue past its deadline; nothing was solved.
    Expired(Expiry),
    /// The GEO tour planned; the solution's `info.status` says how it ended.
    GeoTour(geo_tour::Solution),
    /// The GEO tour rejected the request.
    GeoTourRejected(geo_tour::PlanError),
    /// Planner B iterated on a [`Request::ImpulsiveForm`]; the solution's `info.status` says how
    /// it ended, the end state is in the form the request gave its target in. (A rejection is
    /// [`Outcome::ImpulsiveRejected`].)
    ImpulsiveForm {
        /// The plan.
        solution: impulsive::Solution,
        /// The plan's end state in the user's form.
        end_state: impulsive::EndState,
    },
}

/// How long an expired request waited and the deadline it had, in microseconds.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub struct Expiry {
    /// Time from the service's receipt of the request to its answer, us.
    pub queued_us: u64,
    /// The request's deadline, counted from its receipt, us.
    pub deadline_us: u64,
}

/// A borrowed [`Outcome`]: encodes to the same bytes without copying a solution.
#[derive(Clone, Copy, Debug, Serialize)]
pub enum OutcomeRef<'a> {
    /// See [`Outcome::Pseudospectral`].
    Pseudospectral(&'a pseudospectral::Solution),
    /// See [`Outcome::PseudospectralRejected`].
    PseudospectralRejected(pseudospectral::PlanError),
    /// See [`Outcome::Impulsive`].
    Impulsive(&'a impulsive::Solution),
    /// See [`Outcome::ImpulsiveRejected`].
    ImpulsiveRejected(impulsive::PlanError),
    /// See [`Outcome::BadRequest`].
    BadRequest(FrameError),
    /// See [`Outcome::LimitExceeded`].
    LimitExceeded(crate::limits::LimitViolation),
    /// See [`Outcome::Expired`].
    Expired(Expiry),
    /// See [`Outcome::GeoTour`].
    GeoTour(&'a geo_tour::Solution),
    /// See [`Outcome::GeoTourRejected`].
    GeoTourRejected(geo_tour::PlanError),
    /// See [`Outcome::ImpulsiveForm`].
    ImpulsiveForm {
        /// The plan.
        solution: &'a impulsive::Solution,
        /// The plan's end state in the user's form.
        end_state: impulsive::EndState,
    },
}

/// Why a frame was refused. Sizes in bytes.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[repr(u8)]
pub enum FrameError {
    /// Shorter than its header and trailer, or than its declared body.
    Truncated {
        /// Bytes the frame needs.
        needed: u32,
        /// Bytes received.
        got: u32,
    } = 0,
    /// Longer than the largest frame of its kind, or declares a longer body.
    Oversized {
        /// Bytes received or declared.
        len: u32,
        /// Largest accepted.
        max: u32,
    } = 1,
    /// Does not start with the frame magic.
    BadMagic {
        /// The first two bytes.
        got: [u8; 2],
    } = 2,
    /// Another protocol version.
    WrongVersion {
        /// Version in the frame.
        got: u16,
        /// Version this build speaks.
        expected: u16,
    } = 3,
    /// Bytes after the declared body and CRC.
    TrailingBytes {
        /// Bytes the declared body length implies.
        declared: u32,
        /// Bytes received.
        got: u32,
    } = 4,
    /// The CRC-32 trailer does not match the frame.
    BadCrc {
        /// CRC computed over the frame.
        computed: u32,
        /// CRC in the trailer.
        received: u32,
    } = 5,
    /// The body is not a valid postcard encoding of the expected type.
    Malformed {
        /// Which postcard failure.
        kind: MalformedKind,
    } = 6,
}

/// Classes of postcard decode failure.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[repr(u8)]
pub enum MalformedKind {
    /// The body ended early.
    UnexpectedEnd = 0,
    /// An enum discriminant is out of range.
    BadEnum = 1,
    /// A variable-length integer is bad or out of range.
    BadInteger = 2,
    /// A bool, char, string or option tag is bad.
    BadValue = 3,
    /// A sequence is longer than its fixed capacity, or another shape error.
    BadShape = 4,
    /// Bytes left over after the body.
    TrailingBytes = 5,
}

/// Why a frame could not be encoded.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum EncodeError {
    /// The output buffer is too small, or the body exceeds the frame's maximum.
    BufferTooSmall,
}

impl core::fmt::Display for FrameError {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        match self {
            Self::Truncated { needed, got } => {
                write!(f, "truncated frame: {got} bytes, needs {needed}")
            }
            Self::Oversized { len, max } => write!(f, "oversized frame: {len} bytes, max {max}"),
            Self::BadMagic { got } => write!(f, "bad magic {got:02x?}"),
            Self::WrongVersion { got, expected } => {
                write!(f, "wrong protocol version {got}, expected {expected}")
            }
            Self::TrailingBytes { declared, got } => {
                write!(f, "{got} bytes where the header declares {declared}")
            }
            Self::BadCrc { computed, received } => {
                write!(
                    f,
                    "bad CRC: computed {computed:08x}, received {received:08x}"
                )
            }
            Self::Malformed { kind } => write!(f, "malformed body: {kind:?}"),
        }
    }
}

/// A decoded request frame.
#[derive(Clone, Debug, PartialEq)]
pub struct RequestFrame {
    /// The feeder's sequence number.
    pub seq: u64,
    /// The request.
    pub request: Request,
}

/// A decoded response frame.
#[derive(Clone, Debug, PartialEq)]
pub struct ResponseFrame {
    /// Sequence number of the request answered (0 when the request's header was unreadable).
    pub seq: u64,
    /// The solve's own time measured by the service, ns (0 when nothing was solved).
    pub solve_time_ns: u64,
    /// The answer.
    pub outcome: Outcome,
}

/// A response frame whose header and CRC are valid, with its body still encoded.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct ResponseView<'a> {
    /// See [`ResponseFrame::seq`].
    pub seq: u64,
    /// See [`ResponseFrame::solve_time_ns`].
    pub solve_time_ns: u64,
    /// The postcard bytes of the [`Outcome`].
    pub body: &'a [u8],
}

fn to_u32(n: usize) -> u32 {
    u32::try_from(n).unwrap_or(u32::MAX)
}

fn put(out: &mut [u8], at: usize, bytes: &[u8]) -> Result<(), EncodeError> {
    let end = at
        .checked_add(bytes.len())
        .ok_or(EncodeError::BufferTooSmall)?;
    out.get_mut(at..end)
        .ok_or(EncodeError::BufferTooSmall)?
        .copy_from_slice(bytes);
    Ok(())
}

fn get<const N: usize>(bytes: &[u8], at: usize) -> Option<[u8; N]> {
    let end = at.checked_add(N)?;
    bytes.get(at..end)?.try_into().ok()
}

/// Encode the body after `header` bytes, then write the length field at `len_at` and the CRC.
fn finish_frame<T: Serialize>(
    value: &T,
    out: &mut [u8],
    header: usize,
    len_at: usize,
    max_frame: usize,
) -> Result<usize, EncodeError> {
    let limit = out.len().min(max_frame);
    let room = limit
        .checked_sub(header)
        .and_then(|n| n.checked_sub(CRC_BYTES))
        .ok_or(EncodeError::BufferTooSmall)?;
    let body_end = header
        .checked_add(room)
        .ok_or(EncodeError::BufferTooSmall)?;
    let body_buf = out
        .get_mut(header..body_end)
        .ok_or(EncodeError::BufferTooSmall)?;
    let body_len = postcard::to_slice(value, body_buf)
        .map_err(|_| EncodeError::BufferTooSmall)?
        .len();
    put(out, len_at, &to_u32(body_len).to_le_bytes())?;
    let crc_at = header
        .checked_add(body_len)
        .ok_or(EncodeError::BufferTooSmall)?;
    let crc = CRC32.checksum(out.get(..crc_at).ok_or(EncodeError::BufferTooSmall)?);
    put(out, crc_at, &crc.to_le_bytes())?;
    crc_at
        .checked_add(CRC_BYTES)
        .ok_or(EncodeError::BufferTooSmall)
}

/// Encode a request frame into `out`; returns the frame length.
///
/// # Errors
/// [`EncodeError::BufferTooSmall`] when `out` cannot hold the frame or the body exceeds
/// [`REQUEST_BODY_MAX_BYTES`].
pub fn encode_request(seq: u64, request: &Request, out: &mut [u8]) -> Result<usize, EncodeError> {
    put(out, 0, &REQUEST_MAGIC)?;
    put(out, 2, &PROTOCOL_VERSION.to_le_bytes())?;
    put(out, 4, &seq.to_le_bytes())?;
    finish_frame(request, out, REQUEST_HEADER_BYTES, 12, REQUEST_MAX_BYTES)
}

/// Encode a response frame into `out`; returns the frame length.
///
/// # Errors
/// [`EncodeError::BufferTooSmall`] when `out` cannot hold the frame or the body exceeds
/// [`RESPONSE_BODY_MAX_BYTES`].
pub fn encode_response(
    seq: u64,
    solve_time_ns: u64,
    outcome: &OutcomeRef<'_>,
    out: &mut [u8],
) -> Result<usize, EncodeError> {
    put(out, 0, &RESPONSE_MAGIC)?;
    put(out, 2, &PROTOCOL_VERSION.to_le_bytes())?;
    put(out, 4, &seq.to_le_bytes())?;
    put(out, 12, &solve_time_ns.to_le_bytes())?;
    finish_frame(outcome, out, RESPONSE_HEADER_BYTES, 20, RESPONSE_MAX_BYTES)
}

/// Check size, magic, version, length and CRC of a frame; returns the body.
fn check_frame(
    bytes: &[u8],
    magic: [u8; 2],
    header: usize,
    len_at: usize,
    max_frame: usize,
) -> Result<&[u8], FrameError> {
    let got = to_u32(bytes.len());
    if bytes.len() > max_frame {
        return Err(FrameError::Oversized {
            len: got,
            max: to_u32(max_frame),
        });
    }
    let min = header.saturating_add(CRC_BYTES);
    let truncated = FrameError::Truncated {
        needed: to_u32(min),
        got,
    };
    let got_magic: [u8; 2] = get(bytes, 0).ok_or(truncated)?;
    if got_magic != magic {
        return Err(FrameError::BadMagic { got: got_magic });
    }
    let version = u16::from_le_bytes(get(bytes, 2).ok_or(truncated)?);
    if version != PROTOCOL_VERSION {
        return Err(FrameError::WrongVersion {
            got: version,
            expected: PROTOCOL_VERSION,
        });
    }
    if bytes.len() < min {
        return Err(truncated);
    }
    let body_len = u32::from_le_bytes(get(bytes, len_at).ok_or(truncated)?);
    let body_max = max_frame.saturating_sub(min);
    let body_len_usize = usize::try_from(body_len).unwrap_or(usize::MAX);
    if body_len_usize > body_max {
        return Err(FrameError::Oversized {
            len: body_len,
            max: to_u32(body_max),
        });
    }
    // body_len <= body_max, so this cannot overflow.
    let declared = min.saturating_add(body_len_usize);
    if bytes.len() < declared {
        return Err(FrameError::Truncated {
            needed: to_u32(declared),
            got,
        });
    }
    if bytes.len() > declared {
        return Err(FrameError::TrailingBytes {
            declared: to_u32(declared),
            got,
        });
    }
    let crc_at = header.saturating_add(body_len_usize);
    let covered = bytes.get(..crc_at).ok_or(truncated)?;
    let received = u32::from_le_bytes(get(bytes, crc_at).ok_or(truncated)?);
    let computed = CRC32.checksum(covered);
    if computed != received {
        return Err(FrameError::BadCrc { computed, received });
    }
    covered.get(header..).ok_or(truncated)
}

fn malformed(e: postcard::Error) -> FrameError {
    use postcard::Error as E;
    let kind = match e {
        E::DeserializeUnexpectedEnd => MalformedKind::UnexpectedEnd,
        E::DeserializeBadEnum => MalformedKind::BadEnum,
        E::DeserializeBadVarint => MalformedKind::BadInteger,
        E::DeserializeBadBool
        | E::DeserializeBadChar
        | E::DeserializeBadUtf8
        | E::DeserializeBadOption => MalformedKind::BadValue,
        _ => MalformedKind::BadShape,
    };
    FrameError::Malformed { kind }
}

fn decode_body<'a, T: Deserialize<'a>>(body: &'a [u8]) -> Result<T, FrameError> {
    let (value, rest) = postcard::take_from_bytes::<T>(body).map_err(malformed)?;
    if rest.is_empty() {
        Ok(value)
    } else {
        Err(FrameError::Malformed {
            kind: MalformedKind::TrailingBytes,
        })
    }
}

/// The sequence number in a request header, when the magic and version are right and the
/// header is complete (used to address an error response to an undecodable request).
pub fn peek_request_seq(bytes: &[u8]) -> Option<u64> {
    let magic: [u8; 2] = get(bytes, 0)?;
    let version = u16::from_le_bytes(get(bytes, 2)?);
    if magic != REQUEST_MAGIC || version != PROTOCOL_VERSION {
        return None;
    }
    Some(u64::from_le_bytes(get(bytes, 4)?))
}

/// Decode a request frame.
///
/// # Errors
/// A [`FrameError`] naming the first check that failed.
pub fn decode_request(bytes: &[u8]) -> Result<RequestFrame, FrameError> {
    let body = check_frame(
        bytes,
        REQUEST_MAGIC,
        REQUEST_HEADER_BYTES,
        12,
        REQUEST_MAX_BYTES,
    )?;
    let seq = u64::from_le_bytes(get(bytes, 4).ok_or(FrameError::Truncated {
        needed: 12,
        got: to_u32(bytes.len()),
    })?);
    Ok(RequestFrame {
        seq,
        request: decode_body(body)?,
    })
}

/// Check a response frame's header and CRC without decoding its body.
///
/// # Errors
/// A [`FrameError`] naming the first check that failed.
pub fn view_response(bytes: &[u8]) -> Result<ResponseView<'_>, FrameError> {
    let body = check_frame(
        bytes,
        RESPONSE_MAGIC,
        RESPONSE_HEADER_BYTES,
        20,
        RESPONSE_MAX_BYTES,
    )?;
    let short = FrameError::Truncated {
        needed: to_u32(RESPONSE_HEADER_BYTES),
        got: to_u32(bytes.len()),
    };
    Ok(ResponseView {
        seq: u64::from_le_bytes(get(bytes, 4).ok_or(short)?),
        solve_time_ns: u64::from_le_bytes(get(bytes, 12).ok_or(short)?),
        body,
    })
}

/// Decode a response frame.
///
/// # Errors
/// A [`FrameError`] naming the first check that failed.
pub fn decode_response(bytes: &[u8]) -> Result<ResponseFrame, FrameError> {
    let view = view_response(bytes)?;
    Ok(ResponseFrame {
        seq: view.seq,
        solve_time_ns: view.solve_time_ns,
        outcome: decode_body(view.body)?,
    })
}

/// Encode an outcome's body alone (the bytes [`ResponseView::body`] holds), for comparing two
/// answers to one request; returns the length.
///
/// # Errors
/// [`EncodeError::BufferTooSmall`] when `out` cannot hold it.
pub fn encode_outcome(outcome: &OutcomeRef<'_>, out: &mut [u8]) -> Result<usize, EncodeError> {
    postcard::to_slice(outcome, out)
        .map(|b| b.len())
        .map_err(|_| EncodeError::BufferTooSmall)
}

impl Outcome {
    /// Borrow as an [`OutcomeRef`] (same encoding).
    pub fn as_ref(&self) -> OutcomeRef<'_> {
        match self {
            Self::Pseudospectral(s) => OutcomeRef::Pseudospectral(s),
            Self::PseudospectralRejected(e) => OutcomeRef::PseudospectralRejected(*e),
            Self::Impulsive(s) => OutcomeRef::Impulsive(s),
            Self::ImpulsiveRejected(e) => OutcomeRef::ImpulsiveRejected(*e),
            Self::BadRequest(e) => OutcomeRef::BadRequest(*e),
            Self::LimitExceeded(v) => OutcomeRef::LimitExceeded(*v),
            Self::Expired(x) => OutcomeRef::Expired(*x),
            Self::GeoTour(s) => OutcomeRef::GeoTour(s),
            Self::GeoTourRejected(e) => OutcomeRef::GeoTourRejected(*e),
            Self::ImpulsiveForm {
                solution,
                end_state,
            } => OutcomeRef::ImpulsiveForm {
                solution,
                end_state: *end_state,
            },
        }
    }
}

#[cfg(test)]
#[allow(clippy::unwrap_used, clippy::indexing_slicing, clippy::expect_used)]
mod tests {
    use super::*;

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
        let mut bad = buf;
        bad[2] = 9;
        assert!(matches!(
            decode_request(&bad[..n]),
            Err(FrameError::WrongVersion { got: 9, .. })
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
            CartesianState, EndState, EquinoctialElements, FormProblem, OrbitForm, RelativeForm,
            Roe,
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
                assert_eq!(frame.request.planner(), Planner::Impulsive);
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
}
