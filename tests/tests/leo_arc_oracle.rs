//! The LEO per-arc search against an independent optimiser restarted from its own answers
//! (issue 31 item 2): `tests/oracle/leo_arc_optimum.py` (SciPy SLSQP in its own two-body + J2
//! model, DOP853 with the state transition matrix for gradients; burn epochs and inertial Δv
//! free, the last burn matching the client at the arc's end) took the plans of the held-out
//! arcs 1000-1015 of `examples/leo_arc_campaign.rs` (arcs never used to choose the search's
//! settings) and descended from each, keeping the cheapest answer that arrives within 1 m; its
//! answers are the golden file
//! `fixtures/golden/leo-arc-family-oracle.toml`.
//!
//! Here every arc is planned again (default settings, the on-board budget): the plan must be the
//! one the oracle started from (to the bit), and stays within the measured distance of the
//! oracle's local optimum; the README line holds the figure.
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

use reconfig_core::leo_tour::{solve_arc, ArcProblem, ArcSolution, Settings, Workspace};

/// The most the plan may stay above the oracle's optimum from it, relative: the measured worst
/// (+2.21 %, seed 1001, a four-impulse arc; +5.42 % before the descent) rounded up, so that a
/// regression of the search shows as a wider gap. Not the target: not every plan is at its
/// basin's bottom yet (docs/leo-tour.md, "Against an optimiser restarted from the plans").
const MAX_GAP: f64 = 0.025;

fn state(v: &toml::Value) -> [f64; 6] {
    let a: Vec<f64> = v
        .as_array()
        .unwrap()
        .iter()
        .map(|x| x.as_float().unwrap())
        .collect();
    a.try_into().unwrap()
}

#[test]
fn held_out_arcs_stay_near_the_oracles_optimum_from_their_own_plans() {
    let path = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../fixtures/golden/leo-arc-family-oracle.toml"
    );
    let golden: toml::Table = std::fs::read_to_string(path).unwrap().parse().unwrap();
    let arcs = golden["arcs"].as_array().unwrap();
    assert!(arcs.len() >= 16, "{} arcs", arcs.len());
    let settings = Settings::default();
    let mut ws = Box::new(Workspace::new());
    let (mut gaps, mut within_01) = (Vec::new(), 0);
    for g in arcs {
        let seed = g["seed"].as_integer().unwrap();
        let problem = ArcProblem {
            from: state(&g["from"]),
            to: state(&g["to"]),
            duration_s: g["duration_s"].as_float().unwrap(),
            impulses: u8::try_from(g["impulses"].as_integer().unwrap()).unwrap(),
        };
        let mut out = ArcSolution::new();
        solve_arc(&problem, &settings, &mut ws, &mut out).unwrap();
        let planned = g["plan_dv_mps"].as_float().unwrap();
        assert_eq!(
            out.total_dv_mps.to_bits(),
            planned.to_bits(),
            "seed {seed}: the plan is not the one the oracle started from ({} vs {planned}); \
             re-run the oracle (its usage line) and say why in the commit message",
            out.total_dv_mps
        );
        // The oracle flies the same burns to the same Δv (an independent model of the same
        // physics) and its optimum arrives.
        let flown = g["plan_dv_flown_mps"].as_float().unwrap();
        assert!((flown - planned).abs() < 1e-4 * planned, "seed {seed}");
        assert!(g["oracle_miss_m"].as_float().unwrap() < 1.0, "seed {seed}");
        let oracle = g["oracle_dv_mps"].as_float().unwrap();
        assert!(
            oracle <= flown + 1e-6,
            "seed {seed}: the oracle starts from the plan"
        );
        let gap = planned / oracle - 1.0;
        assert!(
            gap < MAX_GAP,
            "seed {seed}: {planned} m/s, the oracle's optimum from it {oracle} m/s (+{:.3} %)",
            100.0 * gap
        );
        if gap < 1e-3 {
            within_01 += 1;
        }
        gaps.push(gap);
    }
    let n = gaps.len();
    let worst = gaps.iter().fold(0.0_f64, |m, g| m.max(*g));
    let mean = gaps.iter().sum::<f64>() / n as f64;
    reconfig_host::figure_record::hold(
        "leo-arc-oracle",
        &reconfig_host::figure_record::Figure {
            what: "LEO arcs vs an independent J2 optimiser (SLSQP) restarted from our plans, \
                   held-out arcs 1000-1015"
                .into(),
            target: "the optimum of the option space".into(),
            measured: format!(
                "{within_01} of {n} within 0.1 %; mean +{:.2} %, worst +{:.2} %",
                100.0 * mean,
                100.0 * worst
            ),
            met: within_01 == n,
            doc: "leo-tour".into(),
            command: "cargo test -p reconfig-tests --test leo_arc_oracle".into(),
        },
    )
    .unwrap();
}
