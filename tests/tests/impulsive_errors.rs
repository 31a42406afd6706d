//! One test per rejected-input class of planner B, each asserting the exact `PlanError`, plus
//! the singular-geometry statuses (rank deficiency) that are solved and reported.

use reconfig_core::astro::EARTH_RADIUS_KM;
use reconfig_core::capacity::MAX_IMPULSES;
use reconfig_core::impulsive::{
    solve, ImpulsePlan, ImpulsePoint, Orbit, PlanError, Problem, Quantity, SettingId, Settings,
    Solution, SolveStatus, Workspace, MAX_ANGLE_RAD, MAX_SMA_KM,
};

fn points(list: &[(f64, i32)]) -> heapless::Vec<ImpulsePoint, MAX_IMPULSES> {
    list.iter()
        .map(|(u, n)| ImpulsePoint {
            arg_latitude_rad: u.to_radians(),
            revolutions: *n,
        })
        .collect()
}

/// Wang 2018's case (Table 2 points), from its fixture.
fn paper() -> Problem {
    reconfig_tests::impulsive_fixture("wang2018-gco-to-pco-3imp")
}

fn reject(p: &Problem, settings: &Settings) -> PlanError {
    let mut ws = Workspace::new();
    let mut out = Solution::new();
    let err = solve(p, settings, &mut ws, &mut out).unwrap_err();
    // Rejected before iterating: the output buffer is untouched.
    assert_eq!(out, Solution::new());
    assert!(!err.to_string().is_empty());
    err
}

fn rejected(p: &Problem) -> PlanError {
    reject(p, &Settings::default())
}

#[test]
fn nan_and_inf_anywhere() {
    let mut p = paper();
    p.chief.raan_rad = f64::NAN;
    assert_eq!(
        rejected(&p),
        PlanError::NotFinite {
            what: Quantity::Chief,
            index: 3
        }
    );
    let mut p = paper();
    p.initial.dsma_km = f64::INFINITY;
    assert_eq!(
        rejected(&p),
        PlanError::NotFinite {
            what: Quantity::Initial,
            index: 0
        }
    );
    let mut p = paper();
    p.target.dmean_anomaly_rad = f64::NEG_INFINITY;
    assert_eq!(
        rejected(&p),
        PlanError::NotFinite {
            what: Quantity::Target,
            index: 5
        }
    );
    let mut p = paper();
    p.plan = ImpulsePlan::Fixed(points(&[(10.0, 0), (f64::NAN, 1)]));
    assert_eq!(
        rejected(&p),
        PlanError::NotFinite {
            what: Quantity::ImpulsePoint,
            index: 1
        }
    );
}

fn classical(p: &Problem) -> PlanError {
    reject(p, &Settings::paper_classical())
}

#[test]
fn eccentricity_below_threshold_is_reported_in_the_classical_set() {
    // Paper-reproduction mode (classical elements): B holds 1/e, so small e is refused.
    let mut p = paper();
    p.chief.ecc = 1e-6;
    assert_eq!(
        classical(&p),
        PlanError::EccentricityTooSmall {
            orbit: Orbit::Chief,
            ecc: 1e-6,
            min: 1e-4
        }
    );
    let mut p = paper();
    p.chief.ecc = 0.0;
    assert_eq!(
        classical(&p),
        PlanError::EccentricityTooSmall {
            orbit: Orbit::Chief,
            ecc: 0.0,
            min: 1e-4
        }
    );
    // The deputy's own eccentricity counts too.
    let mut p = paper();
    p.chief.ecc = 2e-4;
    p.initial.decc = 0.0;
    p.target.decc = -1.5e-4;
    assert_eq!(
        classical(&p),
        PlanError::EccentricityTooSmall {
            orbit: Orbit::DeputyTarget,
            ecc: 2e-4 - 1.5e-4,
            min: 1e-4
        }
    );
}

