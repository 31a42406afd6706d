//! The host's answer to a fixture, encoded as the firmware prints it: the same problem bytes
//! the firmware decoded, the same settings, a fresh workspace and output buffer.

use std::fmt::Write as _;

use reconfig_core::{geo_tour, impulsive, leo_tour, pseudospectral};
use serde::de::DeserializeOwned;
use serde::Serialize;

use crate::fixture_set::{EncodedFixture, Planner};
use crate::image::Run;

/// The repository's fixtures of one planner, encoded as the firmware bakes them.
pub fn fixtures_of(planners: &[Planner]) -> Vec<EncodedFixture> {
    crate::fixture_set::encode_all(&crate::prerequisites::root().join("fixtures"))
        .expect("fixtures load")
        .into_iter()
        .filter(|f| planners.contains(&f.planner))
        .collect()
}

pub fn hex(bytes: &[u8]) -> String {
    bytes.iter().fold(String::new(), |mut s, b| {
        let _ = write!(s, "{b:02x}");
        s
    })
}

/// Decode the baked bytes as `P`, solve into fresh boxed buffers, and let `answer` encode the
/// result with the buffers (as the firmware encodes them, with [`encode`]).
fn encoded<P: DeserializeOwned, W, S, R>(
    problem: &[u8],
    (workspace, solution): (W, S),
    solve: impl FnOnce(&P, &mut W, &mut S) -> R,
    answer: impl FnOnce(R, &S) -> Vec<u8>,
) -> Vec<u8> {
    let problem: P = postcard::from_bytes(problem).expect("the baked problem decodes");
    let (mut workspace, mut solution) = (Box::new(workspace), Box::new(solution));
    let result = solve(&problem, &mut workspace, &mut solution);
    answer(result, &solution)
}

fn encode<T: Serialize>(value: &T) -> Vec<u8> {
    postcard::to_stdvec(value).expect("encode")
}

/// Planner B's settings for a fixture run with default settings or `fixed_point_only()`.
fn impulsive_settings(fixed_point_only: bool) -> impulsive::Settings {
    if fixed_point_only {
        impulsive::Settings::fixed_point_only()
    } else {
        impulsive::Settings::default()
    }
}

/// The host's encoded result for one fixture.
pub fn host_result(planner: Planner, problem: &[u8]) -> Vec<u8> {
    match planner {
        Planner::Pseudospectral => encoded(
            problem,
            (
                pseudospectral::Workspace::new(),
                pseudospectral::Solution::new(),
            ),
            |p: &pseudospectral::Problem, w, s| {
                pseudospectral::solve(p, &pseudospectral::Settings::default(), w, s)
            },
            |result, s| encode(&result.map(|()| s)),
        ),
        Planner::Impulsive | Planner::ImpulsiveFixedPoint => {
            let settings = impulsive_settings(planner == Planner::ImpulsiveFixedPoint);
            encoded(
                problem,
                (impulsive::Workspace::new(), impulsive::Solution::new()),
                |p: &impulsive::Problem, w, s| impulsive::solve(p, &settings, w, s),
                |result, s| encode(&result.map(|()| s)),
            )
        }
        Planner::ImpulsiveForm | Planner::ImpulsiveFormFixedPoint => {
            let settings = impulsive_settings(planner == Planner::ImpulsiveFormFixedPoint);
            encoded(
                problem,
                (impulsive::Workspace::new(), impulsive::Solution::new()),
                |p: &impulsive::FormProblem, w, s| impulsive::solve_form(p, &settings, w, s),
                |result, s| encode(&result.map(|end| (s, end))),
            )
        }
        // The GEO fixtures' bytes carry `(Problem, Settings)`.
        Planner::GeoTour => encoded(
            problem,
            (geo_tour::Workspace::new(), geo_tour::Solution::new()),
            |(p, settings): &(geo_tour::Problem, geo_tour::Settings), w, s| {
                geo_tour::solve(p, settings, w, s)
            },
            |result, s| encode(&result.map(|()| s)),
        ),
        // A LEO arc's bytes carry `(ArcProblem, Settings)`.
        Planner::LeoArc => encoded(
            problem,
            (leo_tour::Workspace::new(), leo_tour::ArcSolution::new()),
            |(p, settings): &(leo_tour::ArcProblem, leo_tour::Settings), w, s| {
                leo_tour::solve_arc(p, settings, w, s)
            },
            |result, s| encode(&result.map(|()| s)),
        ),
        // The on-board part's bytes carry its `tour_order::OnboardProblem`.
        Planner::LeoOnboard => encoded(
            problem,
            (
                leo_tour::tour_order::SequenceWorkspace::new(),
                leo_tour::tour_order::OnboardPlan::new(),
            ),
            |p: &leo_tour::tour_order::OnboardProblem, w, s| {
                leo_tour::tour_order::plan_onboard(p, w, s)
            },
            |result, s| encode(&result.map(|()| s)),
        ),
    }
}

/// The image `image` ran exactly `fixtures` (all of `planner`), each with the host's result
/// byte for byte.
pub fn assert_bit_identical(run: &Run, fixtures: &[EncodedFixture], image: &str) {
    assert!(!fixtures.is_empty(), "no {image} fixtures to compare");
    let names: Vec<&str> = fixtures.iter().map(|f| f.name.as_str()).collect();
    let m7_names: Vec<&str> = run.fixtures.iter().map(|f| f.name.as_str()).collect();
    assert_eq!(
        m7_names, names,
        "the {image} image ran a different fixture set"
    );
    for (fixture, m7) in fixtures.iter().zip(&run.fixtures) {
        assert_eq!(m7.planner, fixture.planner.key(), "{}", fixture.name);
        let host = hex(&host_result(fixture.planner, &fixture.problem));
        assert!(
            host == m7.hex,
            "{}: the host and the emulated Cortex-M7 differ (host {} bytes, M7 {} bytes)",
            fixture.name,
            host.len() / 2,
            m7.hex.len() / 2
        );
    }
}
