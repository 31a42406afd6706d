//! The GEO servicing tour's image (`cargo firmware-geo`): its own build and a short QEMU run of
//! the GEO fixtures alone, so that the default two-planner image keeps its RAM. Its figures are
//! the record's GEO part (after [`RECORD_MARKER`]), written by its own test.

use std::fmt::Write as _;
use std::sync::OnceLock;

use crate::disassembly::assert_no_fused_multiply_add;
use crate::host::{assert_bit_identical, fixtures_of};
use crate::image::{build_and_run, instructions_or_skip, or_skip, Run};
use crate::prerequisites::{notice, root};
use crate::record::{
    assert_figures, assert_systick_agrees, read_record, record_entries, record_image_ram,
    tables_by, updating, BUDGET_RAM_BYTES, BUDGET_STACK_BYTES, FIGURES_FILE, RECORD_LOCK,
};
use reconfig_core::contract::PlannerKind;

/// The GEO image's binary.
const BIN: &str = "reconfig-firmware-geo";
/// First line of the record's GEO part; everything after it belongs to the GEO image.
const RECORD_MARKER: &str =
    "# GEO servicing tour image (cargo firmware-geo): written by geo_figures_are_within_budget.";
/// Instructions per GEO tour solve (issue 12: at most 20 M for 16 clients).
const BUDGET_INSTRUCTIONS_GEO_TOUR: u64 = 20_000_000;
const BINARY_FIGURES: [(&str, u64); 4] = [
    ("text_bytes", 1024 * 1024),
    ("static_ram_bytes", 256 * 1024),
    ("geo_tour_workspace_bytes", 64 * 1024),
    ("geo_tour_solution_bytes", 16 * 1024),
];

static RUN: OnceLock<Result<Run, String>> = OnceLock::new();

/// The record's GEO part (from its marker to the end; empty when absent).
pub fn record_part(record: &str) -> &str {
    record.find(RECORD_MARKER).map_or("", |at| &record[at..])
}

/// The GEO image's run (shared by the GEO tests), or why there is none.
fn run() -> &'static Result<Run, String> {
    RUN.get_or_init(|| build_and_run(BIN, Some("geo_tour"), "geo-image"))
}

#[test]
fn geo_results_are_bit_identical_to_the_host() {
    let test = "geo_results_are_bit_identical_to_the_host";
    let Some(run) = or_skip(test, run()) else {
        return;
    };
    assert_bit_identical(run, &fixtures_of(&[PlannerKind::GeoTour]), "GEO");
}

#[test]
fn geo_figures_are_within_budget() {
    let test = "geo_figures_are_within_budget";
    let Some(run) = or_skip(test, run()) else {
        return;
    };
    let Some(instructions) = instructions_or_skip(test, run) else {
        return;
    };
    assert_systick_agrees(run, instructions);
    let path = root().join(FIGURES_FILE);
    let file = read_record(FIGURES_FILE);
    let recorded_binary = file.get("geo_binary").and_then(|v| v.as_table());
    let recorded_fixtures = tables_by(&file, "geo_fixture", "name");
    let mut figures = Vec::new();
    let mut text =
        format!("{RECORD_MARKER}\n# Its own QEMU run of the GEO fixtures.\n\n[geo_binary]\n");
    let binary: Vec<(&str, u64, u64)> = BINARY_FIGURES
        .iter()
        .map(|&(key, default_budget)| {
            let measured = *run
                .binary
                .get(key)
                .unwrap_or_else(|| panic!("GEO firmware output lacks {key}"));
            (key, measured, default_budget)
        })
        .collect();
    record_entries(
        &mut text,
        &mut figures,
        recorded_binary,
        "GEO image",
        &binary,
    );
    // The GEO image's RAM as one image among the others (`[[image]]` of the main part): the
    // same three figures, the same 230 KiB budget.
    let recorded_image = file.get("geo_image").and_then(|v| v.as_table());
    let static_ram = run.binary["static_ram_bytes"];
    text.push_str("\n[geo_image]\nplanner = \"geo-tour\"\ncommand = \"cargo firmware-geo\"\n");
    record_image_ram(
        &mut text,
        &mut figures,
        recorded_image,
        "geo-tour",
        static_ram,
        (run.largest_stack_bytes(), BUDGET_STACK_BYTES),
    );
    for (fixture, &count) in run.fixtures.iter().zip(instructions) {
        let recorded = recorded_fixtures.get(&fixture.name).copied();
        let _ = write!(text, "\n[[geo_fixture]]\nname = {:?}\n", fixture.name);
        record_entries(
            &mut text,
            &mut figures,
            recorded,
            &fixture.name,
            &[
                ("instructions", count, BUDGET_INSTRUCTIONS_GEO_TOUR),
                ("stack_bytes", fixture.stack_bytes, BUDGET_STACK_BYTES),
                (
                    "ram_bytes",
                    static_ram + fixture.stack_bytes,
                    BUDGET_RAM_BYTES,
                ),
            ],
        );
    }
    let measured_path = run.elf.with_file_name("m7-figures-measured.toml");
    let _ = std::fs::write(&measured_path, &text);
    let updating = updating();
    if updating {
        let _lock = RECORD_LOCK.lock().unwrap_or_else(|e| e.into_inner());
        let existing = std::fs::read_to_string(&path).unwrap_or_default();
        let main_part = &existing[..existing.len() - record_part(&existing).len()];
        let mut record = main_part.trim_end().to_owned();
        record.push_str("\n\n");
        record.push_str(&text);
        std::fs::write(&path, &record).unwrap_or_else(|e| panic!("{FIGURES_FILE}: {e}"));
        notice(&format!("wrote the GEO image's figures to {FIGURES_FILE}"));
        reconfig_tests::m7_record::update_geo_docs().expect("regenerate the docs");
        reconfig_tests::m7_record::update_images_docs().expect("regenerate the docs");
    }
    assert_figures(
        &figures,
        updating,
        ("GEO image", FIGURES_FILE),
        &measured_path,
    );
}

#[test]
fn geo_no_fused_multiply_add_in_the_firmware() {
    let test = "geo_no_fused_multiply_add_in_the_firmware";
    if let Some(run) = or_skip(test, run()) {
        assert_no_fused_multiply_add(test, &run.elf);
    }
}
