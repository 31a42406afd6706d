//! Regression over the LEO tour fixtures (issue 13): the paper's single arc S1 -> S2 planned by
//! the core and checked against the published cost and against an independent oracle (SciPy's
//! own J2 flight of the same burns, `tests/oracle/leo_tour_j2.py`, golden file
//! `fixtures/golden/leo-tour-example1-single-arc-oracle.toml`).

use reconfig_core::leo_tour::SolveStatus;
use reconfig_core::limits::Limits;
use reconfig_host::drivers::leo_tour::plan;
use reconfig_host::drivers::leo_truth::replan_last_leg;
use reconfig_host::fixture::leo_tour::{load, parse};
use reconfig_tests::doc_blocks::hold;
use reconfig_tests::{fixtures_dir, leo_tables, order_text};

/// This file, as the docs' generated blocks name it.
const TEST: &str = "leo_tour_fixtures";

#[test]
fn paper_single_arc_beats_the_published_run_and_the_oracle_confirms_the_arrival() {
    let f = load(&fixtures_dir().join("leo-tour-example1-single-arc.toml")).unwrap();
    let arcs = plan(&f, &Limits::default()).unwrap();
    assert_eq!(arcs.len(), 1);
    let s = &arcs[0].solution;
    // The on-board budget (4 M units) cuts the search at its share; the plan it had is polished
    // and checked in the planning model with the rest: it arrives, usable.
    assert_eq!(
        s.info.status,
        SolveStatus::BudgetExhausted { verified: true }
    );
    // Published: 149.590 + 234.056 + 53.811 = 437.457 m/s (section 3.2).
    let published = f.published.total_dv_mps.unwrap();
    assert!(s.total_dv_mps <= published, "{} m/s", s.total_dv_mps);
    // The digest's plane-change + Hohmann lower bound for this arc: 403.8 m/s.
    assert!(s.total_dv_mps >= 403.8, "{} m/s", s.total_dv_mps);

    // The oracle's own J2 flight (DOP853, rtol 1e-13) of the plan arrives within 1 m with the
    // client's velocity to 1 mm/s; the planning model's RK4 at 20 s accounts for the rest.
    let misses = check_against_golden(&arcs, "leo-tour-example1-single-arc-oracle.toml");
    assert!(misses[0].0 < 1.0, "oracle miss {} m", misses[0].0);
    assert!(
        misses[0].1 < 1e-3,
        "oracle velocity miss {} m/s",
        misses[0].1
    );
    // Re-planned against the full truth model from the truth state at the last leg's
    // departure, the arc arrives within 1 m (measured 1.1e-5 m) for about the same Δv.
    let (miss_after_m, dv_after) = replan_last_leg(&arcs[0], &f.settings).unwrap();
    assert!(miss_after_m < 1.0, "{miss_after_m} m");
    assert!((dv_after - s.total_dv_mps).abs() < 1.0, "{dv_after} m/s");
    let miss_m = s.miss_m.unwrap();
    assert!(miss_m < 1e-3, "planning-model miss {miss_m} m");
}

/// The burns of `arcs` equal those the oracle flew (so its verdict applies); its (position m,
/// velocity m/s) misses per arc.
fn check_against_golden(
    arcs: &[reconfig_host::drivers::leo_tour::PlannedArc],
    golden: &str,
) -> Vec<(f64, f64)> {
    let golden: toml::Table = toml::from_str(
        &std::fs::read_to_string(fixtures_dir().join("golden").join(golden)).unwrap(),
    )
    .unwrap();
    let garcs = golden["arcs"].as_array().unwrap();
    assert_eq!(garcs.len(), arcs.len());
    let mut out = Vec::new();
    for (a, g) in arcs.iter().zip(garcs) {
        let s = &a.solution;
        let epochs = g["epochs_s"].as_array().unwrap();
        let rtn = g["dv_rtn_mps"].as_array().unwrap();
        for (k, b) in s.burns.iter().take(usize::from(s.impulses)).enumerate() {
            let e = epochs[k].as_float().unwrap();
            assert!(
                (a.start_s + b.epoch_s - e).abs() < 1e-6,
                "burn {k} epoch {} vs {e}",
                a.start_s + b.epoch_s
            );
            for (c, gv) in b.rtn_mps.iter().zip(rtn[k].as_array().unwrap()) {
                let gv = gv.as_float().unwrap();
                assert!((c - gv).abs() < 1e-6, "burn {k}: {c} vs {gv} m/s");
            }
        }
        out.push((
            g["oracle_miss_m"].as_float().unwrap(),
            g["oracle_velocity_miss_mps"].as_float().unwrap(),
        ));
    }
    out
}

