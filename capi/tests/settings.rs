//! Every setting of every planner through the C interface (issues 29 and 33):
//!
//! * the walk: for each `SettingId` of planner A, planner B (both entry points), the GEO
//!   tour, the LEO arc and the hybrid transfer, a value outside its built-in limit (by its `limit_rule`) set in the C settings
//!   struct is refused `RECONFIG_ERR_LIMIT_EXCEEDED` naming it (`error.index` its code,
//!   `reconfig_setting_name` its name, the exact value and limit, the rule), and a value outside
//!   its accepted range (NaN for floats, numbers past either end, a flag or code no core value
//!   is) is refused `RECONFIG_ERR_SETTING_OUT_OF_RANGE` naming it;
//! * the audit's cases: `verify_tol_lu = 1e308` and `correction_tol = 1e308` refused by name,
//!   NaN `verify_tol_lu` and NaN `keep_out_margin_lu` named distinctly;
//! * coverage: a distinctive value of every setting survives core -> C struct -> core (so the
//!   C struct mirrors every field), and the fixture keys (the serde names of the core's
//!   settings) are the settings tables' names;
//! * `reconfig_setting_name` for every code, and NULL for codes no setting has.
#![allow(
    clippy::unwrap_used,
    clippy::expect_used,
    clippy::panic,
    clippy::indexing_slicing,
    clippy::float_cmp,
    clippy::arithmetic_side_effects,
    clippy::undocumented_unsafe_blocks
)]

mod common;
use common::circular;
use core::ffi::c_void;
use reconfig_capi::geo_tour::*;
use reconfig_capi::hybrid::*;
use reconfig_capi::impulsive::*;
use reconfig_capi::leo_tour::*;
use reconfig_capi::names::*;
use reconfig_capi::pseudospectral::*;
use reconfig_capi::settings::SettingsMirror;
use reconfig_capi::status::*;
use reconfig_capi::types_a::*;
use reconfig_capi::types_b::*;
use reconfig_capi::types_b_form::*;
use reconfig_capi::types_geo::*;
use reconfig_capi::types_hybrid::*;
use reconfig_capi::types_leo::*;
use reconfig_core::contract::Rule;
use reconfig_core::contract::{check_limit, Range};
use reconfig_core::limits::Setting;
use reconfig_core::{geo_tour, hybrid, impulsive, leo_tour, pseudospectral};

/// Caller memory of `size` bytes aligned to 8.
fn memory(size: usize) -> Vec<u64> {
    vec![0; size.div_ceil(8) + 1]
}

/// The name `reconfig_setting_name` gives, as a Rust string.
fn setting_name(planner: i32, code: i32) -> Option<String> {
    let p = reconfig_setting_name(planner, code);
    // SAFETY: null or a static NUL-terminated string.
    (!p.is_null()).then(|| {
        unsafe { std::ffi::CStr::from_ptr(p) }
            .to_str()
            .unwrap()
            .to_owned()
    })
}

/// One planner's settings table and C entry point, as the walk needs them.
trait Table {
    /// The settings id.
    type Id: Copy + Into<Setting> + std::fmt::Debug + 'static;
    /// The core's settings.
    type Core: Default + Copy + PartialEq + std::fmt::Debug;
    /// The C mirror.
    type C: SettingsMirror<Core = Self::Core>;
    /// `RECONFIG_PLANNER_*`.
    const PLANNER: i32;
    /// The entry point's name, for messages.
    const ENTRY: &'static str;
    fn all() -> &'static [Self::Id];
    fn name(id: Self::Id) -> &'static str;
    fn range(id: Self::Id) -> Range;
    fn rule(id: Self::Id) -> Option<Rule>;
    fn value(s: &Self::Core, id: Self::Id) -> f64;
    fn set(s: &mut Self::Core, id: Self::Id, value: f64) -> bool;
    /// A workspace, initialised.
    fn workspace() -> Vec<u64>;
    /// Solve a plannable problem with `settings` through the C entry point: (status, error).
    fn solve(workspace: &mut [u64], settings: &Self::C) -> (i32, ReconfigError);
}

