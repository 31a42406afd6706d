//! Generated scenarios within capacity, reproducible from a seed.
//!
//! * Planner A: M spacecraft (2..=8) start on a circle in a random plane and each goes to the
//!   antipodal point, so every path crosses the centre and the keep-out is active. The circle is
//!   wide enough that neighbours start and end at least 1.5 d apart, and every axis's
//!   displacement is at most half of what rest-to-rest bang-bang control covers in T
//!   (`Umax T^2 / (4 m)`), which leaves room to go around each other: the scenarios are
//!   feasible by construction.
//! * Planner B: the published case (Wang 2018, with the errata in SPEC.md) with its initial and
//!   target relative elements scaled by 0.8..1.2 each, and 2-4 fixed impulse points at random
//!   arguments of latitude with at most 14 revolutions in all.

use crate::harness::feeder::Item;
use crate::harness::items::request_item;
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use reconfig_core::capacity::{MAX_DEGREE, MAX_SPACECRAFT};
use reconfig_core::wire::Request;
use reconfig_core::{impulsive, pseudospectral};
use std::f64::consts::PI;

/// Horizon of generated planner-A scenarios, TU.
pub const HORIZON_TU: f64 = 10.0;
/// Control bound of generated planner-A scenarios, FU.
pub const MAX_CONTROL_FU: f64 = 1.0;
/// Keep-out distance of generated planner-A scenarios, LU.
pub const KEEP_OUT_LU: f64 = 2.0;

/// A planner-A crossing scenario with `m` spacecraft and degree `n`.
pub fn crossing(rng: &mut impl Rng, m: usize, n: u16) -> pseudospectral::Problem {
    let m = m.clamp(2, MAX_SPACECRAFT);
    // Neighbours on the circle at least 1.5 d apart: 2 R sin(pi / m) >= 1.5 d.
    let r_min = (1.5 * KEEP_OUT_LU / (2.0 * (PI / m as f64).sin())).max(KEEP_OUT_LU);
    // Displacement 2 R per axis at most half the bang-bang reach Umax T^2 / 4 (unit mass).
    let r_max = 0.5 * MAX_CONTROL_FU * HORIZON_TU * HORIZON_TU / 4.0 / 2.0;
    let radius = rng.random_range(r_min..=r_max.max(r_min));
    // A random orthonormal pair spanning the plane of the circle.
    let u = unit(rng);
    let mut v = unit(rng);
    let d = dot(u, v);
    v = [v[0] - d * u[0], v[1] - d * u[1], v[2] - d * u[2]];
    let norm = dot(v, v).sqrt().max(1e-9);
    v = [v[0] / norm, v[1] / norm, v[2] / norm];
    let centre = [
        rng.random_range(-5.0..5.0),
        rng.random_range(-5.0..5.0),
        rng.random_range(-5.0..5.0),
    ];
    let phase = rng.random_range(0.0..2.0 * PI);
    let mut spacecraft = heapless::Vec::new();
    for k in 0..m {
        let a = phase + 2.0 * PI * k as f64 / m as f64;
        let at = |angle: f64| {
            let (s, c) = angle.sin_cos();
            [
                centre[0] + radius * (c * u[0] + s * v[0]),
                centre[1] + radius * (c * u[1] + s * v[1]),
                centre[2] + radius * (c * u[2] + s * v[2]),
            ]
        };
        let p0 = at(a);
        let p1 = at(a + PI);
        let craft = pseudospectral::Spacecraft {
            mass_mu: 1.0,
            initial_state: [p0[0], p0[1], p0[2], 0.0, 0.0, 0.0],
            final_state: [p1[0], p1[1], p1[2], 0.0, 0.0, 0.0],
        };
        // m <= MAX_SPACECRAFT, so the push cannot fail.
        let _ = spacecraft.push(craft);
    }
    pseudospectral::Problem {
        horizon_tu: HORIZON_TU,
        max_control_fu: MAX_CONTROL_FU,
        keep_out_lu: KEEP_OUT_LU,
        degree: n.min(MAX_DEGREE as u16),
        test_points: true,
        spacecraft,
    }
}

fn unit(rng: &mut impl Rng) -> [f64; 3] {
    loop {
        let v = [
            rng.random_range(-1.0..1.0),
            rng.random_range(-1.0..1.0),
            rng.random_range(-1.0..1.0),
        ];
        let n = dot(v, v).sqrt();
        if n > 0.1 && n <= 1.0 {
            return [v[0] / n, v[1] / n, v[2] / n];
        }
    }
}

