//! Every input checked against its documented range before planning.

use super::error::{check, Field, PlanError};
use super::types::{Problem, Settings, MAX_GAP_LEGS, MAX_LAMBERT_REVOLUTIONS};
use crate::indexed::IndexedExt as _;
use core::f64::consts::PI;

/// Longest mission accepted, s (10 years).
pub const MAX_MISSION_TIME_S: f64 = 3.2e8;
/// Largest per-burn cap accepted, m/s.
pub const MAX_BURN_CAP_MPS: f64 = 1.0e4;

/// Check the request.
pub(crate) fn problem(p: &Problem) -> Result<(), PlanError> {
    check(
        Field::StartLongitude,
        0,
        p.start_lon_rad,
        -2.0 * PI,
        2.0 * PI,
    )?;
    if p.targets_lon_rad.is_empty() {
        return Err(PlanError::NoTargets);
    }
    for (i, &lon) in p.targets_lon_rad.iter().indexed() {
        let idx = u8::try_from(i).unwrap_or(u8::MAX);
        check(Field::TargetLongitude, idx, lon, -2.0 * PI, 2.0 * PI)?;
    }
    check(
        Field::MissionTime,
        0,
        p.mission_time_s,
        1.0,
        MAX_MISSION_TIME_S,
    )?;
    check(Field::MaxBurn, 0, p.max_burn_mps, 1e-6, MAX_BURN_CAP_MPS)?;
    Ok(())
}

/// Check the settings.
pub(crate) fn settings(s: &Settings) -> Result<(), PlanError> {
    let u = |x: u16| f64::from(x);
    check(
        Field::LambertMaxRevolutions,
        0,
        u(s.lambert_max_revolutions),
        0.0,
        u(MAX_LAMBERT_REVOLUTIONS),
    )?;
    check(Field::LambertMaxIter, 0, u(s.lambert_max_iter), 1.0, 200.0)?;
    check(Field::LambertTol, 0, s.lambert_tol, 1e-15, 1e-3)?;
    check(Field::WellIterations, 0, u(s.well_iterations), 1.0, 200.0)?;
    check(Field::RootMaxIter, 0, u(s.root_max_iter), 10.0, 1000.0)?;
    check(Field::PriceMaxIter, 0, u(s.price_max_iter), 1.0, 1000.0)?;
    check(Field::TimeTol, 0, s.time_tol_s, 1e-9, 3600.0)?;
    check(
        Field::GapMaxLegs,
        0,
        f64::from(s.gap_max_legs),
        0.0,
        f64::from(MAX_GAP_LEGS),
    )?;
    check(Field::ExchangeRounds, 0, u(s.exchange_rounds), 0.0, 100.0)?;
    check(Field::ExchangeMargin, 0, s.exchange_margin_mps, 0.0, 100.0)?;
    check(Field::MinRadius, 0, s.min_radius_km, 6378.137, 42_000.0)?;
    check(Field::RuleDriftAbove, 0, s.rule_drift_above_rad, 0.0, PI)?;
    check(
        Field::RuleHohmannAbove,
        0,
        s.rule_hohmann_above_rad,
        0.0,
        s.rule_drift_above_rad,
    )?;
    check(
        Field::RuleRadialAbove,
        0,
        s.rule_radial_above_rad,
        0.0,
        s.rule_hohmann_above_rad,
    )?;
    check(
        Field::LambertDirectTime,
        0,
        s.lambert_direct_time_s,
        60.0,
        864_000.0,
    )?;
    Ok(())
}