macro_rules! table_ids {
    ($Id:ty, $Core:ty) => {
        type Id = $Id;
        type Core = $Core;
        fn all() -> &'static [$Id] {
            <$Id>::ALL
        }
        fn name(id: $Id) -> &'static str {
            id.name()
        }
        fn range(id: $Id) -> Range {
            id.range()
        }
        fn rule(id: $Id) -> Option<Rule> {
            id.limit_rule()
        }
        fn value(s: &$Core, id: $Id) -> f64 {
            s.value(id)
        }
        fn set(s: &mut $Core, id: $Id, value: f64) -> bool {
            s.set(id, value)
        }
    };
}

fn three_sats() -> ReconfigAProblem {
    let mut p = ReconfigAProblem {
        horizon_tu: 10.0,
        max_control_fu: 1.0,
        keep_out_lu: 2.0,
        degree: 10,
        test_points: 1,
        spacecraft_count: 3,
        ..ReconfigAProblem::default()
    };
    let ends = [
        ([0.0, 0.0, 0.0], [12.0, 12.0, 12.0]),
        ([8.0, 0.0, 0.0], [0.0, 12.0, 12.0]),
        ([8.0, 0.0, 8.0], [0.0, 12.0, 0.0]),
    ];
    for (sc, (a, b)) in p.spacecraft.iter_mut().zip(ends) {
        sc.mass_mu = 1.0;
        sc.initial_state_lu_lutu[..3].copy_from_slice(&a);
        sc.final_state_lu_lutu[..3].copy_from_slice(&b);
    }
    p
}

const CHIEF: ReconfigBMeanElements = ReconfigBMeanElements {
    sma_km: 7078.137,
    ecc: 1e-3,
    inc_rad: 1.7,
    raan_rad: 0.5,
    argp_rad: 0.3,
    mean_anomaly_rad: 1.0,
};

fn two_points() -> [ReconfigBImpulsePoint; RECONFIG_B_MAX_IMPULSES] {
    let mut points = [ReconfigBImpulsePoint::default(); RECONFIG_B_MAX_IMPULSES];
    points[1] = ReconfigBImpulsePoint {
        arg_latitude_rad: 3.0,
        revolutions: 1,
    };
    points
}

fn b_problem() -> ReconfigBProblem {
    ReconfigBProblem {
        chief: CHIEF,
        target: ReconfigBRelativeElements {
            dsma_km: 0.1,
            ..Default::default()
        },
        impulse_count: 2,
        points: two_points(),
        ..Default::default()
    }
}

fn b_form_problem() -> ReconfigBFormProblem {
    ReconfigBFormProblem {
        chief: ReconfigBOrbitForm {
            form: RECONFIG_B_ORBIT_CLASSICAL,
            classical: CHIEF,
            ..Default::default()
        },
        relative: ReconfigBRelativeForm {
            form: RECONFIG_B_RELATIVE_ELEMENTS,
            target_elements: ReconfigBRelativeElements {
                dsma_km: 0.1,
                ..Default::default()
            },
            ..Default::default()
        },
        impulse_count: 2,
        points: two_points(),
        ..Default::default()
    }
}

fn geo_problem() -> ReconfigGeoProblem {
    let mut p = ReconfigGeoProblem {
        start_lon_rad: 0.1,
        mission_time_s: 30.0 * 86_400.0,
        max_burn_mps: 10.0,
        target_count: 2,
        sweep: RECONFIG_GEO_SWEEP_EAST,
        ..Default::default()
    };
    p.targets_lon_rad[0] = 0.5;
    p.targets_lon_rad[1] = 0.7;
    p
}

/// A plannable LEO arc (the paper's radii and inclinations, one day): refusals come before
/// any planning, so the walk never plans it.
fn leo_problem() -> ReconfigLeoArcProblem {
    let (from_position_km, from_velocity_km_s) = circular(6778.14, 1.6936, 0.4363);
    let (to_position_km, to_velocity_km_s) = circular(6878.14, 1.7001, 0.2269);
    ReconfigLeoArcProblem {
        from_position_km,
        from_velocity_km_s,
        to_position_km,
        to_velocity_km_s,
        duration_s: 86_400.0,
        impulses: 3,
    }
}

