//! # reconfig-firmware-leo
//!
//! The LEO tour's image: the same Cortex-M7 program as `main.rs` (see there and
//! `docs/firmware.md`), built with the `leo_tour` feature alone so that it carries only the LEO
//! fixtures: the single-arc ones (one arc) and the `[sequence]` ones (the on-board part: the
//! order and its arcs). Its own binary name keeps its ELF beside the default image's. Run it
//! with `cargo firmware-leo`.
#![cfg_attr(target_os = "none", no_std, no_main)]

#[cfg(target_os = "none")]
#[path = "m7/mod.rs"]
mod m7;

#[cfg(not(target_os = "none"))]
fn main() {
    println!(
        "reconfig-firmware-leo runs on the emulated Cortex-M7, not on the host. With \
         qemu-system-arm and the thumbv7em-none-eabihf target installed, run:\n  cargo \
         firmware-leo\nSee docs/firmware.md."
    );
}
