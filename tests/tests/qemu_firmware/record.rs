//! The record of M7 figures (`fixtures/golden/m7-figures.toml`): what each image measured,
//! written beside its budget; the drift check (1 % from the record) and the budget check.

use std::collections::BTreeMap;
use std::fmt::Write as _;
use std::path::Path;
use std::sync::Mutex;

use crate::image::Run;

pub const FIGURES_FILE: &str = "fixtures/golden/m7-figures.toml";
pub const UPDATE_COMMAND: &str =
    "RECONFIG_UPDATE_FIGURES=1 cargo test -p reconfig-tests --test qemu_firmware";
/// A measured figure further than this (relative) from the record fails the drift check.
const DRIFT_TOLERANCE: f64 = 0.01;

/// A record file (`file`, from the repository root) as a table: empty when it does not exist
/// yet, a failure when it does not parse.
pub fn read_record(file: &str) -> toml::Table {
    match std::fs::read_to_string(crate::prerequisites::root().join(file)) {
        Ok(text) => toml::from_str(&text).unwrap_or_else(|e| panic!("{file}: {e}")),
        Err(_) => toml::Table::new(),
    }
}

/// Default budgets for a figure with no entry in the figures file (the on-board budgets of
/// docs/firmware.md; a fixture's entry may set its own).
pub const BUDGET_RAM_BYTES: u64 = 256 * 1024;
pub const BUDGET_STACK_BYTES: u64 = 64 * 1024;
/// RAM (static + stack high-water) of each one-planner image: 230 KiB, 90 % of 256 KiB.
pub const BUDGET_ONE_PLANNER_IMAGE_RAM_BYTES: u64 = 230 * 1024;

/// The record's parts after the default image's, in file order: each starts with its marker
/// line and is written by its own test (the default image's part is everything before the first).
pub const KERNELS_A_MARKER: &str = "# Planner A's kernel image (reconfig-firmware-ka): written by \
                                    kernels_a_cases_are_within_the_per_unit_bound.";
pub const KERNELS_B_MARKER: &str = "# Planner B's kernel image (reconfig-firmware-kb): written by \
                                    kernels_b_cases_are_within_the_per_unit_bound.";
pub const KERNELS_LEO_MARKER: &str =
    "# The LEO arc's kernel image (reconfig-firmware-kl): written \
                                      by kernels_leo_cases_are_within_the_per_unit_bound.";
pub const GEO_MARKER: &str =
    "# GEO servicing tour image (cargo firmware-geo): written by geo_figures_are_within_budget.";
const PARTS: usize = 4;
const PART_MARKERS: [&str; PARTS] = [
    KERNELS_A_MARKER,
    KERNELS_B_MARKER,
    KERNELS_LEO_MARKER,
    GEO_MARKER,
];

/// The record split into its parts: the default image's, then one per marker (empty when
/// absent), in [`PART_MARKERS`] order.
fn parts(record: &str) -> (&str, [&str; PARTS]) {
    let starts: Vec<Option<usize>> = PART_MARKERS.iter().map(|m| record.find(m)).collect();
    let first = starts
        .iter()
        .flatten()
        .min()
        .copied()
        .unwrap_or(record.len());
    let mut out = [""; PARTS];
    for (slot, start) in out.iter_mut().zip(&starts) {
        if let Some(start) = *start {
            let end = starts
                .iter()
                .flatten()
                .filter(|&&other| other > start)
                .min()
                .copied()
                .unwrap_or(record.len());
            *slot = &record[start..end];
        }
    }
    (&record[..first], out)
}

/// The part of `record` that starts with `marker` (empty when absent).
pub fn record_part<'a>(record: &'a str, marker: &str) -> &'a str {
    let (_, rest) = parts(record);
    PART_MARKERS
        .iter()
        .zip(rest)
        .find_map(|(m, part)| (*m == marker).then_some(part))
        .unwrap_or("")
}

/// `record` with one part replaced by `text`: the default image's (`marker` `None`) or the one
/// that starts with `marker`; the others kept, in file order.
pub fn with_part(record: &str, marker: Option<&str>, text: &str) -> String {
    let (main, rest) = parts(record);
    let mut out = match marker {
        None => text.trim_end().to_owned(),
        Some(_) => main.trim_end().to_owned(),
    };
    out.push('\n');
    for (m, part) in PART_MARKERS.iter().zip(rest) {
        let part = if marker == Some(*m) { text } else { part };
        if !part.trim().is_empty() {
            out.push('\n');
            out.push_str(part.trim_end());
            out.push('\n');
        }
    }
    out
}

/// Both tests that may rewrite the record take this first.
pub static RECORD_LOCK: Mutex<()> = Mutex::new(());

/// Whether this run accepts the measured figures as the new record.
pub fn updating() -> bool {
    std::env::var("RECONFIG_UPDATE_FIGURES").as_deref() == Ok("1")
}

/// One figure: what was measured and what it may be.
pub struct Figure {
    pub what: String,
    pub measured: u64,
    pub recorded: Option<u64>,
    pub budget: u64,
}

pub fn table_u64(table: Option<&toml::Table>, key: &str) -> Option<u64> {
    table?
        .get(key)?
        .as_integer()
        .and_then(|v| u64::try_from(v).ok())
}

/// The record's array of tables `array`, by the string each holds under `key`.
pub fn tables_by<'a>(
    file: &'a toml::Table,
    array: &str,
    key: &str,
) -> BTreeMap<String, &'a toml::Table> {
    file.get(array)
        .and_then(|v| v.as_array())
        .into_iter()
        .flatten()
        .filter_map(|v| v.as_table())
        .filter_map(|t| Some((t.get(key)?.as_str()?.to_owned(), t)))
        .collect()
}

