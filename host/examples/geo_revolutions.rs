//! How the GEO tour's total Δv and work depend on the Lambert revolution limit, on generated
//! tours: the measurement that chose the default `lambert_max_revolutions` (issue 31 item 1).
//!
//! ```sh
//! cargo run --release -p reconfig-host --example geo_revolutions -- FIRST LAST
//! cargo run --release -p reconfig-host --example geo_revolutions -- default FIRST LAST
//! ```
//!
//! Tours by seed (ChaCha8): tuning seeds 0-99 draw three kinds — a cluster of 2-6 clients within
//! 0.6 deg in 1-8 days, 3-16 clients spread over up to 180 deg in 20-200 days, and clusters at
//! spread positions in 10-120 days; the held-out seeds (1000 and up) add a fourth kind, tours
//! given 1.02-1.5 times their fastest time (the planner's `fastest_tour_s`), and a burn cap drawn
//! from 0.5-5 m/s instead of 5 m/s. For each tour every revolution limit 0-8 is planned (sweep
//! "cheaper", by cost, other settings at their defaults, work budget at the default); a tour
//! counts when every limit plans it usable. Printed per limit: tours usable, the mean and largest
//! excess of the total over the best of all limits, the mean and largest work units and the
//! mean solve time on this host.

use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use reconfig_core::geo_tour::{
    solve, MethodPolicy, Problem, Settings, Solution, SolveStatus, SweepChoice, Workspace,
};
use std::time::Instant;

const DEG: f64 = std::f64::consts::PI / 180.0;
const DAY_S: f64 = 86_400.0;
const LIMITS: std::ops::RangeInclusive<u16> = 0..=8;

fn usable(s: &SolveStatus) -> bool {
    matches!(
        s,
        SolveStatus::Solved | SolveStatus::BudgetExhausted { verified: true }
    )
}

fn problem(start_deg: f64, targets_deg: &[f64], days: f64, cap_mps: f64) -> Problem {
    let mut targets = heapless::Vec::new();
    for &t in targets_deg {
        let _ = targets.push(t * DEG);
    }
    Problem {
        start_lon_rad: start_deg * DEG,
        targets_lon_rad: targets,
        mission_time_s: days * DAY_S,
        max_burn_mps: cap_mps,
        sweep: SweepChoice::Cheaper,
        policy: MethodPolicy::ByCost,
    }
}

fn plan(p: &Problem, revs: u16, ws: &mut Workspace, out: &mut Solution) -> Option<(f64, u64, f64)> {
    let s = Settings {
        lambert_max_revolutions: revs,
        ..Settings::default()
    };
    let t0 = Instant::now();
    solve(p, &s, ws, out).ok()?;
    let dt = t0.elapsed().as_secs_f64();
    usable(&out.info.status).then_some((out.total_dv_mps, out.info.work_units, dt))
}

/// The tour of a seed.
fn tour(seed: u64, ws: &mut Workspace, out: &mut Solution) -> Problem {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let held_out = seed >= 1000;
    let kinds = if held_out { 4 } else { 3 };
    let start = rng.random_range(0.0..360.0_f64);
    let cap = if held_out {
        rng.random_range(0.5..5.0)
    } else {
        5.0
    };
    let mut targets = Vec::new();
    let kind = rng.random_range(0..kinds);
    let days = match kind {
        0 => {
            let mut lon = start;
            for _ in 0..rng.random_range(2..=6) {
                lon += rng.random_range(0.01..0.15);
                targets.push(lon);
            }
            rng.random_range(1.0..8.0)
        }
        1 => {
            let span = rng.random_range(5.0..180.0);
            for _ in 0..rng.random_range(3..=16) {
                targets.push(start + rng.random_range(0.0..span));
            }
            rng.random_range(20.0..200.0)
        }
        _ => {
            let mut lon = start;
            while targets.len() < 14 {
                lon += rng.random_range(1.0..40.0);
                for _ in 0..rng.random_range(1..=3) {
                    lon += rng.random_range(0.02..0.3);
                    targets.push(lon);
                }
                if rng.random_bool(0.3) {
                    break;
                }
            }
            rng.random_range(10.0..120.0)
        }
    };
    let targets: Vec<f64> = targets.iter().map(|t| t % 360.0).collect();
    let mut p = problem(start, &targets, days, cap);
    if kind == 3 {
        // Just above the fastest tour at the default settings.
        p.mission_time_s = 1e4 * DAY_S;
        if solve(&p, &Settings::default(), ws, out).is_ok() {
            if let Some(f) = out.info.fastest_tour_s {
                p.mission_time_s = f * rng.random_range(1.02..1.5);
            }
        }
    }
    p
}

