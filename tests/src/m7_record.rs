//! The M7 figures record (`fixtures/golden/m7-figures.toml`, written by the QEMU test) and the
//! tables of `docs/firmware.md` generated from it, between the markers
//! `<!-- m7-figures:begin -->` and `<!-- m7-figures:end -->` (the default image),
//! `<!-- m7-geo-figures:... -->` (the GEO image) and `<!-- m7-images:... -->` (RAM per image),
//! and the GEO work budget's tables of `docs/geo-tour.md` (`<!-- geo-work-budget:... -->`: the
//! kernel cases' instructions per unit, the bound they give).
//!
//! `tests/tests/m7_docs.rs` fails when the docs differ from what the record generates;
//! `RECONFIG_UPDATE_DOCS=1 cargo test -p reconfig-tests --test m7_docs` rewrites them (the QEMU
//! test's `RECONFIG_UPDATE_FIGURES=1` run does too, after writing the record).

use std::fmt::Write as _;
use std::path::PathBuf;

/// The record, relative to the workspace.
pub const RECORD_FILE: &str = "fixtures/golden/m7-figures.toml";
/// The generated document, relative to the workspace.
pub const DOCS_FILE: &str = "docs/firmware.md";
/// Start marker of the generated part.
pub const BEGIN: &str =
    "<!-- m7-figures:begin (generated from fixtures/golden/m7-figures.toml; do not edit) -->";
/// End marker of the generated part.
pub const END: &str = "<!-- m7-figures:end -->";
/// The command that rewrites the generated part from the record.
pub const UPDATE_DOCS_COMMAND: &str =
    "RECONFIG_UPDATE_DOCS=1 cargo test -p reconfig-tests --test m7_docs";

/// The workspace root.
pub fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("..")
}

/// `1234567` as `1,234,567`.
pub fn grouped(v: u64) -> String {
    let digits = v.to_string();
    let mut out = String::new();
    for (i, c) in digits.chars().enumerate() {
        if i > 0 && (digits.len() - i) % 3 == 0 {
            out.push(',');
        }
        out.push(c);
    }
    out
}

/// A record table's integer `key` as `u64`.
///
/// # Errors
/// The key is missing, not an integer or negative.
pub(crate) fn int(t: &toml::Table, key: &str) -> Result<u64, String> {
    t.get(key)
        .and_then(toml::Value::as_integer)
        .and_then(|v| u64::try_from(v).ok())
        .ok_or_else(|| format!("{RECORD_FILE}: missing or bad `{key}`"))
}

/// One image's part of the record and its table: which tables hold its binary and its
/// fixtures, how the table's first column is headed, and whether it has a work-units column.
struct FixtureTable {
    binary: &'static str,
    fixtures: &'static str,
    label: &'static str,
    work_units: bool,
}

/// The two-planner image: `[binary]`, `[[fixture]]`, with work units.
const DEFAULT_TABLE: FixtureTable = FixtureTable {
    binary: "binary",
    fixtures: "fixture",
    label: "fixture",
    work_units: true,
};

/// The GEO image: `[geo_binary]`, `[[geo_fixture]]`, with work units.
const GEO_TABLE: FixtureTable = FixtureTable {
    binary: "geo_binary",
    fixtures: "geo_fixture",
    label: "GEO fixture",
    work_units: true,
};

/// An image's fixture table, rendered.
struct Rendered {
    /// The table's Markdown.
    md: String,
    /// The image's `[binary]`-like table.
    binary: toml::Table,
    /// Largest RAM figure over the fixtures, bytes.
    ram_max: u64,
    /// Instructions per work unit, (min, max) per planner key (fixtures with work units).
    per_unit: std::collections::BTreeMap<String, (f64, f64)>,
}