#[test]
fn sin_inclination_below_threshold_is_reported_in_the_classical_set() {
    // Paper-reproduction mode: B holds 1/sin i.
    let mut p = paper();
    p.chief.inc_rad = 0.0;
    assert_eq!(
        classical(&p),
        PlanError::InclinationSingular {
            orbit: Orbit::Chief,
            sin_inc: 0.0,
            min: 1e-3
        }
    );
    let mut p = paper();
    p.chief.inc_rad = std::f64::consts::PI - 1e-5;
    // Retrograde equatorial is singular in the equinoctial set too (tan(i/2) infinite).
    match rejected(&p) {
        PlanError::InclinationSingular {
            orbit: Orbit::Chief,
            sin_inc,
            min,
        } => {
            assert!((sin_inc - 1e-5).abs() < 1e-12, "{sin_inc}");
            assert_eq!(min, 1e-3);
        }
        e => panic!("{e:?}"),
    }
}

#[test]
fn circular_and_equatorial_chiefs_are_ordinary_in_the_equinoctial_set() {
    // The default (equinoctial) set is regular at e = 0 and i = 0: the inputs the classical
    // set refuses above are planned, as long as every orbit is an ellipse (e >= 0).
    for (ecc, inc_rad, decc) in [(0.0, 1.1, 1e-4), (1e-6, 1.1, 1e-4), (0.0, 0.0, 1e-4)] {
        let mut p = paper();
        p.chief.ecc = ecc;
        p.chief.inc_rad = inc_rad;
        p.initial.decc = 0.0;
        p.target.decc = decc;
        p.initial.dinc_rad = 0.0;
        p.target.dinc_rad = 1e-4;
        let mut ws = Workspace::new();
        let mut out = Solution::new();
        solve(&p, &Settings::default(), &mut ws, &mut out).unwrap();
        assert_eq!(out.info.status, SolveStatus::Solved, "e {ecc} i {inc_rad}");
        assert!(
            out.terminal_error
                .expect("nonlinear check flown")
                .position_m
                < 1e-3
        );
    }
}

#[test]
fn eccentricity_at_or_above_one() {
    let mut p = paper();
    p.chief.ecc = 1.0;
    assert_eq!(
        rejected(&p),
        PlanError::NotElliptic {
            orbit: Orbit::Chief,
            ecc: 1.0
        }
    );
    let mut p = paper();
    p.initial.decc = 1.5;
    assert_eq!(
        rejected(&p),
        PlanError::NotElliptic {
            orbit: Orbit::DeputyInitial,
            ecc: 0.0678 + 1.5
        }
    );
    let mut p = paper();
    p.chief.ecc = -0.1;
    assert_eq!(
        rejected(&p),
        PlanError::NotElliptic {
            orbit: Orbit::Chief,
            ecc: -0.1
        }
    );
}

/// The lower limit of a: Re plus the minimum perigee altitude (100 km by default).
const MIN_SMA_KM: f64 = EARTH_RADIUS_KM + 100.0;

#[test]
fn semi_major_axis_out_of_range() {
    for (sma_km, orbit_dsma) in [
        (EARTH_RADIUS_KM, 0.0),
        (-7000.0, 0.0),
        (MAX_SMA_KM * 1.0001, 0.0),
        (1e10, 0.0),
        (1e308, 0.0),
    ] {
        let mut p = paper();
        p.chief.sma_km = sma_km;
        p.initial.dsma_km = orbit_dsma;
        assert_eq!(
            rejected(&p),
            PlanError::SemiMajorAxisOutOfRange {
                orbit: Orbit::Chief,
                sma_km,
                min_km: MIN_SMA_KM,
                max_km: MAX_SMA_KM
            },
            "{sma_km}"
        );
    }
    // A deputy pushed out of range by its difference.
    let mut p = paper();
    p.target.dsma_km = 1e300;
    assert!(matches!(
        rejected(&p),
        PlanError::SemiMajorAxisOutOfRange {
            orbit: Orbit::DeputyTarget,
            ..
        }
    ));
    // The lower limit follows the perigee setting.
    let mut p = paper();
    p.chief.sma_km = EARTH_RADIUS_KM + 150.0;
    p.chief.ecc = 0.001;
    let settings = Settings {
        min_perigee_altitude_km: 200.0,
        ..Settings::default()
    };
    assert_eq!(
        reject(&p, &settings),
        PlanError::SemiMajorAxisOutOfRange {
            orbit: Orbit::Chief,
            sma_km: EARTH_RADIUS_KM + 150.0,
            min_km: EARTH_RADIUS_KM + 200.0,
            max_km: MAX_SMA_KM
        }
    );
}

