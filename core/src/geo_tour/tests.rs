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
