//! Frames: the fixed header, the postcard body and the CRC-32 trailer, encoded into and decoded
//! from caller buffers.

use super::*;
use serde::{Deserialize, Serialize};

const CRC32: crc::Crc<u32> = crc::Crc::<u32>::new(&crc::CRC_32_ISO_HDLC);

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
