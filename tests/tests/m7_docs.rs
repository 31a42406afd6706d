//! `docs/firmware.md`'s M7 tables, `docs/geo-tour.md`'s work budget tables and the README's M7
//! lines are generated from the records `fixtures/golden/m7-figures.toml` and
//! `m7-figures-leo.toml`: this fails when they differ, with the command that regenerates them.
//! No QEMU needed.

use reconfig_tests::m7_record::{self, DOCS_FILE, RECORD_FILE, UPDATE_DOCS_COMMAND};

#[test]
fn the_docs_tables_are_the_record() {
    if std::env::var("RECONFIG_UPDATE_DOCS").as_deref() == Ok("1") {
        let changed = m7_record::update_docs().expect("regenerate the docs");
        eprintln!(
            "{DOCS_FILE}: {}",
            if changed {
                "regenerated"
            } else {
                "already current"
            }
        );
    }
    let record = std::fs::read_to_string(m7_record::root().join(RECORD_FILE)).expect("record");
    let docs = std::fs::read_to_string(m7_record::root().join(DOCS_FILE)).expect("docs");
    let generated = m7_record::render(&record).expect("render");
    let expected = m7_record::splice(&docs, &generated).expect("markers");
    assert!(
        expected == docs,
        "{DOCS_FILE} differs from what {RECORD_FILE} generates; regenerate with\n  {UPDATE_DOCS_COMMAND}"
    );
}

#[test]
fn the_docs_geo_table_is_the_record() {
    if std::env::var("RECONFIG_UPDATE_DOCS").as_deref() == Ok("1") {
        m7_record::update_geo_docs().expect("regenerate the docs");
    }
    let record = std::fs::read_to_string(m7_record::root().join(RECORD_FILE)).expect("record");
    let docs = std::fs::read_to_string(m7_record::root().join(DOCS_FILE)).expect("docs");
    let generated = m7_record::render_geo(&record).expect("render the GEO part");
    let expected = m7_record::splice_geo(&docs, &generated).expect("GEO markers");
    assert!(
        expected == docs,
        "{DOCS_FILE}'s GEO table differs from what {RECORD_FILE} generates; regenerate with\n  {UPDATE_DOCS_COMMAND}"
    );
}

#[test]
fn the_geo_work_budget_tables_are_the_record() {
    use m7_record::GEO_DOCS_FILE;
    if std::env::var("RECONFIG_UPDATE_DOCS").as_deref() == Ok("1") {
        m7_record::update_geo_docs().expect("regenerate the docs");
    }
    let record = std::fs::read_to_string(m7_record::root().join(RECORD_FILE)).expect("record");
    let docs = std::fs::read_to_string(m7_record::root().join(GEO_DOCS_FILE)).expect("docs");
    let generated = m7_record::render_geo_work(&record).expect("render the GEO work budget");
    let expected = m7_record::splice_geo_work(&docs, &generated).expect("GEO work markers");
    assert!(
        expected == docs,
        "{GEO_DOCS_FILE}'s work budget tables differ from what {RECORD_FILE} generates; \
         regenerate with\n  {UPDATE_DOCS_COMMAND}"
    );
}

#[test]
fn the_docs_ram_per_image_table_is_the_record() {
    if std::env::var("RECONFIG_UPDATE_DOCS").as_deref() == Ok("1") {
        m7_record::update_images_docs().expect("regenerate the docs");
    }
    let record = std::fs::read_to_string(m7_record::root().join(RECORD_FILE)).expect("record");
    let docs = std::fs::read_to_string(m7_record::root().join(DOCS_FILE)).expect("docs");
    let generated = m7_record::render_images(&record).expect("render the RAM-per-image table");
    let expected = m7_record::splice_between(
        &docs,
        m7_record::IMAGES_BEGIN,
        m7_record::IMAGES_END,
        &generated,
    )
    .expect("RAM-per-image markers");
    assert!(
        expected == docs,
        "{DOCS_FILE}'s RAM-per-image table differs from what {RECORD_FILE} generates; \
         regenerate with\n  {UPDATE_DOCS_COMMAND}"
    );
}

#[test]
fn the_readme_m7_lines_are_the_record() {
    use reconfig_tests::readme_figures::{expected_readme, update_readme, README_FILE};
    if std::env::var("RECONFIG_UPDATE_DOCS").as_deref() == Ok("1") {
        update_readme().expect("regenerate the README's M7 lines");
    }
    let (readme, expected) = expected_readme().expect("the README's M7 lines");
    assert!(
        expected == readme,
        "{README_FILE}'s M7 lines differ from what the M7 records generate; regenerate with\n  \
         {UPDATE_DOCS_COMMAND}"
    );
}

