//! The deputy's relative motion under a plan, for pictures and checks: the same model as the
//! nonlinear check (J2 secular drift of mean elements between impulses, exact two-body impulse
//! updates), sampled at any time.

use super::elements::{
    add, from_mean, from_relative, Elements, A, E, EARTH_RADIUS_KM, MA, M_PER_KM,
};
use super::error::PlanError;
use super::kepler::true_anomaly;
use super::nonlinear::{relative_position_rtn, state};
use super::secular::rates;
use super::settings::Settings;
use super::solution::Solution;
use super::status::Stage;
use super::transfer::{chief_at, propagate, ImpulseModel, Points, Sequence, XVector};
use super::types::{ImpulsePlan, MeanElements, Problem, RelativeElements};
use super::validate;
use crate::indexed::IndexedExt as _;

/// Why [`relative_position_rtn_km`] could not place the deputy.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum TrajectoryError {
    /// The problem (or the settings) is rejected, as by [`super::solve`].
    Plan(PlanError),
    /// The solution does not belong to the problem: a fixed plan with another number of
    /// impulses than the solution holds.
    Mismatch,
    /// Propagating the plan failed (Kepler's equation, or an orbit leaving the model's domain).
    Numerical(Stage),
}

impl core::fmt::Display for TrajectoryError {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        match self {
            Self::Plan(e) => write!(f, "{e}"),
            Self::Mismatch => write!(f, "the solution's impulses do not match the problem's plan"),
            Self::Numerical(stage) => write!(f, "propagating the plan failed ({stage:?})"),
        }
    }
}

/// `el` drifted by `dt_s` with the J2 secular rates.
fn drift(el: &Elements, dt_s: f64) -> Elements {
    let d = rates(el);
    let mut out = *el;
    for (x, r) in out.iter_mut().zip(d.iter()) {
        *x += *r * dt_s;
    }
    out
}

/// The deputy's position relative to the chief at `t_s` seconds from the epoch, in the chief's
/// local frame (radial, along-track, normal), km, when it flies `solution` for `problem`.
///
/// The model is the one of the solver's nonlinear check: mean elements are treated as
/// two-body elements at each instant and drift with the J2 secular rates; impulse k is applied
/// exactly (through position and velocity) at the k-th impulse point, reached by the same
/// timing rule (Wang 2018, eq. 7) with the exact impulses. Before the first impulse the deputy
/// is on the initial formation; after the last one it flies the achieved (target) formation.
/// The impulse points are the problem's for a fixed plan and the solution's (its
/// `arg_latitude_rad` and `revolutions`) for a search. Impulses are `solution.impulses`.
///
/// Bounded: one propagation through at most [`crate::capacity::MAX_IMPULSES`] impulses and
/// Kepler solves of at most `settings.kepler_max_iter` steps; no heap (about 2.5 KiB of stack).
///
/// # Errors
/// [`TrajectoryError::Plan`] for a request [`super::solve`] rejects,
/// [`TrajectoryError::Mismatch`] when the solution has another number of impulses than a fixed
/// plan, [`TrajectoryError::Numerical`] when Kepler's equation does not converge or an orbit
/// leaves the model's domain (for example a non-finite `t_s`).
pub fn relative_position_rtn_km(
    problem: &Problem,
    settings: &Settings,
    solution: &Solution,
    t_s: f64,
) -> Result<[f64; 3], TrajectoryError> {
    settings
        .validate()
        .map_err(|e| TrajectoryError::Plan(PlanError::InvalidSetting(e)))?;
    let ctx = validate::validate(problem, settings).map_err(TrajectoryError::Plan)?;
    let mut pts = Points::new();
    let mut dv = XVector::zeros();
    for (k, imp) in solution.impulses.iter().indexed() {
        if let Some(p) = pts.at.get_mut(k) {
            p.arg_latitude_rad = imp.arg_latitude_rad;
            p.revolutions = imp.revolutions;
        }
        for (j, c) in imp.dv_rtn_mps.iter().indexed() {
            if let Some(x) = dv.get_mut(k.saturating_mul(3).saturating_add(j)) {
                *x = *c / M_PER_KM;
            }
        }
    }
    pts.n = solution.impulses.len();
    if let ImpulsePlan::Fixed(points) = &problem.plan {
        if points.len() != pts.n {
            return Err(TrajectoryError::Mismatch);
        }
        for (slot, p) in pts.at.iter_mut().zip(points.iter()) {
            *slot = *p;
        }
    }
    let mut seq = Sequence::new();
    propagate(&ctx, &pts, &dv, ImpulseModel::Exact, settings, &mut seq)
        .map_err(TrajectoryError::Numerical)?;
    // The deputy after the last impulse at or before t_s (or at the epoch), and that time.
    let mut since = (0.0, ctx.deputy0);
    for (k, step) in seq.steps.iter().indexed().take(pts.n) {
        if step.time_s > t_s {
            break;
        }
        let after = if k.saturating_add(1) < pts.n {
            seq.steps.get(k.saturating_add(1)).map(|s| s.before)
        } else {
            Some(seq.end)
        };
        if let Some(after) = after {
            since = (step.time_s, after);
        }
    }
    let model = ctx.model;
    let deputy = model.drift(&since.1, t_s - since.0);
    let chief = chief_at(&ctx, t_s);
    let (f_d, ok_d) = model.anomaly(&deputy, settings.kepler_max_iter);
    let (f_c, ok_c) = model.anomaly(&chief, settings.kepler_max_iter);
    if !(ok_d && ok_c) {
        return Err(TrajectoryError::Numerical(Stage::Kepler));
    }
    Ok(relative_position_rtn(
        &model.state(&chief, f_c),
        &model.state(&deputy, f_d),
    ))
}