/// The paper's minimum-fuel transfer at kappa = 1.40, 4.38 days (`hybrid-min-fuel-k140-4p38d`):
/// refusals come before any planning, so the walk never plans it.
fn hybrid_problem() -> ReconfigHybridProblem {
    ReconfigHybridProblem {
        kappa: 1.40,
        theta_rad: -2.0,
        duration_days: 4.38,
        thrust_n: 10.0,
        specific_impulse_s: 3000.0,
        chemical_specific_impulse_s: 300.0,
        parking_radius_km: 6778.0,
        arrival_r_lu: [0.823385182067, 0.0, -0.022277556273],
        arrival_v_vu: [0.0, 0.134184170262, 0.0],
        halo_period_tu: 2.746337,
        costates: [
            1.51293,
            7.36403,
            -0.122107,
            -0.0191786,
            0.014939,
            5.13983e-06,
            0.0596219,
        ],
        design_duration_days: 4.38,
        design_thrust_n: 10.0,
        objective: RECONFIG_HYBRID_OBJECTIVE_MIN_FUEL,
        ..Default::default()
    }
}

struct A;
impl Table for A {
    table_ids!(pseudospectral::SettingId, pseudospectral::Settings);
    type C = ReconfigASettings;
    const PLANNER: i32 = RECONFIG_PLANNER_PSEUDOSPECTRAL;
    const ENTRY: &'static str = "reconfig_pseudospectral_solve";
    fn workspace() -> Vec<u64> {
        let size = reconfig_pseudospectral_workspace_size();
        let mut m = memory(size);
        assert_eq!(
            unsafe { reconfig_pseudospectral_init(m.as_mut_ptr().cast(), size) },
            0
        );
        m
    }
    fn solve(ws: &mut [u64], settings: &ReconfigASettings) -> (i32, ReconfigError) {
        let mut out: Box<ReconfigASolution> = Box::new(unsafe { core::mem::zeroed() });
        let code = unsafe {
            reconfig_pseudospectral_solve(
                ws.as_mut_ptr().cast::<c_void>(),
                &three_sats(),
                settings,
                &mut *out,
            )
        };
        (code, out.error)
    }
}

struct B;
impl Table for B {
    table_ids!(impulsive::SettingId, impulsive::Settings);
    type C = ReconfigBSettings;
    const PLANNER: i32 = RECONFIG_PLANNER_IMPULSIVE;
    const ENTRY: &'static str = "reconfig_impulsive_solve";
    fn workspace() -> Vec<u64> {
        let size = reconfig_impulsive_workspace_size();
        let mut m = memory(size);
        assert_eq!(
            unsafe { reconfig_impulsive_init(m.as_mut_ptr().cast(), size) },
            0
        );
        m
    }
    fn solve(ws: &mut [u64], settings: &ReconfigBSettings) -> (i32, ReconfigError) {
        let mut out = ReconfigBSolution::default();
        let code = unsafe {
            reconfig_impulsive_solve(ws.as_mut_ptr().cast(), &b_problem(), settings, &mut out)
        };
        (code, out.error)
    }
}

/// Planner B's other input forms: the same settings, the other entry point.
struct BForm;
impl Table for BForm {
    table_ids!(impulsive::SettingId, impulsive::Settings);
    type C = ReconfigBSettings;
    const PLANNER: i32 = RECONFIG_PLANNER_IMPULSIVE;
    const ENTRY: &'static str = "reconfig_impulsive_solve_form";
    fn workspace() -> Vec<u64> {
        B::workspace()
    }
    fn solve(ws: &mut [u64], settings: &ReconfigBSettings) -> (i32, ReconfigError) {
        let mut out = ReconfigBFormSolution::default();
        let code = unsafe {
            reconfig_impulsive_solve_form(
                ws.as_mut_ptr().cast(),
                &b_form_problem(),
                settings,
                &mut out,
            )
        };
        (code, out.plan.error)
    }
}

