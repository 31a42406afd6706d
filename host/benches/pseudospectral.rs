//! Planner A wall time per solve (criterion): the paper's case at N = 9, 10, 20 and the
//! generated 8-spacecraft crossing at N = 16, default settings, one core.
//!
//! `cargo bench -p reconfig-host --bench pseudospectral`

use criterion::{criterion_group, criterion_main, Criterion};
use reconfig_core::pseudospectral::{self, Settings, Solution, Workspace};
use reconfig_host::fixture::{self, Fixture};
use std::hint::black_box;
use std::path::PathBuf;

fn problem(stem: &str) -> pseudospectral::Problem {
    let path = PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("../fixtures")
        .join(format!("{stem}.toml"));
    match fixture::load(&path) {
        Ok(Fixture::Pseudospectral(f)) => f.problem,
        _ => panic!("{stem}: not a planner-A fixture"),
    }
}

fn bench(c: &mut Criterion) {
    let settings = Settings::default();
    let mut workspace = Box::new(Workspace::new());
    let mut solution = Box::new(Solution::new());
    let mut group = c.benchmark_group("pseudospectral");
    for stem in [
        "huang2012-three-sats-n10",
        "huang2012-three-sats-n9",
        "huang2012-three-sats-n20",
        "crossing-8-sats-n16",
    ] {
        let p = problem(stem);
        if stem.starts_with("crossing") {
            group.sample_size(10);
        }
        group.bench_function(stem, |b| {
            b.iter(|| {
                pseudospectral::solve(black_box(&p), &settings, &mut workspace, &mut solution)
                    .expect("solve");
                black_box(solution.cost)
            })
        });
    }
    group.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
