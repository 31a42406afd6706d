//! The GEO servicing tour's image (`cargo firmware-geo`): its own build and a short QEMU run of
//! the GEO fixtures alone (`fixtures/geo-*` and the GEO worst cases of `fixtures/worst-case/`),
//! so that the default two-planner image keeps its RAM, then of the work meter's kernel cases
//! (`geo_tour::kernels`). Its figures are the record's GEO part (after `record::GEO_MARKER`),
//! written by its own test: per fixture its instructions, work units, stack and RAM; per kernel
//! case its instructions and the units the solve charges for it; and the work budget's bound,
//! the largest instructions per unit over the kernels (at most `MAX_INSTRUCTIONS_PER_UNIT`) times
//! the default budget (at most 400 M instructions; docs/geo-tour.md, "Work budget").

use std::fmt::Write as _;
use std::sync::OnceLock;

use crate::disassembly::assert_no_fused_multiply_add;
use crate::fixture_set::is_worst_case;
use crate::host::{assert_bit_identical, geo_image_fixtures};
use crate::image::{build_and_run, instructions_or_skip, or_skip, Run};
use crate::prerequisites::{notice, root};
use crate::record::{
    assert_figures, assert_systick_agrees, read_record, record_entries, record_image_ram,
    table_u64, tables_by, updating, with_part, Figure, BUDGET_RAM_BYTES, BUDGET_STACK_BYTES,
    FIGURES_FILE, GEO_MARKER, RECORD_LOCK,
};
use reconfig_core::geo_tour::{kernels, DEFAULT_WORK_BUDGET, MAX_INSTRUCTIONS_PER_UNIT};

/// The GEO image's binary.
const BIN: &str = "reconfig-firmware-geo";
/// Instructions per GEO tour solve (issue 12: at most 20 M for 16 clients).
const BUDGET_INSTRUCTIONS_GEO_TOUR: u64 = 20_000_000;
/// Instructions of any GEO request within the built-in limits, the worst cases among them
/// (issue 33: the default work budget times the bound per unit, 400 M).
const BUDGET_INSTRUCTIONS_ANY_REQUEST: u64 = DEFAULT_WORK_BUDGET * MAX_INSTRUCTIONS_PER_UNIT;
const BINARY_FIGURES: [(&str, u64); 4] = [
    ("text_bytes", 1024 * 1024),
    ("static_ram_bytes", 256 * 1024),
    ("geo_tour_workspace_bytes", 64 * 1024),
    ("geo_tour_solution_bytes", 16 * 1024),
];

static RUN: OnceLock<Result<Run, String>> = OnceLock::new();

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
    assert_bit_identical(run, &geo_image_fixtures(), "GEO");
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
        format!("{GEO_MARKER}\n# Its own QEMU run of the GEO fixtures.\n\n[geo_binary]\n");
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
    let baked = geo_image_fixtures();
    assert_eq!(
        run.fixtures.iter().map(|f| &f.name).collect::<Vec<_>>(),
        baked.iter().map(|f| &f.name).collect::<Vec<_>>(),
        "the GEO image ran a different fixture set"
    );
    let mut fixture_units = Vec::new();
    for ((fixture, &count), encoded) in run.fixtures.iter().zip(instructions).zip(&baked) {
        let recorded = recorded_fixtures.get(&fixture.name).copied();
        let units = fixture
            .work_units
            .unwrap_or_else(|| panic!("{}: the GEO image reports no work units", fixture.name));
        fixture_units.push(units);
        // The published cases and 16 clients: 20 M (issue 12); a worst case: 400 M (issue 33).
        let instructions_budget = if is_worst_case(encoded) {
            BUDGET_INSTRUCTIONS_ANY_REQUEST
        } else {
            BUDGET_INSTRUCTIONS_GEO_TOUR
        };
        let _ = write!(
            text,
            "\n[[geo_fixture]]\nname = {:?}\nplanner = \"geo-tour\"\n",
            fixture.name
        );
        record_entries(
            &mut text,
            &mut figures,
            recorded,
            &fixture.name,
            &[
                ("instructions", count, instructions_budget),
                ("work_units", units, DEFAULT_WORK_BUDGET),
                ("stack_bytes", fixture.stack_bytes, BUDGET_STACK_BYTES),
                (
                    "ram_bytes",
                    static_ram + fixture.stack_bytes,
                    BUDGET_RAM_BYTES,
                ),
            ],
        );
    }
    // Whatever the record's budgets say: no kernel over its units x MAX_INSTRUCTIONS_PER_UNIT,
    // no GEO request over 400 M instructions or over the default work budget, and every solve
    // within its units times the kernels' largest instructions per unit (the bound
    // docs/geo-tour.md proves, seen on every fixture).
    let mut broken = Vec::new();
    let bound = record_kernels(run, &file, (&mut text, &mut figures), &mut broken);
    for ((fixture, &count), &units) in run.fixtures.iter().zip(instructions).zip(&fixture_units) {
        if count > BUDGET_INSTRUCTIONS_ANY_REQUEST || units > DEFAULT_WORK_BUDGET {
            broken.push(format!(
                "{}: {count} instructions (at most {BUDGET_INSTRUCTIONS_ANY_REQUEST}), {units} \
                 units (at most {DEFAULT_WORK_BUDGET})",
                fixture.name
            ));
        }
        if u128::from(count) * 1000 > u128::from(units) * u128::from(bound.milli) {
            broken.push(format!(
                "{}: {count} instructions > {units} units x {:.3} per unit (the kernels' \
                 largest, {})",
                fixture.name,
                bound.milli as f64 / 1000.0,
                bound.kernel
            ));
        }
    }
    let measured_path = run.elf.with_file_name("m7-figures-measured.toml");
    let _ = std::fs::write(&measured_path, &text);
    let updating = updating();
    if updating {
        let _lock = RECORD_LOCK.lock().unwrap_or_else(|e| e.into_inner());
        let existing = std::fs::read_to_string(&path).unwrap_or_default();
        let record = with_part(&existing, Some(GEO_MARKER), &text);
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
    assert!(
        broken.is_empty(),
        "GEO kernels or requests beyond the work budget's bound on the emulated Cortex-M7:\n{}",
        broken.join("\n")
    );
}

