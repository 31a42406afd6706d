//! The default two-planner image (`cargo firmware`) and the one-planner images
//! (`cargo firmware-a`, `firmware-b`): results bit-identical to the host, figures within budget
//! and drift, no fused multiply-add.

use std::fmt::Write as _;
use std::sync::OnceLock;

use reconfig_core::contract::PlannerKind;

use crate::disassembly::assert_no_fused_multiply_add;
use crate::host::{assert_bit_identical, fixtures_of};
use crate::image::{
    build_and_run, build_image_in, instructions_or_skip, or_skip, run_firmware, FixtureReport, Run,
};
use crate::prerequisites::{check_prerequisites, notice, root};
use crate::record::{
    assert_figures, assert_systick_agrees, read_record, record_entries, record_image_ram,
    tables_by, updating, BUDGET_RAM_BYTES, BUDGET_STACK_BYTES, FIGURES_FILE, RECORD_LOCK,
    UPDATE_COMMAND,
};

const BIN: &str = "reconfig-firmware";
/// Default instruction budgets per solve for a fixture with no entry in the figures file.
const BUDGET_INSTRUCTIONS_PSEUDOSPECTRAL: u64 = 40_000_000;
const BUDGET_INSTRUCTIONS_IMPULSIVE: u64 = 2_000_000;
/// `static_ram_bytes` holds both planners' workspaces and solutions (the firmware carries
/// both); the per-planner figures say what each costs alone.
const BINARY_FIGURES: [(&str, u64); 9] = [
    ("text_bytes", 1024 * 1024),
    ("rodata_bytes", 256 * 1024),
    ("data_bytes", 16 * 1024),
    ("bss_bytes", 256 * 1024),
    ("static_ram_bytes", 256 * 1024),
    ("pseudospectral_workspace_bytes", 256 * 1024),
    ("pseudospectral_solution_bytes", 64 * 1024),
    ("impulsive_workspace_bytes", 64 * 1024),
    ("impulsive_solution_bytes", 16 * 1024),
];

/// A one-planner image (docs/firmware.md, "One image per planner"): its planner's key, the
/// cargo features and alias that build it.
const ONE_PLANNER_IMAGES: [(&str, &str, &str); 2] = [
    ("pseudospectral", "pseudospectral", "cargo firmware-a"),
    ("impulsive", "impulsive", "cargo firmware-b"),
];

/// One one-planner image's run, without the instruction plugin (its figures of interest are its
/// RAM: the solves are the default image's, compared byte for byte).
#[derive(Debug)]
struct OnePlannerImage {
    planner: &'static str,
    command: &'static str,
    run: Run,
}

/// The default image's run and the one-planner images'.
#[derive(Debug)]
struct Runs {
    run: Run,
    images: Vec<OnePlannerImage>,
}

/// Build and run one one-planner image (no plugin: about a second of QEMU), in a folder of its
/// own.
fn one_planner_image(
    (planner, features, command): (&'static str, &str, &'static str),
) -> Result<OnePlannerImage, String> {
    let elf = build_image_in(BIN, Some(features), &format!("{planner}-image"))?;
    let run = run_firmware(&elf, None)?;
    Ok(OnePlannerImage {
        planner,
        command,
        run,
    })
}

static RUNS: OnceLock<Result<Runs, String>> = OnceLock::new();

/// The shared runs, or why there are none (`Err` starting with "SKIP: " for a missing
/// prerequisite).
fn runs() -> &'static Result<Runs, String> {
    RUNS.get_or_init(|| {
        check_prerequisites().map_err(|e| format!("SKIP: {e}"))?;
        let images = ONE_PLANNER_IMAGES
            .into_iter()
            .map(one_planner_image)
            .collect::<Result<Vec<_>, String>>()?;
        let run = build_and_run(BIN, None, "default-image")?;
        Ok(Runs { run, images })
    })
}

#[test]
fn results_are_bit_identical_to_the_host() {
    let Some(Runs { run, .. }) = or_skip("results_are_bit_identical_to_the_host", runs()) else {
        return;
    };
    // The GEO and LEO tours run in their own images (geo_ and leo_ tests).
    assert_bit_identical(
        run,
        &fixtures_of(&[PlannerKind::Pseudospectral, PlannerKind::Impulsive]),
        "default",
    );
}

#[test]
fn one_planner_images_give_the_default_images_results() {
    let test = "one_planner_images_give_the_default_images_results";
    let Some(Runs { run, images }) = or_skip(test, runs()) else {
        return;
    };
    assert_eq!(images.len(), ONE_PLANNER_IMAGES.len());
    for image in images {
        // Exactly its planner's fixtures, in the default image's order, with the same bytes.
        let expected: Vec<&FixtureReport> = run
            .fixtures
            .iter()
            .filter(|f| f.planner == image.planner)
            .collect();
        let names =
            |fs: &[&FixtureReport]| -> Vec<String> { fs.iter().map(|f| f.name.clone()).collect() };
        let got: Vec<&FixtureReport> = image.run.fixtures.iter().collect();
        assert_eq!(
            names(&got),
            names(&expected),
            "{} ran another fixture set than the default image's {} fixtures",
            image.command,
            image.planner
        );
        for (one, both) in got.iter().zip(&expected) {
            assert!(
                one.hex == both.hex,
                "{}: {} and the default image give different results",
                one.name,
                image.command
            );
        }
    }
}