struct Geo;
impl Table for Geo {
    table_ids!(geo_tour::SettingId, geo_tour::Settings);
    type C = ReconfigGeoSettings;
    const PLANNER: i32 = RECONFIG_PLANNER_GEO_TOUR;
    const ENTRY: &'static str = "reconfig_geo_tour_solve";
    fn workspace() -> Vec<u64> {
        let size = reconfig_geo_tour_workspace_size();
        let mut m = memory(size);
        assert_eq!(
            unsafe { reconfig_geo_tour_init(m.as_mut_ptr().cast(), size) },
            0
        );
        m
    }
    fn solve(ws: &mut [u64], settings: &ReconfigGeoSettings) -> (i32, ReconfigError) {
        let mut out = ReconfigGeoSolution::default();
        let code = unsafe {
            reconfig_geo_tour_solve(ws.as_mut_ptr().cast(), &geo_problem(), settings, &mut out)
        };
        (code, out.error)
    }
}

struct Leo;
impl Table for Leo {
    table_ids!(leo_tour::SettingId, leo_tour::Settings);
    type C = ReconfigLeoArcSettings;
    const PLANNER: i32 = RECONFIG_PLANNER_LEO_ARC;
    const ENTRY: &'static str = "reconfig_leo_arc_solve";
    fn workspace() -> Vec<u64> {
        let size = reconfig_leo_arc_workspace_size();
        let mut m = memory(size);
        assert_eq!(
            unsafe { reconfig_leo_arc_init(m.as_mut_ptr().cast(), size) },
            0
        );
        m
    }
    fn solve(ws: &mut [u64], settings: &ReconfigLeoArcSettings) -> (i32, ReconfigError) {
        let mut out = ReconfigLeoArcSolution::default();
        let code = unsafe {
            reconfig_leo_arc_solve(ws.as_mut_ptr().cast(), &leo_problem(), settings, &mut out)
        };
        (code, out.error)
    }
}

struct Hybrid;
impl Table for Hybrid {
    table_ids!(hybrid::SettingId, hybrid::Settings);
    type C = ReconfigHybridSettings;
    const PLANNER: i32 = RECONFIG_PLANNER_HYBRID;
    const ENTRY: &'static str = "reconfig_hybrid_solve";
    fn workspace() -> Vec<u64> {
        let size = reconfig_hybrid_workspace_size();
        let mut m = memory(size);
        assert_eq!(
            unsafe { reconfig_hybrid_init(m.as_mut_ptr().cast(), size) },
            0
        );
        m
    }
    fn solve(ws: &mut [u64], settings: &ReconfigHybridSettings) -> (i32, ReconfigError) {
        let mut out = ReconfigHybridSolution::default();
        let code = unsafe {
            reconfig_hybrid_solve(
                ws.as_mut_ptr().cast(),
                &hybrid_problem(),
                settings,
                &mut out,
            )
        };
        (code, out.error)
    }
}

fn code_of<T: Table>(id: T::Id) -> i32 {
    i32::from(Into::<Setting>::into(id).code())
}

/// A value past the built-in limit `limit` by `rule` that the setting's type holds, if any
/// (none for a setting without a limit, or a work-adding flag the built-in limits allow).
fn over_limit<T: Table>(id: T::Id, rule: Rule, limit: f64) -> Option<f64> {
    let candidates: &[f64] = match rule {
        Rule::AtMost | Rule::Below => &[limit + 1.0, limit * 10.0],
        Rule::AtLeast if limit > 0.0 => &[limit - 1.0, limit / 10.0],
        Rule::AtLeast => &[limit - 1.0],
        Rule::MustBeOn => &[0.0],
        Rule::MustBeOff => &[1.0],
    };
    candidates.iter().copied().find(|&v| {
        let mut s = T::Core::default();
        T::set(&mut s, id, v)
            && T::value(&s, id) == v
            && check_limit(id.into(), rule, v, limit).is_err()
    })
}

/// Values outside the setting's range: NaN, past each end (as the range is closed or open).
fn out_of_range(range: Range) -> Vec<f64> {
    let mut v = vec![f64::NAN];
    if range.min > -f64::MAX {
        v.push(if range.min_open {
            range.min
        } else {
            range.min - 1.0
        });
    }
    if range.max < f64::MAX {
        v.push(if range.max_open {
            range.max
        } else {
            range.max + 1.0
        });
    }
    v
}

