//! Least fuel at fixed impulse points: `min sum_k |dv_k|  s.t.  F dv = dY` (the null space of
//! eq. 13 searched exactly), by the cone program of [`super::socp`]; and the minimum-norm solve
//! and totals the rest of the planner shares.

use super::pinv::{solve_full_row_rank, solve_min_norm, Conditioning};
use super::settings::Settings;
use super::socp::{least_fuel, LeastFuel};
use super::status::Stage;
use super::transfer::{FMatrix, XVector};
use super::work_units;
use crate::work::Meter;
use nalgebra::SVector;

/// `F^+ y` by the equilibrated Cholesky fast path, or the SVD when it declines (charged to
/// `work` once done, by its sweeps: the caller's step is charged at the Cholesky's cost).
///
/// # Errors
/// [`Stage::Svd`] from the SVD.
pub(crate) fn min_norm(
    f: &FMatrix,
    columns: usize,
    y: &SVector<f64, 6>,
    settings: &Settings,
    work: &mut Meter,
) -> Result<XVector, Stage> {
    match solve_full_row_rank(f, y) {
        Some(x) => Ok(x),
        None => svd_min_norm(f, columns, y, settings, work).map(|r| r.0),
    }
}

/// `F^+ y` and F's conditioning by the SVD (the settings' rank tolerance and sweep bound),
/// charged to `work` once done by its sweeps (the final reserve keeps SVDs at
/// `svd_max_iter`).
///
/// # Errors
/// [`Stage::Svd`] when the SVD fails.
pub(crate) fn svd_min_norm(
    f: &FMatrix,
    columns: usize,
    y: &SVector<f64, 6>,
    settings: &Settings,
    work: &mut Meter,
) -> Result<(XVector, Conditioning), Stage> {
    let mut sweeps = 0;
    let r = solve_min_norm(
        f,
        columns,
        y,
        settings.rank_rcond,
        settings.svd_max_iter,
        &mut sweeps,
    );
    work.charge(work_units::svd(columns.div_ceil(3), sweeps));
    r
}

/// Euclidean norm of one impulse block.
fn norm3(b: &[f64]) -> f64 {
    let mut s = 0.0;
    for v in b {
        s += *v * *v;
    }
    libm::sqrt(s)
}

/// `sum_k |x_k|` over the impulse blocks, in the units of `x`.
pub(crate) fn total(x: &XVector) -> f64 {
    x.as_slice().chunks_exact(3).map(norm3).sum()
}

/// The least-fuel impulses for `F x = y` (km/s), with the solve's certificate. At most
/// `min_fuel_max_iter` interior-point iterations; optimal when the certified gap is below
/// `min_fuel_tol_mps`. The impulses are feasible whatever the status (at worst the
/// minimum-norm ones).
///
/// # Errors
/// [`Stage::Svd`] when F or y is not finite (nothing feasible could be formed).
pub(crate) fn solve_least_fuel(
    f: &FMatrix,
    columns: usize,
    y: &SVector<f64, 6>,
    settings: &Settings,
) -> Result<(XVector, LeastFuel), Stage> {
    let mut yy = [0.0; 6];
    yy.copy_from_slice(y.as_slice());
    let lf = least_fuel(
        f,
        columns,
        &yy,
        settings.min_fuel_tol_mps / super::elements::M_PER_KM,
        settings.rank_rcond,
        settings.min_fuel_max_iter,
    )
    .ok_or(Stage::Svd)?;
    Ok((XVector::from_column_slice(&lf.x), lf))
}
