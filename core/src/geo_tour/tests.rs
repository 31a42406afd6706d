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
