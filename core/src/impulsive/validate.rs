//! Validation of a planner-B request before any iteration: finite values, angle magnitudes,
//! element ranges, perigee altitudes of the chief and the deputy's initial and target orbits,
//! and the impulse points; builds the solve's [`Context`].

use super::elements::{from_mean, from_relative, sub, Elements, A, E, EARTH_RADIUS_KM, I};
use super::error::{Orbit, PlanError, Quantity, MAX_ANGLE_RAD};
use super::model::{point_phase, Model};
use super::settings::ElementSet;
use super::settings::Settings;
use super::settings::MAX_SMA_KM;
use super::transfer::Context;
use super::types::{ImpulsePlan, Problem};
use crate::capacity::MAX_IMPULSES;
use crate::indexed::IndexedExt as _;

pub(crate) fn index_u8(k: usize) -> u8 {
    u8::try_from(k).unwrap_or(u8::MAX)
}

fn check_finite(v: &Elements, what: Quantity) -> Result<(), PlanError> {
    match v.iter().index_of(|x| !x.is_finite()) {
        Some(k) => Err(PlanError::NotFinite {
            what,
            index: index_u8(k),
        }),
        None => Ok(()),
    }
}

/// Perigee altitude `a (1 - e) - Re`, km.
pub(crate) fn perigee_altitude_km(el: &Elements) -> f64 {
    el[A] * (1.0 - el[E]) - EARTH_RADIUS_KM
}

/// The orbit is an ellipse the model holds on: e in [0, 1), a in (Re + min altitude,
/// MAX_SMA_KM], i in [0, pi], perigee above the minimum altitude, and away from the working
/// set's singularities (checked in that order): e = 0 and sin i = 0 for the classical set,
/// retrograde equatorial (i near pi) for the equinoctial set.
fn check_orbit(el: &Elements, orbit: Orbit, settings: &Settings) -> Result<(), PlanError> {
    let ecc = el[E];
    if !(0.0..1.0).contains(&ecc) {
        return Err(PlanError::NotElliptic { orbit, ecc });
    }
    let min_km = EARTH_RADIUS_KM + settings.min_perigee_altitude_km;
    if !(el[A] > min_km && el[A] <= MAX_SMA_KM) {
        return Err(PlanError::SemiMajorAxisOutOfRange {
            orbit,
            sma_km: el[A],
            min_km,
            max_km: MAX_SMA_KM,
        });
    }
    if !(el[I] >= 0.0 && el[I] <= core::f64::consts::PI) {
        return Err(PlanError::InclinationOutOfRange {
            orbit,
            inc_rad: el[I],
        });
    }
    let perigee = perigee_altitude_km(el);
    if perigee < settings.min_perigee_altitude_km {
        return Err(PlanError::PerigeeTooLow {
            orbit,
            perigee_altitude_km: perigee,
            min_km: settings.min_perigee_altitude_km,
        });
    }
    let classical = settings.element_set == ElementSet::Classical;
    if classical && ecc < settings.min_eccentricity {
        return Err(PlanError::EccentricityTooSmall {
            orbit,
            ecc,
            min: settings.min_eccentricity,
        });
    }
    // The classical set is singular at sin i = 0; the equinoctial one only at i = pi.
    let sin_inc = libm::fabs(libm::sin(el[I]));
    let singular = classical || el[I] > core::f64::consts::FRAC_PI_2;
    if singular && sin_inc < settings.min_sin_inclination {
        return Err(PlanError::InclinationSingular {
            orbit,
            sin_inc,
            min: settings.min_sin_inclination,
        });
    }
    Ok(())
}

/// Angle `value` of `what` (element or impulse index `index`) is within [`MAX_ANGLE_RAD`].
fn check_angle(value: f64, what: Quantity, index: usize) -> Result<(), PlanError> {
    if libm::fabs(value) > MAX_ANGLE_RAD {
        return Err(PlanError::AngleOutOfRange {
            what,
            index: index_u8(index),
            value_rad: value,
            limit_rad: MAX_ANGLE_RAD,
        });
    }
    Ok(())
}

