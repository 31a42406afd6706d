//! The hybrid transfer's image (`cargo firmware-hybrid`): its own build and QEMU run of every
//! hybrid fixture (a ground design re-converged on board through `wire::answer`), each answer
//! the host's byte for byte. Its figures are their own record,
//! `fixtures/golden/m7-figures-hybrid.toml`: per request the instructions, the stack and the
//! instructions per work unit (a step trial of the integrator), and the image's RAM.

use std::fmt::Write as _;
use std::sync::OnceLock;

use crate::disassembly::assert_no_fused_multiply_add;
use crate::host::{assert_bit_identical, hybrid_image_fixtures};
use crate::image::{build_and_run, instructions_or_skip, or_skip, Run};
use crate::prerequisites::{notice, root};
use crate::record::{
    assert_figures, assert_systick_agrees, read_record, record_entries, tables_by, updating,
};

/// The hybrid image's binary.
const BIN: &str = "reconfig-firmware-hybrid";
/// Its record.
const HYBRID_FIGURES_FILE: &str = "fixtures/golden/m7-figures-hybrid.toml";
/// The most M7 instructions one work unit (a DOP853 step trial, with the state-transition
/// matrix's 196 variational equations or without) stood for on the fixtures: measured 210 k on
/// the minimum-energy case (every step with the matrix, none cheap), held here with a margin.
/// A measured bound on these requests, not a proof over every request (there is no kernel
/// image for this planner yet).
const MAX_INSTRUCTIONS_PER_UNIT: u64 = 250_000;
/// Instructions of one published case: 1 G (2.5 s at 400 MHz).
const CEILING_INSTRUCTIONS_HYBRID_REQUEST: u64 = 1_000_000_000;
/// Stack of one solve: the integrator's 13 stages of the 210 equations with the
/// state-transition matrix and the bang-bang law's event location sit on the stack (the
/// planner's workspace is empty), 74 KB measured; 96 KiB, above the other images' 64 KiB.
const BUDGET_STACK_BYTES_HYBRID: u64 = 96 * 1024;
/// The image's RAM (static and stack).
const BUDGET_RAM_BYTES_HYBRID: u64 = 128 * 1024;
const BINARY_FIGURES: [(&str, u64); 3] = [
    ("text_bytes", 1024 * 1024),
    ("static_ram_bytes", 16 * 1024),
    ("hybrid_solution_bytes", 4 * 1024),
];

static RUN: OnceLock<Result<Run, String>> = OnceLock::new();

fn run() -> &'static Result<Run, String> {
    RUN.get_or_init(|| build_and_run(BIN, Some("hybrid"), "hybrid-image"))
}

#[test]
fn hybrid_results_are_bit_identical_to_the_host() {
    let test = "hybrid_results_are_bit_identical_to_the_host";
    let Some(run) = or_skip(test, run()) else {
        return;
    };
    assert_bit_identical(run, &hybrid_image_fixtures(), "hybrid");
}

#[test]
fn hybrid_figures_match_the_record() {
    let test = "hybrid_figures_match_the_record";
    let Some(run) = or_skip(test, run()) else {
        return;
    };
    let Some(instructions) = instructions_or_skip(test, run) else {
        return;
    };
    assert_systick_agrees(run, instructions);
    let path = root().join(HYBRID_FIGURES_FILE);
    let file = read_record(HYBRID_FIGURES_FILE);
    let mut figures = Vec::new();
    let mut text = String::from(
        "# Hybrid transfer image (cargo firmware-hybrid: every hybrid fixture re-converged on\n\
         # board): written by hybrid_figures_match_the_record\n\
         # (RECONFIG_UPDATE_FIGURES=1 cargo test -p reconfig-tests --test qemu_firmware hybrid_).\n\
         # instructions_per_work_unit: a work unit is one DOP853 step trial.\n\n\
         [hybrid_binary]\n",
    );
    let binary: Vec<(&str, u64, u64)> = BINARY_FIGURES
        .iter()
        .map(|&(key, default_budget)| {
            let measured = *run
                .binary
                .get(key)
                .unwrap_or_else(|| panic!("hybrid firmware output lacks {key}"));
            (key, measured, default_budget)
        })
        .collect();
    record_entries(
        &mut text,
        &mut figures,
        file.get("hybrid_binary").and_then(|v| v.as_table()),
        "hybrid image",
        &binary,
    );
    let static_ram = run.binary["static_ram_bytes"];
    let stack = run.largest_stack_bytes();
    text.push_str("\n[hybrid_image]\nplanner = \"hybrid\"\ncommand = \"cargo firmware-hybrid\"\n");
    record_entries(
        &mut text,
        &mut figures,
        file.get("hybrid_image").and_then(|v| v.as_table()),
        "hybrid image",
        &[
            ("stack_bytes", stack, BUDGET_STACK_BYTES_HYBRID),
            ("ram_bytes", static_ram + stack, BUDGET_RAM_BYTES_HYBRID),
        ],
    );
    let recorded_fixtures = tables_by(&file, "hybrid_fixture", "name");
    for (fixture, &count) in run.fixtures.iter().zip(instructions) {
        let units = fixture
            .work_units
            .unwrap_or_else(|| panic!("{}: the hybrid planner meters its work", fixture.name));
        assert!(
            count <= units.saturating_mul(MAX_INSTRUCTIONS_PER_UNIT),
            "{}: {count} M7 instructions for {units} work units, above \
             {MAX_INSTRUCTIONS_PER_UNIT} per unit",
            fixture.name
        );
        let _ = write!(
            text,
            "\n[[hybrid_fixture]]\nname = {:?}\nwork_units = {units}\n\
             instructions_per_work_unit = {:.1}\n",
            fixture.name,
            count as f64 / units.max(1) as f64
        );
        record_entries(
            &mut text,
            &mut figures,
            recorded_fixtures.get(&fixture.name).copied(),
            &fixture.name,
            &[
                ("instructions", count, CEILING_INSTRUCTIONS_HYBRID_REQUEST),
                (
                    "stack_bytes",
                    fixture.stack_bytes,
                    BUDGET_STACK_BYTES_HYBRID,
                ),
            ],
        );
    }
    let measured_path = run.elf.with_file_name("m7-figures-hybrid-measured.toml");
    let _ = std::fs::write(&measured_path, &text);
    let updating = updating();
    if updating {
        std::fs::write(&path, &text).unwrap_or_else(|e| panic!("{HYBRID_FIGURES_FILE}: {e}"));
        notice(&format!(
            "wrote the hybrid image's figures to {HYBRID_FIGURES_FILE}"
        ));
    }
    assert_figures(
        &figures,
        updating,
        ("hybrid image", HYBRID_FIGURES_FILE),
        &measured_path,
    );
}

#[test]
fn hybrid_no_fused_multiply_add_in_the_firmware() {
    let test = "hybrid_no_fused_multiply_add_in_the_firmware";
    if let Some(run) = or_skip(test, run()) {
        assert_no_fused_multiply_add(test, &run.elf);
    }
}
