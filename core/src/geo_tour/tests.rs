//! Unit tests of the whole planner on the published case.
#![allow(
    clippy::unwrap_used,
    clippy::indexing_slicing,
    clippy::float_cmp,
    clippy::arithmetic_side_effects
)]

use super::*;
extern crate std;

pub(crate) const DEG: f64 = core::f64::consts::PI / 180.0;
pub(crate) const DAY: f64 = 86_400.0;

pub(crate) fn published(days: f64, policy: MethodPolicy) -> Problem {
    let mut targets = heapless::Vec::new();
    for lon in [
        50.0, 59.0, 60.0, 60.12, 60.5, 125.0, 128.0, 129.93, 130.0, 160.0, 160.2,
    ] {
        targets.push(lon * DEG).unwrap();
    }
    Problem {
        start_lon_rad: 48.0 * DEG,
        targets_lon_rad: targets,
        mission_time_s: days * DAY,
        max_burn_mps: 5.0,
        sweep: SweepChoice::Cheaper,
        policy,
    }
}

fn run(p: &Problem) -> Solution {
    let mut ws = Workspace::new();
    let mut out = Solution::new();
    solve(p, &Settings::default(), &mut ws, &mut out).unwrap();
    out
}

#[test]
fn published_case_is_solved_both_ways() {
    for policy in [MethodPolicy::ByCost, MethodPolicy::PaperRule] {
        for days in [50.0, 60.0, 70.0, 80.0] {
            let s = run(&published(days, policy));
            std::println!(
                "{policy:?} {days}: {:?} dv {:.4} t {:.4} d max {:.3} price {:.3e} it {} gap {} ref {}",
                s.info.status,
                s.total_dv_mps,
                s.mission_time_s / DAY,
                s.max_burn_mps,
                s.info.price_mps_per_s,
                s.info.price_iterations,
                s.info.gap_assignments,
                s.info.refined_legs
            );
            for l in &s.legs {
                std::println!(
                    "   {:7.2} -> {:7.2} {:?} t {:.4} d dv {:.4} max {:.3} revs {}",
                    l.from_lon_rad / DEG,
                    l.to_lon_rad / DEG,
                    l.method,
                    l.duration_s / DAY,
                    l.dv_mps,
                    l.max_burn_mps,
                    l.revolutions
                );
            }
            assert_eq!(s.info.status, SolveStatus::Solved);
            assert!(s.mission_time_s <= days * DAY);
            assert!(s.max_burn_mps <= 5.0);
        }
    }
}

/// `Cheaper` cuts the west sweep short when it provably cannot fit or cannot be cheaper: its
/// answer must still be exactly the cheaper of the two sweeps planned on their own (east on a
/// tie), in cases where west is infeasible, feasible but dearer, and the only sweep that fits.
#[test]
fn cheaper_is_the_better_of_both_sweeps_planned_alone() {
    let row = |start: f64, spacing: f64, days: f64| {
        let mut p = published(days, MethodPolicy::ByCost);
        p.start_lon_rad = start * DEG;
        p.targets_lon_rad.clear();
        for k in 1..=16 {
            p.targets_lon_rad
                .push(wrap_two_pi((start + spacing * f64::from(k)) * DEG))
                .unwrap();
        }
        p
    };
    let mut cases = std::vec![
        published(40.0, MethodPolicy::ByCost),
        published(120.0, MethodPolicy::ByCost),
        row(48.0, 0.7, 200.0),
        row(48.0, 0.13, 150.0),
        // Clients spread just short of the full ring eastward: the west sweep wins.
        row(48.0, 21.0, 120.0),
    ];
    cases.push(row(48.0, -0.7, 200.0));
    let mut west_won = false;
    for p in cases {
        let cheaper = run(&p);
        let mut e = p.clone();
        e.sweep = SweepChoice::East;
        let mut w = p.clone();
        w.sweep = SweepChoice::West;
        let (east, west) = (run(&e), run(&w));
        let solved = |s: &Solution| s.info.status == SolveStatus::Solved;
        let want = if solved(&west) && (!solved(&east) || west.total_dv_mps < east.total_dv_mps) {
            west_won = true;
            &west
        } else {
            &east
        };
        assert_eq!(cheaper.info.status, want.info.status);
        assert_eq!(cheaper.info.direction, want.info.direction);
        assert_eq!(cheaper.total_dv_mps, want.total_dv_mps);
        assert_eq!(cheaper.legs, want.legs);
    }
    assert!(west_won, "no case where the west sweep wins");
}