#[test]
fn figures_are_within_budget() {
    let test = "figures_are_within_budget";
    let Some(Runs { run, images }) = or_skip(test, runs()) else {
        return;
    };
    let Some(instructions) = instructions_or_skip(test, run) else {
        return;
    };
    assert_systick_agrees(run, instructions);
    let path = root().join(FIGURES_FILE);
    let file = read_record(FIGURES_FILE);
    let recorded_binary = file.get("binary").and_then(|v| v.as_table());
    let recorded_fixtures = tables_by(&file, "fixture", "name");

    let mut figures = Vec::new();
    let mut text = format!(
        "# Figures of the firmware on the emulated Cortex-M7 (QEMU mps2-an500), each with its budget.\n\
         # The tests fail when a measured figure exceeds its budget (tests/tests/qemu_firmware/).\n\
         # Regenerate the measured values (budgets are kept; edit them by hand):\n\
         #   {UPDATE_COMMAND}\n\
         # instructions: guest instructions executed by the solve alone (QEMU plugin\n\
         #   tools/qemu-insn-plugin; deterministic). stack_bytes: stack high-water during the fixture,\n\
         #   from the top of the stack. ram_bytes = static_ram_bytes + stack_bytes. Sizes in bytes.\n\
         \n[binary]\n"
    );
    let binary: Vec<(&str, u64, u64)> = BINARY_FIGURES
        .iter()
        .map(|&(key, default_budget)| {
            let measured = *run
                .binary
                .get(key)
                .unwrap_or_else(|| panic!("firmware output lacks {key}"));
            (key, measured, default_budget)
        })
        .collect();
    record_entries(&mut text, &mut figures, recorded_binary, "binary", &binary);
    let static_ram = run.binary["static_ram_bytes"];
    for (fixture, &count) in run.fixtures.iter().zip(instructions) {
        let recorded = recorded_fixtures.get(&fixture.name).copied();
        let (default_instructions, work_budget) =
            if fixture.planner == PlannerKind::Impulsive.name() {
                (
                    BUDGET_INSTRUCTIONS_IMPULSIVE,
                    reconfig_core::impulsive::Settings::default().work_budget,
                )
            } else {
                (
                    BUDGET_INSTRUCTIONS_PSEUDOSPECTRAL,
                    reconfig_core::pseudospectral::Settings::default().work_budget,
                )
            };
        let work_units = fixture
            .work_units
            .unwrap_or_else(|| panic!("{}: the firmware printed no work_units", fixture.name));
        let _ = write!(
            text,
            "\n[[fixture]]\nname = {:?}\nplanner = {:?}\n",
            fixture.name, fixture.planner
        );
        record_entries(
            &mut text,
            &mut figures,
            recorded,
            &fixture.name,
            &[
                ("instructions", count, default_instructions),
                // The work units beside the instructions (the calibration in
                // docs/firmware.md); their budget is the planner's default `work_budget`.
                ("work_units", work_units, work_budget),
                ("stack_bytes", fixture.stack_bytes, BUDGET_STACK_BYTES),
                (
                    "ram_bytes",
                    static_ram + fixture.stack_bytes,
                    BUDGET_RAM_BYTES,
                ),
            ],
        );
    }

    // The one-planner images' RAM (static + the largest stack over their fixtures), each
    // measured in its own image: its `main` frame differs from the default image's.
    let recorded_images = tables_by(&file, "image", "planner");
    if !images.is_empty() {
        text.push_str(
            "\n# One-planner images (docs/firmware.md): static RAM from the image's linker \
             symbols,\n# stack_bytes the largest over its fixtures in its own run, ram_bytes \
             their sum.\n",
        );
    }
    for image in images {
        let recorded = recorded_images.get(image.planner).copied();
        let _ = write!(
            text,
            "\n[[image]]\nplanner = {:?}\ncommand = {:?}\n",
            image.planner, image.command
        );
        let static_ram = *image
            .run
            .binary
            .get("static_ram_bytes")
            .unwrap_or_else(|| panic!("{} printed no static_ram_bytes", image.command));
        record_image_ram(
            &mut text,
            &mut figures,
            recorded,
            image.planner,
            static_ram,
            (image.run.largest_stack_bytes(), BUDGET_STACK_BYTES),
        );
    }

    // Every run writes what it measured beside the firmware; the record is that file accepted.
    let measured_path = run.elf.with_file_name("m7-figures-measured.toml");
    let _ = std::fs::write(&measured_path, &text);
    let updating = updating();
    if updating {
        let _lock = RECORD_LOCK.lock().unwrap_or_else(|e| e.into_inner());
        // The kernel images' and the GEO image's parts of the record are their own tests'.
        let existing = std::fs::read_to_string(&path).unwrap_or_default();
        let text = crate::record::with_part(&existing, None, &text);
        std::fs::write(&path, &text).unwrap_or_else(|e| panic!("{FIGURES_FILE}: {e}"));
        notice(&format!("wrote the measured figures to {FIGURES_FILE}"));
        let changed = reconfig_tests::m7_record::update_docs().expect("regenerate the docs");
        let images = reconfig_tests::m7_record::update_images_docs().expect("regenerate the docs");
        if changed || images {
            notice("regenerated the tables of docs/firmware.md from the record");
        }
    }
    assert_figures(&figures, updating, ("M7", FIGURES_FILE), &measured_path);
}

#[test]
fn no_fused_multiply_add_in_the_firmware() {
    let test = "no_fused_multiply_add_in_the_firmware";
    if let Some(Runs { run, .. }) = or_skip(test, runs()) {
        assert_no_fused_multiply_add(test, &run.elf);
    }
}
