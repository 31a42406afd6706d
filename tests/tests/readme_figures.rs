//! The README's "Where we stand" lines other than the M7 ones are the figure records of
//! `fixtures/golden/figures/` (each written by the test or command that measures it): this
//! fails when the README differs from them. `RECONFIG_UPDATE_DOCS=1` rewrites the README's
//! lines from the records.

use reconfig_tests::m7_record::{root, splice_between};
use reconfig_tests::readme_figures::{figure_lines, FIGURES_BEGIN, FIGURES_END, README_FILE};

#[test]
fn the_readme_figure_lines_are_the_records() {
    let generated = figure_lines().unwrap();
    let path = root().join(README_FILE);
    let text = std::fs::read_to_string(&path).unwrap();
    let expected = splice_between(&text, FIGURES_BEGIN, FIGURES_END, &generated).unwrap();
    if std::env::var("RECONFIG_UPDATE_DOCS").as_deref() == Ok("1") {
        std::fs::write(&path, expected).unwrap();
        return;
    }
    assert!(
        expected == text,
        "README.md's figure lines differ from fixtures/golden/figures/; expected\n{generated}\
         (rewrite them with RECONFIG_UPDATE_DOCS=1)"
    );
}
