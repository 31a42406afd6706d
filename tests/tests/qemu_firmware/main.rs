//! The core on the emulated Cortex-M7 (QEMU `mps2-an500`): bit-identical results and budgets.
//!
//! Two images run, each once, shared by their tests: the default two-planner image
//! (`firmware/`, built for `thumbv7em-none-eabihf`; with it the one-planner images of
//! `cargo firmware-a` / `firmware-b`) and the GEO tour's image (`cargo firmware-geo`, module
//! [`geo_image`]). Each runs in `qemu-system-arm` with the instruction-counting plugin
//! `tools/qemu-insn-plugin/` (built here with `gcc`):
//! * `results_are_bit_identical_to_the_host` compares every baked request's postcard-encoded
//!   `wire::Outcome` byte for byte with the host build's answer (`wire::answer` under the same
//!   image limits) to the same request bytes the firmware baked in;
//! * `figures_are_within_budget` checks the instructions per solve, stack high-water, RAM and
//!   section sizes against the budgets in `fixtures/golden/m7-figures.toml`.
//!   Every measured figure must also be within 1 % of the record (drift check); accept a new
//!   record (budgets are kept, the docs' tables are regenerated from it) with
//!   `RECONFIG_UPDATE_FIGURES=1 cargo test -p reconfig-tests --test qemu_firmware`.
//! * `no_fused_multiply_add_in_the_firmware` disassembles the firmware and rejects `vfma`-family
//!   instructions, which would break bit-identity with the host.
//!
//! Without `qemu-system-arm`, the thumb target, `gcc` or `arm-none-eabi-objdump` these tests say
//! that they were skipped, why and how to install what is missing, and pass; with
//! `RECONFIG_REQUIRE_QEMU=1` (set by `.ci/run`) they fail instead.
//!
//! Modules: [`prerequisites`] (what the run needs, skip or fail), [`image`] (build, run and parse
//! an image), [`host`] (the host's answer to a baked request), [`record`] (the figures file, drift
//! and budget checks), [`disassembly`] (the fused multiply-add check), [`default_image`],
//! [`geo_image`], [`leo_image`] and [`hybrid_image`] (the tests of each image; the LEO arc
//! image's and the hybrid image's records are their own files,
//! `fixtures/golden/m7-figures-leo.toml` and `m7-figures-hybrid.toml`), and [`kernels_a_image`] /
//! [`kernels_b_image`] / [`kernels_leo_image`] (planners A's and B's and the LEO arc's charged
//! steps one at a time, checked by [`kernels_image`]: fails when one costs more than the
//! planner's `MAX_INSTRUCTIONS_PER_UNIT` M7 instructions per unit it is charged).

#[path = "../../../firmware/fixture_set.rs"]
mod fixture_set;
#[path = "../../../firmware/image_limits.rs"]
mod image_limits;

mod default_image;
mod disassembly;
mod geo_image;
mod host;
mod hybrid_image;
mod image;
mod kernels_a_image;
mod kernels_b_image;
mod kernels_image;
mod kernels_leo_image;
mod leo_image;
mod prerequisites;
mod record;
