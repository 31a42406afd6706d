//! Planner A on the six generated families of issue 9 (`reconfig sweep`, 42 problems each,
//! seed 9): the three pairs of tables of `docs/planner-a.md` (budget lifted; lifted with one
//! alternative start; the on-board budget), statuses and cost gaps to the stored oracle, are
//! measured here and must be the document's (no solve time: a time is not deterministic;
//! `reconfig sweep` prints it). `RECONFIG_UPDATE_DOCS=1` rewrites the tables.

use reconfig_core::pseudospectral::{AlternativeStarts, Settings};
use reconfig_host::drivers::sweep_oracle::{load_golden, load_problems};
use reconfig_host::drivers::sweep_report::table_header;
use reconfig_host::drivers::sweep_run::{oracle_table, sweep, OracleData};
use reconfig_host::families::six;
use reconfig_tests::{doc_blocks, fixtures_dir};

/// `reconfig sweep`'s defaults for the families.
const PER_FAMILY: usize = 42;
const SEED: u64 = 9;

fn tables(block: &str, work_budget: Option<u64>, starts: Option<AlternativeStarts>) {
    let oracle: OracleData = (
        load_golden(&fixtures_dir().join("golden/planner-a-oracle.jsonl")).unwrap(),
        load_problems(&fixtures_dir().join("generated/planner-a-families.jsonl")).unwrap(),
    );
    let problems = six::generate_all(PER_FAMILY, SEED);
    let mut settings = Settings::default();
    if let Some(budget) = work_budget {
        settings.work_budget = budget;
    }
    let swept = sweep(
        &problems,
        Some(&oracle),
        &settings,
        starts,
        0,
        |_, _, _, _| Ok(()),
    )
    .unwrap();
    assert_eq!(
        swept.outcomes.iter().filter(|o| o.oracle.is_some()).count(),
        oracle.0.values().filter(|a| a.cost.is_some()).count(),
        "the generated families are not the stored problems the oracle solved"
    );
    let mut md = table_header("family", false, false);
    md.push('\n');
    let none = Default::default();
    for family in six::FAMILIES {
        md.push_str(
            &swept
                .tallies
                .get(family)
                .unwrap_or(&none)
                .row(family, false, false),
        );
        md.push('\n');
    }
    md.push('\n');
    md.push_str(&oracle_table(&swept.outcomes, &six::FAMILIES, false));
    doc_blocks::hold("docs/planner-a.md", block, "planner_a_families", &md).unwrap();
}

#[test]
fn the_budget_lifted_tables_are_measured() {
    tables("families-lifted", Some(1_000_000_000), None);
}

#[test]
fn the_one_alternative_start_tables_are_measured() {
    tables(
        "families-alternative-start",
        Some(1_000_000_000),
        Some(AlternativeStarts::One),
    );
}

#[test]
fn the_on_board_budget_tables_are_measured() {
    tables("families-on-board", None, None);
}
