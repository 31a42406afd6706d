//! The Earth gravity model's coefficients: JGM-3 to degree and order 8, vendored in
//! `host/data/JGM3-deg8.gfc` (ICGEM format; source and licence in the file's header), read once
//! and un-normalised for the recursion in [`super::gravity`].

use anyhow::{bail, Context, Result};

/// Highest degree (and order) the vendored file holds and the field evaluates.
pub const MAX_DEGREE: usize = 8;
/// Rows of the coefficient tables: degrees 0..=MAX_DEGREE.
pub const ROWS: usize = MAX_DEGREE + 1;

/// The vendored coefficient file (JGM-3, degree and order <= 8).
pub const JGM3_DEG8_GFC: &str = include_str!("../../data/JGM3-deg8.gfc");

/// A spherical-harmonic gravity field with un-normalised coefficients `C[n][m]`, `S[n][m]`.
#[derive(Clone, Debug, PartialEq)]
pub struct GravityModel {
    /// Name from the file's header (`modelname`).
    pub name: String,
    /// Gravitational parameter of the model, km^3/s^2.
    pub gm_km3_s2: f64,
    /// Reference radius of the model, km.
    pub radius_km: f64,
    /// Un-normalised cosine coefficients, `c[n][m]` (0 for m > n).
    pub c: [[f64; ROWS]; ROWS],
    /// Un-normalised sine coefficients, `s[n][m]`.
    pub s: [[f64; ROWS]; ROWS],
}

/// `sqrt((2 - delta_m0) (2n + 1) (n - m)! / (n + m)!)`: a fully normalised coefficient times
/// this is the un-normalised one (Heiskanen & Moritz 1967, eq. 1-73).
fn normalisation(n: usize, m: usize) -> f64 {
    // (n - m)! / (n + m)! = 1 / ((n - m + 1) (n - m + 2) ... (n + m)), at most 16 factors here.
    let ratio: f64 = (n - m + 1..=n + m).map(|k| 1.0 / k as f64).product();
    let kronecker = if m == 0 { 1.0 } else { 2.0 };
    (kronecker * (2 * n + 1) as f64 * ratio).sqrt()
}

impl GravityModel {
    /// JGM-3 to degree and order 8, from the vendored file.
    ///
    /// # Errors
    /// Never for the vendored file (a test parses it); the parser's errors name the line.
    pub fn jgm3() -> Result<Self> {
        Self::parse_gfc(JGM3_DEG8_GFC)
    }

    /// Parse ICGEM `.gfc` text (fully normalised coefficients), keeping degrees `<= MAX_DEGREE`.
    ///
    /// # Errors
    /// A header value or coefficient line that does not parse, a missing `earth_gravity_constant`
    /// or `radius`, or a degree-and-order pair missing below [`MAX_DEGREE`].
    pub fn parse_gfc(text: &str) -> Result<Self> {
        let mut name = String::new();
        let mut gm_m3_s2 = None;
        let mut radius_m = None;
        let mut c = [[0.0; ROWS]; ROWS];
        let mut s = [[0.0; ROWS]; ROWS];
        let mut seen = [[false; ROWS]; ROWS];
        let mut in_body = false;
        for (k, line) in text.lines().enumerate() {
            let line_no = k + 1;
            let mut words = line.split_whitespace();
            let Some(key) = words.next() else { continue };
            if key.starts_with('#') {
                continue;
            }
            if !in_body {
                let value = words.next();
                match (key, value) {
                    ("end_of_head", _) => in_body = true,
                    ("modelname", Some(v)) => name = v.to_string(),
                    ("earth_gravity_constant", Some(v)) => {
                        gm_m3_s2 = Some(parse_number(v, line_no)?);
                    }
                    ("radius", Some(v)) => radius_m = Some(parse_number(v, line_no)?),
                    _ => {}
                }
                continue;
            }
            if key != "gfc" {
                bail!("line {line_no}: expected a 'gfc' coefficient line, found {key:?}");
            }
            let fields: Vec<&str> = words.collect();
            let [n, m, cn, sn, ..] = fields.as_slice() else {
                bail!("line {line_no}: a 'gfc' line needs n, m, C and S");
            };
            let n: usize = n
                .parse()
                .with_context(|| format!("line {line_no}: degree"))?;
            let m: usize = m
                .parse()
                .with_context(|| format!("line {line_no}: order"))?;
            if m > n {
                bail!("line {line_no}: order {m} above degree {n}");
            }
            if n > MAX_DEGREE {
                continue;
            }
            let factor = normalisation(n, m);
            c[n][m] = parse_number(cn, line_no)? * factor;
            s[n][m] = parse_number(sn, line_no)? * factor;
            seen[n][m] = true;
        }
        let gm = gm_m3_s2.context("no earth_gravity_constant in the header")?;
        let radius = radius_m.context("no radius in the header")?;
        for (n, row) in seen.iter().enumerate() {
            for (m, ok) in row.iter().enumerate().take(n + 1) {
                if !ok {
                    bail!("coefficient of degree {n} and order {m} missing");
                }
            }
        }
        Ok(Self {
            name,
            gm_km3_s2: gm * 1e-9,
            radius_km: radius * 1e-3,
            c,
            s,
        })
    }

    /// `J2 = -C20` (un-normalised), the model's oblateness.
    pub fn j2(&self) -> f64 {
        -self.c[2][0]
    }
}

fn parse_number(word: &str, line_no: usize) -> Result<f64> {
    let x: f64 = word
        .replace(['D', 'd'], "e")
        .parse()
        .with_context(|| format!("line {line_no}: {word:?} is not a number"))?;
    if !x.is_finite() {
        bail!("line {line_no}: {word:?} is not finite");
    }
    Ok(x)
}

#[cfg(test)]
#[allow(clippy::unwrap_used)]
mod tests {
    use super::*;

    #[test]
    fn the_vendored_jgm3_parses_with_its_published_constants() {
        let g = GravityModel::jgm3().unwrap();
        assert_eq!(g.name, "JGM3");
        assert_eq!(g.gm_km3_s2, 398_600.441_5);
        assert!((g.radius_km - 6378.1363).abs() < 1e-12);
        // J2 = -sqrt(5) C20bar = 1.0826360e-3 (JGM-3), J3 = -sqrt(7) C30bar = -2.5324e-6.
        assert!((g.j2() - 1.082_636_0e-3).abs() < 1e-10, "J2 {}", g.j2());
        assert!(
            (-g.c[3][0] - (-2.532_43e-6)).abs() < 1e-10,
            "J3 {}",
            -g.c[3][0]
        );
        // C22 = sqrt(5 / 12) C22bar: 1.5745e-6.
        assert!((g.c[2][2] - 1.574_5e-6).abs() < 1e-9, "C22 {}", g.c[2][2]);
    }

    #[test]
    fn a_missing_coefficient_or_header_value_is_named() {
        let text = GravityModel::jgm3().map(|_| JGM3_DEG8_GFC).unwrap();
        // The model's error without the lines that start with `prefix`.
        let without = |prefix: &str| {
            let kept: Vec<&str> = text.lines().filter(|l| !l.starts_with(prefix)).collect();
            GravityModel::parse_gfc(&kept.join("\n"))
                .unwrap_err()
                .to_string()
        };
        let err = without("gfc    5    3");
        assert!(err.contains("degree 5 and order 3"), "{err}");
        let err = without("radius");
        assert!(err.contains("radius"), "{err}");
    }
}
