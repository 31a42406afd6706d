//! Epochs written as text, parsed into the Julian dates the truth model runs on
//! ([`super::ephemeris::julian_date`]). One strict parser for both places an epoch is written:
//! a LEO tour fixture's `epoch` (UTC, [`parse_utc_jd`]) and `reconfig truth --epoch` (TT,
//! [`parse_tt_jd`]).
//!
//! Accepted: ISO 8601's extended calendar form with seconds, `YYYY-MM-DDTHH:MM:SS`, an optional
//! fraction of 1 to 9 digits (`.5`, `.250`, `.123456789`), then the zone: `Z` for UTC, nothing
//! for TT. Everything else is refused, by name: a date alone, minutes without seconds, the basic
//! form (`20221103T000000Z`), a lower-case `t` or `z`, spaces, signs, an offset (`+00:00`,
//! `-05:00`: a flight engineer writes the UTC time itself, so one form is compared and
//! logged), a UTC time without `Z` (it could be a local time), a `Z` on a TT time, and any field
//! out of its range (month 13, day 31 of April, hour 24, second 61). Second 60 is a UTC leap
//! second, accepted at 23:59 only (where UTC inserts them); TT has none. Years 1900..=2100: the
//! Sun and Moon series and the GMST polynomial are fitted near J2000, and a year outside is more
//! likely a typing error than a mission.
//!
//! No crate: the workspace has no date crate, and this subset is a few fixed-position fields;
//! a general ISO 8601 parser would accept forms (week dates, ordinal dates, offsets) that are
//! refused here.

use super::ephemeris::julian_date;
use std::fmt;

/// The form a UTC epoch is written in.
pub const UTC_FORMAT: &str = "YYYY-MM-DDTHH:MM:SS[.fff]Z";
/// The form a TT epoch is written in.
pub const TT_FORMAT: &str = "YYYY-MM-DDTHH:MM:SS[.fff]";

/// The years accepted (the ephemeris series' span, with room).
const YEARS: (i32, i32) = (1900, 2100);
/// `YYYY-MM-DDTHH:MM:SS`: the fixed-position part, bytes.
const FIXED_LEN: usize = 19;
/// Most fraction digits (nanoseconds; a Julian date in `f64` resolves ~40 us anyway).
const MAX_FRACTION_DIGITS: usize = 9;

/// The time scale an epoch is written in.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Scale {
    /// Coordinated Universal Time, marked `Z`.
    Utc,
    /// Terrestrial Time, unmarked.
    Tt,
}

impl Scale {
    fn format(self) -> &'static str {
        match self {
            Self::Utc => UTC_FORMAT,
            Self::Tt => TT_FORMAT,
        }
    }

    fn name(self) -> &'static str {
        match self {
            Self::Utc => "UTC",
            Self::Tt => "TT",
        }
    }
}

/// Why an epoch was refused. Its text follows the epoch as written:
/// `epoch = "yesterday" is not an ISO 8601 UTC time (expected YYYY-MM-DDTHH:MM:SS[.fff]Z)`.
#[derive(Clone, Debug, PartialEq)]
pub enum EpochError {
    /// Not of the accepted form.
    Form(Scale),
    /// A UTC time with no zone: it could be a local time.
    NoUtcMarker,
    /// A UTC time with a numeric offset (as written).
    Offset(String),
    /// A `Z` on a TT time.
    UtcMarkerOnTt,
    /// A field outside its range: its name, its value as written, the range.
    OutOfRange {
        field: &'static str,
        value: String,
        range: String,
    },
    /// Second 60 (a leap second) other than at 23:59, or on a TT time.
    LeapSecond(Scale),
}

impl fmt::Display for EpochError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::Form(s) => write!(
                f,
                "is not an ISO 8601 {} time (expected {})",
                s.name(),
                s.format()
            ),
            Self::NoUtcMarker => write!(
                f,
                "has no UTC marker (expected {UTC_FORMAT}: a time without `Z` could be local)"
            ),
            Self::Offset(o) => write!(
                f,
                "has the offset {o:?} (expected {UTC_FORMAT}: write the UTC time itself)"
            ),
            Self::UtcMarkerOnTt => write!(
                f,
                "ends in `Z` (UTC), but this epoch is TT (expected {TT_FORMAT})"
            ),
            Self::OutOfRange {
                field,
                value,
                range,
            } => write!(f, "has {field} {value} outside {range}"),
            Self::LeapSecond(Scale::Utc) => write!(
                f,
                "has second 60 (a leap second) other than at 23:59, where UTC inserts them"
            ),
            Self::LeapSecond(Scale::Tt) => write!(f, "has second 60, which TT does not have"),
        }
    }
}

