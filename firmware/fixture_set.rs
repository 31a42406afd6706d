//! The fixture set as the firmware sees it: every `fixtures/*.toml` (sorted by file name, not
//! recursive, so `fixtures/golden/` is not read), parsed by `reconfig_host::fixture` and encoded
//! with postcard into the core's own `Problem` bytes.
//!
//! Std-side code shared by two users, which include this file with `#[path]`:
//! * `firmware/build.rs` bakes these bytes into the firmware;
//! * the QEMU tests (`tests/tests/qemu_firmware/`) decode the *same* bytes and solve them on the
//!   host, so the bit-identity comparison cannot drift from what the firmware ran.

#![allow(dead_code)] // each includer uses part of it

use std::path::{Path, PathBuf};

/// Which planner a fixture is for.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Planner {
    /// Planner A, `reconfig_core::pseudospectral`.
    Pseudospectral,
    /// Planner B, `reconfig_core::impulsive`, default settings.
    Impulsive,
    /// Planner B with `Settings::fixed_point_only()`: the fixed-point plan the 2 M instruction
    /// budget is for. Every fixed-point planner-B fixture also runs as `<name>+fixed-point`.
    ImpulsiveFixedPoint,
    /// Planner B on a fixture in other input forms (ROE, an osculating state, ...): the bytes
    /// are its `impulsive::FormProblem`, converted on board by `impulsive::solve_form`.
    ImpulsiveForm,
    /// [`Planner::ImpulsiveForm`] with `Settings::fixed_point_only()`.
    ImpulsiveFormFixedPoint,
    /// The GEO servicing tour, `reconfig_core::geo_tour`, with the fixture's settings: carried
    /// only by the GEO image (`cargo firmware-geo`).
    GeoTour,
    /// One arc of the LEO rendezvous tour, `reconfig_core::leo_tour::solve_arc`, with the
    /// fixture's settings: carried only by the LEO image (`cargo firmware-leo`). Baked from the
    /// single-arc LEO fixtures (an order of two clients, no sequencing).
    LeoArc,
    /// The LEO tour's on-board part, `reconfig_core::leo_tour::tour_order::plan_onboard`: the
    /// order of a `[sequence]` fixture and every arc of it; carried only by the LEO image. The
    /// bytes carry its `tour_order::OnboardProblem`.
    LeoOnboard,
}

impl Planner {
    /// The fixture files' `planner` value.
    pub fn key(self) -> &'static str {
        match self {
            Self::Pseudospectral => "pseudospectral",
            Self::Impulsive
            | Self::ImpulsiveFixedPoint
            | Self::ImpulsiveForm
            | Self::ImpulsiveFormFixedPoint => "impulsive",
            Self::GeoTour => "geo-tour",
            Self::LeoArc | Self::LeoOnboard => "leo-tour",
        }
    }
}

