//! Unit tests of `tour_order.rs` (a child module of it, in its own file to keep that file to
//! one job).
extern crate std;
use super::*;
use std::string::ToString as _;

#[test]
fn the_memo_finds_what_it_kept_and_stops_keeping_when_full() {
    let mut m: Memo<u32, f64, 2> = Memo::new();
    assert_eq!(m.get(&1), None);
    m.put(1, 10.0);
    m.put(2, 20.0);
    m.put(3, 30.0);
    assert_eq!(
        (m.get(&1), m.get(&2), m.get(&3)),
        (Some(10.0), Some(20.0), None)
    );
}

fn tour(clients: &[State]) -> SequenceProblem {
    SequenceProblem {
        clients: heapless::Vec::from_slice(clients).unwrap(),
        impulses: 3,
        first: None,
        intervals: super::super::sequence::Intervals::ByPosition([86_400.0; 7]),
    }
}

fn choose_order(
    problem: &SequenceProblem,
    settings: &SequenceSettings,
    arc_settings: &Settings,
) -> Result<Sequence, SequenceError> {
    let mut workspace = std::boxed::Box::new(SequenceWorkspace::new());
    let mut out = Sequence::new();
    solve_sequence(problem, settings, arc_settings, &mut workspace, &mut out).map(|()| out)
}

#[test]
fn too_few_or_degenerate_clients_are_named() {
    let s = SequenceSettings {
        max_arcs: 10,
        ..SequenceSettings::default()
    };
    let a = [7000.0, 0.0, 0.0, 0.0, 7.546, 0.0];
    assert_eq!(
        choose_order(&tour(&[a]), &s, &Settings::default()).unwrap_err(),
        SequenceError::Clients { count: 1 }
    );
    let b = [7100.0, 0.0, 0.0, 0.0, 7.49, 0.1];
    let nan_margin = SequenceSettings {
        bound_margin: f64::NAN,
        ..s
    };
    let e = choose_order(&tour(&[a, b]), &nan_margin, &Settings::default()).unwrap_err();
    let SequenceError::InvalidSetting(refusal) = e else {
        panic!("{e:?}")
    };
    assert_eq!(
        refusal.setting,
        super::super::sequence::SettingId::BoundMargin
    );
    assert!(refusal.value.is_nan());
    assert!(
        e.to_string().starts_with("setting bound_margin = NaN"),
        "{e}"
    );
    let radial = [7000.0, 0.0, 0.0, 7.5, 0.0, 0.0];
    assert_eq!(
        choose_order(&tour(&[a, radial]), &s, &Settings::default()).unwrap_err(),
        SequenceError::Client { index: 1 }
    );
    // The arc estimates' settings are checked before planning too.
    let bad_arc = Settings {
        step_s: f64::NAN,
        ..Settings::default()
    };
    let e = choose_order(&tour(&[a, b]), &s, &bad_arc).unwrap_err();
    let SequenceError::InvalidArcSetting(refusal) = e else {
        panic!("{e:?}")
    };
    assert_eq!(refusal.setting, super::super::SettingId::StepS);
    // A client inside the Earth (a circular orbit of radius 6000 km): named, with its
    // perigee altitude, instead of an arc estimate refusing it in every order.
    let inside = [6000.0, 0.0, 0.0, 0.0, 8.15, 0.0];
    let e = choose_order(&tour(&[a, b, inside]), &s, &Settings::default()).unwrap_err();
    let SequenceError::ClientPerigee(low) = e else {
        panic!("{e:?}")
    };
    assert_eq!((low.index, low.min_km), (2, 100.0));
    assert!(low.altitude_km < -378.0, "{}", low.altitude_km);
    assert!(
        e.to_string().starts_with("client 2: perigee altitude -"),
        "{e}"
    );
}

#[test]
fn the_sequencing_spends_at_most_its_work_budget_and_says_when_it_was_cut() {
    // Three clients of Example I, the estimates' defaults: the whole tree takes some
    // hundreds of thousands of units; below that the enumeration is cut, never past its
    // budget (an estimate is not started with less left than it charges before it can
    // stop), and an order reached before the cut is usable.
    let clients: std::vec::Vec<State> = [
        (6778.14, 97.0344, 49.0, 25.0),
        (6878.14, 97.4063, 46.0, 13.0),
        (6978.14, 97.7924, 50.5836, 5.0),
    ]
    .iter()
    .map(|&(a_km, i_deg, raan_deg, u_deg)| {
        super::super::elements::state_of(
            crate::astro::EARTH_MU_KM3_S2,
            &super::super::elements::Classical {
                a_km,
                e: 0.0,
                i_rad: f64::to_radians(i_deg),
                raan_rad: f64::to_radians(raan_deg),
                argp_rad: 0.0,
                nu_rad: f64::to_radians(u_deg),
            },
        )
        .unwrap()
    })
    .collect();
    let problem = tour(&clients);
    let run = |work_budget: u64| {
        let settings = SequenceSettings {
            work_budget,
            ..SequenceSettings::default()
        };
        choose_order(&problem, &settings, &ESTIMATE_SETTINGS).unwrap()
    };
    let whole = run(SequenceSettings::DEFAULT.work_budget);
    assert_eq!(whole.info.status, SequenceStatus::Optimal);
    let needed = whole.info.work_units;
    assert!(needed > 50_000, "{needed}");
    let mut usable_cut = 0;
    for k in 1..300_u64 {
        let budget = needed * k / 300;
        let q = run(budget);
        // The fixed part is charged whatever the budget (as an arc's).
        let most = budget.max(super::super::work_units::SEQUENCE_FIXED);
        assert!(q.info.work_units <= most, "{budget}: {}", q.info.work_units);
        assert!(
            matches!(q.info.status, SequenceStatus::BudgetExhausted { .. }),
            "{budget}: {:?}",
            q.info.status
        );
        assert_eq!(q.total_dv_mps.is_some(), q.info.status.is_usable());
        usable_cut += usize::from(q.info.status.is_usable());
    }
    // Past the first complete order, a cut enumeration still returns one.
    assert!(usable_cut > 0);
}

#[test]
fn the_sequencing_is_a_planner_of_the_contract() {
    use crate::contract::{Planner, Status};
    assert_eq!(LeoSequence::KIND, crate::contract::PlannerKind::LeoSequence);
    assert_eq!(Sequence::new().info.status, SequenceStatus::Unsolved);
    assert_eq!(SequenceStatus::default().code(), 0);
    assert_eq!(SequenceStatus::Optimal.code(), 1);
    assert_eq!(SequenceStatus::NoOrder { arc_limit: true }.code(), 4);
    for (status, usable) in [
        (SequenceStatus::Unsolved, false),
        (SequenceStatus::Optimal, true),
        (SequenceStatus::BoundViolated, true),
        (SequenceStatus::ArcLimit, true),
        (SequenceStatus::NoOrder { arc_limit: false }, false),
        (SequenceStatus::NoOrder { arc_limit: true }, false),
        (SequenceStatus::BudgetExhausted { verified: true }, true),
        (SequenceStatus::BudgetExhausted { verified: false }, false),
    ] {
        assert_eq!(Status::is_usable(&status), usable, "{status:?}");
        let budget = match status {
            SequenceStatus::BudgetExhausted { verified } => Some(verified),
            _ => None,
        };
        assert_eq!(status.budget_exhausted(), budget);
    }
    assert_eq!(SequenceStatus::BudgetExhausted { verified: true }.code(), 5);
}
