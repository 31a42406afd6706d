//! Problems the unit tests share.
#![allow(clippy::unwrap_used)]

use super::{Problem, Spacecraft};

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
