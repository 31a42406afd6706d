//! Planner B's kernel image (`reconfig-firmware-kb`, feature `kernels_b`): every case of
//! `reconfig_core::impulsive::kernels` held to `impulsive::work_units::MAX_INSTRUCTIONS_PER_UNIT`
//! M7 instructions per unit charged, each Kepler solve allowed `kepler_max_iter`'s built-in
//! limit of Newton steps (the checks are `kernels_image`'s); its record part generates
//! `docs/planner-b.md`'s "Work budget" table.

use std::sync::OnceLock;

use crate::image::{build_and_run, Run};
use crate::kernels_image::{check, KernelImage};
use crate::record::KERNELS_B_MARKER;
use reconfig_core::impulsive::kernels::CASES;
use reconfig_core::impulsive::{Settings, MAX_INSTRUCTIONS_PER_UNIT};

static RUN: OnceLock<Result<Run, String>> = OnceLock::new();

#[test]
fn kernels_b_cases_are_within_the_per_unit_bound() {
    let image = KernelImage {
        test: "kernels_b_cases_are_within_the_per_unit_bound",
        planner: "B",
        marker: KERNELS_B_MARKER,
        key: "kb",
        source: "core/src/impulsive/kernels.rs",
        work_units: "core/src/impulsive/work_units.rs",
        cases: CASES.iter().map(|c| (c.name, c.charged())).collect(),
        max_instructions_per_unit: MAX_INSTRUCTIONS_PER_UNIT,
        // The built-in limit of `kepler_max_iter` is its default (AtMost).
        newton_steps_allowed: Some(u64::from(Settings::default().kepler_max_iter)),
        update_docs: reconfig_tests::m7_record::update_kernels_b_docs,
    };
    let run = RUN.get_or_init(|| {
        build_and_run("reconfig-firmware-kb", Some("kernels_b"), "kernels-b-image")
    });
    check(&image, run);
}
