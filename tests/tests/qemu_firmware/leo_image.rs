//! The LEO tour's image (`cargo firmware-leo`): its own build and QEMU run of the single-arc
//! LEO fixtures' arc request and of the on-board part of the `[sequence]` fixtures (the
//! sequencing request, then each arc's request of the order it answers), and of the LEO worst
//! cases of `fixtures/worst-case/` likewise, each answered through `wire::answer`. Its figures
//! are their own record, `fixtures/golden/m7-figures-leo.toml`: one entry per request, and per
//! on-board part the sum of its requests' instructions and the largest of their stacks.

use std::collections::BTreeMap;
use std::fmt::Write as _;
use std::sync::OnceLock;

use crate::disassembly::assert_no_fused_multiply_add;
use crate::host::{assert_bit_identical, leo_image_fixtures};
use crate::image::{build_and_run, instructions_or_skip, or_skip, Run};
use crate::prerequisites::{notice, root};
use crate::record::{
    assert_figures, assert_systick_agrees, read_record, record_entries, record_image_ram,
    tables_by, updating, BUDGET_STACK_BYTES,
};
use reconfig_core::leo_tour::work_units::MAX_INSTRUCTIONS_PER_UNIT;

/// The LEO image's binary.
const BIN: &str = "reconfig-firmware-leo";
/// Its record.
const LEO_FIGURES_FILE: &str = "fixtures/golden/m7-figures-leo.toml";
/// Instructions of one request (an arc, or a sequencing): the on-board promise of issue 33,
/// the default (and built-in limit of the) work budget times the most instructions a unit
/// stands for, 4 M x 100 = 400 M (1 s at 400 MHz). Each request is also held to its own
/// units times that bound.
const CEILING_INSTRUCTIONS_LEO_REQUEST: u64 =
    reconfig_core::leo_tour::work_units::DEFAULT_WORK_BUDGET * MAX_INSTRUCTIONS_PER_UNIT;
/// Instructions of the on-board part of Example I's `[sequence]` fixture, summed: the
/// sequencing and its four arcs, five requests of at most 400 M each.
const CEILING_INSTRUCTIONS_LEO_ONBOARD: u64 = 5 * CEILING_INSTRUCTIONS_LEO_REQUEST;
/// Stack of the on-board part: the sequencing's caches and the arc search's large buffers are
/// in the caller's workspace (static), so it is held to the 64 KiB of each single solve (it
/// needed 96 KiB while the caches, about 27 KB for 8 clients, sat on the stack below one arc
/// search of about 32 KB).
const BUDGET_STACK_BYTES_LEO_ONBOARD: u64 = BUDGET_STACK_BYTES;
const BINARY_FIGURES: [(&str, u64); 6] = [
    ("text_bytes", 1024 * 1024),
    ("static_ram_bytes", 256 * 1024),
    // The caller-owned buffers (statics of the image): the arc search's workspace, the
    // sequencing's (its memos and an arc workspace, which the arc requests use too), an arc's
    // answer, the sequencing's answer.
    ("leo_workspace_bytes", 32 * 1024),
    ("leo_sequence_workspace_bytes", 64 * 1024),
    ("leo_arc_solution_bytes", 4 * 1024),
    ("leo_sequence_bytes", 8 * 1024),
];

static RUN: OnceLock<Result<Run, String>> = OnceLock::new();

fn run() -> &'static Result<Run, String> {
    RUN.get_or_init(|| build_and_run(BIN, Some("leo_tour"), "leo-image"))
}

#[test]
fn leo_results_are_bit_identical_to_the_host() {
    let test = "leo_results_are_bit_identical_to_the_host";
    let Some(run) = or_skip(test, run()) else {
        return;
    };
    assert_bit_identical(run, &leo_image_fixtures(), "LEO");
}

