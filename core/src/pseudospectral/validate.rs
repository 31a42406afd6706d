//! Input checks done before any iteration; each bad input has its own [`PlanError`].

use super::error::{Boundary, Capacity, PlanError, Quantity, MAX_MAGNITUDE, MIN_POSITIVE};
use super::kernel::u8_of as index;
use super::problem::Problem;
use super::settings::Settings;
use crate::capacity::{MAX_DEGREE, MAX_SPACECRAFT, MIN_DEGREE};
use crate::indexed::IndexedExt as _;

fn finite_positive(value: f64, what: Quantity, spacecraft: u8) -> Result<(), PlanError> {
    if !value.is_finite() {
        return Err(PlanError::NotFinite {
            what,
            spacecraft,
            value,
        });
    }
    if value <= 0.0 {
        return Err(PlanError::NotPositive {
            what,
            spacecraft,
            value,
        });
    }
    if !(MIN_POSITIVE..=MAX_MAGNITUDE).contains(&value) {
        let limit = if value < MIN_POSITIVE {
            MIN_POSITIVE
        } else {
            MAX_MAGNITUDE
        };
        return Err(PlanError::OutOfRange {
            what,
            spacecraft,
            value,
            limit,
        });
    }
    Ok(())
}

/// Check the problem and settings.
///
/// # Errors
/// The first problem found, in this order: settings, non-finite or non-positive scalars,
/// spacecraft count and degree against capacity, masses and boundary states, boundary
/// separations.
pub(crate) fn check(problem: &Problem, settings: &Settings) -> Result<(), PlanError> {
    settings.validate().map_err(PlanError::InvalidSetting)?;
    finite_positive(problem.horizon_tu, Quantity::Horizon, 0)?;
    finite_positive(problem.max_control_fu, Quantity::MaxControl, 0)?;
    finite_positive(problem.keep_out_lu, Quantity::KeepOut, 0)?;
    let m = problem.spacecraft.len();
    if m == 0 {
        return Err(PlanError::NoSpacecraft);
    }
    if m > MAX_SPACECRAFT {
        return Err(PlanError::CapacityExceeded {
            what: Capacity::Spacecraft,
            requested: u16::try_from(m).unwrap_or(u16::MAX),
            capacity: MAX_SPACECRAFT as u16,
        });
    }
    let n = usize::from(problem.degree);
    if n < MIN_DEGREE {
        return Err(PlanError::DegreeTooLow {
            requested: problem.degree,
        });
    }
    if n > MAX_DEGREE {
        return Err(PlanError::CapacityExceeded {
            what: Capacity::Degree,
            requested: problem.degree,
            capacity: MAX_DEGREE as u16,
        });
    }
    for (i, craft) in problem.spacecraft.iter().indexed() {
        finite_positive(craft.mass_mu, Quantity::Mass, index(i))?;
        for value in craft.initial_state.iter().chain(craft.final_state.iter()) {
            if !value.is_finite() {
                return Err(PlanError::NotFinite {
                    what: Quantity::BoundaryState,
                    spacecraft: index(i),
                    value: *value,
                });
            }
            if libm::fabs(*value) > MAX_MAGNITUDE {
                return Err(PlanError::OutOfRange {
                    what: Quantity::BoundaryState,
                    spacecraft: index(i),
                    value: *value,
                    limit: MAX_MAGNITUDE,
                });
            }
        }
    }
    let d2 = problem.keep_out_lu * problem.keep_out_lu;
    for (i, a) in problem.spacecraft.iter().indexed() {
        for (j, b) in problem
            .spacecraft
            .iter()
            .indexed()
            .skip(i.saturating_add(1))
        {
            for (boundary, pa, pb) in [
                (Boundary::Initial, &a.initial_state, &b.initial_state),
                (Boundary::Final, &a.final_state, &b.final_state),
            ] {
                let mut dist2 = 0.0;
                for (x, y) in pa.iter().zip(pb.iter()).take(3) {
                    dist2 += (x - y) * (x - y);
                }
                if dist2 < d2 {
                    return Err(PlanError::BoundaryTooClose {
                        first: index(i),
                        second: index(j),
                        boundary,
                    });
                }
            }
        }
    }
    Ok(())
}
