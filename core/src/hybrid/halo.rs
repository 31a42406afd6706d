//! The halo orbit through the request's arrival point: its state at another phase (the point
//! flown ballistically along the orbit, either way), and the arrival phase's transversality
//! condition, the cost's derivative in the phase (issue 30, "beyond the paper": the paper
//! fixes the arrival point; a ground tool frees it by finding the condition's root along a
//! family of fixed-arrival plans, `reconfig pareto --walk phase --free-last`).

use super::dynamics::{Augmented, Throttle};
use super::flow::propagate;
use super::integrate::{Counts, Stop};
use super::objective_shooting::model_of;
use super::planner::fly_plan;
use super::problem::Problem;
use super::solution::{Settings, Solution};
use crate::vec3::Vec3;

/// A state on the orbit: position (LU) and velocity (LU/TU), rotating frame.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct HaloState {
    /// Position, LU.
    pub r_lu: Vec3,
    /// Velocity, LU/TU.
    pub v_vu: Vec3,
}

/// The CR3BP's mirror in the x–z plane with time reversed, `(x, −y, z, −ẋ, ẏ, −ż)`: it maps a
/// ballistic flight forward onto the same flight backward, so the orbit is flown back in time
/// by flying its mirror image forward.
fn mirrored(s: &HaloState) -> HaloState {
    let (r, v) = (s.r_lu, s.v_vu);
    HaloState {
        r_lu: [r[0], -r[1], r[2]],
        v_vu: [-v[0], v[1], -v[2]],
    }
}

/// The arrival point of `problem` flown ballistically for `phase_tu` (negative: backward),
/// with the settings' integrator tolerances and at most `work_budget` step trials.
///
/// # Errors
/// The integrator's [`Stop`].
pub fn state_at_phase(
    problem: &Problem,
    phase_tu: f64,
    settings: &Settings,
) -> Result<HaloState, Stop> {
    let start = HaloState {
        r_lu: problem.arrival_r_lu,
        v_vu: problem.arrival_v_vu,
    };
    let backward = phase_tu < 0.0;
    let from = if backward { mirrored(&start) } else { start };
    let y0 = Augmented::ballistic(from.r_lu, from.v_vu);
    let tol = settings.tolerance(settings.work_budget);
    let mut counts = Counts::default();
    let end = propagate(
        &model_of(problem),
        Throttle::Coast,
        &y0,
        libm::fabs(phase_tu),
        &tol,
        &mut counts,
    )?;
    let flown = HaloState {
        r_lu: end.r_lu,
        v_vu: end.v_vu,
    };
    Ok(if backward { mirrored(&flown) } else { flown })
}

/// The arrival phase's transversality condition of a returned plan: the derivative of its
/// cost in the phase of the arrival point along the halo orbit, `−λ(t_f)·ẋ_halo` (the cost's
/// gradient in the final state is `−λ(t_f)`, and the arrival point moves along the orbit at
/// its ballistic rate). 0 where the plan's arrival phase is optimal. The plan is flown again
/// for its final costates (`fly_plan`, one piece).
///
/// # Errors
/// The integrator's [`Stop`].
pub fn arrival_transversality(
    problem: &Problem,
    solution: &Solution,
    settings: &Settings,
) -> Result<f64, Stop> {
    let end = fly_plan(problem, solution, settings, 1, &mut |_| {})?.end;
    let at = Augmented::ballistic(problem.arrival_r_lu, problem.arrival_v_vu);
    let rate = model_of(problem).derivative(Throttle::Coast, &at);
    let dot = |a: &Vec3, b: &Vec3| a.iter().zip(b).map(|(x, y)| x * y).sum::<f64>();
    Ok(-(dot(&end.lambda_r, &rate.r_lu) + dot(&end.lambda_v, &rate.v_vu)))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::hybrid::planner_tests::table_3_min_fuel as published;
    use crate::hybrid::{solve, SolveStatus, Workspace};

    fn miss(a: &HaloState, b: &HaloState) -> f64 {
        a.r_lu
            .iter()
            .zip(b.r_lu)
            .chain(a.v_vu.iter().zip(b.v_vu))
            .map(|(x, y)| libm::fabs(x - y))
            .fold(0.0, f64::max)
    }

    /// Flown forward by a phase and back by the same phase (the mirror), the point is where
    /// it started; backward by a phase is forward by the period less it (the orbit closes to
    /// 1e-6, the period's printed digits); zero phase is the point itself.
    #[test]
    fn the_orbit_flown_either_way_is_one_orbit() {
        let problem = published();
        let settings = Settings::default();
        let start = HaloState {
            r_lu: problem.arrival_r_lu,
            v_vu: problem.arrival_v_vu,
        };
        let p = problem.halo_period_tu;
        assert_eq!(state_at_phase(&problem, 0.0, &settings).ok(), Some(start));
        let ahead = state_at_phase(&problem, 0.3, &settings).unwrap();
        assert!(miss(&ahead, &start) > 1e-2, "it moved");
        let back = state_at_phase(
            &Problem {
                arrival_r_lu: ahead.r_lu,
                arrival_v_vu: ahead.v_vu,
                ..problem
            },
            -0.3,
            &settings,
        )
        .unwrap();
        assert!(miss(&back, &start) < 1e-11, "{}", miss(&back, &start));
        let behind = state_at_phase(&problem, -0.7, &settings).unwrap();
        let around = state_at_phase(&problem, p - 0.7, &settings).unwrap();
        assert!(miss(&behind, &around) < 1e-6, "{}", miss(&behind, &around));
    }

    /// The condition is the derivative of the cost in the arrival phase: at Table 3's first case
    /// it equals `d(1 − m_f)/dφ` from the plans to the orbit's points 1e-3 TU either side
    /// (central differences, the envelope theorem), so its sign and scale are right.
    #[test]
    fn the_arrival_condition_is_the_costs_derivative_in_the_phase() {
        let problem = published();
        let settings = Settings::default();
        let plan = |p: &Problem| {
            let mut out = Solution::new();
            solve(p, &settings, &mut Workspace::new(), &mut out).unwrap();
            assert_eq!(out.info.status, SolveStatus::Solved);
            out
        };
        let at = plan(&problem);
        let condition = arrival_transversality(&problem, &at, &settings).unwrap();
        let h = 1e-3;
        let mass_at = |phase: f64| {
            let s = state_at_phase(&problem, phase, &settings).unwrap();
            let moved = Problem {
                arrival_r_lu: s.r_lu,
                arrival_v_vu: s.v_vu,
                costates: at.costates,
                ..problem
            };
            plan(&moved).flown.unwrap().final_mass
        };
        let slope = -(mass_at(h) - mass_at(-h)) / (2.0 * h);
        assert!(condition.abs() > 1e-3, "{condition}");
        assert!(
            (condition - slope).abs() < 1e-4 * slope.abs(),
            "{condition} against {slope}"
        );
    }
}
