//! Planner B's work units: the cost of each metered step from the impulse count `n` (F is
//! 6 x 3n), each step charged at least its dearest measured cost divided by
//! [`MAX_INSTRUCTIONS_PER_UNIT`]: the kernel cases (`super::kernels`, run one at a time on the
//! Cortex-M7 by the `reconfig-firmware-kb` image) cost at most that many M7 instructions per
//! unit they are charged, each with every Kepler solve it makes held to `kepler_max_iter`'s
//! limit of Newton steps (`kepler::WORST_NEWTON_STEPS` and the QEMU test
//! `tests/tests/qemu_firmware/kernels_b_image.rs`). The hooks charge these at their loop heads
//! (`crate::work::Meter`); a cone program is charged once done, by its iterations.

use super::settings::{Settings, DEFAULT_WORK_BUDGET};
use crate::capacity::MAX_IMPULSES;
use crate::work::units;

/// The bound the units are set for: no kernel case costs more M7 instructions per unit charged
/// (measured under QEMU, `reconfig-firmware-kb`).
pub const MAX_INSTRUCTIONS_PER_UNIT: u64 = 21;

/// The instructions the default budget must bound (the planner's on-board promise).
pub const MAX_SOLVE_INSTRUCTIONS: u64 = 400_000_000;

// The default budget times the bound per unit stays within the promise.
const _: () = assert!(DEFAULT_WORK_BUDGET * MAX_INSTRUCTIONS_PER_UNIT <= MAX_SOLVE_INSTRUCTIONS);

/// One propagation with the linear impulse model: per impulse a Kepler solve, the GVE matrix
/// B (trigonometry of the arc), the J2 drift.
fn linear_propagation(n: usize) -> u64 {
    units(&[150, n])
}

/// One propagation with exact impulses (state vectors and back to elements per impulse, and
/// the end states' anomalies): held to `kepler_max_iter`'s limit of Newton steps in each of its
/// Kepler solves, the Jacobian column costs 52.5 k M7 instructions at n = 6 and a correction
/// step at n = 2 about 22 k (measured).
fn exact_propagation(n: usize) -> u64 {
    units(&[450, n]).saturating_add(200)
}

/// Building F (a 6x6 by 6x3 product per impulse) and dY.
fn system(n: usize) -> u64 {
    units(&[250, n])
}

/// The equilibrated Cholesky minimum-norm solve: the 6x6 Gram matrix of F, its factor, and
/// the back-substitution to the impulses. It runs on the whole capacity-sized F whatever `n`
/// (measured: 27.7 k M7 instructions a correction step at n = 2), so it is charged at capacity.
fn min_norm(_n: usize) -> u64 {
    units(&[110, MAX_IMPULSES]).saturating_add(250)
}

/// One fixed-point iteration: a linear propagation, F, and the minimum-norm solve.
pub(super) fn fixed_point_iteration(n: usize) -> u64 {
    linear_propagation(n)
        .saturating_add(system(n))
        .saturating_add(min_norm(n))
}

/// One rank-revealing SVD of F (one-sided Jacobi) that made `sweeps` sweeps, charged once done:
/// when the Cholesky solve declines, and for the rank and condition of the returned plan. Its
/// set-up and the singular values and solve after the sweeps, and per sweep the 15 column pairs
/// each rotated (a pair left alone costs less). Measured: 11.5 k M7 instructions for the second
/// sweep at n = 6, 10.2 k for the set-up and first sweep at n = 2.
pub(super) fn svd(n: usize, sweeps: u16) -> u64 {
    let sweep = units(&[50, n]).saturating_add(320);
    units(&[60, n])
        .saturating_add(300)
        .saturating_add(sweep.saturating_mul(u64::from(sweeps)))
}

/// A least-fuel cone program that made `iterations` interior-point iterations, charged once
/// done: its set-up (row compression, blocks, Gram matrices, the certificates, the dual back in
/// F's rows), and `iterations + 1` iterations (a 6x6 Cholesky with up to four shifts, the
/// scalings of n cones, two refined solves; the last one is the pass that stopped it, by
/// convergence or by a numerical failure, which `iterations` does not count). Measured: set-up
/// 40-55 k M7 instructions, an iteration 12.7 k at n = 2 and 25.5 k at n = 6.
pub(super) fn cone_program(n: usize, iterations: u16) -> u64 {
    let iteration = units(&[180, n]).saturating_add(340);
    units(&[200, n])
        .saturating_add(1_700)
        .saturating_add(iteration.saturating_mul(u64::from(iterations).saturating_add(1)))
}