/// The kernels' largest instructions per unit, x 1000 rounded up, and the case it comes from.
struct Bound {
    milli: u64,
    kernel: String,
}

/// Write the kernel cases' figures (`[[geo_kernel]]`: instructions within units x
/// `MAX_INSTRUCTIONS_PER_UNIT`, units, stack) and the work budget's bound
/// (`[geo_work_budget]`) into `text` and `figures`; push each kernel over its ceiling (whatever
/// the record says) onto `broken`. The bound, for the fixtures' check.
fn record_kernels(
    run: &Run,
    file: &toml::Table,
    (text, figures): (&mut String, &mut Vec<Figure>),
    broken: &mut Vec<String>,
) -> Bound {
    let counts = run
        .kernel_instructions
        .as_deref()
        .expect("the plugin counted the kernel cases");
    let names: Vec<&str> = run.kernels.iter().map(|k| k.name.as_str()).collect();
    let cases: Vec<&str> = kernels::CASES.iter().map(|c| c.name).collect();
    assert_eq!(names, cases, "the GEO image ran a different kernel set");
    let recorded_kernels = tables_by(file, "geo_kernel", "name");
    let mut bound = Bound {
        milli: 0,
        kernel: String::new(),
    };
    for (kernel, &count) in run.kernels.iter().zip(counts) {
        assert!(
            kernel.systick_instructions.abs_diff(count) <= 200 + count / 1000,
            "kernel {}: the plugin counted {count} instructions, the firmware's SysTick {}",
            kernel.name,
            kernel.systick_instructions
        );
        assert!(kernel.units > 0, "kernel {}: no units charged", kernel.name);
        // Its ceiling: the units the solve charges for it times the bound per unit, computed
        // here (never a budget read back from the record).
        let ceiling = kernel.units.saturating_mul(MAX_INSTRUCTIONS_PER_UNIT);
        if count > ceiling {
            broken.push(format!(
                "kernel {}: {count} instructions > {} units x {MAX_INSTRUCTIONS_PER_UNIT} (raise \
                 its constant in core/src/geo_tour/work_units.rs)",
                kernel.name, kernel.units
            ));
        }
        let milli = (u128::from(count) * 1000).div_ceil(u128::from(kernel.units));
        let milli = u64::try_from(milli).unwrap_or(u64::MAX);
        if milli > bound.milli {
            bound = Bound {
                milli,
                kernel: kernel.name.clone(),
            };
        }
        let recorded = recorded_kernels.get(&kernel.name).copied();
        let _ = write!(text, "\n[[geo_kernel]]\nname = {:?}\n", kernel.name);
        for (key, measured, budget) in [
            ("instructions", count, ceiling),
            ("units", kernel.units, DEFAULT_WORK_BUDGET),
            ("stack_bytes", kernel.stack_bytes, BUDGET_STACK_BYTES),
        ] {
            let _ = writeln!(text, "{key} = {measured}\n{key}_budget = {budget}");
            figures.push(Figure {
                what: format!("kernel {} {key}", kernel.name),
                measured,
                recorded: table_u64(recorded, key),
                budget,
            });
        }
    }
    // The bound: the default budget times the largest instructions per unit.
    let worst = DEFAULT_WORK_BUDGET.saturating_mul(bound.milli) / 1000;
    let recorded = file.get("geo_work_budget").and_then(|v| v.as_table());
    let _ = write!(
        text,
        "\n[geo_work_budget]\n# The kernels' largest instructions per unit (x 1000, rounded up) and \
         the default work budget\n# times it: the most instructions a GEO request may take.\n\
         max_kernel = {:?}\ndefault_work_budget = {DEFAULT_WORK_BUDGET}\n",
        bound.kernel
    );
    for (key, measured, budget) in [
        (
            "max_instructions_per_unit_milli",
            bound.milli,
            MAX_INSTRUCTIONS_PER_UNIT * 1000,
        ),
        (
            "worst_case_instructions",
            worst,
            BUDGET_INSTRUCTIONS_ANY_REQUEST,
        ),
    ] {
        let _ = writeln!(text, "{key} = {measured}\n{key}_budget = {budget}");
        figures.push(Figure {
            what: format!("GEO work budget {key}"),
            measured,
            recorded: table_u64(recorded, key),
            budget,
        });
    }
    bound
}

#[test]
fn geo_no_fused_multiply_add_in_the_firmware() {
    let test = "geo_no_fused_multiply_add_in_the_firmware";
    if let Some(run) = or_skip(test, run()) {
        assert_no_fused_multiply_add(test, &run.elf);
    }
}