/// Write each `(key, measured, default budget)` under the current table of `text` with its
/// budget (the recorded one, else the default) and push it as a figure labelled
/// `"{label} {key}"`.
pub fn record_entries(
    text: &mut String,
    figures: &mut Vec<Figure>,
    recorded: Option<&toml::Table>,
    label: &str,
    entries: &[(&str, u64, u64)],
) {
    for &(key, measured, default_budget) in entries {
        let budget = table_u64(recorded, &format!("{key}_budget")).unwrap_or(default_budget);
        let _ = writeln!(text, "{key} = {measured}\n{key}_budget = {budget}");
        figures.push(Figure {
            what: format!("{label} {key}"),
            measured,
            recorded: table_u64(recorded, key),
            budget,
        });
    }
}

/// One firmware image's RAM figures (static RAM, its largest stack, their sum), labelled
/// `"{planner} image"`, with the one-planner-image budgets by default.
pub fn record_image_ram(
    text: &mut String,
    figures: &mut Vec<Figure>,
    recorded: Option<&toml::Table>,
    planner: &str,
    static_ram: u64,
    (stack, stack_budget): (u64, u64),
) {
    record_entries(
        text,
        figures,
        recorded,
        &format!("{planner} image"),
        &[
            (
                "static_ram_bytes",
                static_ram,
                BUDGET_ONE_PLANNER_IMAGE_RAM_BYTES,
            ),
            ("stack_bytes", stack, stack_budget),
            (
                "ram_bytes",
                static_ram + stack,
                BUDGET_ONE_PLANNER_IMAGE_RAM_BYTES,
            ),
        ],
    );
}

/// The plugin's exact count and the firmware's own SysTick estimate (40-instruction ticks, plus
/// the few instructions of the SysTick reads) measure the same span: they must agree.
pub fn assert_systick_agrees(run: &Run, instructions: &[u64]) {
    for (fixture, &exact) in run.fixtures.iter().zip(instructions) {
        let estimate = fixture.systick_instructions;
        assert!(
            estimate.abs_diff(exact) <= 200 + exact / 1000,
            "{}: the plugin counted {exact} instructions, the firmware's SysTick {estimate}",
            fixture.name
        );
    }
}

/// Print the figures, then fail on drift (a figure more than 1 % from the record, or not in
/// it: a change toward a budget is seen when it happens, not when the budget breaks; skipped
/// when `updating`, which accepts the new record) and on any figure over its budget.
/// `measured_path` is where this run wrote what it measured.
pub fn assert_figures(
    figures: &[Figure],
    updating: bool,
    (image, record_file): (&str, &str),
    measured_path: &Path,
) {
    let mut report = String::from("figure | measured | recorded | budget\n");
    for f in figures {
        let recorded = f.recorded.map_or("-".to_owned(), |r| r.to_string());
        let over = if f.measured > f.budget {
            "  OVER BUDGET"
        } else {
            ""
        };
        let _ = writeln!(
            report,
            "{} | {} | {recorded} | {}{over}",
            f.what, f.measured, f.budget
        );
    }
    println!("{report}");
    let drifted: Vec<String> = figures
        .iter()
        .filter(|_| !updating)
        .filter_map(|f| match f.recorded {
            None => Some(format!(
                "{}: measured {}, not in the record",
                f.what, f.measured
            )),
            Some(r) if (f.measured as f64 - r as f64).abs() > DRIFT_TOLERANCE * r as f64 => {
                Some(format!(
                    "{}: measured {}, recorded {} ({:+.2} %)",
                    f.what,
                    f.measured,
                    r,
                    100.0 * (f.measured as f64 - r as f64) / (r as f64).max(1.0)
                ))
            }
            Some(_) => None,
        })
        .collect();
    assert!(
        drifted.is_empty(),
        "{image} figures drifted more than {:.0} % from {record_file}:\n{}\nIf the change is \
         intended, accept the new record (and say why in the commit message):\n  {UPDATE_COMMAND}\n\
         (the measured figures are in {})",
        DRIFT_TOLERANCE * 100.0,
        drifted.join("\n"),
        measured_path.display()
    );
    let over: Vec<String> = figures
        .iter()
        .filter(|f| f.measured > f.budget)
        .map(|f| format!("{}: {} > {}", f.what, f.measured, f.budget))
        .collect();
    assert!(
        over.is_empty(),
        "{image} figures over budget on the emulated Cortex-M7:\n{}",
        over.join("\n"),
    );
}

#[test]
fn record_parts_are_replaced_one_at_a_time() {
    let record = format!("main\n\n{KERNELS_A_MARKER}\nka\n\n{GEO_MARKER}\ngeo\n");
    assert_eq!(record_part(&record, KERNELS_B_MARKER), "");
    assert_eq!(
        record_part(&record, GEO_MARKER),
        format!("{GEO_MARKER}\ngeo\n")
    );
    let with_b = with_part(
        &record,
        Some(KERNELS_B_MARKER),
        &format!("{KERNELS_B_MARKER}\nkb\n"),
    );
    assert_eq!(
        with_b,
        format!("main\n\n{KERNELS_A_MARKER}\nka\n\n{KERNELS_B_MARKER}\nkb\n\n{GEO_MARKER}\ngeo\n")
    );
    assert_eq!(with_part(&with_b, None, "main"), with_b);
    let new_main = with_part(&with_b, None, "other");
    assert!(new_main.starts_with("other\n\n") && new_main.ends_with("geo\n"));
    assert_eq!(
        record_part(&new_main, KERNELS_A_MARKER),
        format!("{KERNELS_A_MARKER}\nka\n\n")
    );
}