/// The per-fixture table of one image (`spec`): one renderer for every image's section.
fn fixture_table(record: &str, spec: &FixtureTable) -> Result<Rendered, String> {
    let file: toml::Table = toml::from_str(record).map_err(|e| format!("{RECORD_FILE}: {e}"))?;
    let binary = file
        .get(spec.binary)
        .and_then(toml::Value::as_table)
        .ok_or_else(|| format!("{RECORD_FILE}: no [{}]", spec.binary))?
        .clone();
    let fixtures = file
        .get(spec.fixtures)
        .and_then(toml::Value::as_array)
        .ok_or_else(|| format!("{RECORD_FILE}: no [[{}]]", spec.fixtures))?;
    let (units_head, units_rule) = if spec.work_units {
        (" work units |", " ---: |")
    } else {
        ("", "")
    };
    let mut md = format!(
        "| {} | instructions | budget |{units_head} stack bytes | RAM bytes (static + stack) | RAM budget |\n\
         | --- | ---: | ---: |{units_rule} ---: | ---: | ---: |\n",
        spec.label
    );
    let mut ram_max = 0;
    let mut per_unit: std::collections::BTreeMap<String, (f64, f64)> = Default::default();
    for f in fixtures {
        let f = f
            .as_table()
            .ok_or_else(|| format!("a [[{}]] is not a table", spec.fixtures))?;
        let name = f
            .get("name")
            .and_then(toml::Value::as_str)
            .ok_or_else(|| format!("{} without name", spec.label))?;
        let ram = int(f, "ram_bytes")?;
        ram_max = ram_max.max(ram);
        let units = if spec.work_units {
            let planner = f
                .get("planner")
                .and_then(toml::Value::as_str)
                .ok_or_else(|| format!("{} without planner", spec.label))?;
            let units = int(f, "work_units")?;
            if units > 0 {
                let ratio = int(f, "instructions")? as f64 / units as f64;
                let e = per_unit
                    .entry(planner.to_owned())
                    .or_insert((f64::INFINITY, 0.0));
                *e = (e.0.min(ratio), e.1.max(ratio));
            }
            format!(" {} |", grouped(units))
        } else {
            String::new()
        };
        let _ = writeln!(
            md,
            "| {name} | {} | {} |{units} {} | {} | {} |",
            grouped(int(f, "instructions")?),
            grouped(int(f, "instructions_budget")?),
            grouped(int(f, "stack_bytes")?),
            grouped(ram),
            grouped(int(f, "ram_bytes_budget")?),
        );
    }
    Ok(Rendered {
        md,
        binary,
        ram_max,
        per_unit,
    })
}

/// The generated Markdown (without the markers) for a record's text.
///
/// # Errors
/// The record does not parse or lacks a figure.
pub fn render(record: &str) -> Result<String, String> {
    let Rendered {
        mut md,
        binary,
        ram_max,
        per_unit,
    } = fixture_table(record, &DEFAULT_TABLE)?;
    let kib = |v: u64| v as f64 / 1024.0;
    let _ = write!(
        md,
        "\nBinary: `.text` {} B, `.rodata` {} B, `.data` {} B, `.bss` {} B; static RAM {} B, of \
         which planner A's `Workspace` {} B and `Solution` {} B, planner B's `Workspace` {} B and \
         `Solution` {} B. Largest RAM (static + stack) over the fixtures: {} B = {:.1} KiB, {:.1} % \
         of 256 KiB.\n",
        grouped(int(&binary, "text_bytes")?),
        grouped(int(&binary, "rodata_bytes")?),
        grouped(int(&binary, "data_bytes")?),
        grouped(int(&binary, "bss_bytes")?),
        grouped(int(&binary, "static_ram_bytes")?),
        grouped(int(&binary, "pseudospectral_workspace_bytes")?),
        grouped(int(&binary, "pseudospectral_solution_bytes")?),
        grouped(int(&binary, "impulsive_workspace_bytes")?),
        grouped(int(&binary, "impulsive_solution_bytes")?),
        grouped(ram_max),
        kib(ram_max),
        ram_max as f64 / 2621.44,
    );
    md.push_str(
        "\nWork budget (`work_budget`, in work units; instructions per unit over the fixtures \
         above):\n\n\
         | planner | instructions per unit, min | max | max / min | default budget, units | \
         worst case = budget x max, instructions |\n\
         | --- | ---: | ---: | ---: | ---: | ---: |\n",
    );
    for (planner, budget) in [
        (
            "pseudospectral",
            reconfig_core::pseudospectral::Settings::default().work_budget,
        ),
        (
            "impulsive",
            reconfig_core::impulsive::Settings::default().work_budget,
        ),
    ] {
        let Some(&(min, max)) = per_unit.get(planner) else {
            continue;
        };
        let _ = writeln!(
            md,
            "| {planner} | {min:.1} | {max:.1} | {:.2} | {} | {} |",
            max / min,
            grouped(budget),
            grouped((budget as f64 * max).ceil() as u64),
        );
    }
    Ok(md)
}

