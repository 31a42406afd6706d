//! # reconfig-firmware-kl
//!
//! The LEO arc's charged steps on the Cortex-M7, one at a time (issue 33 item 1): every case of
//! `reconfig_core::leo_tour::kernels`, run by the kernel images' shared loop
//! (`m7/kernel_image.rs`, which gives the output protocol), with each case's Kepler solves and
//! Newton steps (the test allows each solve the most steps the search model's flights may
//! take). Built and run by the QEMU test `tests/tests/qemu_firmware/kernels_leo_image.rs`,
//! which fails when a charged case costs more than
//! `leo_tour::work_units::MAX_INSTRUCTIONS_PER_UNIT` instructions per unit (docs/leo-tour.md,
//! "Work budget").
#![cfg_attr(target_os = "none", no_std, no_main)]

#[cfg(target_os = "none")]
#[path = "m7/kernel_image.rs"]
mod kernel_image;

#[cfg(target_os = "none")]
use reconfig_core::impulsive::{newton_counts, newton_counts_reset};
#[cfg(target_os = "none")]
use reconfig_core::leo_tour::kernels;
#[cfg(target_os = "none")]
use reconfig_core::leo_tour::tour_order::SequenceWorkspace;

#[cfg(target_os = "none")]
#[cortex_m_rt::entry]
fn main() -> ! {
    static mut WORKSPACE: SequenceWorkspace = SequenceWorkspace::new();
    let set = kernel_image::KernelSet {
        image: "reconfig-firmware-kl",
        planner: "kernels-leo",
        count: kernels::CASES.len(),
        name: |i| kernels::CASES.get(i).map_or("", |c| c.name),
        prepare: |i, ws: &mut &mut SequenceWorkspace| kernels::prepare(i, ws),
        run: |i, ws, prepared| prepared.as_ref().map_or(0, |p| kernels::run(i, ws, p)),
        kepler: Some((newton_counts_reset, newton_counts)),
    };
    let mut state: &mut SequenceWorkspace = WORKSPACE;
    kernel_image::run_cases(&set, &mut state)
}

#[cfg(not(target_os = "none"))]
fn main() {
    println!(
        "reconfig-firmware-kl runs on the emulated Cortex-M7, not on the host (see the module \
         docs of firmware/src/kl_main.rs)."
    );
}
