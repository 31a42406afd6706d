//! Time, Earth rotation and low-precision Sun and Moon positions (Montenbruck & Gill,
//! *Satellite Orbits*, 2000, sections 3.3.2 and 5.2; the Sun to about 0.1 %, the Moon to a few
//! arcminutes, which is ample for their tidal accelerations: 1 % of a 1e-6 m/s^2 term).
//!
//! Frames: the inertial frame is the mean equator and equinox of date, frozen over a plan
//! (precession over a day is 0.14 arcsec); the Earth-fixed frame is it turned by the Greenwich
//! mean sidereal time about z (polar motion, nutation and UT1 - TT neglected: they move the
//! tesseral field by < 1 arcsec and the Earth's phase by ~ 70 s of rotation, a fixed offset of
//! the epoch's longitude, which is an input anyway).

use std::f64::consts::TAU;

/// Julian date of J2000.0 (2000-01-01 12:00 TT).
pub const JD_J2000: f64 = 2_451_545.0;
/// Seconds in a day.
pub const DAY_S: f64 = 86_400.0;
/// Days in a Julian century.
const JULIAN_CENTURY_DAYS: f64 = 36_525.0;
/// Obliquity of the ecliptic at J2000, rad (23.43929111 deg).
const OBLIQUITY_RAD: f64 = 23.439_291_11 * std::f64::consts::PI / 180.0;
/// General precession in longitude, rad per Julian century (1.3972 deg).
const PRECESSION_RAD_PER_CENTURY: f64 = 1.3972 * std::f64::consts::PI / 180.0;
/// Arcseconds to radians.
const ARCSEC_RAD: f64 = std::f64::consts::PI / (180.0 * 3600.0);
/// Degrees to radians.
const DEG_RAD: f64 = std::f64::consts::PI / 180.0;

/// Julian date (TT) of a calendar date and time (proleptic Gregorian, Meeus's algorithm 7.1).
pub fn julian_date(year: i32, month: u32, day: u32, hour: u32, minute: u32, second: f64) -> f64 {
    let (y, m) = if month <= 2 {
        (year - 1, month + 12)
    } else {
        (year, month)
    };
    let a = y.div_euclid(100);
    let b = 2 - a + a.div_euclid(4);
    (365.25 * f64::from(y + 4716)).floor()
        + (30.6001 * f64::from(m + 1)).floor()
        + f64::from(day)
        + f64::from(b)
        - 1524.5
        + (f64::from(hour) + f64::from(minute) / 60.0 + second / 3600.0) / 24.0
}

/// Julian centuries since J2000 of the Julian date `jd`.
fn centuries(jd: f64) -> f64 {
    (jd - JD_J2000) / JULIAN_CENTURY_DAYS
}

/// Greenwich mean sidereal time, rad in `[0, 2 pi)` (IAU 1982, Aoki et al., with UT1 = TT).
pub fn gmst_rad(jd: f64) -> f64 {
    let d = jd - JD_J2000;
    let t = d / JULIAN_CENTURY_DAYS;
    let deg =
        280.460_618_37 + 360.985_647_366_29 * d + 0.000_387_933 * t * t - t * t * t / 38_710_000.0;
    (deg * DEG_RAD).rem_euclid(TAU)
}

/// Ecliptic-of-date spherical coordinates to the inertial (equator of date) frame, km.
fn equatorial(r_km: f64, lon_rad: f64, lat_rad: f64) -> [f64; 3] {
    let (x, y, z) = (
        r_km * lon_rad.cos() * lat_rad.cos(),
        r_km * lon_rad.sin() * lat_rad.cos(),
        r_km * lat_rad.sin(),
    );
    let (se, ce) = OBLIQUITY_RAD.sin_cos();
    [x, ce * y - se * z, se * y + ce * z]
}

/// Geocentric position of the Sun, km, inertial frame of date (M&G eq. 3.43-3.45, with the
/// precession term that refers the longitude to the equinox of date).
pub fn sun_position_km(jd: f64) -> [f64; 3] {
    let t = centuries(jd);
    let m = (357.525_6 + 35_999.049 * t) * DEG_RAD;
    let lon = 282.94 * DEG_RAD
        + m
        + (6_892.0 * m.sin() + 72.0 * (2.0 * m).sin()) * ARCSEC_RAD
        + PRECESSION_RAD_PER_CENTURY * t;
    let r_km = (149.619 - 2.499 * m.cos() - 0.021 * (2.0 * m).cos()) * 1e6;
    equatorial(r_km, lon, 0.0)
}

