//! # reconfig-firmware
//!
//! `reconfig-core` on a Cortex-M7 with a double-precision FPU, emulated by QEMU's `mps2-an500`
//! board. The firmware runs every fixture of both planners (baked in at build time by
//! `build.rs`), with each planner's workspace in static memory, and prints over semihosting:
//! the postcard encoding (hex) of each result (`Result<Solution, PlanError>`), the stack
//! high-water mark of each solve and the binary's section sizes. Executed instructions per solve
//! are counted from outside by the QEMU plugin in `tools/qemu-insn-plugin/`, between the marker
//! functions `reconfig_measure_start` and `reconfig_measure_stop`.
//!
//! Run it with `cargo firmware` (an alias for
//! `cargo run --release --target thumbv7em-none-eabihf -p reconfig-firmware`); see
//! `docs/firmware.md`. On the host this crate builds a stub that says so, so that workspace-wide
//! host builds, lints and tests need no cross toolchain.
#![cfg_attr(target_os = "none", no_std, no_main)]

#[cfg(target_os = "none")]
mod m7;

#[cfg(not(target_os = "none"))]
fn main() {
    println!(
        "reconfig-firmware runs on the emulated Cortex-M7, not on the host. With qemu-system-arm \
         and the thumbv7em-none-eabihf target installed, run:\n  cargo firmware\n(an alias for \
         `cargo run --release --target thumbv7em-none-eabihf -p reconfig-firmware`). \
         See docs/firmware.md."
    );
}