#[test]
fn example_one_printed_order_is_solved_and_below_the_published_total() {
    let f = load(&fixtures_dir().join("leo-tour-example1-printed.toml")).unwrap();
    let arcs = plan(&f, &Limits::default()).unwrap();
    let published = &f.published.arc_dv_mps;
    let mut total = 0.0;
    // Issue 31's reference: plans of these arcs in the same J2 model, flown independently.
    let reference = [406.761, 376.330, 331.679, 93.888];
    for (n, a) in arcs.iter().enumerate() {
        // Each plan checked: it arrives (three searches cut by the on-board budget of 4 M
        // units, `BudgetExhausted { verified: true }`; arc 3 -> 4 ends within it, `Solved`).
        assert!(a.solution.info.status.is_usable(), "arc {n}");
        assert!(a.solution.info.work_units <= 4_000_000, "arc {n}");
        total += a.solution.total_dv_mps;
        // Every arc at or below Table 2 (418.445 / 412.098 / 347.365 / 115.743 m/s) and
        // within 1 % of the reference (measured 408.307 / 376.608 / 330.728 / 93.885).
        assert!(a.solution.total_dv_mps <= published[n], "arc {n}");
        assert!(
            a.solution.total_dv_mps <= 1.01 * reference[n],
            "arc {n}: {}",
            a.solution.total_dv_mps
        );
    }
    assert!(total <= f.published.total_dv_mps.unwrap(), "{total}");
    // Issue 31's figure: the total at most 1215 m/s (issue 13's was 1245; the paper's
    // stochastic search leaves 6 % on the table).
    assert!(total <= 1215.0, "{total}");
    assert!((total - 1209.528).abs() < 0.01, "{total}");
    let cut = arcs
        .iter()
        .filter(|a| a.solution.info.status == SolveStatus::BudgetExhausted { verified: true })
        .count();
    reconfig_host::figure_record::hold(
        "leo-example-one",
        &reconfig_host::figure_record::Figure {
            what: "LEO tour, Example I printed order".into(),
            target: "total ≤ 1215 m/s".into(),
            measured: format!(
                "{total:.3} m/s, every arc's plan checked ({cut} of {} searches cut by the on-board budget: `BudgetExhausted {{ verified: true }}`)",
                arcs.len()
            ),
            met: total <= 1215.0 && arcs.iter().all(|a| a.solution.info.status.is_usable()),
            doc: "leo-tour".into(),
            command: "cargo test -p reconfig-tests --test leo_tour_fixtures".into(),
        },
    )
    .unwrap();
    // The oracle flies every client from the epoch with its own integrator: the misses include
    // the planning model's RK4 error in the clients' states at each arc start (measured 0.11 /
    // 19.5 / 32.3 / 43.7 m), which is what re-planning against the truth is for.
    let oracle = check_against_golden(&arcs, "leo-tour-example1-printed-oracle.toml");
    for (n, (m, v)) in oracle.iter().enumerate() {
        assert!(*m < 50.0 && *v < 0.05, "arc {n}: {m} m, {v} m/s");
    }
    // The document's tables of these plans, their truth flights and re-plans.
    let oracle_m: Vec<f64> = oracle.iter().map(|(m, _)| *m).collect();
    let (arcs_table, replans) = leo_tables::example_one_arcs_and_replans(&f, &arcs, &oracle_m);
    hold(leo_tables::DOC, "leo-example-one-arcs", TEST, &arcs_table).unwrap();
    hold(leo_tables::DOC, "leo-example-one-replan", TEST, &replans).unwrap();
}

