//! Planner A's kernel image (`reconfig-firmware-ka`, feature `kernels_a`): every case of
//! `reconfig_core::pseudospectral::kernels` (each charged step of a solve, on its dearest path)
//! between the instruction markers, one `fixture` line per case whose `work_units` are the units
//! the solve charges for it. The test fails when a charged case's M7 instructions exceed its
//! units x [`MAX_INSTRUCTIONS_PER_UNIT`]: that per-unit bound is what makes
//! `work_budget x MAX_INSTRUCTIONS_PER_UNIT` bound a solve's instructions (issue 33 item 1).
//! Its figures are the record's kernels part (from [`RECORD_MARKER`] to the GEO part), written
//! by its own test; `docs/planner-a.md`'s "Work budget" table is generated from it.

use std::fmt::Write as _;
use std::sync::OnceLock;

use crate::image::{build_and_run, instructions_or_skip, or_skip, Run};
use crate::prerequisites::{notice, root};
use crate::record::{
    assert_figures, assert_systick_agrees, read_record, tables_by, updating, Figure, FIGURES_FILE,
    RECORD_LOCK,
};
use reconfig_core::pseudospectral::kernels::CASES;
use reconfig_core::pseudospectral::MAX_INSTRUCTIONS_PER_UNIT;

/// The kernel image's binary.
const BIN: &str = "reconfig-firmware-ka";
/// First line of the record's kernels part; it ends where the GEO part starts (or at the end).
pub const RECORD_MARKER: &str = "# Planner A's kernel image (reconfig-firmware-ka): written by \
                                 kernels_a_cases_are_within_the_per_unit_bound.";

static RUN: OnceLock<Result<Run, String>> = OnceLock::new();

/// The record's kernels part (from its marker to the GEO part or the end; empty when absent).
pub fn record_part(record: &str) -> &str {
    let Some(start) = record.find(RECORD_MARKER) else {
        return "";
    };
    let rest = &record[start..];
    let geo = crate::geo_image::record_part(rest);
    &rest[..rest.len() - geo.len()]
}

/// The kernel image's run, or why there is none.
fn run() -> &'static Result<Run, String> {
    RUN.get_or_init(|| build_and_run(BIN, Some("kernels_a"), "kernels-a-image"))
}

#[test]
fn kernels_a_cases_are_within_the_per_unit_bound() {
    let test = "kernels_a_cases_are_within_the_per_unit_bound";
    let Some(run) = or_skip(test, run()) else {
        return;
    };
    let Some(instructions) = instructions_or_skip(test, run) else {
        return;
    };
    assert_systick_agrees(run, instructions);
    assert_eq!(
        run.fixtures.len(),
        CASES.len(),
        "the kernel image ran {} cases, the core has {}",
        run.fixtures.len(),
        CASES.len()
    );
    let file = read_record(FIGURES_FILE);
    let recorded = tables_by(&file, "ka_kernel", "name");
    let mut figures = Vec::new();
    let mut over = Vec::new();
    let mut text = format!(
        "{RECORD_MARKER}\n# Each case of core/src/pseudospectral/kernels.rs: its M7 instructions, \
         the units the solve\n# charges for it, and its budget units x \
         MAX_INSTRUCTIONS_PER_UNIT (none for an uncharged case).\n\n[ka]\n\
         max_instructions_per_unit = {MAX_INSTRUCTIONS_PER_UNIT}\n"
    );
    for ((fixture, &count), case) in run.fixtures.iter().zip(instructions).zip(CASES) {
        assert_eq!(fixture.name, case.name, "the kernel image's case order");
        let units = fixture.work_units.unwrap_or(0);
        let recorded = recorded.get(&fixture.name).copied();
        let _ = write!(
            text,
            "\n[[ka_kernel]]\nname = {:?}\ncharged = {}\ninstructions = {count}\nunits = {units}\n",
            fixture.name,
            case.charged()
        );
        if case.charged() {
            let budget = units.saturating_mul(MAX_INSTRUCTIONS_PER_UNIT);
            let _ = writeln!(text, "instructions_budget = {budget}");
            // A charged case that charges nothing (a step that did not run) proves nothing.
            if units == 0 || count > budget {
                over.push(format!(
                    "{}: {count} instructions for {units} units ({:.2} per unit, at most \
                     {MAX_INSTRUCTIONS_PER_UNIT})",
                    fixture.name,
                    count as f64 / units.max(1) as f64
                ));
            }
        }
        let record = |key: &str| {
            recorded
                .and_then(|t| t.get(key))
                .and_then(toml::Value::as_integer)
                .and_then(|v| u64::try_from(v).ok())
        };
        figures.push(Figure {
            what: format!("{} instructions", fixture.name),
            measured: count,
            recorded: record("instructions"),
            budget: u64::MAX,
        });
        figures.push(Figure {
            what: format!("{} units", fixture.name),
            measured: units,
            recorded: record("units"),
            budget: u64::MAX,
        });
    }
    let measured_path = run.elf.with_file_name("m7-figures-measured.toml");
    let _ = std::fs::write(&measured_path, &text);
    let updating = updating();
    if updating && over.is_empty() {
        let _lock = RECORD_LOCK.lock().unwrap_or_else(|e| e.into_inner());
        let path = root().join(FIGURES_FILE);
        let existing = std::fs::read_to_string(&path).unwrap_or_default();
        let geo_part = crate::geo_image::record_part(&existing);
        let before_geo = &existing[..existing.len() - geo_part.len()];
        let main_part = &before_geo[..before_geo.len() - record_part(before_geo).len()];
        let mut record = main_part.trim_end().to_owned();
        record.push_str("\n\n");
        record.push_str(&text);
        if !geo_part.is_empty() {
            record.push('\n');
            record.push_str(geo_part);
        }
        std::fs::write(&path, &record).unwrap_or_else(|e| panic!("{FIGURES_FILE}: {e}"));
        notice(&format!(
            "wrote the kernel image's figures to {FIGURES_FILE}"
        ));
        reconfig_tests::m7_record::update_kernels_a_docs().expect("regenerate the docs");
    }
    assert!(
        over.is_empty(),
        "planner A's kernel cases over {MAX_INSTRUCTIONS_PER_UNIT} M7 instructions per unit \
         (raise the step's charge in core/src/pseudospectral/work_units.rs):\n{}",
        over.join("\n")
    );
    assert_figures(
        &figures,
        updating,
        ("kernel image", FIGURES_FILE),
        &measured_path,
    );
}
