//! The fixture set as the firmware sees it: the `wire::Request`s of every `fixtures/*.toml`
//! (sorted by file name, not recursive, so `fixtures/golden/` is not read), built by the host's
//! one request builder (`reconfig_host::fixture::Fixture::requests`) and encoded with postcard.
//! The firmware decodes each and answers it through `wire::answer`, as every front end does.
//!
//! Std-side code shared by two users, which include this file with `#[path]`:
//! * `firmware/build.rs` bakes these bytes into the firmware;
//! * the QEMU tests (`tests/tests/qemu_firmware/`) decode the *same* bytes and answer them on
//!   the host, so the bit-identity comparison cannot drift from what the firmware ran.

#![allow(dead_code)] // each includer uses part of it

use reconfig_core::contract::PlannerKind;
use reconfig_core::limits::Limits;
use reconfig_core::wire::Request;
use reconfig_host::fixture::{self, Fixture, FixtureRequest};
use std::path::{Path, PathBuf};

/// One request, ready for the firmware.
#[derive(Clone, Debug)]
pub struct EncodedRequest {
    /// Its name (unique over the set, no white space): the fixture's name, `<name>+fixed-point`
    /// for planner B's fixed-point plan alone, `<name>/order` and `<name>/arc-<k>` for the
    /// requests of a LEO tour's on-board part.
    pub name: String,
    /// The fixture file it came from.
    pub file: PathBuf,
    /// Its planner (`Request::planner`).
    pub planner: PlannerKind,
    /// The LEO tour's on-board part it belongs to (the fixture's name), if any.
    pub part_of: Option<String>,
    /// The `postcard` encoding of the `wire::Request`.
    pub request: Vec<u8>,
}

/// The `*.toml` files directly in `dir`, sorted by file name.
pub fn fixture_files(dir: &Path) -> Result<Vec<PathBuf>, String> {
    let entries =
        std::fs::read_dir(dir).map_err(|e| format!("cannot list {}: {e}", dir.display()))?;
    let mut files = Vec::new();
    for entry in entries {
        let path = entry
            .map_err(|e| format!("cannot list {}: {e}", dir.display()))?
            .path();
        if path.is_file() && path.extension().is_some_and(|ext| ext == "toml") {
            files.push(path);
        }
    }
    files.sort();
    Ok(files)
}

/// The requests the firmware runs for one fixture, with their names (see
/// [`EncodedRequest::name`]) and the on-board part they belong to.
///
/// * planners A and B and the GEO tour: the fixture's request; a fixed-point planner-B fixture
///   also as `<name>+fixed-point`, the same fixture with `Settings::fixed_point_only()`;
/// * the LEO tour: a `[sequence]` fixture's on-board part (its sequencing request, then each
///   arc's request of the order the host answers it, under `limits`); a tour of one arc its
///   request; a tour of several arcs of a given order and a `[schedule]` fixture (a host
///   planning step) stay on the host.
fn requests_of(
    fixture: Fixture,
    limits: &Limits,
) -> Result<Vec<(String, Option<String>, FixtureRequest)>, String> {
    let name = fixture.name().to_owned();
    let built = |requests| named(&name, requests);
    let single = |requests: Vec<FixtureRequest>, name: &str| {
        requests
            .into_iter()
            .map(|r| (name.to_owned(), None, r))
            .collect::<Vec<_>>()
    };
    Ok(match fixture {
        Fixture::Impulsive(f)
            if matches!(
                f.problem.plan,
                reconfig_core::impulsive::ImpulsePlan::Fixed(_)
            ) =>
        {
            let mut fixed_point = f.clone();
            fixed_point.settings = reconfig_core::impulsive::Settings::fixed_point_only();
            let mut out = single(
                built(Fixture::Impulsive(fixed_point).requests())?,
                &format!("{name}+fixed-point"),
            );
            out.extend(single(built(Fixture::Impulsive(f).requests())?, &name));
            out
        }
        Fixture::LeoTour(f) if f.schedule.is_some() => Vec::new(),
        Fixture::LeoTour(f) if f.sequence.is_some() => {
            let requests = built(reconfig_host::drivers::leo_tour::onboard_requests(
                &f, limits,
            ))?;
            requests
                .into_iter()
                .enumerate()
                .map(|(k, r)| {
                    let part = if k == 0 {
                        "order".to_owned()
                    } else {
                        format!("arc-{k}")
                    };
                    (format!("{name}/{part}"), Some(name.clone()), r)
                })
                .collect()
        }
        Fixture::LeoTour(f) if f.order.len() != 2 => Vec::new(),
        other => single(built(other.requests())?, &name),
    })
}

/// The folder of the worst-case requests (relative to the workspace): the heaviest requests
/// found within the built-in limits (docs/harness.md).
pub const WORST_CASE_DIR: &str = "fixtures/worst-case";

/// The worst-case requests of `planners` (the requests of [`WORST_CASE_DIR`] under `root`),
/// which the GEO and LEO images run after their planners' fixtures of `fixtures/`
/// (docs/geo-tour.md and docs/leo-tour.md, "Work budget"). Planners A's and B's worst cases
/// stay out of the images: planner A's would not fit the default image's instruction run.
///
/// # Errors
/// As [`encode_all`].
pub fn worst_cases(
    root: &Path,
    limits: &Limits,
    planners: &[PlannerKind],
) -> Result<Vec<EncodedRequest>, String> {
    Ok(encode_all(&root.join(WORST_CASE_DIR), limits)?
        .into_iter()
        .filter(|f| planners.contains(&f.planner))
        .collect())
}

/// Whether a request comes from [`WORST_CASE_DIR`].
pub fn is_worst_case(f: &EncodedRequest) -> bool {
    f.file
        .parent()
        .and_then(Path::file_name)
        .is_some_and(|n| n == "worst-case")
}

/// `more` appended to `set`, failing on a name `set` already holds.
///
/// # Errors
/// A name used twice.
pub fn append_unique(
    set: &mut Vec<EncodedRequest>,
    more: Vec<EncodedRequest>,
) -> Result<(), String> {
    for f in more {
        if let Some(other) = set.iter().find(|o| o.name == f.name) {
            return Err(format!(
                "fixture name {:?} is used by both {} and {}",
                f.name,
                other.file.display(),
                f.file.display()
            ));
        }
        set.push(f);
    }
    Ok(())
}

/// `result` with its error as text naming the fixture.
fn named<T, E: std::fmt::Display>(name: &str, result: Result<T, E>) -> Result<T, String> {
    result.map_err(|e| format!("{name}: {e:#}"))
}

/// Build and encode every request of the fixtures in `dir` (`limits`: the image's, under which
/// a LEO tour's sequencing is answered here to build its arcs' requests).
///
/// # Errors
/// A fixture that does not parse or whose requests cannot be built, a duplicated name, or an
/// encoding failure: the firmware must run every fixture, so none is skipped silently.
pub fn encode_all(dir: &Path, limits: &Limits) -> Result<Vec<EncodedRequest>, String> {
    let mut out: Vec<EncodedRequest> = Vec::new();
    for file in fixture_files(dir)? {
        let fixture = fixture::load(&file).map_err(|e| format!("{e:#}"))?;
        let requests = requests_of(fixture, limits)?;
        for (name, part_of, r) in requests {
            let request: &Request = &r.request;
            let encoded = EncodedRequest {
                planner: request.planner(),
                request: postcard::to_stdvec(request).map_err(|e| format!("{name}: {e}"))?,
                name,
                file: file.clone(),
                part_of,
            };
            append_unique(&mut out, vec![encoded])?;
        }
    }
    Ok(out)
}