fn dot(a: [f64; 3], b: [f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

/// The published planner-B case (Wang 2018 section 4 with the SPEC's errata), SI-ish units of
/// the core: km and rad.
pub fn wang2018_published() -> impulsive::Problem {
    let deg = PI / 180.0;
    let rel = |v: [f64; 6]| impulsive::RelativeElements {
        dsma_km: v[0],
        decc: v[1],
        dinc_rad: v[2] * deg,
        draan_rad: v[3] * deg,
        dargp_rad: v[4] * deg,
        dmean_anomaly_rad: v[5] * deg,
    };
    impulsive::Problem {
        chief: impulsive::MeanElements {
            sma_km: 7178.137,
            ecc: 0.0678,
            inc_rad: 63.4349 * deg,
            raan_rad: 112.0 * deg,
            argp_rad: 0.0,
            mean_anomaly_rad: 0.0,
        },
        initial: rel([
            4.0940e-4, -1.3888e-4, -1.0831e-3, 1.5409e-2, -1.6134e-2, 9.2428e-3,
        ]),
        target: rel([
            -1.6389e-4, 5.5597e-4, 4.3361e-3, 7.1228e-2, -6.3572e-2, 3.1718e-2,
        ]),
        plan: impulsive::ImpulsePlan::Search {
            impulses: 3,
            max_revolutions: 14,
        },
    }
}

/// The published case with the impulse points of Wang 2018 Table 2 (three impulses).
pub fn wang2018_table2() -> impulsive::Problem {
    let mut p = wang2018_published();
    let deg = PI / 180.0;
    let mut points = heapless::Vec::new();
    for (u, n) in [(274.155, 2), (238.864, 10), (285.649, 2)] {
        let _ = points.push(impulsive::ImpulsePoint {
            arg_latitude_rad: u * deg,
            revolutions: n,
        });
    }
    p.plan = impulsive::ImpulsePlan::Fixed(points);
    p
}

/// A planner-B scenario: the published case perturbed, with `k` (2..=4) fixed impulse points.
pub fn perturbed_impulsive(rng: &mut impl Rng, k: usize) -> impulsive::Problem {
    let mut p = wang2018_published();
    let mut scale = |r: &mut impulsive::RelativeElements| {
        r.dsma_km *= rng.random_range(0.8..1.2);
        r.decc *= rng.random_range(0.8..1.2);
        r.dinc_rad *= rng.random_range(0.8..1.2);
        r.draan_rad *= rng.random_range(0.8..1.2);
        r.dargp_rad *= rng.random_range(0.8..1.2);
        r.dmean_anomaly_rad *= rng.random_range(0.8..1.2);
    };
    scale(&mut p.initial);
    scale(&mut p.target);
    let k = k.clamp(2, 4);
    let mut points = heapless::Vec::new();
    let mut revolutions_left = 14;
    for _ in 0..k {
        let revolutions = rng.random_range(0..=revolutions_left.min(6));
        revolutions_left -= revolutions;
        let _ = points.push(impulsive::ImpulsePoint {
            arg_latitude_rad: rng.random_range(0.0..2.0 * PI),
            revolutions,
        });
    }
    p.plan = impulsive::ImpulsePlan::Fixed(points);
    p
}

/// `count` generated items, alternating planners (2 in 3 for planner A), from `seed`.
pub fn generate(count: usize, seed: u64) -> Vec<Item> {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    (0..count)
        .map(|i| {
            if i % 3 != 2 {
                let m = rng.random_range(2..=MAX_SPACECRAFT);
                let n = [10u16, 16][rng.random_range(0..2)];
                let problem = crossing(&mut rng, m, n);
                let settings = pseudospectral::Settings::default();
                let request = Request::Pseudospectral { problem, settings };
                request_item(format!("random-{i}"), format!("M{m} N{n}"), request)
            } else {
                let k = rng.random_range(2..=4);
                let problem = perturbed_impulsive(&mut rng, k);
                let settings = impulsive::Settings::default();
                let request = Request::Impulsive { problem, settings };
                request_item(format!("random-{i}"), format!("K{k}"), request)
            }
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn crossings_start_and_end_apart_and_within_reach() {
        let mut rng = ChaCha8Rng::seed_from_u64(7);
        for m in 2..=MAX_SPACECRAFT {
            let p = crossing(&mut rng, m, 10);
            let reach = MAX_CONTROL_FU * HORIZON_TU * HORIZON_TU / 4.0;
            for (i, a) in p.spacecraft.iter().enumerate() {
                for axis in 0..3 {
                    assert!(
                        (a.final_state[axis] - a.initial_state[axis]).abs() <= 0.5 * reach + 1e-9
                    );
                }
                for b in p.spacecraft.iter().skip(i + 1) {
                    for (pa, pb) in [
                        (a.initial_state, b.initial_state),
                        (a.final_state, b.final_state),
                    ] {
                        let d = ((pa[0] - pb[0]).powi(2)
                            + (pa[1] - pb[1]).powi(2)
                            + (pa[2] - pb[2]).powi(2))
                        .sqrt();
                        assert!(d >= 1.5 * KEEP_OUT_LU - 1e-9, "m={m} d={d}");
                    }
                }
            }
        }
    }

    #[test]
    fn generation_is_reproducible() {
        let a = generate(30, 5);
        let b = generate(30, 5);
        for (x, y) in a.iter().zip(&b) {
            assert_eq!(format!("{:?}", x.payload), format!("{:?}", y.payload));
        }
    }
}
