//! The LEO tour document's tables of the published examples, built from what the regression
//! tests in `tests/tests/leo_tour_fixtures.rs` already computed (the plans, the oracle's
//! misses, the multi-round correction) plus the truth-model flights of each arc. Deterministic
//! (no times: those are in the on-board figure); the tests hold them to `docs/leo-tour.md`.

use reconfig_host::drivers::leo_tour::PlannedArc;
use reconfig_host::drivers::leo_truth::{replan_last_leg, truth_miss_m, Round};
use reconfig_host::fixture::leo_tour::LeoTourFixture;

/// The document the tables are in.
pub const DOC: &str = "docs/leo-tour.md";

/// "from → to", numbered from 1 as the paper does.
fn arc_label(a: &PlannedArc) -> String {
    format!("{} → {}", a.from + 1, a.to + 1)
}

/// Example I's arc table and its re-plan table, from its plans and the oracle's position
/// misses per arc (m).
///
/// # Panics
/// When a truth-model flight or re-plan fails (a test's failure).
pub fn example_one_arcs_and_replans(
    f: &LeoTourFixture,
    arcs: &[PlannedArc],
    oracle_m: &[f64],
) -> (String, String) {
    assert_eq!(oracle_m.len(), arcs.len());
    let mut table = String::from(
        "| arc | published Δv | ours | burns (m/s) | oracle miss (J2, from epoch) | truth J2-only \
         | truth full | evaluations / work units |\n| --- | --- | --- | --- | --- | --- | --- | --- |\n",
    );
    let mut replans = String::from(
        "| arc | miss before (truth full) | miss after | arc Δv after (before) |\n\
         | --- | --- | --- | --- |\n",
    );
    let (mut total, mut units) = (0.0, 0u64);
    for ((a, published), oracle_m) in arcs.iter().zip(&f.published.arc_dv_mps).zip(oracle_m) {
        let s = &a.solution;
        let burns: Vec<String> = s
            .burns
            .iter()
            .take(usize::from(s.impulses))
            .map(|b| format!("{:.3}", b.rtn_mps.iter().map(|x| x * x).sum::<f64>().sqrt()))
            .collect();
        let j2_m = truth_miss_m(a, false).unwrap();
        let full_m = truth_miss_m(a, true).unwrap();
        table.push_str(&format!(
            "| {} | {published:.3} | **{:.3}** | {} | {oracle_m:.2} m | {j2_m:.2} m | {full_m:.0} m \
             | {} / {:.2} M |\n",
            arc_label(a),
            s.total_dv_mps,
            burns.join(" / "),
            s.info.evaluations,
            s.info.work_units as f64 / 1e6,
        ));
        let (after_m, after_dv) = replan_last_leg(a, &f.settings).unwrap();
        replans.push_str(&format!(
            "| {} | {full_m:.0} m | {after_m:.1e} m | {after_dv:.3} ({:.3}) m/s |\n",
            arc_label(a),
            s.total_dv_mps
        ));
        total += s.total_dv_mps;
        units += s.info.work_units;
    }
    table.push_str(&format!(
        "| total | {:.3} | **{total:.3}** | | | | | {:.2} M |\n",
        f.published.total_dv_mps.unwrap(),
        units as f64 / 1e6
    ));
    (table, replans)
}

/// Example I's chained multi-round table.
pub fn example_one_multi_round(rounds: &[Round]) -> String {
    let mut chained = String::from(
        "| arc | planned from the truth (m/s) | flown (m/s) | start offset carried in | truth miss \
         before | after |\n| --- | --- | --- | --- | --- | --- |\n",
    );
    for r in rounds {
        let offset = if r.start_offset_m == 0.0 {
            "0".to_string()
        } else {
            format!("{:.1e} m", r.start_offset_m)
        };
        chained.push_str(&format!(
            "| {} | {:.3} | {:.3} | {offset} | {:.0} m | {:.1e} m |\n",
            arc_label(&r.arc),
            r.arc.solution.total_dv_mps,
            r.dv_after_mps,
            r.miss_before_m,
            r.miss_after_m
        ));
    }
    let flown: f64 = rounds.iter().map(|r| r.dv_after_mps).sum();
    chained.push_str(&format!("| total | | **{flown:.3}** | | | |\n"));
    chained
}

/// Example II's table (arcs as columns).
///
/// # Panics
/// When a truth-model flight fails (a test's failure).
pub fn example_two(f: &LeoTourFixture, arcs: &[PlannedArc]) -> String {
    let row = |name: &str, cells: Vec<String>, total: String| {
        format!("| {name} | {} | {total} |\n", cells.join(" | "))
    };
    let mut table = row("arc", arcs.iter().map(arc_label).collect(), "total".into());
    table.push_str(&row(
        "---",
        arcs.iter().map(|_| "---".to_string()).collect(),
        "---".into(),
    ));
    table.push_str(&row(
        "published Δv (m/s)",
        f.published
            .arc_dv_mps
            .iter()
            .map(|p| format!("{p:.3}"))
            .collect(),
        format!("{:.3}", f.published.total_dv_mps.unwrap()),
    ));
    let ours: f64 = arcs.iter().map(|a| a.solution.total_dv_mps).sum();
    table.push_str(&row(
        "ours (m/s)",
        arcs.iter()
            .map(|a| format!("{:.3}", a.solution.total_dv_mps))
            .collect(),
        format!("{ours:.3}"),
    ));
    table.push_str(&row(
        "truth J2-only miss (m)",
        arcs.iter()
            .map(|a| format!("{:.1}", truth_miss_m(a, false).unwrap()))
            .collect(),
        String::new(),
    ));
    table.push_str(&row(
        "truth full miss (km)",
        arcs.iter()
            .map(|a| format!("{:.1}", truth_miss_m(a, true).unwrap() / 1e3))
            .collect(),
        String::new(),
    ));
    table
}