/// The angle entries (i, Omega, omega, M) of an element vector or difference are in range.
fn check_angles(v: &Elements, what: Quantity) -> Result<(), PlanError> {
    for (k, value) in v.iter().indexed().skip(I) {
        check_angle(*value, what, k)?;
    }
    Ok(())
}

/// Check the request; on success the working context.
///
/// # Errors
/// Every [`PlanError`] class except `InvalidSetting` (checked by the caller first).
pub(crate) fn validate(problem: &Problem, settings: &Settings) -> Result<Context, PlanError> {
    let chief0 = from_mean(&problem.chief);
    let initial = from_relative(&problem.initial);
    let target = from_relative(&problem.target);
    check_finite(&chief0, Quantity::Chief)?;
    check_finite(&initial, Quantity::Initial)?;
    check_finite(&target, Quantity::Target)?;
    check_angles(&chief0, Quantity::Chief)?;
    check_angles(&initial, Quantity::Initial)?;
    check_angles(&target, Quantity::Target)?;
    let deputy0 = super::elements::add(&chief0, &initial);
    let deputy_target = super::elements::add(&chief0, &target);
    check_orbit(&chief0, Orbit::Chief, settings)?;
    check_orbit(&deputy0, Orbit::DeputyInitial, settings)?;
    check_orbit(&deputy_target, Orbit::DeputyTarget, settings)?;
    match &problem.plan {
        ImpulsePlan::Fixed(points) => {
            if points.is_empty() {
                return Err(PlanError::NoImpulses);
            }
            let mut sum: i64 = 0;
            for (k, p) in points.iter().indexed() {
                if !p.arg_latitude_rad.is_finite() {
                    return Err(PlanError::NotFinite {
                        what: Quantity::ImpulsePoint,
                        index: index_u8(k),
                    });
                }
                check_angle(p.arg_latitude_rad, Quantity::ImpulsePoint, k)?;
                if p.revolutions < 0 {
                    return Err(PlanError::NegativeRevolutions {
                        impulse: index_u8(k),
                        revolutions: p.revolutions,
                    });
                }
                sum = sum.saturating_add(i64::from(p.revolutions));
            }
            if sum > i64::from(settings.max_total_revolutions) {
                return Err(PlanError::RevolutionsOverLimit {
                    requested: i32::try_from(sum).unwrap_or(i32::MAX),
                    limit: settings.max_total_revolutions,
                });
            }
        }
        ImpulsePlan::Search {
            impulses,
            max_revolutions,
        } => {
            if *impulses == 0 {
                return Err(PlanError::NoImpulses);
            }
            if usize::from(*impulses) > MAX_IMPULSES {
                return Err(PlanError::CapacityExceeded {
                    requested: u16::from(*impulses),
                    capacity: u16::try_from(MAX_IMPULSES).unwrap_or(u16::MAX),
                });
            }
            if *max_revolutions < 0 {
                return Err(PlanError::NegativeRevolutions {
                    impulse: 0,
                    revolutions: *max_revolutions,
                });
            }
            if *max_revolutions > settings.max_total_revolutions {
                return Err(PlanError::RevolutionsOverLimit {
                    requested: *max_revolutions,
                    limit: settings.max_total_revolutions,
                });
            }
        }
    }
    let phase = point_phase(&problem.chief, settings);
    let model = Model {
        set: settings.element_set,
        phase,
    };
    if model.set == ElementSet::Classical {
        return Ok(Context {
            model,
            chief0,
            deputy0,
            initial,
            target,
        });
    }
    // The working set: differences of the converted orbits.
    let chief_w = model.working_of_classical(&chief0);
    let deputy_w = model.working_of_classical(&deputy0);
    let target_w = model.working_of_classical(&deputy_target);
    Ok(Context {
        model,
        chief0: chief_w,
        deputy0: deputy_w,
        initial: sub(&deputy_w, &chief_w),
        target: sub(&target_w, &chief_w),
    })
}