/// The position of a free-flying deputy relative to the chief at `t_s` seconds from the epoch,
/// in the chief's local frame (radial, along-track, normal), km: the deputy has relative mean
/// elements `rel` at `formed_s` (the chief drifted to that time plus `rel`), and from there both
/// drift with their own J2 secular rates, without impulses. The model of
/// [`relative_position_rtn_km`] (mean elements taken as two-body elements at each instant), so
/// a formation drawn with this and a planned trajectory agree.
///
/// Bounded: two Kepler solves of at most `settings.kepler_max_iter` steps; no heap.
///
/// # Errors
/// [`TrajectoryError::Numerical`]: `Kepler` when Kepler's equation does not converge,
/// `NonFinite` when a number is not finite (for example a non-finite time), `SingularState`
/// when the chief or the deputy is not an ellipse above Earth's radius.
pub fn formation_position_rtn_km(
    chief: &MeanElements,
    rel: &RelativeElements,
    formed_s: f64,
    t_s: f64,
    settings: &Settings,
) -> Result<[f64; 3], TrajectoryError> {
    let chief0 = from_mean(chief);
    let formed = drift(&chief0, formed_s);
    let deputy_formed = add(&formed, &from_relative(rel));
    // a and e do not drift: check the ellipses before the rates use sqrt(1 - e^2).
    let ellipse = |el: &Elements| (0.0..1.0).contains(&el[E]) && el[A] > EARTH_RADIUS_KM;
    if !(ellipse(&formed) && ellipse(&deputy_formed)) {
        return Err(TrajectoryError::Numerical(Stage::SingularState));
    }
    let c = drift(&formed, t_s - formed_s);
    let d = drift(&deputy_formed, t_s - formed_s);
    if !c.iter().chain(d.iter()).all(|x| x.is_finite()) {
        return Err(TrajectoryError::Numerical(Stage::NonFinite));
    }
    let (f_d, ok_d) = true_anomaly(d[MA], d[E], settings.kepler_max_iter);
    let (f_c, ok_c) = true_anomaly(c[MA], c[E], settings.kepler_max_iter);
    if !(ok_d && ok_c) {
        return Err(TrajectoryError::Numerical(Stage::Kepler));
    }
    Ok(relative_position_rtn(&state(&c, f_c), &state(&d, f_d)))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::impulsive::elements::TWO_PI;
    use crate::impulsive::types::ImpulsePoint;
    use crate::impulsive::{solve, SolveStatus, Workspace};

    fn paper(plan: ImpulsePlan) -> Problem {
        let rel = |v: [f64; 6]| RelativeElements {
            dsma_km: v[0],
            decc: v[1],
            dinc_rad: v[2].to_radians(),
            draan_rad: v[3].to_radians(),
            dargp_rad: v[4].to_radians(),
            dmean_anomaly_rad: v[5].to_radians(),
        };
        Problem {
            chief: MeanElements::test_paper_chief(),
            initial: rel([
                4.0940e-4, -1.3888e-4, -1.0831e-3, 1.5409e-2, -1.6134e-2, 9.2428e-3,
            ]),
            target: rel([
                -1.6389e-4, 5.5597e-4, 4.3361e-3, 7.1228e-2, -6.3572e-2, 3.1718e-2,
            ]),
            plan,
        }
    }

    fn table2() -> Problem {
        let mut pts = heapless::Vec::new();
        for (u, n) in [(274.155, 2), (238.864, 10), (285.649, 2)] {
            pts.push(ImpulsePoint {
                arg_latitude_rad: f64::to_radians(u),
                revolutions: n,
            })
            .unwrap();
        }
        paper(ImpulsePlan::Fixed(pts))
    }

    /// The formation with relative elements `rel` at `t0_s`, seen at `t_s` (both spacecraft
    /// drifting with their own J2 rates, no impulses), m.
    fn formation_m(p: &Problem, rel: &RelativeElements, t0_s: f64, t_s: f64) -> [f64; 3] {
        formation_position_rtn_km(&p.chief, rel, t0_s, t_s, &Settings::default())
            .unwrap()
            .map(|x| x * M_PER_KM)
    }

    #[test]
    fn a_formation_that_cannot_be_placed_is_an_error() {
        let p = table2();
        assert_eq!(
            formation_position_rtn_km(&p.chief, &p.initial, 0.0, f64::NAN, &Settings::default()),
            Err(TrajectoryError::Numerical(Stage::NonFinite))
        );
        let mut hyperbolic = p.initial;
        hyperbolic.decc = 1.5;
        assert_eq!(
            formation_position_rtn_km(&p.chief, &hyperbolic, 0.0, 0.0, &Settings::default()),
            Err(TrajectoryError::Numerical(Stage::SingularState))
        );
    }

    fn dist(a: [f64; 3], b: [f64; 3]) -> f64 {
        ((a[0] - b[0]).powi(2) + (a[1] - b[1]).powi(2) + (a[2] - b[2]).powi(2)).sqrt()
    }

    fn check(p: &Problem) {
        let settings = Settings::default();
        let mut ws = Workspace::new();
        let mut sol = Solution::new();
        solve(p, &settings, &mut ws, &mut sol).unwrap();
        // A usable plan: a search may stop at the work budget with a verified plan.
        assert!(
            matches!(
                sol.info.status,
                SolveStatus::Solved | SolveStatus::BudgetExhausted { verified: true }
            ),
            "{:?}",
            sol.info.status
        );
        let at = |t: f64| {
            relative_position_rtn_km(p, &settings, &sol, t)
                .unwrap()
                .map(|x| x * M_PER_KM)
        };
        let t1 = sol.impulses[0].time_s;
        // Before the first impulse: the initial formation (same model, same numbers).
        for t in [0.0, 0.3 * t1, 0.99 * t1] {
            let d = dist(at(t), formation_m(p, &p.initial, 0.0, t));
            assert!(d < 1e-6, "t = {t}: {d} m off the initial formation");
        }
        // Continuous through every impulse.
        for imp in sol.impulses.iter() {
            let d = dist(at(imp.time_s - 1e-4), at(imp.time_s + 1e-4));
            assert!(d < 2e-3, "jump of {d} m at t = {}", imp.time_s);
        }
        // After the last impulse: on the target formation (to centimetres: the nonlinear
        // correction met its tolerance), over two more orbits.
        let period = TWO_PI / super::super::elements::mean_motion_rad_s(p.chief.sma_km);
        let tn = sol.final_time_s;
        for k in 0..=16 {
            let t = tn + period * f64::from(k) / 8.0;
            let d = dist(at(t), formation_m(p, &p.target, tn, t));
            assert!(d < 0.05, "t = tn + {k}/8 T: {d} m off the target formation");
        }
        // ... and not on it at the start (the plan really moves the deputy).
        assert!(dist(at(0.0), formation_m(p, &p.target, tn, 0.0)) > 50.0);
    }

    #[test]
    fn fixed_plan_goes_from_the_initial_to_the_target_formation() {
        check(&table2());
    }

    #[test]
    fn searched_plan_goes_from_the_initial_to_the_target_formation() {
        check(&paper(ImpulsePlan::Search {
            impulses: 3,
            max_revolutions: 14,
        }));
    }

    #[test]
    fn mismatched_solution_is_refused() {
        let p = table2();
        let sol = Solution::new();
        assert_eq!(
            relative_position_rtn_km(&p, &Settings::default(), &sol, 0.0),
            Err(TrajectoryError::Mismatch)
        );
    }
}
