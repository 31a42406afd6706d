//! A campaign's dispersions: which numbers of a fixture file vary from case to case, and how.
//!
//! A dispersion names a number of the fixture's TOML by its path (`relative.initial_roe_m[1]`,
//! `impulse[0].arg_latitude_deg`, `spacecraft[2].initial_position[0]`): keys joined by dots,
//! array elements by `[index]`. So one mechanism serves every planner's fixture, in the units
//! the file itself uses (degrees, metres, days), and the case a row describes is the file with
//! those numbers replaced, which `reconfig solve` reads as it is.

use anyhow::{anyhow, bail, Context, Result};
use rand::Rng;
use rand_chacha::ChaCha8Rng;
use rand_distr::{Distribution, StandardNormal};
use std::fmt;
use std::str::FromStr;

/// One step of a path: a table's key or an array's index.
#[derive(Debug, Clone, PartialEq, Eq)]
enum Step {
    Key(String),
    Index(usize),
}

/// The path of one number in a fixture file.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Path {
    text: String,
    steps: Vec<Step>,
}

impl fmt::Display for Path {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.text)
    }
}

impl FromStr for Path {
    type Err = anyhow::Error;

    fn from_str(text: &str) -> Result<Self> {
        let mut steps = Vec::new();
        for part in text.split('.') {
            let (key, mut rest) = part.split_at(part.find('[').unwrap_or(part.len()));
            if key.is_empty() {
                bail!("path `{text}`: an empty key (keys are joined by `.`)");
            }
            steps.push(Step::Key(key.to_owned()));
            while let Some(inner) = rest.strip_prefix('[') {
                let close = inner
                    .find(']')
                    .ok_or_else(|| anyhow!("path `{text}`: `[` without `]`"))?;
                let index = inner[..close]
                    .parse::<usize>()
                    .with_context(|| format!("path `{text}`: index `{}`", &inner[..close]))?;
                steps.push(Step::Index(index));
                rest = &inner[close + 1..];
            }
            if !rest.is_empty() {
                bail!("path `{text}`: `{rest}` after an index");
            }
        }
        Ok(Self {
            text: text.to_owned(),
            steps,
        })
    }
}

impl Path {
    /// The number at this path in `doc`, for replacing: an error naming the path and what is
    /// there instead when it is not a number.
    fn float_mut<'a>(&self, doc: &'a mut toml::Value) -> Result<&'a mut f64> {
        let mut at = doc;
        for step in &self.steps {
            at = match (step, at) {
                (Step::Key(k), toml::Value::Table(t)) => t
                    .get_mut(k)
                    .ok_or_else(|| anyhow!("path `{self}`: no key `{k}` in the fixture"))?,
                (Step::Index(i), toml::Value::Array(a)) => {
                    let len = a.len();
                    a.get_mut(*i).ok_or_else(|| {
                        anyhow!("path `{self}`: index {i} is past the array's {len} elements")
                    })?
                }
                (Step::Key(k), other) => {
                    bail!("path `{self}`: `{k}` looked up in a {}", other.type_str())
                }
                (Step::Index(i), other) => {
                    bail!("path `{self}`: [{i}] taken of a {}", other.type_str())
                }
            };
        }
        // An integer is written as the same number in float form (`initial = [8, 0, 0]` in a
        // planner-A fixture); a field that takes only integers then refuses the file, which
        // [`super::Campaign::new`] checks before any case runs.
        if let toml::Value::Integer(i) = *at {
            *at = toml::Value::Float(i as f64);
        }
        match at {
            toml::Value::Float(x) => Ok(x),
            other => bail!(
                "path `{self}` is a {} ({other}), not a number",
                other.type_str()
            ),
        }
    }

    /// Write the number at this path in float form, unchanged: the file a field that takes
    /// only integers refuses.
    ///
    /// # Errors
    /// The path names no number of `doc`.
    pub fn as_float(&self, doc: &mut toml::Value) -> Result<()> {
        self.float_mut(doc).map(|_| ())
    }
}

/// How a dispersed number is drawn.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Law {
    /// The file's value plus a normal deviate of this standard deviation (the file's units).
    Gaussian { sigma: f64 },
    /// A value drawn uniformly in `[low, high)`, replacing the file's.
    Uniform { low: f64, high: f64 },
}

/// One dispersed number: its path and its law.
#[derive(Debug, Clone, PartialEq)]
pub struct Dispersion {
    /// Where the number is.
    pub path: Path,
    /// How it is drawn.
    pub law: Law,
}

impl Dispersion {
    /// `PATH=SIGMA`: the file's value plus a normal deviate of standard deviation `SIGMA`.
    ///
    /// # Errors
    /// No `=`, a bad path, or a `SIGMA` that is not a finite number ≥ 0 (named).
    pub fn gaussian(arg: &str) -> Result<Self> {
        let (path, sigma) = split(arg, "PATH=SIGMA")?;
        let sigma: f64 = number(sigma, arg)?;
        if sigma < 0.0 {
            bail!("`{arg}`: sigma = {sigma} is below 0");
        }
        Ok(Self {
            path: path.parse()?,
            law: Law::Gaussian { sigma },
        })
    }