#[test]
fn a_lambert_well_whose_bottom_is_within_the_cap_is_kept() {
    // Issue 31: one client 2 deg east in 3 days under a 2 m/s cap. The two-revolution Lambert
    // well's first golden points break the cap, but its bottom does not (3.8023 m/s, largest
    // burn 1.901 m/s, the same plan as under a 3 m/s cap); the section used to close on the
    // window's near end and lose the well, planning a drift leg at 4.5366 m/s.
    let mut targets = heapless::Vec::new();
    targets.push(50.0 * DEG).unwrap();
    let problem = |cap_mps: f64| Problem {
        start_lon_rad: 48.0 * DEG,
        targets_lon_rad: targets.clone(),
        mission_time_s: 3.0 * DAY,
        max_burn_mps: cap_mps,
        sweep: SweepChoice::Cheaper,
        policy: MethodPolicy::ByCost,
    };
    let (tight, loose) = (run(&problem(2.0)), run(&problem(3.0)));
    for s in [&tight, &loose] {
        assert_eq!(s.info.status, SolveStatus::Solved);
        let leg = &s.legs[0];
        assert_eq!(
            (leg.method, leg.revolutions),
            (Method::Lambert, 2),
            "{leg:?}"
        );
        assert!((s.total_dv_mps - 3.8023).abs() < 1e-3, "{}", s.total_dv_mps);
        assert!(
            s.max_burn_mps <= 2.0 && s.max_burn_mps > 1.9,
            "{}",
            s.max_burn_mps
        );
    }
}

#[test]
fn a_client_given_as_the_start_slots_equivalent_longitude_is_in_the_start_slot() {
    // Issue 31: -312 deg is 48 deg; the wrapped offset's rounding made it a leg (a 9-hour
    // Lambert of 0 m/s that took time from the next leg), or a revolution away.
    let one = |lons: &[f64]| {
        let mut targets = heapless::Vec::new();
        for &l in lons {
            targets.push(l * DEG).unwrap();
        }
        run(&Problem {
            start_lon_rad: 48.0 * DEG,
            targets_lon_rad: targets,
            mission_time_s: 5.0 * DAY,
            max_burn_mps: 5.0,
            sweep: SweepChoice::Cheaper,
            policy: MethodPolicy::ByCost,
        })
    };
    let (equivalent, alone) = (one(&[-312.0, 50.0]), one(&[50.0]));
    assert_eq!(equivalent.info.status, SolveStatus::Solved);
    let first = &equivalent.legs[0];
    assert_eq!(
        (first.method, first.duration_s, first.dv_mps),
        (Method::None, 0.0, 0.0),
        "{first:?}"
    );
    // The whole mission is left to the one leg that flies: the plan of the client alone.
    assert_eq!(
        equivalent.total_dv_mps.to_bits(),
        alone.total_dv_mps.to_bits()
    );
    assert_eq!(
        equivalent.legs[1].duration_s.to_bits(),
        alone.legs[0].duration_s.to_bits()
    );
}

#[test]
fn the_paper_rule_gives_a_phase_at_its_threshold_the_same_method_at_any_base_longitude() {
    // Issue 31: a client 0.25 deg east (the rule's Hohmann threshold) got `Radial` or
    // `Hohmann` depending on how the base longitude rounded the offset; at the threshold the
    // rule says radial ("Hohmann above 0.25 deg").
    for base_deg in [0.1, 10.3, 48.0, 123.7, 200.9, 300.3, 359.6] {
        let mut targets = heapless::Vec::new();
        targets
            .push(crate::astro::wrap_two_pi((base_deg + 0.25) * DEG))
            .unwrap();
        let s = run(&Problem {
            start_lon_rad: base_deg * DEG,
            targets_lon_rad: targets,
            mission_time_s: 5.0 * DAY,
            max_burn_mps: 5.0,
            sweep: SweepChoice::East,
            policy: MethodPolicy::PaperRule,
        });
        assert_eq!(s.info.status, SolveStatus::Solved, "{base_deg}");
        assert_eq!(s.legs[0].method, Method::Radial, "{base_deg}");
    }
}

#[test]
fn the_paper_rule_with_free_lambert_time_keeps_the_rules_methods_and_costs_no_more() {
    // Issue 31: the rule's methods, its Lambert legs timed by the allocation (their wells)
    // instead of the rule's 9 h: never dearer than the rule, never cheaper than by cost.
    for days in [50.0, 60.0, 70.0, 80.0] {
        let rule = run(&published(days, MethodPolicy::PaperRule));
        let free = run(&published(days, MethodPolicy::PaperRuleFreeLambert));
        let cost = run(&published(days, MethodPolicy::ByCost));
        std::println!(
            "{days} d: rule {:.4} free Lambert {:.4} by cost {:.4}",
            rule.total_dv_mps,
            free.total_dv_mps,
            cost.total_dv_mps
        );
        assert_eq!(free.info.status, SolveStatus::Solved);
        for (r, f) in rule.legs.iter().zip(free.legs.iter()) {
            assert_eq!(r.method, f.method, "{days} d");
        }
        // Both Lambert legs (0.12 and 0.07 deg) leave the rule's 9 h for a well.
        let lambert: std::vec::Vec<_> = free
            .legs
            .iter()
            .filter(|l| l.method == Method::Lambert)
            .collect();
        assert_eq!(lambert.len(), 2);
        assert!(lambert.iter().all(|l| l.transfer_s > 12.0 * 3600.0));
        assert!(free.total_dv_mps < rule.total_dv_mps - 1.0, "{days} d");
        assert!(free.total_dv_mps >= cost.total_dv_mps - 1e-9, "{days} d");
    }
}
