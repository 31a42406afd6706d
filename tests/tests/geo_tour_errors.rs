//! GEO tour: every bad input refused with the field, value and limit; infeasible requests end
//! with a status naming the leg; no panic, no NaN.
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

use reconfig_core::geo_tour::{
    solve, Field, MethodPolicy, PlanError, Problem, SettingId, Settings, Solution, SolveStatus,
    SweepChoice, Workspace,
};

type ProblemEdit = Box<dyn Fn(&mut Problem)>;
type SettingsEdit = Box<dyn Fn(&mut Settings)>;

const DEG: f64 = std::f64::consts::PI / 180.0;
const DAY: f64 = 86_400.0;

fn base() -> Problem {
    let mut t = heapless::Vec::new();
    for lon in [50.0, 59.0, 60.0, 60.12, 60.5, 125.0] {
        t.push(lon * DEG).unwrap();
    }
    Problem {
        start_lon_rad: 48.0 * DEG,
        targets_lon_rad: t,
        mission_time_s: 40.0 * DAY,
        max_burn_mps: 5.0,
        sweep: SweepChoice::Cheaper,
        policy: MethodPolicy::ByCost,
    }
}

fn run(p: &Problem, s: &Settings) -> Result<Box<Solution>, PlanError> {
    let mut ws = Box::new(Workspace::new());
    let mut out = Box::new(Solution::new());
    solve(p, s, &mut ws, &mut out)?;
    Ok(out)
}

fn field_of(e: PlanError) -> (Field, u8, f64) {
    match e {
        PlanError::OutOfRange {
            field,
            index,
            value,
            min,
            max,
        } => {
            assert!(min <= max);
            (field, index, value)
        }
        other => panic!("unexpected {other:?}"),
    }
}

#[test]
fn every_bad_input_is_named() {
    let s = Settings::default();
    let cases: Vec<(ProblemEdit, Field, u8)> = vec![
        (
            Box::new(|p| p.start_lon_rad = f64::NAN),
            Field::StartLongitude,
            0,
        ),
        (
            Box::new(|p| p.targets_lon_rad[3] = f64::INFINITY),
            Field::TargetLongitude,
            3,
        ),
        (
            Box::new(|p| p.targets_lon_rad[1] = 100.0),
            Field::TargetLongitude,
            1,
        ),
        (Box::new(|p| p.mission_time_s = -1.0), Field::MissionTime, 0),
        (
            Box::new(|p| p.mission_time_s = f64::NAN),
            Field::MissionTime,
            0,
        ),
        (Box::new(|p| p.max_burn_mps = 0.0), Field::MaxBurn, 0),
        (Box::new(|p| p.max_burn_mps = f64::NAN), Field::MaxBurn, 0),
    ];
    for (edit, field, index) in cases {
        let mut p = base();
        edit(&mut p);
        let e = run(&p, &s).expect_err("refused");
        let (f, i, _) = field_of(e);
        assert_eq!((f, i), (field, index), "{e}");
        assert!(e.to_string().contains(&format!("{field:?}")));
    }
    let mut p = base();
    p.targets_lon_rad.clear();
    assert_eq!(run(&p, &s).err(), Some(PlanError::NoTargets));
}

#[test]
fn every_bad_setting_is_named() {
    let p = base();
    let cases: Vec<(SettingsEdit, SettingId)> = vec![
        (
            Box::new(|s| s.lambert_max_revolutions = 9),
            SettingId::LambertMaxRevolutions,
        ),
        (
            Box::new(|s| s.lambert_max_iter = 0),
            SettingId::LambertMaxIter,
        ),
        (
            Box::new(|s| s.lambert_tol = f64::NAN),
            SettingId::LambertTol,
        ),
        (
            Box::new(|s| s.well_iterations = 0),
            SettingId::WellIterations,
        ),
        (Box::new(|s| s.root_max_iter = 5), SettingId::RootMaxIter),
        (Box::new(|s| s.price_max_iter = 0), SettingId::PriceMaxIter),
        (Box::new(|s| s.time_tol_s = 0.0), SettingId::TimeTolS),
        (Box::new(|s| s.gap_max_legs = 7), SettingId::GapMaxLegs),
        (
            Box::new(|s| s.exchange_rounds = 1000),
            SettingId::ExchangeRounds,
        ),
        (
            Box::new(|s| s.exchange_margin_mps = -1.0),
            SettingId::ExchangeMarginMps,
        ),
        (
            Box::new(|s| s.min_radius_km = 100.0),
            SettingId::MinRadiusKm,
        ),
        (
            Box::new(|s| s.rule_drift_above_rad = 4.0),
            SettingId::RuleDriftAboveRad,
        ),
        (
            Box::new(|s| s.rule_hohmann_above_rad = 1.0),
            SettingId::RuleHohmannAboveRad,
        ),
        (
            Box::new(|s| s.rule_radial_above_rad = 0.5),
            SettingId::RuleRadialAboveRad,
        ),
        (
            Box::new(|s| s.lambert_direct_time_s = 1.0),
            SettingId::LambertDirectTimeS,
        ),
    ];
    for (edit, id) in cases {
        let mut s = Settings::default();
        edit(&mut s);
        let e = run(&p, &s).expect_err("refused");
        let PlanError::InvalidSetting(refusal) = e else {
            panic!("{id:?}: {e:?}")
        };
        assert_eq!(refusal.setting, id, "{e}");
        assert!(e.to_string().contains(id.name()), "{e}");
        assert!(!refusal.range.contains(refusal.value), "{e}");
    }
}

