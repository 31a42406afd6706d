//! Unit tests of `sequence.rs` (a child module of it, in its own file to keep that file to one
//! job).

use super::*;
extern crate std;
use std::vec::Vec;

fn planes(n: usize) -> Vec<Plane> {
    (0..n)
        .map(|k| Plane {
            a_km: 6800.0 + 60.0 * (k as f64),
            e: 0.0,
            i_rad: (97.0 + 0.3 * ((k * 7 % 5) as f64)).to_radians(),
            raan_rad: (40.0 + 1.7 * ((k * 3 % 7) as f64)).to_radians(),
            raan_rate_rad_s: 0.0,
        })
        .collect()
}

const G: Gravity = Gravity {
    j2: 0.0,
    ..Gravity::EARTH
};

#[test]
fn branch_and_bound_finds_the_brute_force_optimum() {
    // A synthetic arc cost: the bound at zero margins plus a position-dependent
    // surcharge, so the bound (with its margins) is admissible and the order matters.
    for n in 3..=6 {
        let p = planes(n);
        let tight = BoundSettings {
            band_margin_km: 0.0,
            band_margin_rad: 0.0,
            margin: 0.0,
        };
        let cost = |i: usize, j: usize, t: f64, d: f64| {
            bound::arc_bound_mps(&G, &p[i], &p[j], t, d, &tight)
                + 3.0 * (((i * 5 + j * 3) % 7) as f64)
                + t * 1e-5
        };
        let settings = SequenceSettings {
            max_arcs: 1_000_000,
            ..SequenceSettings::default()
        };
        let intervals = Intervals::ByPosition([8e4, 1.6e5, 1.6e5, 1.6e5, 1.6e5, 1.6e5, 1.6e5]);
        let mut s = Sequence::new();
        best_order(
            &G,
            &p,
            (None, &intervals),
            &settings,
            |_, i, j, t, d| Some(cost(i, j, t, d)),
            &mut s,
        )
        .unwrap();
        // Brute force over every permutation.
        let mut idx: Vec<usize> = (0..n).collect();
        let mut best = f64::INFINITY;
        permute(&mut idx, 0, &mut |o: &[usize]| {
            let mut t = 0.0;
            let mut c = 0.0;
            for (k, w) in o.windows(2).enumerate() {
                let d = [8e4, 1.6e5, 1.6e5, 1.6e5, 1.6e5, 1.6e5, 1.6e5][k];
                c += cost(w[0], w[1], t, d);
                t += d;
            }
            best = best.min(c);
        });
        assert_eq!(s.info.status, SequenceStatus::Optimal);
        let total = s.total_dv_mps.unwrap();
        assert!((total - best).abs() < 1e-9, "n {n}: {total} vs {best}");
        let i = s.info;
        assert!(i.arcs_planned < i.arcs_in_tree, "n {n}: no pruning");
        assert_eq!(i.orders_total, factorial(u8::try_from(n).unwrap()));
        assert_eq!(i.arcs_in_tree, [0, 0, 2, 12, 60, 320, 1950][n]);
        std::println!(
            "n {n}: planned {} of {} arcs, {} of {} orders",
            i.arcs_planned,
            i.arcs_in_tree,
            i.orders_completed,
            i.orders_total
        );
    }
}

fn permute(v: &mut Vec<usize>, k: usize, f: &mut dyn FnMut(&[usize])) {
    if k == v.len() {
        f(v);
        return;
    }
    for i in k..v.len() {
        v.swap(k, i);
        permute(v, k + 1, f);
        v.swap(k, i);
    }
}

#[test]
fn a_cost_below_the_bound_is_reported_and_limits_stop_it() {
    let p = planes(4);
    let settings = SequenceSettings {
        max_arcs: 1_000,
        ..SequenceSettings::default()
    };
    let intervals = Intervals::ByPosition([8e4; MAX_CLIENTS - 1]);
    let tour = (Some(0), &intervals);
    let run = |settings: &SequenceSettings, cost: Option<f64>| {
        let mut s = Sequence::new();
        best_order(&G, &p, tour, settings, |_, _, _, _, _| cost, &mut s).map(|()| s)
    };
    let s = run(&settings, Some(0.0)).unwrap();
    assert_eq!(s.info.status, SequenceStatus::BoundViolated);
    assert!(s.info.bound_violations > 0);
    let few = SequenceSettings {
        max_arcs: 2,
        ..settings
    };
    // Two arcs of a four-client tour: stopped before any complete order.
    let s = run(&few, Some(100.0)).unwrap();
    assert_eq!(s.info.status, SequenceStatus::NoOrder { arc_limit: true });
    assert_eq!(s.info.arcs_planned, 2);
    assert_eq!((s.len, s.total_dv_mps), (0, None));
    // Three arcs: one complete order, stopped at the next arc (far above every bound, so
    // never pruned).
    let three = SequenceSettings {
        max_arcs: 3,
        ..settings
    };
    let s = run(&three, Some(1e6)).unwrap();
    assert_eq!(s.info.status, SequenceStatus::ArcLimit);
    assert!(s.info.status.is_usable());
    assert_eq!((s.len, s.total_dv_mps), (4, Some(3e6)));
    let s = run(&settings, None).unwrap();
    assert_eq!(s.info.status, SequenceStatus::NoOrder { arc_limit: false });
    assert!(!s.info.status.is_usable());
    let mut untouched = Sequence::new();
    assert!(matches!(
        best_order(
            &G,
            &p[..1],
            tour,
            &settings,
            |_, _, _, _, _| None,
            &mut untouched
        ),
        Err(SequenceError::Clients { count: 1 })
    ));
    assert!(matches!(
        best_order(
            &G,
            &p,
            (Some(9), &intervals),
            &settings,
            |_, _, _, _, _| None,
            &mut untouched
        ),
        Err(SequenceError::First { index: 9 })
    ));
    assert_eq!(untouched, Sequence::new());
}

