//! Problems the unit tests share.
#![allow(clippy::unwrap_used, clippy::expect_used)]

use super::{Problem, Settings, Solution, Spacecraft, Workspace};

/// Rest-to-rest moves `(from, to)` in LU, T = 10, Umax = 1, unit masses, keep-out `keep_out_lu`
/// (the paper's settings with d = 2).
pub(super) fn rest_to_rest(
    moves: &[([f64; 3], [f64; 3])],
    keep_out_lu: f64,
    degree: u16,
    test_points: bool,
) -> Problem {
    let mut spacecraft = heapless::Vec::new();
    for (a, b) in moves {
        spacecraft
            .push(Spacecraft {
                mass_mu: 1.0,
                initial_state: [a[0], a[1], a[2], 0.0, 0.0, 0.0],
                final_state: [b[0], b[1], b[2], 0.0, 0.0, 0.0],
            })
            .unwrap();
    }
    Problem {
        horizon_tu: 10.0,
        max_control_fu: 1.0,
        keep_out_lu,
        degree,
        test_points,
        spacecraft,
    }
}

/// `ws` holding the rows of a solve's last linearisation: one subproblem, no verification
/// round (for an infeasible problem, the first subproblem's rows, which ended it).
pub(super) fn first_subproblem(problem: &Problem, ws: &mut Workspace) {
    let settings = Settings {
        sqp_max_iter: 1,
        verify_max_rounds: 0,
        ..Settings::default()
    };
    let mut out = Solution::new();
    super::solve(problem, &settings, ws, &mut out).expect("accepted");
}
