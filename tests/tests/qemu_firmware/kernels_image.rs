//! The kernel images, one per metered planner: planner A's (`reconfig-firmware-ka`, feature
//! `kernels_a`, module `kernels_a_image`), planner B's (`reconfig-firmware-kb`, feature
//! `kernels_b`, module `kernels_b_image`) and the LEO arc's (`reconfig-firmware-kl`, feature
//! `kernels_leo`, module `kernels_leo_image`). Each runs every case of the planner's `kernels`
//! module (each charged step of a solve, on its dearest path) between the instruction markers,
//! one `fixture` line per case whose `work_units` are the units the solve charges for it. The
//! test fails when a charged case's M7 instructions exceed its units x the planner's
//! `MAX_INSTRUCTIONS_PER_UNIT`: that per-unit bound is what makes `work_budget x
//! MAX_INSTRUCTIONS_PER_UNIT` bound a solve's instructions (issue 33 item 1).
//!
//! Planner B's and the LEO arc's cases also report their Kepler solves and Newton steps. A solve's Newton steps
//! depend on the orbit, so each case is held to its instructions plus the steps it did not take
//! up to the built-in limit per solve, at the measured cost of one step (the
//! difference of the `kepler-2` and `kepler-1` cases): the bound holds at any accepted orbit.
//!
//! Each image's figures are its own part of the record (from its marker line), written by its
//! test; the planner's docs page has a table generated from it.

use std::fmt::Write as _;

use crate::image::{instructions_or_skip, or_skip, Run};
use crate::prerequisites::{notice, root};
use crate::record::{
    assert_figures, assert_systick_agrees, read_record, tables_by, updating, with_part, Figure,
    FIGURES_FILE, RECORD_LOCK,
};

/// What differs between the planners' kernel images.
pub struct KernelImage {
    /// The test's name.
    pub test: &'static str,
    /// "A" or "B".
    pub planner: &'static str,
    /// The record part's first line.
    pub marker: &'static str,
    /// The record's table names: `[<key>]` and `[[<key>_kernel]]`.
    pub key: &'static str,
    /// The core's kernels and work-unit files, for the messages.
    pub source: &'static str,
    pub work_units: &'static str,
    /// Each case's name and whether the solve charges it, in the image's order.
    pub cases: Vec<(&'static str, bool)>,
    pub max_instructions_per_unit: u64,
    /// Planner B: the Newton steps a Kepler solve may take (the two cases whose difference
    /// is one step are named `kepler-1` and `kepler-2`).
    pub newton_steps_allowed: Option<u64>,
    /// Regenerates the planner's docs table from the record.
    pub update_docs: fn() -> Result<bool, String>,
}

/// The cost of one Newton step: `kepler-2` minus `kepler-1`.
fn newton_step_instructions(run: &Run, instructions: &[u64]) -> u64 {
    let count = |name: &str| {
        run.fixtures
            .iter()
            .zip(instructions)
            .find_map(|(f, &c)| (f.name == name).then_some(c))
            .unwrap_or_else(|| panic!("the kernel image has no {name} case"))
    };
    count("kepler-2").saturating_sub(count("kepler-1"))
}

/// Runs the checks of one kernel image and, when updating, writes its record part.
pub fn check(image: &KernelImage, run: &'static Result<Run, String>) {
    let test = image.test;
    let Some(run) = or_skip(test, run) else {
        return;
    };
    let Some(instructions) = instructions_or_skip(test, run) else {
        return;
    };
    assert_systick_agrees(run, instructions);
    assert_eq!(
        run.fixtures.len(),
        image.cases.len(),
        "the kernel image ran {} cases, the core has {}",
        run.fixtures.len(),
        image.cases.len()
    );
    let (key, max) = (image.key, image.max_instructions_per_unit);
    let step = image
        .newton_steps_allowed
        .map(|allowed| (allowed, newton_step_instructions(run, instructions)));
    let file = read_record(FIGURES_FILE);
    let recorded = tables_by(&file, &format!("{key}_kernel"), "name");
    let mut figures = Vec::new();
    let mut over = Vec::new();
    let mut text = format!(
        "{}\n# Each case of {}: its M7 instructions, the units the solve\n# charges for it, \
         and its budget units x MAX_INSTRUCTIONS_PER_UNIT (none for an uncharged case).\n",
        image.marker, image.source
    );
    if step.is_some() {
        text.push_str(
            "# instructions_worst_kepler adds the Newton steps the case did not take, up to\n# \
             newton_steps_allowed per Kepler solve, at newton_step_instructions each.\n",
        );
    }
    let _ = write!(text, "\n[{key}]\nmax_instructions_per_unit = {max}\n");
    if let Some((allowed, cost)) = step {
        let _ = write!(
            text,
            "newton_steps_allowed = {allowed}\nnewton_step_instructions = {cost}\n"
        );
    }
    for ((fixture, &count), &(name, charged)) in
        run.fixtures.iter().zip(instructions).zip(&image.cases)
    {
        assert_eq!(fixture.name, name, "the kernel image's case order");
        let units = fixture.work_units.unwrap_or(0);
        let recorded = recorded.get(&fixture.name).copied();
        let _ = write!(
            text,
            "\n[[{key}_kernel]]\nname = {:?}\ncharged = {charged}\ninstructions = {count}\n\
             units = {units}\n",
            fixture.name
        );
        // The instructions the case is held to: with planner B's Newton-step allowance.
        let worst = match (step, fixture.kepler) {
            (Some((allowed, cost)), Some((solves, steps))) => {
                let untaken = solves.saturating_mul(allowed).saturating_sub(steps);
                let worst = count.saturating_add(untaken.saturating_mul(cost));
                let _ = write!(
                    text,
                    "kepler_solves = {solves}\nkepler_steps = {steps}\n\
                     instructions_worst_kepler = {worst}\n"
                );
                worst
            }
            (Some(_), None) => panic!("{}: no Kepler counts in the kernel image", fixture.name),
            (None, _) => count,
        };
        if charged {
            let budget = units.saturating_mul(max);
            let _ = writeln!(text, "instructions_budget = {budget}");
            // A charged case that charges nothing (a step that did not run) proves nothing.
            if units == 0 || worst > budget {
                over.push(format!(
                    "{}: {worst} instructions for {units} units ({:.2} per unit, at most {max})",
                    fixture.name,
                    worst as f64 / units.max(1) as f64
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
        let record = with_part(&existing, Some(image.marker), &text);
        std::fs::write(&path, &record).unwrap_or_else(|e| panic!("{FIGURES_FILE}: {e}"));
        notice(&format!(
            "wrote planner {}'s kernel image's figures to {FIGURES_FILE}",
            image.planner
        ));
        (image.update_docs)().expect("regenerate the docs");
    }
    assert!(
        over.is_empty(),
        "planner {}'s kernel cases over {max} M7 instructions per unit (raise the step's charge \
         in {}):\n{}",
        image.planner,
        image.work_units,
        over.join("\n")
    );
    assert_figures(
        &figures,
        updating,
        (
            &format!("planner {}'s kernel image", image.planner),
            FIGURES_FILE,
        ),
        &measured_path,
    );
}
