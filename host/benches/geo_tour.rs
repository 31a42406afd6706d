//! GEO servicing tour wall-clock benchmarks, each fixture as given (`<name>/as-given`: the
//! published case, 11 clients, 60 d, and the 16-client capacity case, 80 d, plan both sweeps;
//! the slowest request found within the default limits,
//! `fixtures/worst-case/geo-16-clients-0p7deg-200d-west.toml`, fixes the west sweep) and east
//! only (`<name>/east`).
//!
//! `cargo bench -p reconfig-host --bench geo_tour`

use criterion::{criterion_group, criterion_main, Criterion};
use reconfig_core::geo_tour::{solve, Solution, SweepChoice, Workspace};
use reconfig_host::fixture::geo_tour::{load, GeoTourFixture};
use std::hint::black_box;
use std::path::PathBuf;
use std::time::Duration;

fn fixture(name: &str) -> GeoTourFixture {
    let path = PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("../fixtures")
        .join(format!("{name}.toml"));
    load(&path).expect("fixture")
}

fn tours(c: &mut Criterion) {
    let mut group = c.benchmark_group("geo_tour");
    group
        .sample_size(20)
        .measurement_time(Duration::from_secs(3));
    let mut ws = Box::new(Workspace::new());
    let mut out = Box::new(Solution::new());
    for name in [
        "geo-servicing-published-60d",
        "geo-servicing-16-targets",
        "worst-case/geo-16-clients-0p7deg-200d-west",
    ] {
        let f = fixture(name);
        group.bench_function(format!("{name}/as-given"), |b| {
            b.iter(|| solve(black_box(&f.problem), &f.settings, &mut ws, &mut out))
        });
        let mut east = f.problem.clone();
        east.sweep = SweepChoice::East;
        group.bench_function(format!("{name}/east"), |b| {
            b.iter(|| solve(black_box(&east), &f.settings, &mut ws, &mut out))
        });
    }
    group.finish();
}

criterion_group!(benches, tours);
criterion_main!(benches);
