//! The LEO arc's kernel image (`reconfig-firmware-kl`, feature `kernels_leo`): every case of
//! `reconfig_core::leo_tour::kernels` held to `leo_tour::work_units::MAX_INSTRUCTIONS_PER_UNIT`
//! M7 instructions per unit charged, each Kepler solve of the search model's flights allowed
//! `mean_j2::KEPLER_MAX_ITER` Newton steps (the checks are `kernels_image`'s); its record part
//! generates `docs/leo-tour.md`'s "Work budget" table.

use std::sync::OnceLock;

use crate::image::{build_and_run, Run};
use crate::kernels_image::{check, KernelImage};
use crate::record::KERNELS_LEO_MARKER;
use reconfig_core::leo_tour::kernels::CASES;
use reconfig_core::leo_tour::mean_j2::KEPLER_MAX_ITER;
use reconfig_core::leo_tour::work_units::MAX_INSTRUCTIONS_PER_UNIT;

static RUN: OnceLock<Result<Run, String>> = OnceLock::new();

#[test]
fn kernels_leo_cases_are_within_the_per_unit_bound() {
    let image = KernelImage {
        test: "kernels_leo_cases_are_within_the_per_unit_bound",
        planner: "LEO arc",
        marker: KERNELS_LEO_MARKER,
        key: "kl",
        source: "core/src/leo_tour/kernels/mod.rs",
        work_units: "core/src/leo_tour/work_units.rs",
        cases: CASES.iter().map(|c| (c.name, c.charged())).collect(),
        max_instructions_per_unit: MAX_INSTRUCTIONS_PER_UNIT,
        newton_steps_allowed: Some(u64::from(KEPLER_MAX_ITER)),
        update_docs: reconfig_tests::m7_record::update_kernels_leo_docs,
    };
    let run = RUN.get_or_init(|| {
        build_and_run(
            "reconfig-firmware-kl",
            Some("kernels_leo"),
            "kernels-leo-image",
        )
    });
    check(&image, run);
}