/// Walk every setting of `T`; returns the names of the settings that admit no refused value
/// (neither a limit nor a range a C value can break).
fn walk<T: Table>() -> Vec<&'static str> {
    let mut ws = T::workspace();
    let defaults = T::C::from_core(&T::Core::default());
    let mut never_refused = Vec::new();
    for &id in T::all() {
        let name = T::name(id);
        let code = code_of::<T>(id);
        let limit = T::value(&T::Core::default(), id);
        let mut refused = 0;
        // A value past the built-in limit (the limits are the defaults).
        if let Some(rule) = T::rule(id) {
            if let Some(v) = over_limit::<T>(id, rule, limit) {
                let mut core = T::Core::default();
                assert!(T::set(&mut core, id, v));
                let (status, e) = T::solve(&mut ws, &T::C::from_core(&core));
                let what = format!("{}: {name} = {v} (limit {limit}, {rule:?})", T::ENTRY);
                assert_eq!(status, RECONFIG_ERR_LIMIT_EXCEEDED, "{what}: {e:?}");
                assert_eq!(
                    (e.code, e.field, e.index, e.detail),
                    (status, RECONFIG_FIELD_SETTINGS, code, i32::from(rule as u8)),
                    "{what}"
                );
                assert_eq!(e.value.to_bits(), v.to_bits(), "{what}");
                assert_eq!(e.limit.to_bits(), limit.to_bits(), "{what}");
                assert_eq!(setting_name(T::PLANNER, e.index).as_deref(), Some(name));
                refused += 1;
            }
        }
        // Values outside the range that the limit lets through (the limits are checked first,
        // as the service checks them): the planner's range check names them.
        let range = T::range(id);
        for v in out_of_range(range) {
            let mut core = T::Core::default();
            if !T::set(&mut core, id, v) {
                continue; // no value of the type (NaN or a negative for an integer)
            }
            let passes_limit =
                T::rule(id).is_none_or(|rule| check_limit(id.into(), rule, v, limit).is_ok());
            if !passes_limit {
                continue;
            }
            assert!(!range.contains(v));
            let (status, e) = T::solve(&mut ws, &T::C::from_core(&core));
            let what = format!("{}: {name} = {v} (range {range})", T::ENTRY);
            assert_eq!(status, RECONFIG_ERR_SETTING_OUT_OF_RANGE, "{what}: {e:?}");
            let (detail, end) = if v.is_nan() {
                (2, range.max)
            } else if v <= range.min {
                (0, range.min)
            } else {
                (1, range.max)
            };
            assert_eq!(
                (e.field, e.index, e.detail),
                (RECONFIG_FIELD_SETTINGS, code, detail),
                "{what}"
            );
            assert_eq!(e.value.to_bits(), v.to_bits(), "{what}");
            assert_eq!(e.limit.to_bits(), end.to_bits(), "{what}");
            assert_eq!(setting_name(T::PLANNER, e.index).as_deref(), Some(name));
            refused += 1;
        }
        // A C value no core value is (a flag or code of 2): refused in C, named as a range.
        let mut core = T::Core::default();
        let mut c = defaults;
        if !T::set(&mut core, id, 2.0) && c.c_set(name, 2.0) {
            let (status, e) = T::solve(&mut ws, &c);
            let what = format!("{}: {name} = 2 in C", T::ENTRY);
            assert_eq!(status, RECONFIG_ERR_SETTING_OUT_OF_RANGE, "{what}: {e:?}");
            assert_eq!(
                (e.field, e.index, e.detail, e.value, e.limit),
                (RECONFIG_FIELD_SETTINGS, code, 1, 2.0, 1.0),
                "{what}"
            );
            assert_eq!(setting_name(T::PLANNER, e.index).as_deref(), Some(name));
            refused += 1;
        }
        if refused == 0 {
            never_refused.push(name);
        }
    }
    never_refused
}