#[test]
fn leo_figures_match_the_record() {
    let test = "leo_figures_match_the_record";
    let Some(run) = or_skip(test, run()) else {
        return;
    };
    let Some(instructions) = instructions_or_skip(test, run) else {
        return;
    };
    assert_systick_agrees(run, instructions);
    let path = root().join(LEO_FIGURES_FILE);
    let file = read_record(LEO_FIGURES_FILE);
    let mut figures = Vec::new();
    let mut text = String::from(
        "# LEO tour image (cargo firmware-leo: one arc, and the on-board part of a [sequence]\n\
         # fixture): written by leo_figures_match_the_record\n\
         # (RECONFIG_UPDATE_FIGURES=1 cargo test -p reconfig-tests --test qemu_firmware leo_).\n\
         # instructions_budget of a request: 400 M, the work budget's bound (issue 33).\n\n\
         [leo_binary]\n",
    );
    let binary: Vec<(&str, u64, u64)> = BINARY_FIGURES
        .iter()
        .map(|&(key, default_budget)| {
            let measured = *run
                .binary
                .get(key)
                .unwrap_or_else(|| panic!("LEO firmware output lacks {key}"));
            (key, measured, default_budget)
        })
        .collect();
    let recorded_binary = file.get("leo_binary").and_then(|v| v.as_table());
    record_entries(
        &mut text,
        &mut figures,
        recorded_binary,
        "LEO image",
        &binary,
    );
    let recorded_image = file.get("leo_image").and_then(|v| v.as_table());
    let static_ram = run.binary["static_ram_bytes"];
    text.push_str("\n[leo_image]\nplanner = \"leo-tour\"\ncommand = \"cargo firmware-leo\"\n");
    record_image_ram(
        &mut text,
        &mut figures,
        recorded_image,
        "leo-tour",
        static_ram,
        (run.largest_stack_bytes(), BUDGET_STACK_BYTES_LEO_ONBOARD),
    );
    let recorded_fixtures = tables_by(&file, "leo_fixture", "name");
    let parts: BTreeMap<String, Option<String>> = leo_image_fixtures()
        .into_iter()
        .map(|f| (f.name, f.part_of))
        .collect();
    // Per on-board part: instructions summed, the largest stack, the requests' work units
    // summed.
    let mut onboard: BTreeMap<String, (u64, u64, u64)> = BTreeMap::new();
    for (fixture, &count) in run.fixtures.iter().zip(instructions) {
        let recorded = recorded_fixtures.get(&fixture.name).copied();
        let _ = write!(text, "\n[[leo_fixture]]\nname = {:?}\n", fixture.name);
        let units = fixture.work_units;
        let (ceiling, stack_budget) = match parts.get(&fixture.name).cloned().flatten() {
            Some(part) => {
                let sum = onboard.entry(part.clone()).or_default();
                sum.0 += count;
                sum.1 = sum.1.max(fixture.stack_bytes);
                sum.2 += units.unwrap_or(0);
                let _ = writeln!(text, "part_of = {part:?}");
                (
                    CEILING_INSTRUCTIONS_LEO_REQUEST,
                    BUDGET_STACK_BYTES_LEO_ONBOARD,
                )
            }
            None => (CEILING_INSTRUCTIONS_LEO_REQUEST, BUDGET_STACK_BYTES),
        };
        // Every LEO request is metered (an arc, a sequencing): its units bound its instructions.
        let bound = units.map(|u| u.saturating_mul(MAX_INSTRUCTIONS_PER_UNIT));
        assert!(
            bound.is_some_and(|b| count <= b),
            "{}: {count} M7 instructions for {units:?} work units, above {MAX_INSTRUCTIONS_PER_UNIT} \
             per unit",
            fixture.name
        );
        if let Some(units) = units {
            let _ = writeln!(
                text,
                "work_units = {units}\ninstructions_per_work_unit = {:.1}",
                count as f64 / units.max(1) as f64
            );
        }
        record_entries(
            &mut text,
            &mut figures,
            recorded,
            &fixture.name,
            &[
                ("instructions", count, ceiling),
                ("stack_bytes", fixture.stack_bytes, stack_budget),
            ],
        );
    }
    for (name, (count, stack, units)) in &onboard {
        let recorded = recorded_fixtures.get(name).copied();
        let _ = write!(
            text,
            "\n[[leo_fixture]]\nname = {name:?}\npart = \"on-board: the sequencing request and \
             every arc request of its order, summed\"\nwork_units = {units}\n"
        );
        record_entries(
            &mut text,
            &mut figures,
            recorded,
            name,
            &[
                ("instructions", *count, CEILING_INSTRUCTIONS_LEO_ONBOARD),
                ("stack_bytes", *stack, BUDGET_STACK_BYTES_LEO_ONBOARD),
            ],
        );
    }
    let measured_path = run.elf.with_file_name("m7-figures-leo-measured.toml");
    let _ = std::fs::write(&measured_path, &text);
    let updating = updating();
    if updating {
        std::fs::write(&path, &text).unwrap_or_else(|e| panic!("{LEO_FIGURES_FILE}: {e}"));
        notice(&format!(
            "wrote the LEO image's figures to {LEO_FIGURES_FILE}"
        ));
    }
    assert_figures(
        &figures,
        updating,
        ("LEO image", LEO_FIGURES_FILE),
        &measured_path,
    );
}

#[test]
fn leo_no_fused_multiply_add_in_the_firmware() {
    let test = "leo_no_fused_multiply_add_in_the_firmware";
    if let Some(run) = or_skip(test, run()) {
        assert_no_fused_multiply_add(test, &run.elf);
    }
}
