//! # reconfig-firmware-kb
//!
//! Planner B's charged steps on the Cortex-M7, one at a time (issue 33 item 1): every case of
//! `reconfig_core::impulsive::kernels`, run by the kernel images' shared loop
//! (`m7/kernel_image.rs`, which gives the output protocol), with each case's Kepler solves and
//! Newton steps (the test allows each solve the most steps a request may take). Built and run
//! by the QEMU test `tests/tests/qemu_firmware/kernels_b_image.rs`, which fails when a charged
//! case costs more than `impulsive::work_units::MAX_INSTRUCTIONS_PER_UNIT` instructions per unit
//! (docs/planner-b.md, "Work budget").
#![cfg_attr(target_os = "none", no_std, no_main)]

#[cfg(target_os = "none")]
#[path = "m7/kernel_image.rs"]
mod kernel_image;

#[cfg(target_os = "none")]
use reconfig_core::impulsive::{kernels, newton_counts, newton_counts_reset, Solution, Workspace};

#[cfg(target_os = "none")]
#[cortex_m_rt::entry]
fn main() -> ! {
    static mut WORKSPACE: Workspace = Workspace::new();
    static mut SOLUTION: Solution = Solution::new();
    let set = kernel_image::KernelSet {
        image: "reconfig-firmware-kb",
        planner: "kernels-b",
        count: kernels::CASES.len(),
        name: |i| kernels::CASES.get(i).map_or("", |c| c.name),
        prepare: |i, (ws, out): &mut (&mut Workspace, &mut Solution)| kernels::prepare(i, ws, out),
        run: |i, (ws, out), prepared| kernels::run(i, ws, out, prepared),
        kepler: Some((newton_counts_reset, newton_counts)),
    };
    kernel_image::run_cases(&set, &mut (WORKSPACE, SOLUTION))
}

#[cfg(not(target_os = "none"))]
fn main() {
    println!(
        "reconfig-firmware-kb runs on the emulated Cortex-M7, not on the host (see the module \
         docs of firmware/src/kb_main.rs)."
    );
}