#[test]
fn every_setting_of_every_planner_is_refused_by_name_value_and_limit() {
    assert_eq!(walk::<A>(), Vec::<&str>::new());
    // The search's seed takes any value (it picks samples, not how many): nothing to refuse.
    assert_eq!(walk::<B>(), vec!["search_seed"]);
    assert_eq!(walk::<BForm>(), vec!["search_seed"]);
    assert_eq!(walk::<Geo>(), Vec::<&str>::new());
    assert_eq!(walk::<Leo>(), Vec::<&str>::new());
    assert_eq!(walk::<Hybrid>(), Vec::<&str>::new());
}

#[test]
fn the_audit_requests_are_refused_by_name() {
    // Issue 33: a C caller could loosen exactly what the service refuses, and a NaN
    // tolerance or margin was refused without naming the setting.
    let mut ws = A::workspace();
    let mut s = ReconfigASettings::from_core(&Default::default());
    s.verify_tol_lu = 1e308;
    let (status, e) = A::solve(&mut ws, &s);
    assert_eq!(status, RECONFIG_ERR_LIMIT_EXCEEDED);
    assert_eq!((e.value, e.limit), (1e308, 1e-7));
    assert_eq!(
        setting_name(RECONFIG_PLANNER_PSEUDOSPECTRAL, e.index).as_deref(),
        Some("verify_tol_lu")
    );

    let mut wb = B::workspace();
    let mut s = ReconfigBSettings::from_core(&Default::default());
    s.correction_tol = 1e308;
    let (status, e) = B::solve(&mut wb, &s);
    assert_eq!(status, RECONFIG_ERR_LIMIT_EXCEEDED);
    assert_eq!((e.value, e.limit), (1e308, 1e-12));
    assert_eq!(
        setting_name(RECONFIG_PLANNER_IMPULSIVE, e.index).as_deref(),
        Some("correction_tol")
    );

    let mut names = Vec::new();
    let nans: [fn(&mut ReconfigASettings); 2] = [
        |s| s.verify_tol_lu = f64::NAN,
        |s| s.keep_out_margin_lu = f64::NAN,
    ];
    for nan in nans {
        let mut s = ReconfigASettings::from_core(&Default::default());
        nan(&mut s);
        let (status, e) = A::solve(&mut ws, &s);
        assert_eq!(status, RECONFIG_ERR_SETTING_OUT_OF_RANGE);
        assert_eq!((e.field, e.detail), (RECONFIG_FIELD_SETTINGS, 2));
        assert!(e.value.is_nan());
        names.push(setting_name(RECONFIG_PLANNER_PSEUDOSPECTRAL, e.index).unwrap());
    }
    assert_eq!(names, ["verify_tol_lu", "keep_out_margin_lu"]);
}

/// A value of setting `id` other than its default that its type holds.
fn distinctive<T: Table>(id: T::Id) -> f64 {
    let d = T::value(&T::Core::default(), id);
    [d + 1.0, d - 1.0, d * 2.0 + 3.0, 0.5 * d + 0.375]
        .into_iter()
        .find(|&v| {
            let mut s = T::Core::default();
            v != d && T::set(&mut s, id, v) && T::value(&s, id) == v
        })
        .unwrap_or_else(|| panic!("{}: no distinctive value", T::name(id)))
}

fn mirror_covers<T: Table>() {
    for &id in T::all() {
        let name = T::name(id);
        let v = distinctive::<T>(id);
        let mut core = T::Core::default();
        assert!(T::set(&mut core, id, v));
        let c = T::C::from_core(&core);
        assert_eq!(
            c.c_value(name).map(f64::to_bits),
            Some(v.to_bits()),
            "{name}: the C struct holds it under the setting's name"
        );
        let mut back = T::Core::default();
        c.to_core(&mut back).unwrap();
        assert_eq!(back, core, "{name} = {v}: core -> C -> core");
        assert_eq!(T::value(&back, id).to_bits(), v.to_bits());
    }
    // And the other way: a C struct of default-distinct values converts field for field.
    let c = T::C::from_core(&T::Core::default());
    let mut back = T::Core::default();
    c.to_core(&mut back).unwrap();
    assert_eq!(back, T::Core::default());
}