#[test]
fn infeasible_requests_name_the_leg() {
    let s = Settings::default();
    // One day: even without the cap the six legs need more (each at least a 9-hour Lambert
    // arc); the leg needing the most time under the cap (64.5 deg, index 5) is named.
    let mut p = base();
    p.mission_time_s = 1.0 * DAY;
    p.sweep = SweepChoice::East;
    let out = run(&p, &s).unwrap();
    assert_eq!(out.info.status, SolveStatus::MissionTooShort { leg: 5 });
    assert!(out
        .info
        .fastest_tour_s
        .is_some_and(|t| t > p.mission_time_s && t.is_finite()));
    // Five days fit without the cap (large burns), not with 5 m/s: CapTooLow names the leg
    // the cap slows most.
    let mut p = base();
    p.mission_time_s = 5.0 * DAY;
    p.sweep = SweepChoice::East;
    let out = run(&p, &s).unwrap();
    assert_eq!(out.info.status, SolveStatus::CapTooLow { leg: 5 });
    // A 0.05 m/s cap: the tour would fit in 40 days uncapped, not with the cap.
    let mut p = base();
    p.max_burn_mps = 0.05;
    p.sweep = SweepChoice::East;
    let out = run(&p, &s).unwrap();
    assert_eq!(out.info.status, SolveStatus::CapTooLow { leg: 5 });
    // The paper's rule with a cap under the radial burns of a 0.2 deg leg.
    let mut p = base();
    p.targets_lon_rad.push(60.7 * DEG).unwrap();
    p.policy = MethodPolicy::PaperRule;
    p.max_burn_mps = 2.0;
    p.sweep = SweepChoice::East;
    p.mission_time_s = 60.0 * DAY;
    let out = run(&p, &s).unwrap();
    assert!(
        matches!(out.info.status, SolveStatus::CapTooLow { .. })
            || matches!(out.info.status, SolveStatus::RuleMethodInadmissible { .. }),
        "{:?}",
        out.info.status
    );
    // No tour is admissible at all (a leg has no method within the cap): the fastest tour
    // does not exist, and is absent rather than infinite.
    assert_eq!(out.info.fastest_tour_s, None, "{:?}", out.info);
    assert!(!out.info.status.is_usable());
}

#[test]
fn odd_but_valid_requests_never_give_nan() {
    let s = Settings::default();
    // Duplicate slots, a client in the servicer's slot, a longitude given as -300 deg.
    let mut p = base();
    p.targets_lon_rad.push(48.0 * DEG).unwrap();
    p.targets_lon_rad
        .push(60.0 * DEG - 2.0 * std::f64::consts::PI)
        .unwrap();
    for sweep in [SweepChoice::East, SweepChoice::West, SweepChoice::Cheaper] {
        for days in [1.0, 10.0, 40.0, 400.0] {
            p.sweep = sweep;
            p.mission_time_s = days * DAY;
            let out = run(&p, &s).unwrap();
            assert!(out.total_dv_mps.is_finite() && out.mission_time_s.is_finite());
            assert!(out.info.price_mps_per_s.is_finite());
            assert!(out.info.fastest_tour_s.is_none_or(f64::is_finite));
            if out.info.status == SolveStatus::Solved {
                assert_eq!(out.legs.len(), p.targets_lon_rad.len());
                assert!(out.mission_time_s <= p.mission_time_s);
                assert!(out.max_burn_mps <= p.max_burn_mps);
                for l in &out.legs {
                    assert!(l.dv_mps.is_finite() && l.duration_s >= 0.0);
                }
            }
        }
    }
}