    /// `PATH=LOW:HIGH`: a value drawn uniformly in `[LOW, HIGH)`.
    ///
    /// # Errors
    /// No `=` or `:`, a bad path, or bounds that are not finite with `LOW ≤ HIGH` (named).
    pub fn uniform(arg: &str) -> Result<Self> {
        let (path, range) = split(arg, "PATH=LOW:HIGH")?;
        let (low, high) = range
            .split_once(':')
            .ok_or_else(|| anyhow!("`{arg}`: expected PATH=LOW:HIGH"))?;
        let (low, high) = (number(low, arg)?, number(high, arg)?);
        if low > high {
            bail!("`{arg}`: low = {low} is above high = {high}");
        }
        Ok(Self {
            path: path.parse()?,
            law: Law::Uniform { low, high },
        })
    }

    /// Draw this dispersion's number for one case into `doc`; the value written.
    ///
    /// # Errors
    /// The path names no float of `doc`.
    pub fn apply(&self, doc: &mut toml::Value, rng: &mut ChaCha8Rng) -> Result<f64> {
        let x = self.path.float_mut(doc)?;
        *x = match self.law {
            Law::Gaussian { sigma } => {
                let z: f64 = StandardNormal.sample(rng);
                *x + sigma * z
            }
            // An empty range is the one value (`random_range` refuses it).
            Law::Uniform { low, high } if low == high => low,
            Law::Uniform { low, high } => rng.random_range(low..high),
        };
        Ok(*x)
    }
}

fn split<'a>(arg: &'a str, form: &str) -> Result<(&'a str, &'a str)> {
    arg.split_once('=')
        .ok_or_else(|| anyhow!("`{arg}`: expected {form}"))
}

fn number(text: &str, arg: &str) -> Result<f64> {
    let x: f64 = text
        .trim()
        .parse()
        .with_context(|| format!("`{arg}`: `{text}` is not a number"))?;
    if !x.is_finite() {
        bail!("`{arg}`: {x} is not finite");
    }
    Ok(x)
}

#[cfg(test)]
#[allow(clippy::unwrap_used)]
mod tests {
    use super::*;
    use rand::SeedableRng;

    fn doc() -> toml::Value {
        toml::from_str(
            "name = \"x\"\n[relative]\ninitial = [1.0, 2.0]\n[[impulse]]\nrevolutions = 3\n\
             arg_latitude_deg = 30.0\n",
        )
        .unwrap()
    }

    #[test]
    fn a_path_reaches_keys_array_elements_and_tables_of_arrays() {
        let mut d = doc();
        let mut rng = ChaCha8Rng::seed_from_u64(1);
        let u = Dispersion::uniform("impulse[0].arg_latitude_deg=40:40").unwrap();
        assert_eq!(u.apply(&mut d, &mut rng).unwrap(), 40.0);
        let g = Dispersion::gaussian("relative.initial[1]=0").unwrap();
        assert_eq!(g.apply(&mut d, &mut rng).unwrap(), 2.0);
        assert_eq!(d["impulse"][0]["arg_latitude_deg"].as_float(), Some(40.0));
    }

    #[test]
    fn a_gaussian_draw_moves_the_value_by_its_sigma() {
        let g = Dispersion::gaussian("relative.initial[0]=0.5").unwrap();
        let mut rng = ChaCha8Rng::seed_from_u64(7);
        let draws: Vec<f64> = (0..4000)
            .map(|_| g.apply(&mut doc(), &mut rng).unwrap())
            .collect();
        let mean = draws.iter().sum::<f64>() / 4000.0;
        let var = draws.iter().map(|x| (x - mean).powi(2)).sum::<f64>() / 3999.0;
        // 1.0 + N(0, 0.5^2): the mean within 4 standard errors, the deviation within 5 %.
        assert!((mean - 1.0).abs() < 4.0 * 0.5 / 4000f64.sqrt(), "{mean}");
        assert!((var.sqrt() - 0.5).abs() < 0.025, "{}", var.sqrt());
    }

    #[test]
    fn a_bad_dispersion_names_the_path_and_what_is_wrong() {
        let mut rng = ChaCha8Rng::seed_from_u64(1);
        let mut err = |arg: &str| {
            let d = if arg.contains(':') {
                Dispersion::uniform(arg)
            } else {
                Dispersion::gaussian(arg)
            };
            match d {
                Err(e) => format!("{e:#}"),
                Ok(d) => format!("{:#}", d.apply(&mut doc(), &mut rng).unwrap_err()),
            }
        };
        assert!(err("relative.final[0]=1").contains("no key `final`"));
        assert!(err("relative.initial[2]=1").contains("index 2 is past the array's 2"));
        assert!(err("name=1").contains("is a string (\"x\"), not a number"));
        assert!(err("relative.initial=1").contains("is a array"));
        assert!(err("relative.initial[0]=-1").contains("sigma = -1 is below 0"));
        assert!(err("relative.initial[0]=2:1").contains("low = 2 is above high = 1"));
        assert!(err("relative.initial[0]=nan").contains("not finite"));
        assert!(err("relative.initial[0]").contains("expected PATH=SIGMA"));
        assert!(err("relative..x=1").contains("an empty key"));
        assert!(err("relative.initial[x]=1").contains("index `x`"));
    }
}