/// `docs` with its generated part replaced by `generated`.
///
/// # Errors
/// The markers are missing or out of order.
pub fn splice(docs: &str, generated: &str) -> Result<String, String> {
    splice_between(docs, BEGIN, END, generated)
}

/// Regenerate the docs' generated parts (all of them) from the record on disk; returns whether
/// they changed.
///
/// # Errors
/// A file cannot be read or written, or does not parse.
pub fn update_docs() -> Result<bool, String> {
    update_all()
}

/// Start marker of the GEO image's generated table.
pub const GEO_BEGIN: &str =
    "<!-- m7-geo-figures:begin (generated from fixtures/golden/m7-figures.toml; do not edit) -->";
/// End marker of the GEO image's generated table.
pub const GEO_END: &str = "<!-- m7-geo-figures:end -->";

/// The generated Markdown (without the markers) for the record's GEO image part
/// (`[geo_binary]`, `[[geo_fixture]]`).
///
/// # Errors
/// The record does not parse or lacks a figure.
pub fn render_geo(record: &str) -> Result<String, String> {
    let Rendered { mut md, binary, .. } = fixture_table(record, &GEO_TABLE)?;
    let _ = write!(
        md,
        "\nGEO image: `.text` {} B; static RAM {} B, of which the GEO tour's `Workspace` {} B and \
         `Solution` {} B.\n",
        grouped(int(&binary, "text_bytes")?),
        grouped(int(&binary, "static_ram_bytes")?),
        grouped(int(&binary, "geo_tour_workspace_bytes")?),
        grouped(int(&binary, "geo_tour_solution_bytes")?),
    );
    Ok(md)
}

/// `docs` with its GEO table replaced by `generated`.
///
/// # Errors
/// The GEO markers are missing or out of order.
pub fn splice_geo(docs: &str, generated: &str) -> Result<String, String> {
    splice_between(docs, GEO_BEGIN, GEO_END, generated)
}

/// Regenerate the docs' generated parts (all of them, the GEO table among them) from the record
/// on disk; returns whether they changed.
///
/// # Errors
/// A file cannot be read or written, or does not parse.
pub fn update_geo_docs() -> Result<bool, String> {
    update_all()
}

/// Start marker of the generated RAM-per-image table.
pub const IMAGES_BEGIN: &str =
    "<!-- m7-images:begin (generated from fixtures/golden/m7-figures.toml; do not edit) -->";
/// End marker of the generated RAM-per-image table.
pub const IMAGES_END: &str = "<!-- m7-images:end -->";

/// One row of the RAM-per-image table.
fn image_row(md: &mut String, image: &str, t: &toml::Table) -> Result<(), String> {
    let ram = int(t, "ram_bytes")?;
    let budget = int(t, "ram_bytes_budget")?;
    let margin = if ram <= budget {
        format!("within, {} B to spare", grouped(budget - ram))
    } else {
        format!("**over by {} B**", grouped(ram - budget))
    };
    let _ = writeln!(
        md,
        "| {image} | {} | {} | {} ({:.1} %) | {} | {margin} |",
        grouped(int(t, "static_ram_bytes")?),
        grouped(int(t, "stack_bytes")?),
        grouped(ram),
        ram as f64 / 2621.44,
        grouped(budget),
    );
    Ok(())
}