#[test]
fn a_tour_fixture_outside_the_limits_is_refused_by_name() {
    let text = std::fs::read_to_string(fixtures_dir().join("leo-tour-example1-single-arc.toml"))
        .unwrap()
        .replace("impulses = 3", "impulses = 5");
    let f = parse(&text).unwrap();
    // Refused by the limits (at most 4 impulses an arc) before the planner sees it, named.
    let err = plan(&f, &Limits::default()).unwrap_err().to_string();
    assert!(err.contains("impulses = 5 is above the limit 4"), "{err}");
    let bad = std::fs::read_to_string(fixtures_dir().join("leo-tour-example1-single-arc.toml"))
        .unwrap()
        .replace("order = [1, 2]", "order = [1, 3]");
    let err = parse(&bad).unwrap_err().to_string();
    assert!(err.contains("order[1] = 3"), "{err}");
}

#[test]
fn example_one_order_is_chosen_by_branch_and_bound_deterministically() {
    use reconfig_core::leo_tour::bound::{arc_bound_mps, plane_of, BoundSettings};
    use reconfig_core::leo_tour::sequence::SequenceSettings;
    use reconfig_core::leo_tour::sequence::SequenceStatus;
    use reconfig_host::drivers::leo_tour::choose_order;
    // On board: the estimates' and the sequencing's defaults, the built-in limits.
    let f = load(&fixtures_dir().join("leo-tour-example1-sequence.toml")).unwrap();
    let (chosen, c) = choose_order(&f, &Limits::default()).unwrap().unwrap();
    let q = c.sequence;
    // Over all 120 orders (free first client), every arc either planned or pruned by the
    // bound, and no planned arc cheaper than its bound, within the work budget: the order is
    // the cheapest for the sequencing's arc estimates (`leo_tour::estimate_arc_mps`, the
    // search model's costs; measured 4 -> 3 -> 1 -> 5 -> 2, 1079.782 m/s with the coarse
    // estimates, 86 of the tree's 320 arcs planned, 3,215,457 of the 4 M units; 3 -> 4 -> 5 ->
    // 1 -> 2 and 1227.143 m/s before the node seed, issue 31).
    let i = q.info;
    assert_eq!(i.status, SequenceStatus::Optimal);
    assert_eq!(i.orders_total, 120);
    assert_eq!(i.arcs_in_tree, 320);
    assert_eq!(i.bound_violations, 0);
    assert!(i.arcs_planned < 160, "{} arcs planned", i.arcs_planned);
    let budget = SequenceSettings::DEFAULT.work_budget;
    assert!(
        i.work_units <= budget && i.work_units > budget / 2,
        "{}",
        i.work_units
    );
    assert_eq!(chosen.order, vec![3, 2, 0, 4, 1]);
    let q_total = q.total_dv_mps.unwrap();
    assert!((q_total - 1079.782).abs() < 0.01, "{q_total}");
    // Repeatable: the same request gives the same bits.
    let (_, again) = choose_order(&f, &Limits::default()).unwrap().unwrap();
    assert_eq!(again.sequence, q);
    // The chosen order planned with the full arc search: below the paper's best order of
    // Table 5 (2 -> 5 -> 4 -> 3 -> 1, 1224.122 m/s; measured 1041.217 m/s), every arc's plan
    // checked (some searches cut by the on-board budget: `BudgetExhausted { verified: true }`).
    let arcs = plan(&chosen, &Limits::default()).unwrap();
    let total: f64 = arcs.iter().map(|a| a.solution.total_dv_mps).sum();
    assert!(arcs.iter().all(|a| a.solution.info.status.is_usable()));
    assert!((total - 1041.217).abs() < 0.01, "{total}");
    assert!(total <= 1224.122, "{total}");
    let on_board = (
        order_text(&chosen.order),
        i.work_units,
        total,
        arcs.iter().all(|a| a.solution.info.status.is_usable()),
    );

    // On the ground: the finer estimates need the whole tree's 22.7 M units, above the
    // built-in limit (refused, naming the setting), within the ground limits.
    let ground =
        load(&fixtures_dir().join("over-limits/leo-tour-example1-sequence-ground.toml")).unwrap();
    let refused = choose_order(&ground, &Limits::default())
        .unwrap_err()
        .to_string();
    assert!(
        refused.contains("work_budget = 24000000 is above the limit 4000000"),
        "{refused}"
    );
    let limits =
        reconfig_host::limits::load(&fixtures_dir().join("over-limits/ground-limits.toml"))
            .unwrap();
    let (chosen, c) = choose_order(&ground, &limits).unwrap().unwrap();
    let i = c.sequence.info;
    assert_eq!(i.status, SequenceStatus::Optimal);
    assert!(
        i.work_units > budget && i.work_units <= 24_000_000,
        "{}",
        i.work_units
    );
    // Measured 4 -> 3 -> 1 -> 5 -> 2, 1046.836 m/s in the finer estimates, 95 arcs planned, 20.0
    // M units: the on-board order (before the node seed the ground's was 7.7 % cheaper).
    assert_eq!(chosen.order, vec![3, 2, 0, 4, 1]);
    let ground_total = c.sequence.total_dv_mps.unwrap();
    assert!((ground_total - 1046.836).abs() < 0.01, "{ground_total}");
    // Planned in full: 1041.217 m/s, the on-board order's plans.
    let arcs = plan(&chosen, &Limits::default()).unwrap();
    let total: f64 = arcs.iter().map(|a| a.solution.total_dv_mps).sum();
    assert!(arcs.iter().all(|a| a.solution.info.status.is_usable()));
    assert!((total - 1041.217).abs() < 0.01, "{total}");
    assert!(total <= ground_total + 1e-9, "{total}");
    reconfig_host::figure_record::hold(
        "leo-sequencing-on-board",
        &reconfig_host::figure_record::Figure {
            what: "LEO tour sequencing, all 120 orders, one on-board request (4 M units)".into(),
            target: "best order for its estimates, deterministic".into(),
            measured: format!(
                "{} `Optimal` in {:.2} M units, {:.3} m/s planned (ground, {:.1} M units: {}, {total:.3})",
                on_board.0,
                on_board.1 as f64 / 1e6,
                on_board.2,
                i.work_units as f64 / 1e6,
                order_text(&chosen.order),
            ),
            met: on_board.3,
            doc: "leo-tour".into(),
            command: "cargo test -p reconfig-tests --test leo_tour_fixtures".into(),
        },
    )
    .unwrap();
    // Ranked by full plans (a ground design): refused on board by name even within the
    // budget, and the cheapest full plan of the tree on the ground (its brute force:
    // tests/tests/leo_tour_sequence_oracle.rs), below both orders above planned in full.
    let full_path = fixtures_dir().join("over-limits/leo-tour-example1-sequence-full-plans.toml");
    let within_budget = parse(
        &std::fs::read_to_string(&full_path)
            .unwrap()
            .replace("work_budget = 400000000", "work_budget = 4000000"),
    )
    .unwrap();
    let refused = choose_order(&within_budget, &Limits::default())
        .unwrap_err()
        .to_string();
    assert!(
        refused.contains("full_plans = on: the limits require it off"),
        "{refused}"
    );
    let full = load(&full_path).unwrap();
    let (chosen, c) = choose_order(&full, &limits).unwrap().unwrap();
    assert!(c.full_plans);
    assert_eq!(c.sequence.info.status, SequenceStatus::Optimal);
    let ranked = c.sequence.total_dv_mps.unwrap();
    let arcs = plan(&chosen, &Limits::default()).unwrap();
    let flown: f64 = arcs.iter().map(|a| a.solution.total_dv_mps).sum();
    // The arcs planned again are the plans that ranked the order (same search, same bits
    // up to the sum's order).
    assert!((flown - ranked).abs() < 1e-9, "{flown} {ranked}");
    // The same order as the finer estimates' (measured 4 -> 3 -> 1 -> 5 -> 2, 1041.217 m/s;
    // before the node seed the full plans' order was more than 5 m/s below the finer
    // estimates' 1103.145).
    assert!((flown - total).abs() < 1e-9, "{flown}");
    // The bound is below every planned arc of both Example I tours.
    let g = f.settings.gravity();
    let printed = load(&fixtures_dir().join("leo-tour-example1-printed.toml")).unwrap();
    for a in arcs
        .iter()
        .chain(plan(&printed, &Limits::default()).unwrap().iter())
    {
        let pa = plane_of(&g, &f.clients[a.from]).unwrap();
        let pb = plane_of(&g, &f.clients[a.to]).unwrap();
        let b = arc_bound_mps(
            &g,
            &pa,
            &pb,
            a.start_s,
            a.end_s - a.start_s,
            &BoundSettings::default(),
        );
        println!(
            "arc {} -> {} at {:.0} s: bound {b:.3} m/s, planned {:.3} m/s ({:.1} %)",
            a.from + 1,
            a.to + 1,
            a.start_s,
            a.solution.total_dv_mps,
            100.0 * b / a.solution.total_dv_mps
        );
        assert!(b <= a.solution.total_dv_mps && b > 0.5 * a.solution.total_dv_mps);
    }
}

