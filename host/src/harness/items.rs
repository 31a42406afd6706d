//! What the feeders send from fixture files: each fixture's requests
//! ([`Fixture::requests`]) as feed items, labelled and sized for the reports.

use super::feeder::{Item, Payload};
use crate::drivers::leo_tour::prepare;
use crate::fixture::{self, Fixture, FixtureRequest};
use anyhow::{anyhow, Result};
use reconfig_core::limits::Limits;
use reconfig_core::wire::Request;
use std::path::{Path, PathBuf};

/// The repository's fixtures folder: `./fixtures` when run from the repository, else the one
/// beside this crate's sources.
pub fn default_fixtures_dir() -> PathBuf {
    let here = PathBuf::from("fixtures");
    if here.is_dir() {
        here
    } else {
        PathBuf::from(env!("CARGO_MANIFEST_DIR"))
            .join("..")
            .join("fixtures")
    }
}

/// Feed items for every fixture file, of any planner: the requests each stands for
/// ([`Fixture::requests`]). A LEO tour with a `[schedule]` table has its order (for a
/// `[sequence]` fixture) and its arcs' durations chosen here first, on the host, and each arc of
/// that schedule is one request: the schedule is a planning step, not a request of the flight
/// service. A fixture that does not load is reported and skipped.
pub fn fixture_items(paths: &[PathBuf], limits: &Limits) -> Vec<Item> {
    let mut items = Vec::new();
    for path in paths {
        let requests = fixture::load(path).and_then(|f| match f {
            Fixture::LeoTour(f) if f.schedule.is_some() => prepare(&f, limits)?.fixture.requests(),
            other => other.requests(),
        });
        match requests {
            Ok(requests) => items.extend(requests_items(requests)),
            Err(e) => eprintln!("skipped {}: {e:#}", path.display()),
        }
    }
    items
}

/// A feed item sending `request` (its planner named by the request).
pub fn request_item(label: String, size: String, request: Request) -> Item {
    Item {
        label,
        planner: Some(request.planner()),
        size,
        payload: Payload::Request(Box::new(request)),
    }
}

/// Feed items of a fixture's requests ([`Fixture::requests`]).
pub fn requests_items(requests: Vec<FixtureRequest>) -> impl Iterator<Item = Item> {
    requests
        .into_iter()
        .map(|r| request_item(r.label, r.size, r.request))
}

/// Every `*.toml` in a folder, sorted.
pub fn fixture_files(dir: &Path) -> Result<Vec<PathBuf>> {
    let mut files: Vec<PathBuf> = std::fs::read_dir(dir)
        .map_err(|e| anyhow!("cannot read {}: {e}", dir.display()))?
        .filter_map(|e| e.ok().map(|e| e.path()))
        .filter(|p| p.extension().is_some_and(|x| x == "toml"))
        .collect();
    files.sort();
    Ok(files)
}
