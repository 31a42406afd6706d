//! The host's answer to a baked request, encoded as the firmware prints it: the same request
//! bytes the firmware decoded, answered through the same request path (`wire::answer`) under
//! the same image limits, into fresh buffers.

use std::fmt::Write as _;

use reconfig_core::contract::PlannerKind;
use reconfig_core::wire::{self, AllPlanners, Request};

use crate::fixture_set::EncodedRequest;
use crate::image::Run;
use crate::image_limits::IMAGE_LIMITS;

/// The repository's requests of some planners, encoded as the firmware bakes them.
pub fn fixtures_of(planners: &[PlannerKind]) -> Vec<EncodedRequest> {
    crate::fixture_set::encode_all(
        &crate::prerequisites::root().join("fixtures"),
        &IMAGE_LIMITS,
    )
    .expect("fixtures load")
    .into_iter()
    .filter(|f| planners.contains(&f.planner))
    .collect()
}

/// An image's requests, as `firmware/build.rs` bakes them: its planners' fixtures, then their
/// worst cases (`fixtures/worst-case/`).
fn image_fixtures(planners: &[PlannerKind]) -> Vec<EncodedRequest> {
    let mut set = fixtures_of(planners);
    let root = crate::prerequisites::root();
    let worst =
        crate::fixture_set::worst_cases(&root, &IMAGE_LIMITS, planners).expect("worst cases load");
    crate::fixture_set::append_unique(&mut set, worst).expect("unique names");
    set
}

/// The GEO image's requests: the GEO fixtures and the GEO worst cases.
pub fn geo_image_fixtures() -> Vec<EncodedRequest> {
    image_fixtures(&[PlannerKind::GeoTour])
}

/// The LEO image's requests: the LEO fixtures and the LEO worst cases.
pub fn leo_image_fixtures() -> Vec<EncodedRequest> {
    image_fixtures(&[PlannerKind::LeoArc, PlannerKind::LeoSequence])
}

/// The hybrid image's requests: the hybrid fixtures.
pub fn hybrid_image_fixtures() -> Vec<EncodedRequest> {
    image_fixtures(&[PlannerKind::Hybrid])
}

pub fn hex(bytes: &[u8]) -> String {
    bytes.iter().fold(String::new(), |mut s, b| {
        let _ = write!(s, "{b:02x}");
        s
    })
}

/// The host's encoded outcome for one baked request.
pub fn host_result(request: &[u8]) -> Vec<u8> {
    let request: Request = postcard::from_bytes(request).expect("the baked request decodes");
    let mut buffers = Box::new(AllPlanners::new());
    let outcome = wire::answer(&request, &IMAGE_LIMITS, &mut *buffers);
    postcard::to_stdvec(&outcome).expect("encode")
}

/// The image `image` ran exactly `fixtures`, each with the host's answer byte for byte.
pub fn assert_bit_identical(run: &Run, fixtures: &[EncodedRequest], image: &str) {
    assert!(!fixtures.is_empty(), "no {image} fixtures to compare");
    let names: Vec<&str> = fixtures.iter().map(|f| f.name.as_str()).collect();
    let m7_names: Vec<&str> = run.fixtures.iter().map(|f| f.name.as_str()).collect();
    assert_eq!(
        m7_names, names,
        "the {image} image ran a different fixture set"
    );
    let mismatches: Vec<String> = fixtures
        .iter()
        .zip(&run.fixtures)
        .filter_map(|(fixture, m7)| {
            assert_eq!(m7.planner, fixture.planner.name(), "{}", fixture.name);
            let host = hex(&host_result(&fixture.request));
            (host != m7.hex).then(|| {
                let first = host
                    .bytes()
                    .zip(m7.hex.bytes())
                    .position(|(a, b)| a != b)
                    .unwrap_or(host.len().min(m7.hex.len()));
                format!(
                    "{}: host {} bytes, M7 {} bytes, first difference at byte {}",
                    fixture.name,
                    host.len() / 2,
                    m7.hex.len() / 2,
                    first / 2
                )
            })
        })
        .collect();
    assert!(
        mismatches.is_empty(),
        "answers differ between the host and the emulated Cortex-M7 ({image} image):\n{}",
        mismatches.join("\n")
    );
}
