//! The six generated families of issue 9 (`reconfig sweep`, the default set): `random`,
//! `symmetric`, `tight`, `fly-through`, `dense`, `mixed`. Planner A's settings were tuned on
//! them, and the oracle's golden file
//! (`fixtures/generated/planner-a-families.jsonl`) holds their problems at seed 9, 42 per family;
//! their generation must stay bit for bit what it is (one ChaCha8 stream over the families in
//! table order, each problem drawn in turn).

use super::Named;
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use reconfig_core::pseudospectral::{Problem, Spacecraft};

/// The family names, in table order.
pub const FAMILIES: [&str; 6] = [
    "random",
    "symmetric",
    "tight",
    "fly-through",
    "dense",
    "mixed",
];

const KEEP_OUT_LU: f64 = 2.0;
const HORIZON_TU: f64 = 10.0;

fn craft(mass: f64, a: [f64; 6], b: [f64; 6]) -> Spacecraft {
    Spacecraft {
        mass_mu: mass,
        initial_state: a,
        final_state: b,
    }
}

fn at_rest(p: [f64; 3]) -> [f64; 6] {
    [p[0], p[1], p[2], 0.0, 0.0, 0.0]
}

/// `count` points in a cube of half-width `half`, pairwise at least `gap` apart.
fn spread(rng: &mut ChaCha8Rng, count: usize, half: f64, gap: f64) -> Vec<[f64; 3]> {
    let mut points: Vec<[f64; 3]> = Vec::new();
    // Bounded rejection sampling: the cube is large enough for 8 points at this gap.
    for _ in 0..10_000 {
        if points.len() == count {
            break;
        }
        let p = [
            rng.random_range(-half..half),
            rng.random_range(-half..half),
            rng.random_range(-half..half),
        ];
        let clear = points.iter().all(|q| {
            let d2: f64 = (0..3).map(|k| (p[k] - q[k]).powi(2)).sum();
            d2 >= gap * gap
        });
        if clear {
            points.push(p);
        }
    }
    points
}

fn problem(umax: f64, degree: u16, spacecraft: Vec<Spacecraft>) -> Problem {
    let mut list = heapless::Vec::new();
    for c in spacecraft.into_iter().take(8) {
        let _ = list.push(c);
    }
    Problem {
        horizon_tu: HORIZON_TU,
        max_control_fu: umax,
        keep_out_lu: KEEP_OUT_LU,
        degree,
        test_points: true,
        spacecraft: list,
    }
}

/// Spacecraft at rest at `starts`, each to rest at its end, with the masses `mass` gives (in
/// order: a generator's draws stay in the same sequence).
fn rest_to_rest(
    starts: &[[f64; 3]],
    ends: &[[f64; 3]],
    mut mass: impl FnMut() -> f64,
) -> Vec<Spacecraft> {
    starts
        .iter()
        .zip(ends)
        .map(|(a, b)| craft(mass(), at_rest(*a), at_rest(*b)))
        .collect()
}

/// Generate one problem of `family`.
pub fn generate(family: &str, rng: &mut ChaCha8Rng) -> Problem {
    let gap = KEEP_OUT_LU + 0.5;
    match family {
        "symmetric" => {
            let m = rng.random_range(2..=8usize);
            let radius = 6.0;
            let phase = rng.random_range(0.0..std::f64::consts::PI);
            let crafts = (0..m)
                .map(|k| {
                    let a = phase + 2.0 * std::f64::consts::PI * k as f64 / m as f64;
                    let p = [radius * a.cos(), radius * a.sin(), 0.0];
                    craft(1.0, at_rest(p), at_rest([-p[0], -p[1], 0.0]))
                })
                .collect();
            problem(1.0, 16, crafts)
        }
        "tight" => {
            let m = rng.random_range(2..=6usize);
            let (starts, ends) = (spread(rng, m, 8.0, gap), spread(rng, m, 8.0, gap));
            // Rest to rest along one axis needs 4 D / T^2 at least.
            let mut need = 0.0f64;
            for (a, b) in starts.iter().zip(ends.iter()) {
                for k in 0..3 {
                    need = need.max(4.0 * (b[k] - a[k]).abs() / (HORIZON_TU * HORIZON_TU));
                }
            }
            problem(
                1.15 * need.max(0.05),
                12,
                rest_to_rest(&starts, &ends, || 1.0),
            )
        }
        "fly-through" => {
            let per_side = rng.random_range(1..=4usize);
            let mut crafts = Vec::new();
            for k in 0..per_side {
                let y = 3.0 * k as f64 - 1.5 * (per_side - 1) as f64;
                let z = rng.random_range(-0.5..0.5);
                let speed = rng.random_range(0.5..1.5);
                crafts.push(craft(
                    1.0,
                    [-10.0, y, z, speed, 0.0, 0.0],
                    [10.0, y + rng.random_range(-1.0..1.0), z, speed, 0.0, 0.0],
                ));
                crafts.push(craft(
                    1.0,
                    [10.0, y + 0.5, -z, -speed, 0.0, 0.0],
                    [-10.0, y + 0.5, -z, -speed, 0.0, 0.0],
                ));
            }
            problem(1.0, 14, crafts)
        }
        "dense" => {
            let mut cells: Vec<[f64; 3]> = Vec::new();
            for i in 0..2 {
                for j in 0..2 {
                    for k in 0..2 {
                        cells.push([2.4 * i as f64, 2.4 * j as f64, 2.4 * k as f64]);
                    }
                }
            }
            let mut order: Vec<usize> = (0..8).collect();
            for i in (1..8).rev() {
                order.swap(i, rng.random_range(0..=i));
            }
            let crafts = (0..8)
                .map(|i| craft(1.0, at_rest(cells[i]), at_rest(cells[order[i]])))
                .collect();
            problem(1.0, 12, crafts)
        }
        "mixed" => {
            let m = rng.random_range(2..=8usize);
            let (starts, ends) = (spread(rng, m, 10.0, gap), spread(rng, m, 10.0, gap));
            let degree = rng.random_range(8..=24u16);
            let crafts = rest_to_rest(&starts, &ends, || rng.random_range(0.5..2.0));
            problem(1.0, degree, crafts)
        }
        _ => {
            let m = rng.random_range(2..=8usize);
            let (starts, ends) = (spread(rng, m, 10.0, gap), spread(rng, m, 10.0, gap));
            problem(1.0, 12, rest_to_rest(&starts, &ends, || 1.0))
        }
    }
}

/// The whole default set: `per_family` problems of each family in table order, from one
/// ChaCha8 stream seeded with `seed`, each named by its family.
pub fn generate_all(per_family: usize, seed: u64) -> Vec<Named> {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let mut out = Vec::with_capacity(FAMILIES.len() * per_family);
    for family in FAMILIES {
        for _ in 0..per_family {
            out.push((family, generate(family, &mut rng)));
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::drivers::sweep_oracle;

    #[test]
    fn the_six_families_are_still_the_oracles_problems() {
        let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
            .join("..")
            .join(sweep_oracle::PROBLEMS_DEFAULT);
        let stored = sweep_oracle::load_problems(&path).expect("the stored families");
        let generated = generate_all(42, 9);
        assert_eq!(generated.len(), stored.len());
        for (i, ((family, p), (f, q))) in generated.iter().zip(&stored).enumerate() {
            assert_eq!(family, f, "#{i}");
            assert!(sweep_oracle::same_problem(p, q), "#{i} ({family}) changed");
        }
    }
}
