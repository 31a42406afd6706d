//! # reconfig-firmware-hybrid
//!
//! The hybrid transfer's image: the same Cortex-M7 program as `main.rs` (see there and
//! `docs/firmware.md`), built with the `hybrid` feature alone so that it carries only the
//! hybrid fixtures, each a ground design re-converged on board (docs/hybrid.md). Its own binary
//! name keeps its ELF beside the default image's. Run it with `cargo firmware-hybrid`.
#![cfg_attr(target_os = "none", no_std, no_main)]

#[cfg(target_os = "none")]
#[path = "m7/mod.rs"]
mod m7;

#[cfg(not(target_os = "none"))]
fn main() {
    println!(
        "reconfig-firmware-hybrid runs on the emulated Cortex-M7, not on the host. With \
         qemu-system-arm and the thumbv7em-none-eabihf target installed, run:\n  cargo \
         firmware-hybrid\nSee docs/firmware.md."
    );
}