/// A kernel image's docs table is what the record generates (regenerated first when updating).
fn kernel_table_is_the_record(docs: &m7_record::KernelDocs) {
    if std::env::var("RECONFIG_UPDATE_DOCS").as_deref() == Ok("1") {
        m7_record::update_kernels_docs(docs).expect("regenerate the kernel table");
    }
    let record = std::fs::read_to_string(m7_record::root().join(RECORD_FILE)).expect("record");
    let text = std::fs::read_to_string(m7_record::root().join(docs.file)).expect("docs");
    let generated = m7_record::render_kernels(docs, &record).expect("render the kernel table");
    let expected = m7_record::splice_between(&text, docs.begin, docs.end, &generated)
        .expect("kernel table markers");
    assert!(
        expected == text,
        "{}'s kernel table differs from what {RECORD_FILE} generates; regenerate with\n  \
         {UPDATE_DOCS_COMMAND}",
        docs.file
    );
}

#[test]
fn the_planner_a_kernel_table_is_the_record() {
    kernel_table_is_the_record(&m7_record::KERNELS_A_DOCS);
}

#[test]
fn the_planner_b_kernel_table_is_the_record() {
    kernel_table_is_the_record(&m7_record::KERNELS_B_DOCS);
}

#[test]
fn the_leo_arc_kernel_table_is_the_record() {
    kernel_table_is_the_record(&m7_record::KERNELS_LEO_DOCS);
}

#[test]
fn the_leo_image_table_is_the_record() {
    let record = std::fs::read_to_string(
        m7_record::root().join(reconfig_tests::readme_figures::LEO_RECORD_FILE),
    )
    .expect("LEO record");
    let table = reconfig_tests::readme_figures::leo_image_table(&record).expect("render");
    reconfig_tests::doc_blocks::hold(DOCS_FILE, "m7-leo-image", "m7_docs", &table).unwrap();
}

/// docs/hybrid.md's M7 table, from `fixtures/golden/m7-figures-hybrid.toml`: per fixture the
/// instructions, the time at 400 MHz, the work units and instructions per unit, the stack.
fn hybrid_image_table(record: &str) -> Result<String, String> {
    let file: toml::Table = record.parse().map_err(|e| format!("{e}"))?;
    let number = |t: &toml::Table, key: &str| -> Result<f64, String> {
        t.get(key)
            .and_then(|v| v.as_float().or_else(|| v.as_integer().map(|i| i as f64)))
            .ok_or_else(|| format!("{key} missing"))
    };
    let mut out = String::from(
        "| fixture | instructions | at 400 MHz | work units | instructions per unit | stack |\n\
         | --- | ---: | ---: | ---: | ---: | ---: |\n",
    );
    let fixtures = file
        .get("hybrid_fixture")
        .and_then(|v| v.as_array())
        .ok_or("no [[hybrid_fixture]]")?;
    for f in fixtures {
        let t = f.as_table().ok_or("not a table")?;
        let name = t.get("name").and_then(|v| v.as_str()).ok_or("no name")?;
        let instructions = number(t, "instructions")?;
        out.push_str(&format!(
            "| `{name}` | {:.3} G | {:.2} s | {:.0} | {:.0} | {:.1} KB |\n",
            instructions / 1e9,
            instructions / 400e6,
            number(t, "work_units")?,
            number(t, "instructions_per_work_unit")?,
            number(t, "stack_bytes")? / 1000.0
        ));
    }
    let image = file
        .get("hybrid_image")
        .and_then(|v| v.as_table())
        .ok_or("no [hybrid_image]")?;
    let binary = file
        .get("hybrid_binary")
        .and_then(|v| v.as_table())
        .ok_or("no [hybrid_binary]")?;
    out.push_str(&format!(
        "\nThe image: {:.0} B of static RAM, {:.0} B of RAM with its largest stack, {:.1} KB of \
         text.\n",
        number(binary, "static_ram_bytes")?,
        number(image, "ram_bytes")?,
        number(binary, "text_bytes")? / 1000.0
    ));
    Ok(out)
}

#[test]
fn the_hybrid_image_table_is_the_record() {
    let record =
        std::fs::read_to_string(m7_record::root().join("fixtures/golden/m7-figures-hybrid.toml"))
            .expect("hybrid record");
    let table = hybrid_image_table(&record).expect("render");
    reconfig_tests::doc_blocks::hold("docs/hybrid.md", "m7-hybrid-image", "m7_docs", &table)
        .unwrap();
}
