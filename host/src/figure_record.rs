//! One figure of the README's "Where we stand", written by the code that measures it.
//!
//! Each figure is a small TOML file in `fixtures/golden/figures/` (what, target, the measured
//! value as the README prints it, met or not, the document that explains it, the command that
//! measures it). Deterministic figures are written and held by the regression test that
//! measures them: the test fails when its measurement no longer gives the stored line, and
//! `RECONFIG_UPDATE_RECORDS=1` rewrites it (say why in the commit message). Timings are written
//! by the command that measures them (`cargo run --release -p reconfig-host --example
//! record_timings` after `cargo bench`, `reconfig demo`), never by a test. The README's lines
//! are generated from these files (`tests/tests/readme_figures.rs` fails when they differ).

use serde::{Deserialize, Serialize};
use std::path::{Path, PathBuf};

/// Where the figure records live, relative to the workspace.
pub const DIR: &str = "fixtures/golden/figures";

/// The environment variable that makes [`hold`] rewrite a record instead of checking it.
pub const UPDATE_ENV: &str = "RECONFIG_UPDATE_RECORDS";

/// One line of "Where we stand".
#[derive(Clone, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub struct Figure {
    /// What is measured.
    pub what: String,
    /// The bar it is held to.
    pub target: String,
    /// The measured value, as the README prints it.
    pub measured: String,
    /// Whether the measured value meets the target.
    pub met: bool,
    /// The document in `docs/` that explains it (its stem, e.g. `planner-a`).
    pub doc: String,
    /// The command that measures it.
    pub command: String,
}

impl Figure {
    /// The README's line for this figure.
    pub fn readme_line(&self) -> String {
        let met = if self.met { "met" } else { "**not met**" };
        format!(
            "| {} | {} | {} | {met} | [{}](docs/{}.md) |",
            self.what, self.target, self.measured, self.doc, self.doc
        )
    }
}

/// The workspace's root (the folder above `host/`).
pub fn root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("..")
}

/// The record file of figure `name`.
pub fn path(name: &str) -> PathBuf {
    root().join(DIR).join(format!("{name}.toml"))
}

/// The stored record of figure `name`.
pub fn load(name: &str) -> Result<Figure, String> {
    let path = path(name);
    let text = std::fs::read_to_string(&path).map_err(|e| format!("{}: {e}", path.display()))?;
    toml::from_str(&text).map_err(|e| format!("{}: {e}", path.display()))
}

/// Write the record of figure `name`.
pub fn write(name: &str, figure: &Figure) -> Result<(), String> {
    let path = path(name);
    let text = toml::to_string(figure).map_err(|e| format!("{name}: {e}"))?;
    std::fs::write(&path, text).map_err(|e| format!("{}: {e}", path.display()))
}

/// Hold a deterministic measurement to its record: with [`UPDATE_ENV`]`=1` the record is
/// rewritten; otherwise an error names the figure and both lines when they differ.
pub fn hold(name: &str, measured: &Figure) -> Result<(), String> {
    if std::env::var(UPDATE_ENV).as_deref() == Ok("1") {
        return write(name, measured);
    }
    let stored = load(name)?;
    if &stored == measured {
        Ok(())
    } else {
        Err(format!(
            "figure {name} drifted from {}:\n stored:   {}\n measured: {}\n\
             (re-record with {UPDATE_ENV}=1 and say why in the commit message)",
            path(name).display(),
            stored.readme_line(),
            measured.readme_line()
        ))
    }
}

/// The names of every stored figure record, sorted.
pub fn names() -> Result<Vec<String>, String> {
    let dir = root().join(DIR);
    let mut names = Vec::new();
    for entry in std::fs::read_dir(&dir).map_err(|e| format!("{}: {e}", dir.display()))? {
        let p = entry.map_err(|e| e.to_string())?.path();
        if p.extension().is_some_and(|x| x == "toml") {
            if let Some(stem) = p.file_stem().and_then(|s| s.to_str()) {
                names.push(stem.to_owned());
            }
        }
    }
    names.sort();
    Ok(names)
}
