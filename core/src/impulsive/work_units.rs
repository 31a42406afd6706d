//! Planner B's work units: the cost of each metered step from the impulse count `n` (F is
//! 6 x 3n), about one unit per multiply-add (a transcendental function counts as a few),
//! calibrated against M7 instructions in `docs/firmware.md`. The hooks charge these at their
//! loop heads (`crate::work::Meter`).

use super::settings::Settings;
use crate::work::units;

/// One propagation with the linear impulse model: per impulse a Kepler solve, the GVE matrix
/// B (trigonometry of the arc), the J2 drift.
fn linear_propagation(n: usize) -> u64 {
    units(&[150, n])
}

/// One propagation with exact impulses (state vectors and back to elements per impulse).
fn exact_propagation(n: usize) -> u64 {
    units(&[400, n])
}

/// Building F (a 6x6 by 6x3 product per impulse) and dY.
fn system(n: usize) -> u64 {
    units(&[250, n])
}

/// The equilibrated Cholesky minimum-norm solve: the 6x6 Gram matrix of F, its factor, and
/// the back-substitution to 3n impulses.
fn min_norm(n: usize) -> u64 {
    units(&[110, n]).saturating_add(250)
}

/// One fixed-point iteration: a linear propagation, F, and the minimum-norm solve.
pub(super) fn fixed_point_iteration(n: usize) -> u64 {
    linear_propagation(n)
        .saturating_add(system(n))
        .saturating_add(min_norm(n))
}

/// One rank-revealing SVD of F (one-sided Jacobi sweeps), when the Cholesky solve declines
/// and for the rank and condition of the returned plan.
pub(super) fn svd(n: usize) -> u64 {
    units(&[800, n])
}

/// `iterations` interior-point iterations of the least-fuel cone program (a 6x6 Cholesky, the
/// scalings of n cones, two solves), charged once they are done.
pub(super) fn cone_program(n: usize, iterations: u16) -> u64 {
    units(&[150, n])
        .saturating_add(300)
        .saturating_mul(u64::from(iterations))
}

/// Fixed cost of a search evaluation whatever its size: the candidate's points (sorting,
/// wrapping), the cone program's set-up, the bookkeeping of the pattern search (calibrated: the
/// intercept of instructions against units over the 2- to 6-impulse searches).
const EVALUATION_OVERHEAD: u64 = 1_100;

/// One short-period evaluation of the osculating <-> mean conversion (`osculating.rs`):
/// `SAMPLES` Kepler solves and J2 rates, two Fourier analyses of `SAMPLES^2 / 2` terms with a
/// sine and cosine each (calibrated: about 0.9 M M7 instructions per evaluation).
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

/// The checks of the returned plan: rank and condition at it (a linear propagation, F, an
/// SVD) and the nonlinear re-check with the transfer arcs' perigees (an exact propagation),
/// plus the nonlinear check that starts the correction.
pub(super) fn final_checks(n: usize) -> u64 {
    linear_propagation(n)
        .saturating_add(system(n))
        .saturating_add(svd(n))
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
/// `FINAL_FIXED_POINT_ITERATIONS` per phase, the Jacobian and `FINAL_CORRECTION_STEPS`) and the
/// final checks.
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
        .saturating_add(final_checks(n))
}