#[test]
fn a_nan_or_infinity_in_an_unused_interval_is_refused_zero_is_not() {
    // Issue 29 (finite answers): a NaN travels in no answered request, even in the slots
    // past the last arc, which the search never reads (found by tests/finite_answers.rs).
    let p = planes(3);
    let settings = SequenceSettings::default();
    let run = |list: [f64; MAX_CLIENTS - 1]| {
        let mut s = Sequence::new();
        let intervals = Intervals::ByPosition(list);
        best_order(
            &G,
            &p,
            (Some(0), &intervals),
            &settings,
            |_, _, _, _, _| Some(1.0),
            &mut s,
        )
        .map(|()| s)
    };
    let mut list = [0.0; MAX_CLIENTS - 1];
    list[0] = 8e4;
    list[1] = 8e4;
    assert_eq!(run(list).unwrap().len, 3);
    for bad in [f64::NAN, f64::INFINITY, f64::NEG_INFINITY] {
        list[4] = bad;
        let r = run(list);
        assert!(
            matches!(r, Err(SequenceError::Interval { position: 4, value_s })
                if value_s.to_bits() == bad.to_bits()),
            "{bad}: {r:?}"
        );
    }
    // A used interval must still be positive; an unused one may be anything finite.
    list[4] = -5.0;
    assert_eq!(run(list).unwrap().len, 3);
    list[1] = 0.0;
    assert!(matches!(
        run(list),
        Err(SequenceError::Interval { position: 1, .. })
    ));
}

#[test]
fn the_work_budget_stops_the_enumeration_and_says_whether_an_order_was_reached() {
    // Four clients, the first fixed; every arc costs 1e6 m/s (never pruned) and its estimate
    // 1,000 units. The first complete order takes the fixed part, three nodes and three arcs.
    let p = planes(4);
    let intervals = Intervals::ByPosition([8e4; MAX_CLIENTS - 1]);
    let first_order = work_units::SEQUENCE_FIXED
        + 3 * work_units::SEQUENCE_NODE
        + 3 * (work_units::SEQUENCE_ARC + 1_000);
    let run = |work_budget: u64| {
        let settings = SequenceSettings {
            work_budget,
            ..SequenceSettings::default()
        };
        let mut s = Sequence::new();
        best_order(
            &G,
            &p,
            (Some(0), &intervals),
            &settings,
            |meter: &mut Meter, _, _, _, _| meter.spend(1_000).then_some(1e6),
            &mut s,
        )
        .map(|()| s)
        .unwrap()
    };
    // Enough for the whole tree: 3! orders, 3 + 6 + 6 = 15 arcs, each node charged once.
    let whole = run(10_000_000);
    assert_eq!(whole.info.status, SequenceStatus::Optimal);
    assert_eq!(whole.info.arcs_planned, 15);
    let nodes = 1 + 3 + 6;
    assert_eq!(
        whole.info.work_units,
        work_units::SEQUENCE_FIXED
            + nodes * work_units::SEQUENCE_NODE
            + 15 * (work_units::SEQUENCE_ARC + 1_000)
    );
    // Exactly the first order's units: that order, stopped at the next arc.
    let s = run(first_order);
    assert_eq!(
        s.info.status,
        SequenceStatus::BudgetExhausted { verified: true }
    );
    assert!(s.info.status.is_usable());
    assert_eq!((s.len, s.total_dv_mps), (4, Some(3e6)));
    assert_eq!((s.info.arcs_planned, s.info.work_units), (3, first_order));
    // One unit less: the third estimate is refused, no order.
    let s = run(first_order - 1);
    assert_eq!(
        s.info.status,
        SequenceStatus::BudgetExhausted { verified: false }
    );
    assert!(!s.info.status.is_usable());
    assert_eq!((s.len, s.total_dv_mps), (0, None));
    assert!(s.info.work_units < first_order);
    // An estimate that reports itself cut by the budget (it exhausts the meter) on the very
    // last arc of the tree: the tree is finished but the outcome is not `Optimal`.
    let mut calls = 0_u32;
    let mut s = Sequence::new();
    best_order(
        &G,
        &p,
        (Some(0), &intervals),
        &SequenceSettings::default(),
        |meter: &mut Meter, _, _, _, _| {
            calls += 1;
            if calls == 15 {
                let _ = meter.spend(u64::MAX);
            }
            Some(1e6)
        },
        &mut s,
    )
    .unwrap();
    assert_eq!(s.info.arcs_planned, 15);
    assert_eq!(
        s.info.status,
        SequenceStatus::BudgetExhausted { verified: true }
    );
}
