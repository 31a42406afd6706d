//! Helpers shared by the regression tests in `tests/tests/`.

use reconfig_core::pseudospectral::{self, Settings, Solution, Workspace};
use reconfig_host::fixture::{self, Fixture};
use std::path::PathBuf;

/// The repository's `fixtures/` folder.
pub fn fixtures_dir() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("..")
        .join("fixtures")
}

/// Every fixture file, sorted by name.
pub fn fixture_paths() -> Vec<PathBuf> {
    let mut paths: Vec<PathBuf> = std::fs::read_dir(fixtures_dir())
        .expect("fixtures dir")
        .filter_map(|e| e.ok().map(|e| e.path()))
        .filter(|p| p.extension().is_some_and(|x| x == "toml"))
        .collect();
    paths.sort();
    paths
}

/// Load a planner-A fixture by file stem.
pub fn pseudospectral_fixture(stem: &str) -> pseudospectral::Problem {
    let path = fixtures_dir().join(format!("{stem}.toml"));
    match fixture::load(&path).expect("fixture loads") {
        Fixture::Pseudospectral(f) => f.problem,
        Fixture::Impulsive(_) => panic!("{stem} is not a planner-A fixture"),
    }
}

/// Solve a planner-A problem in a fresh boxed workspace.
pub fn solve_pseudospectral(
    problem: &pseudospectral::Problem,
    settings: &Settings,
) -> Result<Box<Solution>, pseudospectral::PlanError> {
    let mut workspace = Box::new(Workspace::new());
    let mut solution = Box::new(Solution::new());
    pseudospectral::solve(problem, settings, &mut workspace, &mut solution)?;
    Ok(solution)
}

/// The golden value `key` of `name` in `fixtures/golden/FILE`.
pub fn golden(file: &str, name: &str, key: &str) -> f64 {
    let text = std::fs::read_to_string(fixtures_dir().join("golden").join(file)).expect("golden");
    let table: toml::Table = toml::from_str(&text).expect("golden toml");
    table[name][key].as_float().expect("float")
}