/// The generated RAM-per-image table (without the markers): the default two-planner image
/// (`[binary]` and the largest `[[fixture]]` stack), each one-planner image (`[[image]]`) and
/// the GEO image (`[geo_image]`, when recorded).
///
/// # Errors
/// The record does not parse or lacks a figure.
pub fn render_images(record: &str) -> Result<String, String> {
    let file: toml::Table = toml::from_str(record).map_err(|e| format!("{RECORD_FILE}: {e}"))?;
    let binary = file
        .get("binary")
        .and_then(toml::Value::as_table)
        .ok_or_else(|| format!("{RECORD_FILE}: no [binary]"))?;
    let fixtures = file
        .get("fixture")
        .and_then(toml::Value::as_array)
        .ok_or_else(|| format!("{RECORD_FILE}: no [[fixture]]"))?;
    let images = file
        .get("image")
        .and_then(toml::Value::as_array)
        .ok_or_else(|| format!("{RECORD_FILE}: no [[image]]"))?;
    let mut md = String::from(
        "| image | static RAM | stack high-water | RAM (% of 256 KiB) | budget | against the budget |\n\
         | --- | ---: | ---: | ---: | ---: | --- |\n",
    );
    // The default image: its RAM figure and budget are per fixture; the row takes the largest.
    let (mut stack, mut ram, mut budget) = (0, 0, u64::MAX);
    for f in fixtures {
        let f = f.as_table().ok_or("a [[fixture]] is not a table")?;
        stack = stack.max(int(f, "stack_bytes")?);
        ram = ram.max(int(f, "ram_bytes")?);
        budget = budget.min(int(f, "ram_bytes_budget")?);
    }
    let mut both = toml::Table::new();
    for (key, value) in [
        ("static_ram_bytes", int(binary, "static_ram_bytes")?),
        ("stack_bytes", stack),
        ("ram_bytes", ram),
        ("ram_bytes_budget", budget),
    ] {
        let value = i64::try_from(value).map_err(|e| e.to_string())?;
        both.insert(key.to_owned(), toml::Value::Integer(value));
    }
    image_row(
        &mut md,
        "both planners (`cargo firmware`, the QEMU tests' instruction run)",
        &both,
    )?;
    let geo = file.get("geo_image").and_then(toml::Value::as_table);
    for t in images
        .iter()
        .map(|i| i.as_table().ok_or("an [[image]] is not a table"))
        .chain(geo.map(Ok))
    {
        let t = t?;
        let field = |key: &str| {
            t.get(key)
                .and_then(toml::Value::as_str)
                .ok_or_else(|| format!("{RECORD_FILE}: an image without `{key}`"))
        };
        let name = format!("{} alone (`{}`)", field("planner")?, field("command")?);
        image_row(&mut md, &name, t)?;
    }
    Ok(md)
}

/// `docs` with the part between `begin` and `end` replaced by `generated`.
///
/// # Errors
/// The markers are missing or out of order.
pub fn splice_between(
    docs: &str,
    begin: &str,
    end: &str,
    generated: &str,
) -> Result<String, String> {
    let start = docs
        .find(begin)
        .ok_or_else(|| format!("the document lacks the marker {begin}"))?;
    let stop = docs
        .find(end)
        .filter(|&e| e > start)
        .ok_or_else(|| format!("the document lacks the marker {end} after its begin marker"))?;
    Ok(format!(
        "{}{begin}\n{generated}{}",
        &docs[..start],
        &docs[stop..]
    ))
}

/// The GEO tour's document, relative to the workspace.
pub const GEO_DOCS_FILE: &str = "docs/geo-tour.md";
/// Start marker of the GEO work budget's generated tables (in [`GEO_DOCS_FILE`]).
pub const GEO_WORK_BEGIN: &str =
    "<!-- geo-work-budget:begin (generated from fixtures/golden/m7-figures.toml; do not edit) -->";
/// End marker of the GEO work budget's generated tables.
pub const GEO_WORK_END: &str = "<!-- geo-work-budget:end -->";