#[test]
fn example_one_flown_in_the_truth_model_with_multi_round_correction_arrives_within_a_metre() {
    use reconfig_host::drivers::leo_truth::{all_within, multi_round};
    // The paper's multi-round correction, chained: each arc planned by the core from the truth
    // states reached (JGM-3 8x8, drag, Sun, Moon), its last leg re-planned against the truth,
    // the next arc starting where the chaser really is. Issue 13: every arrival within 1 m
    // (the paper's tolerance was 5 km); the misses before and after are in the table held
    // below; flown 1209.500 m/s (each round warm-started; 1235.148 before the node seed).
    let f = load(&fixtures_dir().join("leo-tour-example1-printed.toml")).unwrap();
    let rounds = multi_round(
        &f,
        &plan(&f, &Limits::default()).unwrap(),
        &Limits::default(),
    )
    .unwrap();
    assert_eq!(rounds.len(), 4);
    assert!(all_within(&rounds, 1.0));
    for r in &rounds {
        // The previous round's arrival miss is what the next one starts with.
        assert!(r.start_offset_m < 1.0, "{}", r.start_offset_m);
        // Uncorrected, the J2 plan misses by far more than the tolerance: the correction is
        // doing the work (a wrong truth model or no correction would fail one or the other).
        assert!(r.miss_before_m > 100.0, "{}", r.miss_before_m);
        assert!((r.dv_after_mps - r.arc.solution.total_dv_mps).abs() < 1.0);
    }
    let flown: f64 = rounds.iter().map(|r| r.dv_after_mps).sum();
    assert!((flown - 1209.500).abs() < 0.05, "{flown}");
    let table = leo_tables::example_one_multi_round(&rounds);
    hold(leo_tables::DOC, "leo-example-one-multi-round", TEST, &table).unwrap();
}