#[test]
fn perigee_below_the_minimum_altitude() {
    // e = 0.9 at the paper's a: perigee inside the Earth.
    let mut p = paper();
    p.chief.ecc = 0.9;
    match rejected(&p) {
        PlanError::PerigeeTooLow {
            orbit: Orbit::Chief,
            perigee_altitude_km,
            min_km,
        } => {
            let want = 7178.137 * 0.1 - EARTH_RADIUS_KM;
            assert!(
                (perigee_altitude_km - want).abs() < 1e-9,
                "{perigee_altitude_km}"
            );
            assert_eq!(min_km, 100.0);
        }
        e => panic!("{e:?}"),
    }
    // The paper's chief has a 313 km perigee: a deputy eccentricity that lowers it to ~60 km.
    let mut p = paper();
    p.target.decc = 0.0358;
    assert!(matches!(
        rejected(&p),
        PlanError::PerigeeTooLow {
            orbit: Orbit::DeputyTarget,
            ..
        }
    ));
    let mut p = paper();
    p.initial.decc = 0.0358;
    assert!(matches!(
        rejected(&p),
        PlanError::PerigeeTooLow {
            orbit: Orbit::DeputyInitial,
            ..
        }
    ));
    // A lower setting accepts it.
    let settings = Settings {
        min_perigee_altitude_km: 50.0,
        ..Settings::default()
    };
    let mut ws = Workspace::new();
    let mut out = Solution::new();
    assert!(solve(&p, &settings, &mut ws, &mut out).is_ok());
}

#[test]
fn inclination_outside_zero_to_pi() {
    for inc_rad in [-0.5, 3.5] {
        let mut p = paper();
        p.chief.inc_rad = inc_rad;
        assert_eq!(
            rejected(&p),
            PlanError::InclinationOutOfRange {
                orbit: Orbit::Chief,
                inc_rad
            }
        );
    }
}

#[test]
fn angles_beyond_the_limit() {
    let mut p = paper();
    p.chief.mean_anomaly_rad = 1e300;
    assert_eq!(
        rejected(&p),
        PlanError::AngleOutOfRange {
            what: Quantity::Chief,
            index: 5,
            value_rad: 1e300,
            limit_rad: MAX_ANGLE_RAD
        }
    );
    let mut p = paper();
    p.target.draan_rad = -2e4;
    assert_eq!(
        rejected(&p),
        PlanError::AngleOutOfRange {
            what: Quantity::Target,
            index: 3,
            value_rad: -2e4,
            limit_rad: MAX_ANGLE_RAD
        }
    );
    let mut p = paper();
    p.plan = ImpulsePlan::Fixed(points(&[(10.0, 0), (1e7, 1)]));
    assert_eq!(
        rejected(&p),
        PlanError::AngleOutOfRange {
            what: Quantity::ImpulsePoint,
            index: 1,
            value_rad: 1e7_f64.to_radians(),
            limit_rad: MAX_ANGLE_RAD
        }
    );
}

#[test]
fn negative_revolutions() {
    let mut p = paper();
    p.plan = ImpulsePlan::Fixed(points(&[(10.0, 1), (20.0, -1)]));
    assert_eq!(
        rejected(&p),
        PlanError::NegativeRevolutions {
            impulse: 1,
            revolutions: -1
        }
    );
    p.plan = ImpulsePlan::Search {
        impulses: 3,
        max_revolutions: -1,
    };
    assert_eq!(
        rejected(&p),
        PlanError::NegativeRevolutions {
            impulse: 0,
            revolutions: -1
        }
    );
}

#[test]
fn revolutions_over_the_limit() {
    let mut p = paper();
    p.plan = ImpulsePlan::Fixed(points(&[(10.0, 60), (20.0, 41)]));
    assert_eq!(
        rejected(&p),
        PlanError::RevolutionsOverLimit {
            requested: 101,
            limit: 100
        }
    );
    p.plan = ImpulsePlan::Fixed(points(&[(10.0, i32::MAX), (20.0, i32::MAX)]));
    assert_eq!(
        rejected(&p),
        PlanError::RevolutionsOverLimit {
            requested: i32::MAX,
            limit: 100
        }
    );
    p.plan = ImpulsePlan::Search {
        impulses: 3,
        max_revolutions: 15,
    };
    let tight = Settings {
        max_total_revolutions: 14,
        ..Settings::default()
    };
    assert_eq!(
        reject(&p, &tight),
        PlanError::RevolutionsOverLimit {
            requested: 15,
            limit: 14
        }
    );
}

