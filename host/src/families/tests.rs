//! The generated sets: deterministic, disjoint, every kind in each, sizes and degrees covered,
//! every problem accepted by planner A, the control bounds as the kinds promise.

use super::bound::{
    axis_need, cubic_position, need, END_CLEARANCE_LU, KEEP_OUT_LU, MIN_CONTROL_FU,
};
use super::kinds::{self, KINDS};
use super::sets::{generate_set, problem_seed, Set};
use reconfig_core::pseudospectral::{self, Problem, Settings, Solution, Workspace};
use std::collections::{BTreeMap, BTreeSet, HashSet};

const COUNT: usize = 2000;
const SEED: u64 = 9;

fn both() -> [(Set, Vec<(&'static str, Problem)>); 2] {
    [
        (Set::Tuning, generate_set(Set::Tuning, SEED, COUNT)),
        (Set::HeldOut, generate_set(Set::HeldOut, SEED, COUNT)),
    ]
}

#[test]
fn kinds_are_named_once_in_kebab_case() {
    let names = kinds::names();
    assert!(names.len() >= 22);
    let unique: BTreeSet<&str> = names.iter().copied().collect();
    assert_eq!(unique.len(), names.len());
    for name in names {
        assert!(
            name.chars().all(|c| c.is_ascii_lowercase() || c == '-'),
            "{name}"
        );
        assert!(kinds::by_name(name).is_some());
    }
}

#[test]
fn same_arguments_same_problems() {
    for set in [Set::Tuning, Set::HeldOut] {
        let a = generate_set(set, SEED, 300);
        let b = generate_set(set, SEED, 300);
        assert_eq!(a, b);
        // A problem does not depend on the count.
        assert_eq!(generate_set(set, SEED, 100), a[..100].to_vec());
        // The seed shifts the set.
        assert_ne!(generate_set(set, SEED + 1, 10), a[..10].to_vec());
    }
}

#[test]
fn the_sets_share_no_problem() {
    let [(_, tuning), (_, held_out)] = both();
    let text = |p: &Problem| serde_json::to_string(p).expect("json");
    let tuning: HashSet<String> = tuning.iter().map(|(_, p)| text(p)).collect();
    assert_eq!(
        tuning.len(),
        COUNT,
        "a problem repeats within the tuning set"
    );
    assert!(held_out.iter().all(|(_, p)| !tuning.contains(&text(p))));
    let seeds: HashSet<u64> = (0..COUNT)
        .map(|i| problem_seed(Set::Tuning, SEED, i))
        .collect();
    assert!((0..COUNT).all(|i| !seeds.contains(&problem_seed(Set::HeldOut, SEED, i))));
}

#[test]
fn every_kind_size_and_degree_appears_in_each_set() {
    for (set, problems) in both() {
        let mut per_kind: BTreeMap<&str, usize> = BTreeMap::new();
        let mut sizes = BTreeSet::new();
        let mut degrees = BTreeSet::new();
        for (kind, p) in &problems {
            *per_kind.entry(kind).or_default() += 1;
            sizes.insert(p.spacecraft.len());
            degrees.insert(p.degree);
        }
        for kind in &KINDS {
            assert!(
                per_kind.get(kind.name).copied().unwrap_or(0) >= COUNT / KINDS.len(),
                "{}: {} is missing",
                set.name(),
                kind.name
            );
        }
        assert_eq!(sizes, (2..=8).collect(), "{}", set.name());
        assert_eq!(degrees, (8..=24).collect(), "{}", set.name());
    }
}

#[test]
fn ends_bounds_and_horizons_are_in_range() {
    for (set, problems) in both() {
        for (i, (kind, p)) in problems.iter().enumerate() {
            let what = format!("{} #{i} ({kind})", set.name());
            assert!((2..=8).contains(&p.spacecraft.len()), "{what}");
            assert!((6.0..=20.0).contains(&p.horizon_tu), "{what}: T");
            assert_eq!(p.keep_out_lu, KEEP_OUT_LU, "{what}");
            assert!(p.test_points, "{what}");
            assert!(p.max_control_fu >= MIN_CONTROL_FU, "{what}: Umax");
            let ratio = p.max_control_fu / need(p);
            assert!(ratio >= 1.15 * (1.0 - 1e-12), "{what}: Umax / need {ratio}");
            if kinds::by_name(kind).expect("kind").tight {
                assert!(ratio <= 1.5 * (1.0 + 1e-12), "{what}: Umax / need {ratio}");
                for c in &p.spacecraft {
                    assert!(c.initial_state[3..].iter().all(|v| *v == 0.0), "{what}");
                    assert!(c.final_state[3..].iter().all(|v| *v == 0.0), "{what}");
                }
            }
            for (a, x) in p.spacecraft.iter().enumerate() {
                assert!((0.5..=2.0).contains(&x.mass_mu), "{what}: mass");
                for y in &p.spacecraft[a + 1..] {
                    for (u, v) in [
                        (&x.initial_state, &y.initial_state),
                        (&x.final_state, &y.final_state),
                    ] {
                        let d = (0..3).map(|k| (u[k] - v[k]).powi(2)).sum::<f64>().sqrt();
                        assert!(d >= END_CLEARANCE_LU, "{what}: ends {d} apart");
                    }
                }
            }
        }
    }
}

#[test]
fn planner_a_accepts_every_problem() {
    // A work budget of one unit: the solve checks the request (`validate`, then the analytic
    // guess of every axis, which rejects an unreachable one) and stops at once.
    let settings = Settings {
        work_budget: 1,
        ..Settings::default()
    };
    let mut workspace = Box::new(Workspace::new());
    let mut out = Box::new(Solution::new());
    // The check is real: a tight problem's bound below the need, or two ends closer than d,
    // are rejected.
    let (kind, tight) = super::sets::problem(Set::HeldOut, SEED, 13);
    assert_eq!(kind, "random-tight");
    let mut short = tight.clone();
    short.max_control_fu = 0.9 * need(&tight);
    assert!(pseudospectral::solve(&short, &settings, &mut workspace, &mut out).is_err());
    let mut close = tight.clone();
    close.spacecraft[1].initial_state = close.spacecraft[0].initial_state;
    close.spacecraft[1].initial_state[0] += 0.9 * KEEP_OUT_LU;
    assert!(pseudospectral::solve(&close, &settings, &mut workspace, &mut out).is_err());
    for (set, problems) in both() {
        for (i, (kind, p)) in problems.iter().enumerate() {
            if let Err(e) = pseudospectral::solve(p, &settings, &mut workspace, &mut out) {
                panic!("{} #{i} ({kind}) rejected: {e}", set.name());
            }
        }
    }
}

#[test]
fn the_need_is_the_bang_bang_bound_at_rest_and_the_cubic_peak_otherwise() {
    assert_eq!(axis_need(1.0, 0.0, 6.0, 0.0, 10.0), 4.0 * 5.0 / 100.0);
    // Coasting needs nothing.
    assert!(axis_need(0.0, 0.5, 5.0, 0.5, 10.0).abs() < 1e-15);
    // From rest to a velocity: a(t) = 6 dp / T^2 - 2 dv / T ... at the ends.
    let (t, v1) = (4.0, 1.0);
    let a0: f64 = 6.0 * 0.0 / (t * t) - 2.0 * v1 / t;
    let a1: f64 = 4.0 * v1 / t;
    assert!((axis_need(0.0, 0.0, 0.0, v1, t) - a0.abs().max(a1)).abs() < 1e-15);
}

#[test]
fn the_cubic_meets_both_ends() {
    let (p0, v0, p1, v1, t) = (1.0, -0.5, 7.0, 2.0, 9.0);
    assert!((cubic_position(p0, v0, p1, v1, t, 0.0) - p0).abs() < 1e-12);
    assert!((cubic_position(p0, v0, p1, v1, t, t) - p1).abs() < 1e-12);
    let h = 1e-5;
    let slope = |s: f64| {
        (cubic_position(p0, v0, p1, v1, t, s + h) - cubic_position(p0, v0, p1, v1, t, s - h))
            / (2.0 * h)
    };
    assert!((slope(h) - v0).abs() < 1e-4);
    assert!((slope(t - h) - v1).abs() < 1e-4);
}