/// `instructions / units` with one decimal.
fn per_unit(instructions: u64, units: u64) -> String {
    format!("{:.1}", instructions as f64 / units.max(1) as f64)
}

/// The generated Markdown (without the markers) of the GEO work budget: each kernel case
/// (`[[geo_kernel]]`: instructions, units, instructions per unit), the largest ratio against
/// `MAX_INSTRUCTIONS_PER_UNIT`, the bound it gives (`[geo_work_budget]`), and each GEO request
/// the image ran (`[[geo_fixture]]`) with its ratio.
///
/// # Errors
/// The record does not parse or lacks a figure.
pub fn render_geo_work(record: &str) -> Result<String, String> {
    use reconfig_core::geo_tour::MAX_INSTRUCTIONS_PER_UNIT;
    let file: toml::Table = toml::from_str(record).map_err(|e| format!("{RECORD_FILE}: {e}"))?;
    let array = |key: &str| {
        file.get(key)
            .and_then(toml::Value::as_array)
            .ok_or_else(|| format!("{RECORD_FILE}: no [[{key}]]"))
    };
    let name = |t: &toml::Table| {
        t.get("name")
            .and_then(toml::Value::as_str)
            .map(str::to_owned)
            .ok_or_else(|| format!("{RECORD_FILE}: an entry without name"))
    };
    let mut md = String::from(
        "| kernel case | M7 instructions | units charged | instructions per unit |\n\
         | --- | ---: | ---: | ---: |\n",
    );
    let mut largest = (0.0_f64, String::new());
    for k in array("geo_kernel")? {
        let k = k.as_table().ok_or("a [[geo_kernel]] is not a table")?;
        let (instructions, units) = (int(k, "instructions")?, int(k, "units")?);
        let ratio = instructions as f64 / units.max(1) as f64;
        if ratio > largest.0 {
            largest = (ratio, name(k)?);
        }
        let _ = writeln!(
            md,
            "| {} | {} | {} | {} |",
            name(k)?,
            grouped(instructions),
            grouped(units),
            per_unit(instructions, units)
        );
    }
    let bound = file
        .get("geo_work_budget")
        .and_then(toml::Value::as_table)
        .ok_or_else(|| format!("{RECORD_FILE}: no [geo_work_budget]"))?;
    let milli = int(bound, "max_instructions_per_unit_milli")?;
    let within = milli <= MAX_INSTRUCTIONS_PER_UNIT * 1000;
    let _ = write!(
        md,
        "\nLargest instructions per unit over the kernel cases: **{:.3}** (`{}`), against the bound \
         `MAX_INSTRUCTIONS_PER_UNIT` = {MAX_INSTRUCTIONS_PER_UNIT}: {}. Default budget {} units x \
         {:.3} = **{} instructions** at most per request (400 M allowed).\n\n\
         | GEO request (the GEO image) | M7 instructions | work units | instructions per unit |\n\
         | --- | ---: | ---: | ---: |\n",
        milli as f64 / 1000.0,
        largest.1,
        if within { "within" } else { "**over**" },
        grouped(int(bound, "default_work_budget")?),
        milli as f64 / 1000.0,
        grouped(int(bound, "worst_case_instructions")?),
    );
    for f in array("geo_fixture")? {
        let f = f.as_table().ok_or("a [[geo_fixture]] is not a table")?;
        let (instructions, units) = (int(f, "instructions")?, int(f, "work_units")?);
        let _ = writeln!(
            md,
            "| {} | {} | {} | {} |",
            name(f)?,
            grouped(instructions),
            grouped(units),
            per_unit(instructions, units)
        );
    }
    Ok(md)
}

/// `docs` (the text of [`GEO_DOCS_FILE`]) with its GEO work budget tables replaced by
/// `generated`.
///
/// # Errors
/// The markers are missing or out of order.
pub fn splice_geo_work(docs: &str, generated: &str) -> Result<String, String> {
    splice_between(docs, GEO_WORK_BEGIN, GEO_WORK_END, generated)
        .map_err(|e| format!("{GEO_DOCS_FILE}: {e}"))
}