/// The fixture keys (and limits-file keys): the serde names of the core's settings.
fn fixture_keys<S: serde::Serialize + Default>() -> Vec<String> {
    let value = serde_json::to_value(S::default()).unwrap();
    let mut keys: Vec<String> = value.as_object().unwrap().keys().cloned().collect();
    keys.sort();
    keys
}

fn table_names<T: Table>() -> Vec<String> {
    let mut names: Vec<String> = T::all().iter().map(|&id| T::name(id).to_owned()).collect();
    names.sort();
    names
}

#[test]
fn the_c_structs_and_the_fixture_keys_cover_every_setting() {
    mirror_covers::<A>();
    mirror_covers::<B>();
    mirror_covers::<Geo>();
    mirror_covers::<Leo>();
    mirror_covers::<Hybrid>();
    assert_eq!(
        fixture_keys::<pseudospectral::Settings>(),
        table_names::<A>()
    );
    assert_eq!(fixture_keys::<impulsive::Settings>(), table_names::<B>());
    assert_eq!(fixture_keys::<geo_tour::Settings>(), table_names::<Geo>());
    assert_eq!(fixture_keys::<leo_tour::Settings>(), table_names::<Leo>());
    assert_eq!(fixture_keys::<hybrid::Settings>(), table_names::<Hybrid>());
}

fn names_match<T: Table>() {
    for &id in T::all() {
        let code = code_of::<T>(id);
        assert_eq!(
            setting_name(T::PLANNER, code).as_deref(),
            Some(T::name(id)),
            "{id:?}"
        );
        // The same static string every call.
        assert_eq!(
            reconfig_setting_name(T::PLANNER, code),
            reconfig_setting_name(T::PLANNER, code)
        );
    }
    let count = i32::try_from(T::all().len()).unwrap();
    for code in [-1, count, 127, 128 + 14, 255, 256, i32::MAX, i32::MIN] {
        assert_eq!(setting_name(T::PLANNER, code), None, "code {code}");
    }
}

#[test]
fn setting_names_come_from_the_tables() {
    names_match::<A>();
    names_match::<B>();
    names_match::<Geo>();
    names_match::<Leo>();
    names_match::<Hybrid>();
    // Problem quantities: 128 + their code, under their own planner only.
    let (p, b, g, l) = (
        RECONFIG_PLANNER_PSEUDOSPECTRAL,
        RECONFIG_PLANNER_IMPULSIVE,
        RECONFIG_PLANNER_GEO_TOUR,
        RECONFIG_PLANNER_LEO_ARC,
    );
    assert_eq!(setting_name(p, 128).as_deref(), Some("spacecraft"));
    assert_eq!(setting_name(p, 129).as_deref(), Some("nodes"));
    assert_eq!(
        setting_name(b, 128 + 4).as_deref(),
        Some("chief.eccentricity")
    );
    assert_eq!(setting_name(g, 128 + 11).as_deref(), Some("targets"));
    assert_eq!(setting_name(p, 128 + 4), None);
    assert_eq!(setting_name(b, 128), None);
    assert_eq!(setting_name(l, 128 + 12).as_deref(), Some("impulses"));
    assert_eq!(setting_name(g, 128 + 12), None);
    assert_eq!(setting_name(l, 0).as_deref(), Some("mu_km3_s2"));
    // The hybrid transfer: its settings by code; it bounds no problem quantity.
    let h = RECONFIG_PLANNER_HYBRID;
    assert_eq!(setting_name(h, 0).as_deref(), Some("max_iterations"));
    assert_eq!(setting_name(h, 8).as_deref(), Some("work_budget"));
    assert_eq!(setting_name(h, 10).as_deref(), Some("continuation_steps"));
    for code in 128..128 + 14 {
        assert_eq!(setting_name(h, code), None, "code {code}");
    }
    // The LEO sequencing is not in the C interface: its planner code names nothing.
    assert_eq!(setting_name(4, 0), None);
    assert_eq!(setting_name(-1, 0), None);
}