impl std::error::Error for EpochError {}

/// The fields of an epoch, as numbers and (the second) as written.
struct Fields<'a> {
    year: i32,
    month: u32,
    day: u32,
    hour: u32,
    minute: u32,
    second: f64,
    second_text: &'a str,
}

/// Parse a UTC epoch (`YYYY-MM-DDTHH:MM:SS[.fff]Z`) into its Julian date, UTC.
///
/// # Errors
/// Another form, no `Z`, an offset, or a field out of its range ([`EpochError`]).
pub fn parse_utc_jd(text: &str) -> Result<f64, EpochError> {
    parse_jd(text, Scale::Utc)
}

/// Parse a TT epoch (`YYYY-MM-DDTHH:MM:SS[.fff]`, no zone) into its Julian date, TT.
///
/// # Errors
/// Another form, a `Z`, or a field out of its range ([`EpochError`]).
pub fn parse_tt_jd(text: &str) -> Result<f64, EpochError> {
    parse_jd(text, Scale::Tt)
}

fn parse_jd(text: &str, scale: Scale) -> Result<f64, EpochError> {
    let (fields, zone) = split(text).ok_or(EpochError::Form(scale))?;
    check_zone(zone, scale)?;
    check_ranges(&fields, scale)?;
    Ok(julian_date(
        fields.year,
        fields.month,
        fields.day,
        fields.hour,
        fields.minute,
        fields.second,
    ))
}

/// The fields and what follows them (the zone), or `None` when the text is not of the form.
fn split(text: &str) -> Option<(Fields<'_>, &str)> {
    // ASCII only, so every byte index below is a character boundary.
    if !text.is_ascii() || text.len() < FIXED_LEN {
        return None;
    }
    let b = text.as_bytes();
    let separators = [(4, b'-'), (7, b'-'), (10, b'T'), (13, b':'), (16, b':')];
    if separators.iter().any(|&(k, c)| b[k] != c) {
        return None;
    }
    let digits = |from: usize, to: usize| -> Option<u32> {
        let s = text.get(from..to)?;
        if !s.bytes().all(|c| c.is_ascii_digit()) {
            return None;
        }
        s.parse().ok()
    };
    let fraction_digits = b[FIXED_LEN..].first().filter(|&&c| c == b'.').map(|_| {
        b[FIXED_LEN + 1..]
            .iter()
            .take_while(|c| c.is_ascii_digit())
            .count()
    });
    let second_end = match fraction_digits {
        None => FIXED_LEN,
        Some(n) if (1..=MAX_FRACTION_DIGITS).contains(&n) => FIXED_LEN + 1 + n,
        Some(_) => return None,
    };
    digits(17, 19)?;
    let second_text = text.get(17..second_end)?;
    let fields = Fields {
        year: i32::try_from(digits(0, 4)?).ok()?,
        month: digits(5, 7)?,
        day: digits(8, 10)?,
        hour: digits(11, 13)?,
        minute: digits(14, 16)?,
        second: second_text.parse().ok()?,
        second_text,
    };
    Some((fields, text.get(second_end..)?))
}

/// The zone the scale wants: `Z` for UTC, none for TT.
fn check_zone(zone: &str, scale: Scale) -> Result<(), EpochError> {
    match (scale, zone) {
        (Scale::Utc, "Z") | (Scale::Tt, "") => Ok(()),
        (Scale::Utc, "") => Err(EpochError::NoUtcMarker),
        (Scale::Utc, o) if o.starts_with(['+', '-']) => Err(EpochError::Offset(o.to_owned())),
        (Scale::Tt, "Z") => Err(EpochError::UtcMarkerOnTt),
        _ => Err(EpochError::Form(scale)),
    }
}