#[test]
fn example_two_every_arc_is_usable_and_its_table_is_measured() {
    let f = load(&fixtures_dir().join("leo-tour-example2.toml")).unwrap();
    let arcs = plan(&f, &Limits::default()).unwrap();
    assert!(arcs.iter().all(|a| a.solution.info.status.is_usable()));
    let table = leo_tables::example_two(&f, &arcs);
    hold(leo_tables::DOC, "leo-example-two", TEST, &table).unwrap();
}

#[test]
fn the_papers_interval_rule_gives_the_digests_intervals() {
    use reconfig_core::leo_tour::bound::plane_of;
    use reconfig_core::leo_tour::sequence::paper_rule_duration_s;
    // Along each example's printed order, each arc starting where the rule's previous arcs end,
    // the nodes drifted to that start by the secular J2 rates. The digest (SPEC-servicing.md, "Checked here") finds 1/2, 1, 1/2, 1 for
    // Example I (printed 1/2, 1, 1, 1: arc 5 -> 3 is a knife edge between sun-synchronous
    // clients) and, with drifted nodes, 1, 1, 1, 1/2, 1.93 d, 1 for Example II (printed 1, 1/2,
    // 1, 1/2, 1, 1).
    for (fixture, expected) in [
        ("leo-tour-example1-printed.toml", vec![0.5, 1.0, 0.5, 1.0]),
        (
            "leo-tour-example2.toml",
            vec![1.0, 1.0, 1.0, 0.5, f64::NAN, 1.0],
        ),
    ] {
        let f = load(&fixtures_dir().join(fixture)).unwrap();
        let g = f.settings.gravity();
        let planes: Vec<_> = f.clients.iter().map(|s| plane_of(&g, s).unwrap()).collect();
        let first = &planes[f.order[0]];
        let dt_max = 30.0 * 2.0 * std::f64::consts::PI * (first.a_km.powi(3) / g.mu_km3_s2).sqrt();
        let mut t0 = 0.0;
        let mut got = Vec::new();
        for pair in f.order.windows(2) {
            let dt = paper_rule_duration_s(
                &g,
                first,
                (&planes[pair[0]], &planes[pair[1]]),
                t0,
                (30.0, 6000.0),
            );
            got.push(dt / dt_max);
            t0 += dt;
        }
        println!("{fixture}: {got:?} of dt_max {dt_max:.1} s");
        for (k, (g, e)) in got.iter().zip(&expected).enumerate() {
            if e.is_nan() {
                // A closing gap: shorter than dt_max, about 1.93 days.
                assert!(
                    *g < 1.0 && (g * dt_max / 86_400.0 - 1.93).abs() < 0.1,
                    "arc {k}: {g}"
                );
            } else {
                assert!((g - e).abs() < 1e-12, "{fixture} arc {k}: {g} vs {e}");
            }
        }
    }
}

