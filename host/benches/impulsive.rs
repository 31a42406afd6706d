//! Planner B wall-clock benchmarks: the fixed-point solve at the paper's three impulse points
//! (Wang 2018, Table 2), with and without the min-fuel refinement and the nonlinear correction,
//! and the impulse-point search for 2, 3 and 4 impulses.
//!
//! `cargo bench -p reconfig-host --bench impulsive`

use criterion::{criterion_group, criterion_main, Criterion};
use reconfig_core::impulsive::{solve, Problem, Settings, Solution, Workspace};
use reconfig_host::fixture::{impulsive::ImpulsiveFixture, load_as};
use std::hint::black_box;
use std::path::PathBuf;
use std::time::Duration;

fn problem(name: &str) -> Problem {
    let path = PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("../fixtures")
        .join(format!("{name}.toml"));
    load_as::<ImpulsiveFixture>(&path)
        .expect("a planner-B fixture")
        .problem
}

fn fixed(c: &mut Criterion) {
    let p = problem("wang2018-gco-to-pco-3imp");
    let mut ws = Box::new(Workspace::new());
    let mut out = Box::new(Solution::new());
    let min_norm = Settings {
        min_fuel: false,
        nonlinear_correction: false,
        ..Settings::default()
    };
    c.bench_function("fixed_point_3imp_min_norm", |b| {
        b.iter(|| solve(black_box(&p), black_box(&min_norm), &mut ws, &mut out))
    });
    let corrected = Settings {
        min_fuel: false,
        ..Settings::default()
    };
    c.bench_function("fixed_point_3imp_min_norm_corrected", |b| {
        b.iter(|| solve(black_box(&p), black_box(&corrected), &mut ws, &mut out))
    });
    let default = Settings::default();
    c.bench_function("fixed_point_3imp_min_fuel_corrected", |b| {
        b.iter(|| solve(black_box(&p), black_box(&default), &mut ws, &mut out))
    });
}

fn search(c: &mut Criterion) {
    let mut group = c.benchmark_group("search");
    group
        .sample_size(10)
        .measurement_time(Duration::from_secs(8));
    let settings = Settings::default();
    let mut ws = Box::new(Workspace::new());
    let mut out = Box::new(Solution::new());
    for n in [2, 3, 4] {
        let p = problem(&format!("wang2018-gco-to-pco-search-{n}imp"));
        group.bench_function(format!("{n}imp"), |b| {
            b.iter(|| solve(black_box(&p), black_box(&settings), &mut ws, &mut out))
        });
    }
    group.finish();
}

criterion_group!(benches, fixed, search);
criterion_main!(benches);