/// Geocentric position of the Moon, km, inertial frame of date (M&G eq. 3.47-3.49; the mean
/// longitude kept on the equinox of date, i.e. without its `- 1.3972 T` term).
pub fn moon_position_km(jd: f64) -> [f64; 3] {
    let t = centuries(jd);
    let l0 = (218.316_17 + 481_267.880_88 * t) * DEG_RAD;
    let l = (134.962_92 + 477_198.867_53 * t) * DEG_RAD;
    let lp = (357.525_43 + 35_999.049_44 * t) * DEG_RAD;
    let f = (93.272_83 + 483_202.018_73 * t) * DEG_RAD;
    let d = (297.850_27 + 445_267.111_35 * t) * DEG_RAD;
    let dlon = 22_640.0 * l.sin() + 769.0 * (2.0 * l).sin() - 4_586.0 * (l - 2.0 * d).sin()
        + 2_370.0 * (2.0 * d).sin()
        - 668.0 * lp.sin()
        - 412.0 * (2.0 * f).sin()
        - 212.0 * (2.0 * l - 2.0 * d).sin()
        - 206.0 * (l + lp - 2.0 * d).sin()
        + 192.0 * (l + 2.0 * d).sin()
        - 165.0 * (lp - 2.0 * d).sin()
        + 148.0 * (l - lp).sin()
        - 125.0 * d.sin()
        - 110.0 * (l + lp).sin()
        - 55.0 * (2.0 * f - 2.0 * d).sin();
    let lon = l0 + dlon * ARCSEC_RAD;
    let lat = (18_520.0
        * (f + lon - l0 + (412.0 * (2.0 * f).sin() + 541.0 * lp.sin()) * ARCSEC_RAD).sin()
        - 526.0 * (f - 2.0 * d).sin()
        + 44.0 * (l + f - 2.0 * d).sin()
        - 31.0 * (-l + f - 2.0 * d).sin()
        - 25.0 * (-2.0 * l + f).sin()
        - 23.0 * (lp + f - 2.0 * d).sin()
        + 21.0 * (-l + f).sin()
        + 11.0 * (-lp + f - 2.0 * d).sin())
        * ARCSEC_RAD;
    let r_km = 385_000.0
        - 20_905.0 * l.cos()
        - 3_699.0 * (2.0 * d - l).cos()
        - 2_956.0 * (2.0 * d).cos()
        - 570.0 * (2.0 * l).cos()
        + 246.0 * (2.0 * l - 2.0 * d).cos()
        - 205.0 * (lp - 2.0 * d).cos()
        - 171.0 * (l + 2.0 * d).cos()
        - 152.0 * (l + lp - 2.0 * d).cos();
    equatorial(r_km, lon, lat)
}

#[cfg(test)]
#[allow(clippy::unwrap_used)]
mod tests {
    use super::*;

    fn norm(v: [f64; 3]) -> f64 {
        (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt()
    }

    #[test]
    fn calendar_dates_and_sidereal_time() {
        assert_eq!(julian_date(2000, 1, 1, 12, 0, 0.0), JD_J2000);
        // Meeus example 7.a: 1957 October 4.81 = JD 2436116.31.
        let jd = julian_date(1957, 10, 4, 19, 26, 24.0);
        assert!((jd - 2_436_116.31).abs() < 1e-6, "{jd}");
        // Meeus example 12.a: 1987 April 10, 0h UT: GMST 13h10m46.3668s.
        let g = gmst_rad(julian_date(1987, 4, 10, 0, 0, 0.0));
        let want = (13.0 + 10.0 / 60.0 + 46.3668 / 3600.0) * 15.0 * DEG_RAD;
        assert!((g - want).abs() < 1e-8, "{g} vs {want}");
    }

    /// Meeus, *Astronomical Algorithms*, examples 25.a (Sun, 1992 October 13.0 TD: apparent
    /// RA 198.38083 deg, dec -7.78507 deg, R 0.99760775 au) and 47.a (Moon, 1992 April 12.0
    /// TD: RA 134.688470 deg, dec 13.768368 deg, distance 368409.7 km); the low-precision series
    /// are good to ~0.03 deg (Sun: the published values are apparent, with nutation and
    /// aberration) and ~0.1 deg, ~100 km (Moon).
    #[test]
    fn sun_and_moon_match_published_positions() {
        let ra_dec = |v: [f64; 3]| {
            let r = norm(v);
            (
                v[1].atan2(v[0]).rem_euclid(TAU).to_degrees(),
                (v[2] / r).asin().to_degrees(),
                r,
            )
        };
        let (ra, dec, r) = ra_dec(sun_position_km(julian_date(1992, 10, 13, 0, 0, 0.0)));
        assert!((ra - 198.380_83).abs() < 0.03, "sun ra {ra}");
        assert!((dec - -7.785_07).abs() < 0.02, "sun dec {dec}");
        assert!((r / 149_597_870.7 - 0.997_607_75).abs() < 2e-4, "sun r {r}");
        let (ra, dec, r) = ra_dec(moon_position_km(julian_date(1992, 4, 12, 0, 0, 0.0)));
        assert!((ra - 134.688_47).abs() < 0.1, "moon ra {ra}");
        assert!((dec - 13.768_368).abs() < 0.1, "moon dec {dec}");
        assert!((r - 368_409.7).abs() < 200.0, "moon r {r}");
    }
}
