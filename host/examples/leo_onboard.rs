//! The LEO tour's on-board part timed in one thread: the sequencing request (for a fixture with
//! a `[sequence]` table) and every arc's request of the order (`drivers::leo_tour`), answered
//! through the request path as `reconfig solve` answers them but without the truth-model
//! checks. Prints each run and the
//! fastest of the runs (the figure docs/leo-tour.md quotes).
//!
//! `cargo run --release -p reconfig-host --example leo_onboard -- FIXTURE [RUNS]`

use anyhow::{anyhow, Context, Result};
use reconfig_core::leo_tour::SolveStatus;
use reconfig_core::limits::Limits;
use reconfig_host::drivers::leo_tour::{choose_order, plan};
use reconfig_host::fixture::leo_tour::load;
use std::time::Instant;

fn main() -> Result<()> {
    let mut args = std::env::args().skip(1);
    let path = args
        .next()
        .ok_or_else(|| anyhow!("usage: leo_onboard FIXTURE [RUNS]"))?;
    let runs: usize = match args.next() {
        Some(s) => s.parse().context("RUNS")?,
        None => 5,
    };
    let f = load(std::path::Path::new(&path))?;
    let (mut best_seq_s, mut best_arcs_s, mut best_total_s) =
        (f64::INFINITY, f64::INFINITY, f64::INFINITY);
    for _ in 0..runs {
        let started = Instant::now();
        let (tour, seq_s) = match choose_order(&f, &Limits::default())? {
            Some((chosen, c)) => {
                let q = &c.sequence;
                let order: Vec<u8> = q
                    .order
                    .iter()
                    .take(usize::from(q.len))
                    .map(|k| k + 1)
                    .collect();
                print!(
                    "sequencing {:?} {:?} {:.3} m/s, {} / {} arcs, {:.4} s | ",
                    order,
                    q.info.status,
                    q.total_dv_mps.unwrap_or(0.0),
                    q.info.arcs_planned,
                    q.info.arcs_in_tree,
                    c.time_s
                );
                (chosen, c.time_s)
            }
            None => (f.clone(), 0.0),
        };
        let arcs_started = Instant::now();
        let arcs = plan(&tour, &Limits::default())?;
        let total_mps: f64 = arcs.iter().map(|a| a.solution.total_dv_mps).sum();
        let dvs: Vec<String> = arcs
            .iter()
            .map(|a| {
                let status = a.solution.info.status;
                let flag = if status == SolveStatus::Solved {
                    String::new()
                } else {
                    format!(" ({status:?})")
                };
                format!("{:.3}{flag}", a.solution.total_dv_mps)
            })
            .collect();
        let arcs_s = arcs_started.elapsed().as_secs_f64();
        let total_s = started.elapsed().as_secs_f64();
        println!(
            "arcs [{}] = {total_mps:.3} m/s, {arcs_s:.4} s | {total_s:.4} s",
            dvs.join(", ")
        );
        best_seq_s = best_seq_s.min(seq_s);
        best_arcs_s = best_arcs_s.min(arcs_s);
        best_total_s = best_total_s.min(total_s);
    }
    println!(
        "fastest of {runs}: sequencing {best_seq_s:.4} s, arcs {best_arcs_s:.4} s, total {best_total_s:.4} s"
    );
    Ok(())
}