/// What one step may charge once done beyond what it spent before it ran (the loops stop only
/// at the next step's head, so a stage may pass its share by this much): a cone program at its
/// iteration cap, and SVDs at `svd_max_iter` sweeps for its minimum-norm solves (a fixed-point
/// iteration's fallback, or one per further linearisation of a search evaluation).
fn step_overshoot(n: usize, settings: &Settings) -> u64 {
    let cone = if settings.min_fuel {
        cone_program(n, settings.min_fuel_max_iter)
    } else {
        0
    };
    let svds = u64::from(settings.search_fixed_point_max_iter.max(1));
    cone.saturating_add(svd(n, settings.svd_max_iter).saturating_mul(svds))
}

/// What the loops keep back for the end of a solve: the final checks with their SVD at
/// `svd_max_iter` sweeps, and one step's overshoot.
pub(super) fn final_reserve(n: usize, settings: &Settings) -> u64 {
    final_checks(n)
        .saturating_add(svd(n, settings.svd_max_iter))
        .saturating_add(step_overshoot(n, settings))
}

/// Fixed cost of a search evaluation whatever its size: the candidate's points (sorting,
/// wrapping), the bookkeeping of the pattern search (measured with the whole search, the
/// `search-64` kernel cases).
const EVALUATION_OVERHEAD: u64 = 1_100;

/// One short-period evaluation of the osculating <-> mean conversion (`osculating.rs`):
/// `SAMPLES` Kepler solves and J2 rates, two Fourier analyses of `SAMPLES^2 / 2` terms with a
/// sine and cosine each (measured: 0.74 M M7 instructions per evaluation).
pub(super) fn osculating_evaluation() -> u64 {
    units(&[super::osculating::SAMPLES, 1_200])
}

/// One search evaluation's linearisations (a linear propagation and F each, a minimum-norm
/// solve between them) and its dual bound; its cone program is charged as it is done.
pub(super) fn evaluation(n: usize, linearisations: u16) -> u64 {
    let each = linear_propagation(n).saturating_add(system(n));
    let count = u64::from(linearisations.max(1));
    each.saturating_mul(count)
        .saturating_add(min_norm(n).saturating_mul(count.saturating_sub(1)))
        .saturating_add(units(&[40, n]))
        .saturating_add(EVALUATION_OVERHEAD)
}

/// One column of the finite-difference Jacobian of the defect: an exact propagation.
pub(super) fn jacobian_column(n: usize) -> u64 {
    exact_propagation(n)
}

/// One Broyden step: a minimum-norm solve, an exact propagation, the rank-one update.
pub(super) fn correction_step(n: usize) -> u64 {
    min_norm(n)
        .saturating_add(exact_propagation(n))
        .saturating_add(units(&[24, n]))
}

/// The checks of the returned plan: rank and condition at it (a linear propagation and F; the
/// SVD is charged once done) and the nonlinear re-check with the transfer arcs' perigees (an
/// exact propagation), plus the nonlinear check that starts the correction.
pub(super) fn final_checks(n: usize) -> u64 {
    linear_propagation(n)
        .saturating_add(system(n))
        .saturating_add(exact_propagation(n).saturating_mul(2))
}

/// Fixed-point iterations per phase the final solve after a search is given room for (the
/// search's best points converge in a few; a final solve that needs more stops at the budget
/// with an unverified plan).
const FINAL_FIXED_POINT_ITERATIONS: u16 = 8;
/// Broyden steps the final solve after a search is given room for.
const FINAL_CORRECTION_STEPS: u16 = 6;
/// Interior-point iterations per cone program the final solve is given room for.
const FINAL_CONE_ITERATIONS: u16 = 20;

/// What a search keeps back: the final solve at the best points it found (room for
/// `FINAL_FIXED_POINT_ITERATIONS` per phase, the Jacobian and `FINAL_CORRECTION_STEPS`), the
/// final solve's own reserve, and the overshoot of the search's last step.
pub(super) fn search_reserve(n: usize, settings: &Settings) -> u64 {
    let iterations = u64::from(
        settings
            .fixed_point_max_iter
            .min(FINAL_FIXED_POINT_ITERATIONS),
    );
    let cones = cone_program(n, settings.min_fuel_max_iter.min(FINAL_CONE_ITERATIONS));
    let phases = fixed_point_iteration(n)
        .saturating_mul(iterations)
        .saturating_mul(2)
        .saturating_add(cones.saturating_mul(iterations));
    let steps = u64::from(settings.correction_max_iter.min(FINAL_CORRECTION_STEPS));
    let correction = jacobian_column(n)
        .saturating_mul(units(&[3, n]))
        .saturating_add(correction_step(n).saturating_mul(steps));
    phases
        .saturating_add(correction)
        .saturating_add(final_reserve(n, settings))
        .saturating_add(step_overshoot(n, settings))
}
