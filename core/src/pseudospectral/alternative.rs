//! Deterministic alternative starts (issue 9, item 6): a certified answer is a local minimum,
//! and the basin it lies in is decided by the sides the pairs pass on in the first subproblems.
//! The same problem is solved again from the analytic guess lifted sideways by a bump
//! `d (1 - tau^2)^2`, the spacecraft alternately one way and the other
//! (`setup::initial_iterate`), and the best answer is kept. Measured on the generated dense
//! lattices (`reconfig sweep --work-budget 1000000000 --alternative-starts 1`,
//! docs/planner-a.md): the lifted start reaches the oracle's lower basin where the guess's
//! roundabout leads to another one.

use super::error::PlanError;
use super::problem::Problem;
use super::settings::Settings;
use super::solution::Solution;
use super::solver;
use super::status::SolveStatus;
use super::workspace::Workspace;

/// How many alternative starts to try after the analytic guess's solve.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum AlternativeStarts {
    /// The guess lifted once: along y, even-numbered spacecraft down and odd ones up, by d at
    /// mid-horizon.
    One,
    /// The lift above, then the same along z.
    Two,
}

impl AlternativeStarts {
    /// The lifts tried, in order (signs of the even-numbered spacecraft's bump, in units of d).
    fn lifts(self) -> &'static [[f64; 3]] {
        match self {
            Self::One => &LIFTS[..1],
            Self::Two => &LIFTS,
        }
    }
}

/// The lift of each alternative start, per axis, in units of d, for the even-numbered
/// spacecraft (the odd-numbered ones get the opposite): first along y (even-numbered down),
/// then along z. Chosen on the generated dense lattices against the oracle
/// (`reconfig sweep --work-budget 1000000000 --alternative-starts K`, docs/planner-a.md), among
/// six single lifts and pairs: y down alone brought 7 of the 10 answers > 0.5 % above the
/// oracle to its basin, y up 1, z down 3, x 4 (and made others worse); the same family serves
/// as the test, so this is a fit to it, not a held-out result.
const LIFTS: [[f64; 3]; 2] = [[0.0, -1.0, 0.0], [0.0, 0.0, -1.0]];

/// A lower cost than this (relative) makes an answer of the same rank better.
const BETTER_REL: f64 = 1e-6;

/// What the alternative starts did.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct StartsOutcome {
    /// Which start's answer is returned: 0 the analytic guess, k the k-th alternative.
    pub kept: u8,
    /// Alternative starts solved (fewer than asked when the work budget ran out).
    pub tried: u8,
    /// Work units of all the solves together (at most the settings' budget).
    pub work_units: u64,
}

/// Rank of a status for keeping the best answer: certified, usable, neither.
fn rank(status: SolveStatus) -> u8 {
    if status == SolveStatus::Solved {
        2
    } else if status.is_usable() {
        1
    } else {
        0
    }
}

/// Whether `candidate` is a better answer than `incumbent`: a higher rank, or the same usable
/// rank at a lower cost.
fn better(candidate: &Solution, incumbent: &Solution) -> bool {
    let (a, b) = (rank(candidate.info.status), rank(incumbent.info.status));
    a > b
        || (a == b
            && a > 0
            && candidate.cost < incumbent.cost - BETTER_REL * (1.0 + incumbent.cost))
}

