//! Refuse a request before planning: each refusal names the field, the value and the limit.

use super::types::{ArcProblem, Field, PlanError, Settings, MAX_CANDIDATES, MAX_IMPULSES};

fn range(field: Field, value: f64, min: f64, max: f64) -> Result<(), PlanError> {
    if value.is_finite() && (min..=max).contains(&value) {
        Ok(())
    } else {
        Err(PlanError::OutOfRange {
            field,
            value,
            min,
            max,
        })
    }
}

/// Check `problem` and `settings`.
///
/// # Errors
/// The first field outside its range.
pub fn check(problem: &ArcProblem, settings: &Settings) -> Result<(), PlanError> {
    for (field, s) in [(Field::From, &problem.from), (Field::To, &problem.to)] {
        for v in s {
            range(field, *v, -1e6, 1e6)?;
        }
    }
    range(Field::Duration, problem.duration_s, 600.0, 3e6)?;
    range(
        Field::Impulses,
        f64::from(problem.impulses),
        2.0,
        MAX_IMPULSES as f64,
    )?;
    let s = settings;
    range(Field::Mu, s.mu_km3_s2, 1.0, 1e7)?;
    range(Field::EquatorialRadius, s.re_km, 0.0, 1e5)?;
    range(Field::J2, s.j2, 0.0, 1e-2)?;
    range(Field::Step, s.step_s, 0.1, 600.0)?;
    range(Field::MaxSteps, f64::from(s.max_steps), 1.0, 1e6)?;
    range(
        Field::LambertMaxIter,
        f64::from(s.lambert_max_iter),
        1.0,
        200.0,
    )?;
    range(Field::LambertTol, s.lambert_tol, 1e-15, 1e-6)?;
    range(
        Field::MaxRevolutions,
        f64::from(s.max_revolutions),
        0.0,
        200.0,
    )?;
    range(Field::ShootMaxIter, f64::from(s.shoot_max_iter), 1.0, 100.0)?;
    range(Field::ArrivalTol, s.arrival_tol_km, 1e-9, 100.0)?;
    range(Field::GridPoints, f64::from(s.grid_points), 1.0, 4096.0)?;
    range(
        Field::Candidates,
        f64::from(s.candidates),
        1.0,
        MAX_CANDIDATES as f64,
    )?;
    range(Field::HopRounds, f64::from(s.hop_rounds), 0.0, 16.0)?;
    range(
        Field::SearchMaxEvals,
        f64::from(s.search_max_evals),
        0.0,
        1e6,
    )?;
    range(
        Field::PolishMaxEvals,
        f64::from(s.polish_max_evals),
        0.0,
        1e6,
    )?;
    range(Field::SearchStep, s.search_step_s, 0.0, 1e5)?;
    range(Field::SearchStepKmps, s.search_step_km_s, 0.0, 1.0)?;
    range(Field::SearchMinStep, s.search_min_step_s, 1e-6, 1e5)?;
    range(Field::MinGap, s.min_gap_s, 0.0, problem.duration_s / 8.0)?;
    // The budget is an integer; as f64 only for the error's value (exact below 2^53).
    #[allow(clippy::cast_precision_loss)]
    let budget = s.work_budget as f64;
    range(Field::WorkBudget, budget, 1.0, 1e10)?;
    Ok(())
}