#[test]
fn more_impulses_than_capacity_and_none() {
    let mut p = paper();
    p.plan = ImpulsePlan::Search {
        impulses: 7,
        max_revolutions: 14,
    };
    assert_eq!(
        rejected(&p),
        PlanError::CapacityExceeded {
            requested: 7,
            capacity: 6
        }
    );
    p.plan = ImpulsePlan::Search {
        impulses: 0,
        max_revolutions: 14,
    };
    assert_eq!(rejected(&p), PlanError::NoImpulses);
    p.plan = ImpulsePlan::Fixed(heapless::Vec::new());
    assert_eq!(rejected(&p), PlanError::NoImpulses);
}

#[test]
fn invalid_settings_name_the_setting_the_value_and_the_range() {
    let p = paper();
    for (s, id, value, end) in [
        (
            Settings {
                fixed_point_max_iter: 0,
                ..Settings::default()
            },
            SettingId::FixedPointMaxIter,
            0.0,
            1.0,
        ),
        (
            Settings {
                fixed_point_tol_mps: -1.0,
                ..Settings::default()
            },
            SettingId::FixedPointTolMps,
            -1.0,
            0.0,
        ),
        (
            Settings {
                min_sin_inclination: 2.0,
                ..Settings::default()
            },
            SettingId::MinSinInclination,
            2.0,
            1.0,
        ),
        (
            Settings {
                search_starts: 0,
                ..Settings::default()
            },
            SettingId::SearchStarts,
            0.0,
            1.0,
        ),
    ] {
        let PlanError::InvalidSetting(e) = reject(&p, &s) else {
            panic!("{id:?}: not a setting refusal")
        };
        assert_eq!((e.setting, e.value), (id, value), "{id:?}");
        let broken = if value < e.range.min {
            e.range.min
        } else {
            e.range.max
        };
        assert_eq!(broken, end, "{id:?}");
    }
}

#[test]
fn coincident_points_are_least_squares_with_their_rank_reported() {
    // Two impulses at the same point: F = [F1 F1] has rank 3.
    let mut p = paper();
    p.plan = ImpulsePlan::Fixed(points(&[(274.155, 2), (274.155, 0)]));
    let mut ws = Workspace::new();
    let mut out = Solution::new();
    solve(&p, &Settings::default(), &mut ws, &mut out).unwrap();
    assert_eq!(out.info.status, SolveStatus::RankDeficient);
    assert!(!out.info.status.is_usable());
    assert_eq!(out.info.rank, 3);
    assert_eq!(out.info.condition_number, None);
    assert_eq!(out.impulses.len(), 2);
    assert!(out.total_dv_mps.is_finite());
    // Minimum norm splits the least-squares impulse evenly between the two coincident points.
    for axis in 0..3 {
        let (a, b) = (
            out.impulses[0].dv_rtn_mps[axis],
            out.impulses[1].dv_rtn_mps[axis],
        );
        assert!((a - b).abs() < 1e-9 * a.abs().max(1.0), "{a} vs {b}");
    }
    // A single impulse cannot reach six elements either: rank 3 as well.
    p.plan = ImpulsePlan::Fixed(points(&[(274.155, 2)]));
    solve(&p, &Settings::default(), &mut ws, &mut out).unwrap();
    assert_eq!(out.info.status, SolveStatus::RankDeficient);
    assert_eq!(out.info.rank, 3);
}

#[test]
fn errors_round_trip_the_wire() {
    let e = PlanError::RevolutionsOverLimit {
        requested: 20,
        limit: 14,
    };
    let bytes = postcard::to_allocvec(&e).unwrap();
    assert_eq!(postcard::from_bytes::<PlanError>(&bytes).unwrap(), e);
    let p = paper();
    let bytes = postcard::to_allocvec(&p).unwrap();
    assert_eq!(postcard::from_bytes::<Problem>(&bytes).unwrap(), p);
    let s = Settings::default();
    let bytes = postcard::to_allocvec(&s).unwrap();
    assert_eq!(postcard::from_bytes::<Settings>(&bytes).unwrap(), s);
}
