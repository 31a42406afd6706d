//! Why a frame is refused, or cannot be encoded.

use serde::{Deserialize, Serialize};

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
