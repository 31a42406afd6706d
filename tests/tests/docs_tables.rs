//! The timing tables of `docs/` are the records their commands wrote
//! (`fixtures/golden/tables/NAME.md`, see `reconfig_host::table_record`): this fails when a
//! document's block differs from its record, when a block names no record, or when a record is
//! shown nowhere. `RECONFIG_UPDATE_DOCS=1` copies the records into the documents.

use reconfig_host::table_record::{self, DIR};
use reconfig_tests::m7_record::{root, splice_between};
use std::collections::BTreeSet;

/// The begin marker of the block that shows record `name`.
fn begin(name: &str) -> String {
    format!(
        "<!-- table {name}:begin (the record {}; do not edit) -->",
        table_record::relative_path(name)
    )
}

/// The end marker of the block that shows record `name`.
fn end(name: &str) -> String {
    format!("<!-- table {name}:end -->")
}

/// The records' names, from the files in [`DIR`].
fn records() -> BTreeSet<String> {
    std::fs::read_dir(root().join(DIR))
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|x| x == "md"))
        .map(|p| p.file_stem().unwrap().to_string_lossy().into_owned())
        .collect()
}

/// The names of the records that `text` shows, in order.
fn shown(text: &str) -> Vec<String> {
    text.match_indices("<!-- table ")
        .filter_map(|(at, _)| {
            let rest = &text[at + "<!-- table ".len()..];
            let (name, after) = rest.split_once(':')?;
            after.starts_with("begin").then(|| name.to_string())
        })
        .collect()
}

#[test]
fn every_timing_table_in_the_docs_is_its_record() {
    let update = std::env::var("RECONFIG_UPDATE_DOCS").as_deref() == Ok("1");
    let records = records();
    let mut used = BTreeSet::new();
    let mut docs: Vec<_> = std::fs::read_dir(root().join("docs"))
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|x| x == "md"))
        .collect();
    docs.push(root().join("README.md"));
    let mut problems = Vec::new();
    for doc in docs {
        let text = std::fs::read_to_string(&doc).unwrap();
        let mut expected = text.clone();
        for name in shown(&text) {
            if !records.contains(&name) {
                problems.push(format!("{}: no record {name} in {DIR}", doc.display()));
                continue;
            }
            used.insert(name.clone());
            let record = std::fs::read_to_string(table_record::path(&name)).unwrap();
            expected = splice_between(&expected, &begin(&name), &end(&name), &record)
                .unwrap_or_else(|e| panic!("{}: {e}", doc.display()));
        }
        if expected != text {
            if update {
                std::fs::write(&doc, &expected).unwrap();
            } else {
                problems.push(format!(
                    "{}: a timing table differs from its record (rewrite with \
                     RECONFIG_UPDATE_DOCS=1)",
                    doc.display()
                ));
            }
        }
    }
    for name in records.difference(&used) {
        problems.push(format!("the record {name} is shown in no document"));
    }
    assert!(problems.is_empty(), "{}", problems.join("\n"));
}

#[test]
fn a_record_line_names_its_command_and_its_date() {
    for name in records() {
        let text = std::fs::read_to_string(table_record::path(&name)).unwrap();
        let first = text.lines().next().unwrap_or("");
        assert!(
            (first.starts_with("Measured by `cargo run --release -p reconfig-host ")
                // The Python package's figures, measured from Python (docs/python.md).
                || first.starts_with("Measured by `python python/examples/"))
                && first.contains(" UTC (")
                && first.contains(" CPUs, load average "),
            "{name}: the first line does not say the command, the date and the load: {first}"
        );
    }
}
