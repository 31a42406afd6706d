//! The LEO tour's flight models, wall clock: one flight of the search model (the first-order
//! J2 theory in closed form, `mean_j2::fly`), the state of a mean orbit at an epoch
//! (`MeanOrbit::state_at`) and one RK4 step of the planning model, on the host. The work units
//! charged for them (`leo_tour::work_units`) are not set from these: they are the Cortex-M7
//! instructions of each on its dearest path, measured by the kernel image (docs/leo-tour.md,
//! "Work budget").
//!
//! `cargo bench -p reconfig-host --bench leo_flight`

use criterion::{criterion_group, criterion_main, Criterion};
use reconfig_core::astro::Gravity;
use reconfig_core::leo_tour::elements::{state_of, Classical};
use reconfig_core::leo_tour::j2::{propagate_steps, State};
use reconfig_core::leo_tour::mean_j2::{fly, MeanOrbit};
use std::hint::black_box;
use std::time::Duration;

fn orbit() -> State {
    state_of(
        Gravity::EARTH.mu_km3_s2,
        &Classical {
            a_km: 7078.0,
            e: 0.001,
            i_rad: 98.2_f64.to_radians(),
            raan_rad: 30.0_f64.to_radians(),
            argp_rad: 0.0,
            nu_rad: 40.0_f64.to_radians(),
        },
    )
    .expect("an elliptic orbit")
}

fn flights(c: &mut Criterion) {
    let g = Gravity::EARTH;
    let s = orbit();
    let mean = MeanOrbit::of_state(&g, &s).expect("a mean orbit");
    let mut group = c.benchmark_group("leo_flight");
    group
        .sample_size(50)
        .measurement_time(Duration::from_secs(2));
    group.bench_function("search-model flight", |b| {
        b.iter(|| fly(&g, black_box(&s), black_box(1000.0)))
    });
    group.bench_function("mean-orbit state", |b| {
        b.iter(|| mean.state_at(&g, black_box(1000.0)))
    });
    group.bench_function("planning-model RK4 step", |b| {
        b.iter(|| propagate_steps(&g, black_box(&s), black_box(20.0), 1))
    });
    group.finish();
}

criterion_group!(benches, flights);
criterion_main!(benches);