/// Regenerate the docs' generated parts (all of them, the RAM-per-image table among them) from
/// the record on disk; returns whether they changed.
///
/// # Errors
/// A file cannot be read or written, or does not parse.
pub fn update_images_docs() -> Result<bool, String> {
    update_all()
}

/// Regenerate every generated part of the docs from the record on disk; returns whether the
/// docs changed. Each `update_*` does all of them, so that tests updating at the same time all
/// write the same file.
fn update_all() -> Result<bool, String> {
    let record = std::fs::read_to_string(root().join(RECORD_FILE)).map_err(|e| e.to_string())?;
    let docs_path = root().join(DOCS_FILE);
    let docs = std::fs::read_to_string(&docs_path).map_err(|e| e.to_string())?;
    let new = splice(&docs, &render(&record)?)?;
    let new = splice_geo(&new, &render_geo(&record)?)?;
    let new = splice_between(&new, IMAGES_BEGIN, IMAGES_END, &render_images(&record)?)?;
    let readme_changed = crate::readme_figures::update_readme()?;
    let geo_path = root().join(GEO_DOCS_FILE);
    let geo_docs = std::fs::read_to_string(&geo_path).map_err(|e| e.to_string())?;
    let new_geo = splice_geo_work(&geo_docs, &render_geo_work(&record)?)?;
    let geo_changed = new_geo != geo_docs;
    if geo_changed {
        std::fs::write(&geo_path, &new_geo).map_err(|e| e.to_string())?;
    }
    if new != docs {
        std::fs::write(&docs_path, &new).map_err(|e| e.to_string())?;
        return Ok(true);
    }
    Ok(readme_changed || geo_changed)
}

// The kernel images (`tests/tests/qemu_firmware/kernels_image.rs`): the record's
// `[[ka_kernel]]` / `[[kb_kernel]]` tables and the planners' generated "Work budget" tables.

/// One kernel image's docs table: where it goes and what bounds it states.
pub struct KernelDocs {
    /// The record's table name (`ka_kernel`, `kb_kernel`).
    pub key: &'static str,
    /// The document, relative to the workspace, and its markers.
    pub file: &'static str,
    pub begin: &'static str,
    pub end: &'static str,
    /// The planner's default work budget, per-unit bound and on-board instruction promise.
    pub budget: u64,
    pub max_instructions_per_unit: u64,
    pub max_solve_instructions: u64,
}

/// Planner A's kernel table in `docs/planner-a.md`.
pub const KERNELS_A_DOCS: KernelDocs = KernelDocs {
    key: "ka_kernel",
    file: "docs/planner-a.md",
    begin:
        "<!-- m7-kernels-a:begin (generated from fixtures/golden/m7-figures.toml; do not edit) -->",
    end: "<!-- m7-kernels-a:end -->",
    budget: reconfig_core::pseudospectral::DEFAULT_WORK_BUDGET,
    max_instructions_per_unit: reconfig_core::pseudospectral::MAX_INSTRUCTIONS_PER_UNIT,
    max_solve_instructions: reconfig_core::pseudospectral::MAX_SOLVE_INSTRUCTIONS,
};

/// Planner B's kernel table in `docs/planner-b.md`.
pub const KERNELS_B_DOCS: KernelDocs = KernelDocs {
    key: "kb_kernel",
    file: "docs/planner-b.md",
    begin:
        "<!-- m7-kernels-b:begin (generated from fixtures/golden/m7-figures.toml; do not edit) -->",
    end: "<!-- m7-kernels-b:end -->",
    budget: reconfig_core::impulsive::DEFAULT_WORK_BUDGET,
    max_instructions_per_unit: reconfig_core::impulsive::MAX_INSTRUCTIONS_PER_UNIT,
    max_solve_instructions: reconfig_core::impulsive::MAX_SOLVE_INSTRUCTIONS,
};