#[test]
fn the_on_board_part_in_the_core_is_the_hosts_sequencing_and_plans_bit_for_bit() {
    use reconfig_core::leo_tour::tour_order::{
        plan_onboard, OnboardPlan, OnboardProblem, SequenceWorkspace,
    };
    use reconfig_host::drivers::leo_tour::choose_order;
    // The core's whole on-board part as one function against what `reconfig solve` does (the
    // sequencing request, then each arc's request): the same order and the same arcs, to the
    // bit.
    let f = load(&fixtures_dir().join("leo-tour-example1-sequence.toml")).unwrap();
    let spec = f.sequence.unwrap();
    let problem = OnboardProblem {
        tour: f.sequence_problem().unwrap(),
        sequence: spec.settings,
        estimates: spec.arc_settings,
        arcs: f.settings,
    };
    let mut onboard = Box::new(OnboardPlan::new());
    let mut workspace = Box::new(SequenceWorkspace::new());
    plan_onboard(&problem, &mut workspace, &mut onboard).unwrap();
    let (chosen, c) = choose_order(&f, &Limits::default()).unwrap().unwrap();
    assert_eq!(onboard.sequence, c.sequence);
    let host = plan(&chosen, &Limits::default()).unwrap();
    assert_eq!(host.len(), 4);
    for (k, (core_arc, host_arc)) in onboard.arcs.iter().zip(&host).enumerate() {
        assert_eq!(
            core_arc.as_ref().unwrap().as_ref().unwrap(),
            &host_arc.solution,
            "arc {k}"
        );
    }
    assert!(onboard.arcs[4..].iter().all(Option::is_none));
    let total: f64 = host.iter().map(|a| a.solution.total_dv_mps).sum();
    assert!((total - 1041.217).abs() < 0.01, "{total}");
}

#[test]
fn the_leo_worst_case_sequencing_spends_its_whole_budget_and_stays_within_it() {
    use reconfig_core::leo_tour::sequence::{SequenceSettings, SequenceStatus};
    use reconfig_host::drivers::leo_tour::choose_order;
    // fixtures/worst-case/: the held-out generated tour whose on-board sequencing spent the
    // most (`leo_sequence_campaign -- fixture 1039`), which the LEO image runs on the M7.
    let f =
        load(&fixtures_dir().join("worst-case/leo-sequence-5-clients-full-budget.toml")).unwrap();
    let (_, c) = choose_order(&f, &Limits::default()).unwrap().unwrap();
    let i = c.sequence.info;
    let budget = SequenceSettings::DEFAULT.work_budget;
    assert_eq!(i.status, SequenceStatus::BudgetExhausted { verified: true });
    assert!(
        i.work_units <= budget && i.work_units > budget - 1_000,
        "{}",
        i.work_units
    );
    assert_eq!(c.sequence.len, 5);
}