/// One fixture, ready for the firmware.
#[derive(Clone, Debug)]
pub struct EncodedFixture {
    /// The fixture's `name` (unique over the set).
    pub name: String,
    /// The file it came from.
    pub file: PathBuf,
    /// Which planner.
    pub planner: Planner,
    /// `postcard` encoding of the planner's core `Problem` (GEO tour: of the pair
    /// `(Problem, Settings)`, since its fixtures may set their settings).
    pub problem: Vec<u8>,
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

/// Append `fixture` unless its name is taken.
fn push_unique(out: &mut Vec<EncodedFixture>, fixture: EncodedFixture) -> Result<(), String> {
    if let Some(other) = out.iter().find(|f| f.name == fixture.name) {
        return Err(format!(
            "fixture name {:?} is used by both {} and {}",
            fixture.name,
            other.file.display(),
            fixture.file.display()
        ));
    }
    out.push(fixture);
    Ok(())
}

/// Parse and encode every fixture in `dir`.
///
/// # Errors
/// A fixture that does not parse, a duplicated name, or an encoding failure: the firmware must
/// run every fixture, so none is skipped silently.
pub fn encode_all(dir: &Path) -> Result<Vec<EncodedFixture>, String> {
    use reconfig_host::fixture::{load, Fixture};
    let mut out: Vec<EncodedFixture> = Vec::new();
    for file in fixture_files(dir)? {
        let text = std::fs::read_to_string(&file).unwrap_or_default();
        // The LEO tour (issue 13): its single-arc fixtures and the on-board part of a
        // `[sequence]` fixture (the order and its arcs) run on the LEO image; a tour of a given
        // order (several arcs, the truth model) and a `[schedule]` fixture are host-only.
        if reconfig_host::fixture::leo_tour::is_leo_tour(&text) {
            let f = reconfig_host::fixture::leo_tour::load(&file).map_err(|e| format!("{e:#}"))?;
            // A chosen schedule is a host planning step, not part of the on-board request.
            if f.schedule.is_some() {
                continue;
            }
            if f.sequence.is_some() {
                let problem = reconfig_host::cli::leo_tour_sequence::onboard_problem(&f)
                    .and_then(|p| Ok(postcard::to_stdvec(&p)?))
                    .map_err(|e| format!("{}: {e:#}", f.name))?;
                push_unique(
                    &mut out,
                    EncodedFixture {
                        name: f.name,
                        file,
                        planner: Planner::LeoOnboard,
                        problem,
                    },
                )?;
                continue;
            }
            if f.order.len() != 2 {
                continue;
            }
            let (Some(&from), Some(&to), Some(&duration_s)) =
                (f.order.first(), f.order.get(1), f.intervals_s.first())
            else {
                continue;
            };
            let problem = reconfig_core::leo_tour::ArcProblem {
                from: f.clients[from],
                to: f.clients[to],
                duration_s,
                impulses: f.impulses,
            };
            let problem = postcard::to_stdvec(&(&problem, &f.settings))
                .map_err(|e| format!("{}: {e}", f.name))?;
            push_unique(
                &mut out,
                EncodedFixture {
                    name: f.name,
                    file,
                    planner: Planner::LeoArc,
                    problem,
                },
            )?;
            continue;
        }
        if reconfig_host::fixture::geo_tour::is_geo_tour(&text) {
            let f = reconfig_host::fixture::geo_tour::load(&file).map_err(|e| format!("{e:#}"))?;
            let problem = postcard::to_stdvec(&(&f.problem, &f.settings))
                .map_err(|e| format!("{}: {e}", f.name))?;
            push_unique(
                &mut out,
                EncodedFixture {
                    name: f.name,
                    file,
                    planner: Planner::GeoTour,
                    problem,
                },
            )?;
            continue;
        }
        let fixture = load(&file).map_err(|e| format!("{e:#}"))?;
        let name = fixture.name().to_owned();
        if let Some(other) = out.iter().find(|f| f.name == name) {
            return Err(format!(
                "fixture name {name:?} is used by both {} and {}",
                other.file.display(),
                file.display()
            ));
        }
        let (planner, problem) = match &fixture {
            Fixture::Pseudospectral(f) => (
                Planner::Pseudospectral,
                postcard::to_stdvec(&f.problem).map_err(|e| format!("{name}: {e}"))?,
            ),
            // A fixture in other input forms is baked in them: the M7 converts it.
            Fixture::Impulsive(f) => match &f.form {
                Some(form) => (
                    Planner::ImpulsiveForm,
                    postcard::to_stdvec(form).map_err(|e| format!("{name}: {e}"))?,
                ),
                None => (
                    Planner::Impulsive,
                    postcard::to_stdvec(&f.problem).map_err(|e| format!("{name}: {e}"))?,
                ),
            },
        };
        let fixed_point = matches!(
            &fixture,
            Fixture::Impulsive(f) if matches!(f.problem.plan, reconfig_core::impulsive::ImpulsePlan::Fixed(_))
        );
        if fixed_point {
            out.push(EncodedFixture {
                name: format!("{name}+fixed-point"),
                file: file.clone(),
                planner: if planner == Planner::ImpulsiveForm {
                    Planner::ImpulsiveFormFixedPoint
                } else {
                    Planner::ImpulsiveFixedPoint
                },
                problem: problem.clone(),
            });
        }
        out.push(EncodedFixture {
            name,
            file,
            planner,
            problem,
        });
    }
    Ok(out)
}