/// The LEO arc's kernel table in `docs/leo-tour.md`.
pub const KERNELS_LEO_DOCS: KernelDocs = KernelDocs {
    key: "kl_kernel",
    file: "docs/leo-tour.md",
    begin:
        "<!-- m7-kernels-leo:begin (generated from fixtures/golden/m7-figures.toml; do not edit) -->",
    end: "<!-- m7-kernels-leo:end -->",
    budget: reconfig_core::leo_tour::work_units::DEFAULT_WORK_BUDGET,
    max_instructions_per_unit: reconfig_core::leo_tour::work_units::MAX_INSTRUCTIONS_PER_UNIT,
    max_solve_instructions: reconfig_core::pseudospectral::MAX_SOLVE_INSTRUCTIONS,
};

/// A kernel case's instructions as the bound holds it: with planner B's Newton-step allowance
/// (`instructions_worst_kepler`) when the record has one.
fn held_instructions(t: &toml::Table) -> Result<u64, String> {
    match t.get("instructions_worst_kepler") {
        Some(_) => int(t, "instructions_worst_kepler"),
        None => int(t, "instructions"),
    }
}

/// The largest instructions per unit over a record's charged kernel cases of one image (as the
/// bound holds them) and its case; `None` without charged cases.
///
/// # Errors
/// The record lacks a figure.
pub fn kernels_worst_ratio(file: &toml::Table, key: &str) -> Result<Option<(f64, String)>, String> {
    let mut worst: Option<(f64, String)> = None;
    for t in file
        .get(key)
        .and_then(toml::Value::as_array)
        .into_iter()
        .flatten()
        .filter_map(toml::Value::as_table)
    {
        if t.get("charged").and_then(toml::Value::as_bool) != Some(true) {
            continue;
        }
        let name = t.get("name").and_then(toml::Value::as_str).unwrap_or("?");
        let r = held_instructions(t)? as f64 / int(t, "units")?.max(1) as f64;
        if worst.as_ref().is_none_or(|(w, _)| r > *w) {
            worst = Some((r, name.to_owned()));
        }
    }
    Ok(worst)
}

/// A kernel image's table (without the markers) for a record's text: each case's M7
/// instructions, its units and their ratio (planner B: also with the Newton-step allowance),
/// and what the largest ratio bounds.
///
/// # Errors
/// The record does not parse, lacks a figure or has no kernel cases.
pub fn render_kernels(docs: &KernelDocs, record: &str) -> Result<String, String> {
    let file: toml::Table = toml::from_str(record).map_err(|e| format!("{RECORD_FILE}: {e}"))?;
    let key = docs.key;
    let kernels: Vec<&toml::Table> = file
        .get(key)
        .and_then(toml::Value::as_array)
        .into_iter()
        .flatten()
        .filter_map(toml::Value::as_table)
        .collect();
    if kernels.is_empty() {
        return Err(format!("{RECORD_FILE}: no [[{key}]] tables"));
    }
    let kepler = kernels
        .iter()
        .any(|t| t.contains_key("instructions_worst_kepler"));
    let mut md = if kepler {
        String::from(
            "| case | M7 instructions | Kepler solves / Newton steps | with every solve at the \
             step limit | units charged | instructions per unit (at the limit) |\n\
             | --- | ---: | ---: | ---: | ---: | ---: |\n",
        )
    } else {
        String::from(
            "| case | M7 instructions | units charged | instructions per unit |\n\
             | --- | ---: | ---: | ---: |\n",
        )
    };
    for t in &kernels {
        let name = t
            .get("name")
            .and_then(toml::Value::as_str)
            .ok_or_else(|| format!("{RECORD_FILE}: a [[{key}]] without a name"))?;
        let charged = t
            .get("charged")
            .and_then(toml::Value::as_bool)
            .unwrap_or(true);
        let (count, units) = (int(t, "instructions")?, int(t, "units")?);
        let held = held_instructions(t)?;
        let ratio = if charged && units > 0 {
            format!("{:.2}", held as f64 / units as f64)
        } else {
            "not charged".to_owned()
        };
        if kepler {
            let _ = writeln!(
                md,
                "| `{name}` | {} | {} / {} | {} | {} | {ratio} |",
                grouped(count),
                int(t, "kepler_solves")?,
                int(t, "kepler_steps")?,
                grouped(held),
                grouped(units)
            );
        } else {
            let _ = writeln!(
                md,
                "| `{name}` | {} | {} | {ratio} |",
                grouped(count),
                grouped(units)
            );
        }
    }
    let max = docs.max_instructions_per_unit;
    if kepler {
        let part = file
            .get(key.trim_end_matches("_kernel"))
            .and_then(toml::Value::as_table)
            .ok_or_else(|| format!("{RECORD_FILE}: no [{}]", key.trim_end_matches("_kernel")))?;
        let _ = write!(
            md,
            "\nA Newton step of Kepler's equation costs {} instructions (`kepler-2` minus \
             `kepler-1`); each case is held to its instructions plus the steps its solves did not \
             take, up to {} per solve (the built-in limit).\n",
            int(part, "newton_step_instructions")?,
            int(part, "newton_steps_allowed")?
        );
    }
    if let Some((ratio, name)) = kernels_worst_ratio(&file, key)? {
        let bound = docs.budget.saturating_mul(max);
        let promise = if bound <= docs.max_solve_instructions {
            format!("at most {}", grouped(docs.max_solve_instructions))
        } else {
            format!(
                "more than the {} of the on-board promise: not met",
                grouped(docs.max_solve_instructions)
            )
        };
        let _ = write!(
            md,
            "\nLargest over the charged cases: {ratio:.2} instructions per unit (`{name}`); the \
             QEMU test fails above `MAX_INSTRUCTIONS_PER_UNIT` = {max}. Default budget {} units \
             x {max} = {} instructions ({promise}).\n",
            grouped(docs.budget),
            grouped(bound),
        );
    }
    Ok(md)
}

