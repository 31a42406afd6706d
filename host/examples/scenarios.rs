//! Solve the demo's generated planner-A crossing scenarios (every spacecraft swaps to the
//! antipodal point of a circle, so all of them meet at its centre at T/2) and count the
//! statuses; print the ones that are not `Solved`.
//!
//! `cargo run --release -p reconfig-host --example scenarios -- [COUNT] [TRACE_INDEX]`
//! With TRACE_INDEX, print that scenario's cost after 1..=80 convex subproblems instead.

use reconfig_core::pseudospectral::{self, Settings, Solution, SolveStatus, Workspace};
use reconfig_core::wire::Request;
use reconfig_host::harness::feeder::Payload;
use std::collections::BTreeMap;

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let count: usize = std::env::args()
        .nth(1)
        .map(|s| s.parse())
        .transpose()?
        .unwrap_or(300);
    let trace: Option<usize> = std::env::args().nth(2).map(|s| s.parse()).transpose()?;
    let mut ws = Box::new(Workspace::new());
    let mut out = Box::new(Solution::new());
    let mut statuses = BTreeMap::new();
    for (k, item) in reconfig_host::scenario::generate(count, 1)
        .into_iter()
        .enumerate()
    {
        let Payload::Request(request) = item.payload else {
            continue;
        };
        let Request::Pseudospectral { problem, .. } = *request else {
            continue;
        };
        if let Some(index) = trace {
            if index == k {
                for iterations in 1..=80u16 {
                    let settings = Settings {
                        sqp_max_iter: iterations,
                        verify_max_rounds: 0,
                        ..Settings::default()
                    };
                    pseudospectral::solve(&problem, &settings, &mut ws, &mut out)?;
                    println!(
                        "{iterations} J={:.12} min_sep={:.9?} {:?}",
                        out.cost, out.min_separation_lu, out.info.status
                    );
                }
                return Ok(());
            }
            continue;
        }
        pseudospectral::solve(&problem, &Settings::default(), &mut ws, &mut out)?;
        *statuses
            .entry(format!("{:?}", out.info.status))
            .or_insert(0) += 1;
        if out.info.status != SolveStatus::Solved {
            println!(
                "#{k} M{} N{} {:?} min_sep={:.9?} subproblems={} rounds={} points={} peak_active={}",
                problem.spacecraft.len(),
                problem.degree,
                out.info.status,
                out.min_separation_lu,
                out.info.sqp_iterations,
                out.info.verify_rounds,
                out.info.verify_points_added,
                out.info.max_active
            );
        }
    }
    println!("{statuses:?}");
    Ok(())
}