/// Solve from the analytic guess, then from each alternative start while the work budget
/// lasts (each solve gets what the earlier ones left), and return the best answer in `out`:
/// `Solved` before any other status, then usable before not, then the lower cost. `spare`
/// receives the other answers (scratch: the caller provides it, so the core needs no second
/// `Solution` of its own). Each solve is a complete one (its own saddle escapes and
/// verification); `out.info.work_units` is the kept solve's, `StartsOutcome::work_units` all
/// of them.
///
/// # Errors
/// As [`super::solve`]: the request is rejected before any iteration.
pub fn solve_with_alternative_starts(
    problem: &Problem,
    settings: &Settings,
    starts: AlternativeStarts,
    workspace: &mut Workspace,
    spare: &mut Solution,
    out: &mut Solution,
) -> Result<StartsOutcome, PlanError> {
    solver::solve(problem, settings, workspace, None, [0.0; 3], out)?;
    let mut outcome = StartsOutcome {
        kept: 0,
        tried: 0,
        work_units: out.info.work_units,
    };
    for (number, lift) in (1u8..).zip(starts.lifts()) {
        let remaining = settings.work_budget.saturating_sub(outcome.work_units);
        if remaining == 0 {
            break;
        }
        let budgeted = Settings {
            work_budget: remaining,
            ..*settings
        };
        solver::solve(problem, &budgeted, workspace, None, *lift, spare)?;
        outcome.tried = number;
        outcome.work_units = outcome.work_units.saturating_add(spare.info.work_units);
        if better(spare, out) {
            core::mem::swap(spare, out);
            outcome.kept = number;
        }
    }
    Ok(outcome)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::pseudospectral::{solve, Spacecraft};

    fn at_rest(p: [f64; 3]) -> [f64; 6] {
        [p[0], p[1], p[2], 0.0, 0.0, 0.0]
    }

    /// The square swap: four spacecraft to the opposite corners.
    fn square_swap() -> Problem {
        let corners = [[6.0, 6.0], [-6.0, 6.0], [-6.0, -6.0], [6.0, -6.0]];
        let mut spacecraft = heapless::Vec::new();
        for (c, o) in corners.iter().zip(corners.iter().cycle().skip(2)) {
            let _ = spacecraft.push(Spacecraft {
                mass_mu: 1.0,
                initial_state: at_rest([c[0], c[1], 0.0]),
                final_state: at_rest([o[0], o[1], 0.0]),
            });
        }
        Problem {
            horizon_tu: 10.0,
            max_control_fu: 1.0,
            keep_out_lu: 2.0,
            degree: 16,
            test_points: true,
            spacecraft,
        }
    }

    fn both_lifts(
        problem: &Problem,
        settings: &Settings,
        ws: &mut Workspace,
    ) -> (StartsOutcome, Solution) {
        let (mut out, mut spare) = (Solution::new(), Solution::new());
        let outcome = solve_with_alternative_starts(
            problem,
            settings,
            AlternativeStarts::Two,
            ws,
            &mut spare,
            &mut out,
        )
        .unwrap();
        (outcome, out)
    }

    #[test]
    fn the_kept_answer_is_never_worse_than_the_guess_and_the_budget_holds() {
        let problem = square_swap();
        let settings = Settings::default();
        let mut ws = Workspace::new();
        let mut single = Solution::new();
        solve(&problem, &settings, &mut ws, &mut single).unwrap();
        let (outcome, out) = both_lifts(&problem, &settings, &mut ws);
        assert_eq!(outcome.tried, 2);
        assert!(outcome.work_units <= settings.work_budget);
        assert_eq!(out.info.status, SolveStatus::Solved);
        assert!(rank(out.info.status) >= rank(single.info.status));
        assert!(
            out.cost <= single.cost * (1.0 + 1e-9),
            "{} > {}",
            out.cost,
            single.cost
        );
        if outcome.kept == 0 {
            // The guess's answer, bit for bit (the alternatives went to `spare`).
            assert_eq!(out.cost.to_bits(), single.cost.to_bits());
        }
        // Same input, same bits.
        let (repeat, again) = both_lifts(&problem, &settings, &mut ws);
        assert_eq!(repeat, outcome);
        assert_eq!(again.cost.to_bits(), out.cost.to_bits());
    }

    #[test]
    fn a_spent_budget_tries_no_alternative() {
        // A budget the first solve uses up leaves nothing for the alternatives.
        let problem = square_swap();
        let settings = Settings {
            work_budget: 1_000,
            ..Settings::default()
        };
        let mut ws = Workspace::new();
        let (outcome, out) = both_lifts(&problem, &settings, &mut ws);
        assert_eq!(outcome.tried, 0);
        assert_eq!(outcome.kept, 0);
        assert!(matches!(
            out.info.status,
            SolveStatus::BudgetExhausted { .. }
        ));
    }

    #[test]
    fn better_ranks_certified_then_usable_then_cost() {
        let with = |status: SolveStatus, cost: f64| {
            let mut s = Solution::new();
            s.info.status = status;
            s.cost = cost;
            s
        };
        let solved = with(SolveStatus::Solved, 2.0);
        let cheaper_feasible = with(SolveStatus::Feasible, 1.0);
        assert!(!better(&cheaper_feasible, &solved));
        assert!(better(&solved, &cheaper_feasible));
        assert!(better(&with(SolveStatus::Solved, 1.9), &solved));
        // Within the tolerance: not better (the first answer stays).
        assert!(!better(&with(SolveStatus::Solved, 2.0 - 1e-9), &solved));
        // Two unusable answers: neither replaces the other on cost.
        let unusable = with(SolveStatus::MaxIterations, 1.0);
        assert!(!better(&unusable, &with(SolveStatus::Infeasible, 3.0)));
        assert!(better(&cheaper_feasible, &unusable));
    }
}
