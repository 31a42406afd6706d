//! # reconfig-firmware-ka
//!
//! Planner A's charged steps on the Cortex-M7, one at a time (issue 33 item 1): every case of
//! `reconfig_core::pseudospectral::kernels`, run by the kernel images' shared loop
//! (`m7/kernel_image.rs`, which gives the output protocol). Built and run by the QEMU test
//! `tests/tests/qemu_firmware/kernels_a_image.rs`, which fails when a charged case costs more
//! than `MAX_INSTRUCTIONS_PER_UNIT` instructions per unit (docs/planner-a.md, "Work budget").
#![cfg_attr(target_os = "none", no_std, no_main)]

#[cfg(target_os = "none")]
#[path = "m7/kernel_image.rs"]
mod kernel_image;

#[cfg(target_os = "none")]
use reconfig_core::pseudospectral::{kernels, Solution, Workspace};

#[cfg(target_os = "none")]
#[cortex_m_rt::entry]
fn main() -> ! {
    static mut WORKSPACE: Workspace = Workspace::new();
    static mut SOLUTION: Solution = Solution::new();
    let set = kernel_image::KernelSet {
        image: "reconfig-firmware-ka",
        planner: "kernels-a",
        count: kernels::CASES.len(),
        name: |i| kernels::CASES.get(i).map_or("", |c| c.name),
        prepare: |i, (ws, out): &mut (&mut Workspace, &mut Solution)| kernels::prepare(i, ws, out),
        run: |i, (ws, out), prepared| kernels::run(i, ws, out, prepared),
        kepler: None,
    };
    kernel_image::run_cases(&set, &mut (WORKSPACE, SOLUTION))
}

#[cfg(not(target_os = "none"))]
fn main() {
    println!(
        "reconfig-firmware-ka runs on the emulated Cortex-M7, not on the host (see the module \
         docs of firmware/src/ka_main.rs)."
    );
}