/// Each field within its range (the day within its month's, leap years counted).
fn check_ranges(f: &Fields<'_>, scale: Scale) -> Result<(), EpochError> {
    let out = |field: &'static str, value: String, lo: u32, hi: u32| EpochError::OutOfRange {
        field,
        value,
        range: format!("[{lo}, {hi}]"),
    };
    if !(YEARS.0..=YEARS.1).contains(&f.year) {
        return Err(EpochError::OutOfRange {
            field: "year",
            value: f.year.to_string(),
            range: format!("[{}, {}]", YEARS.0, YEARS.1),
        });
    }
    // Each field's own range first, then the day against its month's length, so a time with
    // several errors names the plainest one.
    for (field, value, lo, hi) in [
        ("month", f.month, 1, 12),
        ("day", f.day, 1, 31),
        ("hour", f.hour, 0, 23),
        ("minute", f.minute, 0, 59),
    ] {
        if !(lo..=hi).contains(&value) {
            return Err(out(field, value.to_string(), lo, hi));
        }
    }
    check_second(f, scale)?;
    let days = days_in_month(f.year, f.month);
    if f.day > days {
        return Err(EpochError::OutOfRange {
            field: "day",
            value: f.day.to_string(),
            range: format!("[1, {days}] for {:04}-{:02}", f.year, f.month),
        });
    }
    Ok(())
}

/// Seconds in `[0, 60)`; `[60, 61)` is a leap second, UTC's only, at 23:59 only.
fn check_second(f: &Fields<'_>, scale: Scale) -> Result<(), EpochError> {
    if f.second < 60.0 {
        return Ok(());
    }
    if f.second >= 61.0 {
        return Err(EpochError::OutOfRange {
            field: "second",
            value: f.second_text.to_owned(),
            range: "[0, 60) (60.x only as a UTC leap second at 23:59)".to_owned(),
        });
    }
    // A leap second's Julian date is that of the next day's first second: a Julian date in UTC
    // cannot tell them apart, and the 1 s is far below what the truth model resolves in the
    // Sun's, Moon's and Earth's positions.
    if scale == Scale::Utc && f.hour == 23 && f.minute == 59 {
        Ok(())
    } else {
        Err(EpochError::LeapSecond(scale))
    }
}

fn days_in_month(year: i32, month: u32) -> u32 {
    let leap = (year % 4 == 0 && year % 100 != 0) || year % 400 == 0;
    match month {
        2 if leap => 29,
        2 => 28,
        4 | 6 | 9 | 11 => 30,
        _ => 31,
    }
}

#[cfg(test)]
#[allow(clippy::unwrap_used)]
mod tests {
    use super::*;

    fn utc_err(text: &str) -> String {
        parse_utc_jd(text).unwrap_err().to_string()
    }

    #[test]
    fn utc_epochs_of_the_accepted_form_parse_to_their_julian_date() {
        // J2000.0's calendar instant (JD 2451545.0), whole and with fractions of a second.
        assert_eq!(parse_utc_jd("2000-01-01T12:00:00Z").unwrap(), 2_451_545.0);
        assert_eq!(parse_utc_jd("2000-01-01T12:00:00.0Z").unwrap(), 2_451_545.0);
        assert_eq!(
            parse_utc_jd("2000-01-01T12:00:00.000000000Z").unwrap(),
            2_451_545.0
        );
        // The fixtures' epoch: JD 2459886.5.
        assert_eq!(parse_utc_jd("2022-11-03T00:00:00Z").unwrap(), 2_459_886.5);
        // Half a second is 0.5 / 86400 d (to the f64 resolution of a JD, ~40 us).
        let half = parse_utc_jd("2022-11-03T00:00:00.5Z").unwrap();
        assert!(
            ((half - 2_459_886.5) * 86_400.0 - 0.5).abs() < 1e-4,
            "{half}"
        );
        assert_eq!(
            parse_utc_jd("2022-11-03T06:30:15.250Z").unwrap(),
            julian_date(2022, 11, 3, 6, 30, 15.25)
        );
        // Leap days and a leap second at 23:59.
        assert!(parse_utc_jd("2024-02-29T00:00:00Z").is_ok());
        assert!(parse_utc_jd("2000-02-29T00:00:00Z").is_ok());
        assert!(parse_utc_jd("2016-12-31T23:59:60Z").is_ok());
        assert!(parse_utc_jd("2016-12-31T23:59:60.999Z").is_ok());
    }

