//! Planner A's kernel image (`reconfig-firmware-ka`, feature `kernels_a`): every case of
//! `reconfig_core::pseudospectral::kernels` held to `pseudospectral::MAX_INSTRUCTIONS_PER_UNIT`
//! M7 instructions per unit charged (the checks are `kernels_image`'s); its record part
//! generates `docs/planner-a.md`'s "Work budget" table.

use std::sync::OnceLock;

use crate::image::{build_and_run, Run};
use crate::kernels_image::{check, KernelImage};
use crate::record::KERNELS_A_MARKER;
use reconfig_core::pseudospectral::kernels::CASES;
use reconfig_core::pseudospectral::MAX_INSTRUCTIONS_PER_UNIT;

static RUN: OnceLock<Result<Run, String>> = OnceLock::new();

#[test]
fn kernels_a_cases_are_within_the_per_unit_bound() {
    let image = KernelImage {
        test: "kernels_a_cases_are_within_the_per_unit_bound",
        planner: "A",
        marker: KERNELS_A_MARKER,
        key: "ka",
        source: "core/src/pseudospectral/kernels.rs",
        work_units: "core/src/pseudospectral/work_units.rs",
        cases: CASES.iter().map(|c| (c.name, c.charged())).collect(),
        max_instructions_per_unit: MAX_INSTRUCTIONS_PER_UNIT,
        newton_steps_allowed: None,
        update_docs: reconfig_tests::m7_record::update_kernels_a_docs,
    };
    let run = RUN.get_or_init(|| {
        build_and_run("reconfig-firmware-ka", Some("kernels_a"), "kernels-a-image")
    });
    check(&image, run);
}