/// The tour of `seed` as a fixture (`fixture SEED`), to plan it with `reconfig solve`.
fn print_fixture(seed: u64, ws: &mut Workspace, out: &mut Solution) {
    let p = tour(seed, ws, out);
    let targets: Vec<String> = p
        .targets_lon_rad
        .iter()
        .map(|t| format!("{:.6}", t / DEG))
        .collect();
    println!("name = \"geo-revolutions-seed-{seed}\"");
    println!("# examples/geo_revolutions.rs, seed {seed}");
    println!("planner = \"geo-tour\"");
    println!("start_lon_deg = {:.6}", p.start_lon_rad / DEG);
    println!("targets_lon_deg = [{}]", targets.join(", "));
    println!("mission_time_days = {:.6}", p.mission_time_s / DAY_S);
    println!("max_burn_mps = {:.6}", p.max_burn_mps);
    println!("sweep = \"cheaper\"");
    println!("policy = \"by-cost\"");
}

/// One line per tour at the default settings (`default FIRST LAST`): seed, clients, status,
/// total Δv to the bit and work units, to compare two builds tour by tour.
fn print_default(first: u64, last: u64) {
    let mut ws = Box::new(Workspace::new());
    let mut out = Box::new(Solution::new());
    for seed in first..=last {
        let p = tour(seed, &mut ws, &mut out);
        match solve(&p, &Settings::default(), &mut ws, &mut out) {
            Ok(()) => println!(
                "{seed} {} {:?} {:.9} {}",
                p.targets_lon_rad.len(),
                out.info.status,
                out.total_dv_mps,
                out.info.work_units
            ),
            Err(e) => println!("{seed} {} refused {e:?}", p.targets_lon_rad.len()),
        }
    }
}

fn main() {
    let raw: Vec<String> = std::env::args().skip(1).collect();
    if let [cmd, seed] = raw.as_slice() {
        if cmd == "fixture" {
            let seed = seed.parse().unwrap_or(0);
            print_fixture(seed, &mut Workspace::new(), &mut Solution::new());
            return;
        }
    }
    if let [cmd, first, last] = raw.as_slice() {
        if cmd == "default" {
            print_default(first.parse().unwrap_or(0), last.parse().unwrap_or(0));
            return;
        }
    }
    let args: Vec<u64> = std::env::args()
        .skip(1)
        .filter_map(|a| a.parse().ok())
        .collect();
    let (first, last) = match args.as_slice() {
        [a, b] => (*a, *b),
        _ => (0, 99),
    };
    let mut ws = Box::new(Workspace::new());
    let mut out = Box::new(Solution::new());
    let n_limits = LIMITS.count();
    // Per limit: (excess sum %, excess max %, units sum, units max, time sum, usable count).
    let mut rows = vec![(0.0_f64, 0.0_f64, 0_u64, 0_u64, 0.0_f64, 0_usize); n_limits];
    let mut counted = 0usize;
    let mut skipped = 0usize;
    for seed in first..=last {
        let p = tour(seed, &mut ws, &mut out);
        let results: Vec<Option<(f64, u64, f64)>> =
            LIMITS.map(|r| plan(&p, r, &mut ws, &mut out)).collect();
        for (row, r) in rows.iter_mut().zip(&results) {
            row.5 += usize::from(r.is_some());
        }
        if std::env::var_os("GEO_REVS_VERBOSE").is_some() {
            let line: Vec<String> = results
                .iter()
                .map(|r| r.map_or("-".to_string(), |r| format!("{:.4}/{}", r.0, r.1)))
                .collect();
            println!(
                "seed {seed} ({} clients, {:.2} d, cap {:.2}): {}",
                p.targets_lon_rad.len(),
                p.mission_time_s / DAY_S,
                p.max_burn_mps,
                line.join(" ")
            );
        }
        if results.iter().any(Option::is_none) {
            skipped += 1;
            continue;
        }
        counted += 1;
        let best = results
            .iter()
            .flatten()
            .fold(f64::INFINITY, |b, r| b.min(r.0));
        for (row, r) in rows.iter_mut().zip(results.iter().flatten()) {
            let excess = if best > 0.0 {
                100.0 * (r.0 - best) / best
            } else {
                0.0
            };
            row.0 += excess;
            row.1 = row.1.max(excess);
            row.2 += r.1;
            row.3 = row.3.max(r.1);
            row.4 += r.2;
        }
    }
    println!(
        "seeds {first}-{last}: {counted} tours usable at every limit ({skipped} not; excess over the best of all limits)"
    );
    println!("revs  usable  excess mean %  excess max %  units mean  units max  time mean ms");
    for (revs, row) in LIMITS.zip(&rows) {
        let n = counted.max(1) as f64;
        println!(
            "{revs:>4}  {:>6}  {:>13.4}  {:>12.4}  {:>10.0}  {:>9}  {:>12.3}",
            row.5,
            row.0 / n,
            row.1,
            row.2 as f64 / n,
            row.3,
            1e3 * row.4 / n
        );
    }
}