/// The docs page with its kernel table regenerated from the record on disk; returns whether it
/// changed.
///
/// # Errors
/// A file cannot be read or written, or does not parse.
pub fn update_kernels_docs(docs: &KernelDocs) -> Result<bool, String> {
    let record = std::fs::read_to_string(root().join(RECORD_FILE)).map_err(|e| e.to_string())?;
    let path = root().join(docs.file);
    let text = std::fs::read_to_string(&path).map_err(|e| e.to_string())?;
    let new = splice_between(&text, docs.begin, docs.end, &render_kernels(docs, &record)?)?;
    if new != text {
        std::fs::write(&path, &new).map_err(|e| e.to_string())?;
        return Ok(true);
    }
    Ok(false)
}

/// Planner A's kernel table regenerated (`update_kernels_docs`).
///
/// # Errors
/// As `update_kernels_docs`.
pub fn update_kernels_a_docs() -> Result<bool, String> {
    update_kernels_docs(&KERNELS_A_DOCS)
}

/// Planner B's kernel table regenerated (`update_kernels_docs`).
///
/// # Errors
/// As `update_kernels_docs`.
pub fn update_kernels_b_docs() -> Result<bool, String> {
    update_kernels_docs(&KERNELS_B_DOCS)
}

/// The LEO arc's kernel table regenerated (`update_kernels_docs`).
///
/// # Errors
/// As `update_kernels_docs`.
pub fn update_kernels_leo_docs() -> Result<bool, String> {
    update_kernels_docs(&KERNELS_LEO_DOCS)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn grouping_and_splicing() {
        assert_eq!(grouped(0), "0");
        assert_eq!(grouped(999), "999");
        assert_eq!(grouped(1000), "1,000");
        assert_eq!(grouped(420_863_326), "420,863,326");
        let docs = format!("a\n{BEGIN}\nold\n{END}\nb\n");
        assert_eq!(
            splice(&docs, "new\n").unwrap(),
            format!("a\n{BEGIN}\nnew\n{END}\nb\n")
        );
        assert!(splice("no markers", "x").is_err());
    }
}