    #[test]
    fn text_not_of_the_form_is_refused_with_the_form_expected() {
        let want = "is not an ISO 8601 UTC time (expected YYYY-MM-DDTHH:MM:SS[.fff]Z)";
        for bad in [
            "yesterday",
            "",
            "2022-11-03",
            "2022-11-03T00:00Z",
            "20221103T000000Z",
            "2022-11-03 00:00:00Z",
            "2022-11-03t00:00:00Z",
            "2022-11-03T00:00:00z",
            "2022-11-03T00:00:00.Z",
            "2022-11-03T00:00:00.1234567890Z",
            "2022-11-03T00:00:00,5Z",
            " 2022-11-03T00:00:00Z",
            "2022-11-03T00:00:00Z ",
            "2022-11-03T00:00:00ZZ",
            "+2022-11-03T00:00:00Z",
            "2022-1-03T00:00:00Z",
            "2022-11-03T0:00:00Z",
            "2022-11-03T00:00:+0Z",
            "2022-11-03T00:00:00\u{00b7}Z",
            "２022-11-03T00:00:00Z",
        ] {
            assert_eq!(utc_err(bad), want, "{bad:?}");
        }
    }

    #[test]
    fn a_utc_time_without_z_or_with_an_offset_is_refused() {
        let err = utc_err("2022-11-03T00:00:00");
        assert!(err.contains("no UTC marker"), "{err}");
        assert!(err.contains(UTC_FORMAT), "{err}");
        let err = utc_err("2022-11-03T00:00:00+00:00");
        assert!(err.contains("offset \"+00:00\""), "{err}");
        let err = utc_err("2022-11-03T00:00:00.5-05:00");
        assert!(err.contains("offset \"-05:00\""), "{err}");
    }

    #[test]
    fn fields_out_of_range_are_named() {
        for (bad, want) in [
            ("2022-13-03T00:00:00Z", "has month 13 outside [1, 12]"),
            ("2022-00-03T00:00:00Z", "has month 0 outside [1, 12]"),
            (
                "2022-11-31T00:00:00Z",
                "has day 31 outside [1, 30] for 2022-11",
            ),
            ("2022-11-00T00:00:00Z", "has day 0 outside [1, 31]"),
            ("2022-11-32T00:00:00Z", "has day 32 outside [1, 31]"),
            // The plainest error first: hour 25 before 30 February.
            ("2025-02-30T25:00:00Z", "has hour 25 outside [0, 23]"),
            (
                "2023-02-29T00:00:00Z",
                "has day 29 outside [1, 28] for 2023-02",
            ),
            (
                "1900-02-29T00:00:00Z",
                "has day 29 outside [1, 28] for 1900-02",
            ),
            ("2022-11-03T24:00:00Z", "has hour 24 outside [0, 23]"),
            ("2022-11-03T00:60:00Z", "has minute 60 outside [0, 59]"),
            ("2022-11-03T00:00:61Z", "has second 61 outside [0, 60)"),
            ("2022-11-03T00:00:99.5Z", "has second 99.5 outside [0, 60)"),
            (
                "2022-11-03T12:00:60Z",
                "has second 60 (a leap second) other than at 23:59",
            ),
            ("1899-12-31T00:00:00Z", "has year 1899 outside [1900, 2100]"),
            ("2101-01-01T00:00:00Z", "has year 2101 outside [1900, 2100]"),
        ] {
            let err = utc_err(bad);
            assert!(err.starts_with(want), "{bad}: {err}");
        }
    }

    #[test]
    fn tt_epochs_take_no_zone_and_no_leap_second() {
        assert_eq!(parse_tt_jd("2000-01-01T12:00:00").unwrap(), 2_451_545.0);
        let half = parse_tt_jd("2000-01-01T12:00:00.5").unwrap();
        assert!(
            ((half - 2_451_545.0) * 86_400.0 - 0.5).abs() < 1e-4,
            "{half}"
        );
        let err = parse_tt_jd("2000-01-01T12:00:00Z").unwrap_err().to_string();
        assert!(
            err.contains("this epoch is TT (expected YYYY-MM-DDTHH:MM:SS[.fff])"),
            "{err}"
        );
        let err = parse_tt_jd("2016-12-31T23:59:60").unwrap_err().to_string();
        assert!(err.contains("which TT does not have"), "{err}");
        let err = parse_tt_jd("tomorrow").unwrap_err().to_string();
        assert_eq!(
            err,
            "is not an ISO 8601 TT time (expected YYYY-MM-DDTHH:MM:SS[.fff])"
        );
    }
}
