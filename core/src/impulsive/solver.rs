//! The fixed-point solve at given impulse points (validated by [`super::validate`]): the
//! minimum-norm fixed point (Wang 2018, section 2), the min-fuel refinement, the nonlinear check
//! and correction, and the checks of the returned plan.

use super::elements::{
    sub, to_relative, wrap_pi, wrap_two_pi, Elements, A, ARGP, E, M_PER_KM, RAAN,
};
use super::kepler::true_anomaly;
use super::min_fuel::{min_norm, solve_least_fuel, total};
use super::nonlinear::{relative_position_rtn, state};
use super::pinv::{solve_full_row_rank, solve_min_norm, Conditioning};
use super::settings::Settings;
use super::solution::{Impulse, Solution};
use super::status::{SolveStatus, Stage};
use super::transfer::{
    build_system, chief_at, propagate, Context, ImpulseModel, Points, Sequence, XVector,
};
use super::validate::{index_u8, perigee_altitude_km};
use super::work_units;

/// Result of a fixed-point run.
#[derive(Clone, Copy, Debug, Default)]
pub(crate) struct FixedPoint {
    /// Iterations used.
    pub iterations: u16,
    /// Met `fixed_point_tol_mps`.
    pub converged: bool,
    /// Interior-point iterations used (min-fuel phase).
    pub min_fuel_steps: u16,
    /// Certified gap of the last least-fuel solve (upper minus lower bound), km/s.
    pub min_fuel_gap_km_s: f64,
    /// Rank and condition of F at the last iteration.
    pub conditioning: Conditioning,
}

/// Iterate `dv <- solve(F(dv), dY(dv))` (minimum norm, or min fuel when `min_fuel`) from `dv`,
/// at most `max_iter` times.
///
/// # Errors
/// The failing [`Stage`]; `dv` then holds the last good iterate.
pub(crate) fn fixed_point(
    ctx: &Context,
    pts: &Points,
    settings: &Settings,
    seq: &mut Sequence,
    dv: &mut XVector,
    min_fuel: bool,
    max_iter: u16,
) -> Result<FixedPoint, Stage> {
    let columns = pts.n.saturating_mul(3);
    // Reweighting converges linearly and the sum of norms is flat along its valley, so the joint
    // min-fuel fixed point is judged by the change of its total; the nonlinear correction
    // afterwards fixes the terminal error either way.
    let tol = if min_fuel {
        settings.min_fuel_step_tol_mps
    } else {
        settings.fixed_point_tol_mps
    } / M_PER_KM;
    let mut out = FixedPoint::default();
    for _ in 0..max_iter {
        if !seq.work.spend(work_units::fixed_point_iteration(pts.n)) {
            break;
        }
        propagate(ctx, pts, dv, ImpulseModel::Linear, settings, seq)?;
        build_system(ctx, pts, seq);
        // The equilibrated Cholesky solve gives the minimum-norm impulses at full row rank;
        // when it declines (near rank deficiency) the rank-revealing SVD decides. The returned
        // plan's rank and condition number come from an SVD of F rebuilt at the returned
        // impulses (see `conditioning_at`).
        let fast = solve_full_row_rank(&seq.f, &seq.dy);
        let x0 = match fast {
            Some(x) => {
                // Full row rank (Cholesky pivots bounded away from zero); the condition number
                // is measured by the SVD at the end.
                out.conditioning = Conditioning {
                    rank: 6,
                    condition_number: f64::NAN,
                };
                x
            }
            None => {
                seq.work.charge(work_units::svd(pts.n));
                let (x, cond) = solve_min_norm(
                    &seq.f,
                    columns,
                    &seq.dy,
                    settings.rank_rcond,
                    settings.svd_max_iter,
                )?;
                out.conditioning = cond;
                if cond.rank < 6 {
                    // Rank-deficient F (coincident points, or fewer than two impulses): the
                    // least-squares impulses at the current states are the answer; iterating
                    // on them would chase a target they cannot reach.
                    *dv = x;
                    out.iterations = out.iterations.saturating_add(1);
                    break;
                }
                x
            }
        };
        let x = if min_fuel {
            // Exact least fuel on this linearisation (a cone program, `socp`); its impulses
            // are feasible whatever its status, and the certified gap is reported.
            let (x, lf) = solve_least_fuel(&seq.f, columns, &seq.dy, settings)?;
            seq.work
                .charge(work_units::cone_program(pts.n, lf.iterations));
            out.min_fuel_steps = out.min_fuel_steps.saturating_add(lf.iterations);
            out.min_fuel_gap_km_s = lf.total - lf.lower_bound;
            if total(&x) <= total(&x0) {
                x
            } else {
                x0
            }
        } else {
            x0
        };
        // The sum of norms is flat along its valley: judge the min-fuel phase by its total.
        let change = if min_fuel {
            libm::fabs(total(&x) - total(dv))
        } else {
            max_abs_diff(&x, dv)
        };
        *dv = x;
        out.iterations = out.iterations.saturating_add(1);
        if change <= tol {
            out.converged = true;
            break;
        }
    }
    Ok(out)
}

/// `max_i |a_i - b_i|`.
fn max_abs_diff(a: &XVector, b: &XVector) -> f64 {
    let mut m = 0.0f64;
    for (x, y) in a.iter().zip(b.iter()) {
        m = m.max(libm::fabs(*x - *y));
    }
    m
}

/// Nonlinear check: propagate with exact impulses and compare with the target at the last
/// impulse. Returns (element error with wrapped angles, along-track error m, position error m).
///
/// # Errors
/// The failing [`Stage`].
pub(crate) fn nonlinear_error(
    ctx: &Context,
    pts: &Points,
    dv: &XVector,
    settings: &Settings,
    seq: &mut Sequence,
) -> Result<(Elements, f64, f64), Stage> {
    propagate(ctx, pts, dv, ImpulseModel::Exact, settings, seq)?;
    let chief = chief_at(ctx, seq.final_time_s);
    let achieved = sub(&seq.end, &chief);
    let mut err = sub(&achieved, &ctx.target);
    for k in [RAAN, ARGP, super::elements::MA] {
        if let Some(x) = err.get_mut(k) {
            *x = wrap_pi(*x);
        }
    }
    let wanted = super::elements::add(&chief, &ctx.target);
    let (f_w, ok_w) = true_anomaly(
        wanted[super::elements::MA],
        wanted[E],
        settings.kepler_max_iter,
    );
    let (f_a, ok_a) = true_anomaly(
        seq.end[super::elements::MA],
        seq.end[E],
        settings.kepler_max_iter,
    );
    if !(ok_w && ok_a) {
        return Err(Stage::Kepler);
    }
    let d = relative_position_rtn(&state(&wanted, f_w), &state(&seq.end, f_a));
    let along_m = d[1] * M_PER_KM;
    let pos_m = libm::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]) * M_PER_KM;
    Ok((err, along_m, pos_m))
}

/// Largest of `|da|/a, |de|, |di|, |dOmega|, |domega|, |dM|`.
fn scaled_error(err: &Elements, sma_km: f64) -> f64 {
    let mut m = libm::fabs(err[A]) / sma_km;
    for x in err.iter().skip(1) {
        m = m.max(libm::fabs(*x));
    }
    m
}

/// Everything a fixed-point solve found, before it is written out.
pub(crate) struct Report {
    pub dv: XVector,
    pub status: SolveStatus,
    pub iterations: u16,
    pub min_fuel_steps: u16,
    pub min_fuel_gap_km_s: f64,
    pub correction_steps: u16,
    pub min_norm_total_km_s: f64,
    pub linear_total_km_s: f64,
    pub min_fuel_used: bool,
    pub correction_used: bool,
    pub conditioning: Conditioning,
}

/// The full fixed-point solve at the points in `pts`.
pub(crate) fn solve_points(
    ctx: &Context,
    pts: &Points,
    settings: &Settings,
    seq: &mut Sequence,
) -> Report {
    let mut rep = Report {
        dv: XVector::zeros(),
        status: SolveStatus::Solved,
        iterations: 0,
        min_fuel_steps: 0,
        min_fuel_gap_km_s: 0.0,
        correction_steps: 0,
        min_norm_total_km_s: 0.0,
        linear_total_km_s: 0.0,
        min_fuel_used: false,
        correction_used: false,
        conditioning: Conditioning::default(),
    };
    let mut dv = XVector::zeros();
    let fp = match fixed_point(
        ctx,
        pts,
        settings,
        seq,
        &mut dv,
        false,
        settings.fixed_point_max_iter,
    ) {
        Ok(fp) => fp,
        Err(stage) => {
            rep.status = SolveStatus::NumericalFailure(stage);
            rep.dv = dv;
            return rep;
        }
    };
    rep.iterations = fp.iterations;
    rep.conditioning = fp.conditioning;
    rep.min_norm_total_km_s = total(&dv);
    rep.dv = dv;
    let mut converged = fp.converged;
    if fp.conditioning.rank < 6 {
        rep.status = SolveStatus::RankDeficient;
        // Leave the least-squares plan's own propagation in `seq` for the report; if it
        // leaves the domain the report keeps the last good states (the status says why).
        let _ = propagate(ctx, pts, &rep.dv, ImpulseModel::Linear, settings, seq);
        return rep;
    }
    if settings.min_fuel {
        let mut fuel_dv = dv;
        match fixed_point(
            ctx,
            pts,
            settings,
            seq,
            &mut fuel_dv,
            true,
            settings.fixed_point_max_iter,
        ) {
            Ok(fp2) => {
                rep.iterations = rep.iterations.saturating_add(fp2.iterations);
                rep.min_fuel_steps = fp2.min_fuel_steps;
                rep.min_fuel_gap_km_s = fp2.min_fuel_gap_km_s;
                if total(&fuel_dv) <= rep.min_norm_total_km_s && fp2.conditioning.rank == 6 {
                    rep.dv = fuel_dv;
                    rep.min_fuel_used = true;
                    converged = fp2.converged;
                }
            }
            Err(stage) => {
                rep.status = SolveStatus::NumericalFailure(stage);
                return rep;
            }
        }
    }
    rep.linear_total_km_s = total(&rep.dv);
    if settings.nonlinear_correction {
        match correct(ctx, pts, settings, seq, &mut rep) {
            Ok(true) => {}
            Ok(false) => rep.status = SolveStatus::CorrectionNotConverged,
            Err(stage) => rep.status = SolveStatus::NumericalFailure(stage),
        }
    } else if !converged {
        rep.status = SolveStatus::MaxIterations;
    } else {
        // The linear model's fixed point is not a plan that reaches the target when flown; the
        // miss is measured by the nonlinear check in `write_solution`.
        rep.status = SolveStatus::Linearised { miss_m: 0.0 };
    }
    match conditioning_at(ctx, pts, &rep.dv, settings, seq) {
        Ok(c) => {
            rep.conditioning = c;
            if c.rank < 6 && !matches!(rep.status, SolveStatus::NumericalFailure(_)) {
                rep.status = SolveStatus::RankDeficient;
            }
        }
        Err(stage) => {
            if !matches!(rep.status, SolveStatus::NumericalFailure(_)) {
                rep.status = SolveStatus::NumericalFailure(stage);
            }
        }
    }
    rep
}

/// Rank and condition number, by the SVD, of F rebuilt at the returned impulses `dv` (linear
/// propagation). Leaves that propagation in `seq` (the linear-model times of the plan).
///
/// # Errors
/// The failing [`Stage`].
fn conditioning_at(
    ctx: &Context,
    pts: &Points,
    dv: &XVector,
    settings: &Settings,
    seq: &mut Sequence,
) -> Result<Conditioning, Stage> {
    propagate(ctx, pts, dv, ImpulseModel::Linear, settings, seq)?;
    build_system(ctx, pts, seq);
    let columns = pts.n.saturating_mul(3);
    let (_, c) = solve_min_norm(
        &seq.f,
        columns,
        &seq.dy,
        settings.rank_rcond,
        settings.svd_max_iter,
    )?;
    Ok(c)
}

/// Nonlinear correction: Broyden's method on the defect `e(dv)` of the exact model (exact
/// impulses, J2 secular drift), `dv <- dv - J^+ e(dv)` with minimum-norm steps, `J` started at
/// the linear model's F at the current impulses and given a rank-one secant update
/// `J += (de - J s) s^T / (s^T s)` after each step. The linear F misses the exact map's
/// sensitivity of the impulse timing to the impulses, so plain defect correction with F
/// contracts by only ~0.45 a step; the secant updates learn the difference and converge
/// superlinearly. Stops when the largest scaled terminal error is below `correction_tol`, at
/// most `correction_max_iter` steps (each one exact propagation and one minimum-norm solve,
/// plus one linear propagation to start). Returns whether it converged.
fn correct(
    ctx: &Context,
    pts: &Points,
    settings: &Settings,
    seq: &mut Sequence,
    rep: &mut Report,
) -> Result<bool, Stage> {
    let columns = pts.n.saturating_mul(3);
    let mut dv = rep.dv;
    let (err, _, _) = nonlinear_error(ctx, pts, &dv, settings, seq)?;
    if scaled_error(&err, ctx.chief0[A]) <= settings.correction_tol {
        return Ok(true);
    }
    let mut e = nalgebra::SVector::<f64, 6>::from(err);
    let mut jac = defect_jacobian(ctx, pts, &dv, &err, settings, seq)?;
    for _ in 0..settings.correction_max_iter {
        if !seq.work.spend(work_units::correction_step(pts.n)) {
            break;
        }
        let d = min_norm(&jac, columns, &e, settings)?;
        dv.axpy(-1.0, &d, 1.0);
        rep.correction_steps = rep.correction_steps.saturating_add(1);
        rep.correction_used = true;
        rep.dv = dv;
        let (err, _, _) = nonlinear_error(ctx, pts, &dv, settings, seq)?;
        if scaled_error(&err, ctx.chief0[A]) <= settings.correction_tol {
            return Ok(true);
        }
        let e_new = nalgebra::SVector::<f64, 6>::from(err);
        // Secant update with step s = -d: J s should equal e_new - e.
        let ss = d.dot(&d);
        if ss > 0.0 {
            let mut r = e_new;
            r.axpy(-1.0, &e, 1.0);
            r.gemv(1.0, &jac, &d, 1.0);
            jac.ger(-1.0 / ss, &r, &d, 1.0);
        }
        e = e_new;
    }
    Ok(false)
}

/// Step of the forward differences of the defect, km/s (0.1 mm/s): the exact map's second
/// derivative makes the Jacobian's relative error about `h / v` ~ 1e-8, and rounding of the
/// elements (~1e-12 km on a, ~1e-14 rad on angles) stays below 1e-4 of the columns.
const DEFECT_STEP_KM_S: f64 = 1e-7;

/// The Jacobian of the exact model's terminal defect with respect to the impulses, by forward
/// differences (`3N` exact propagations) at `dv`, whose defect is `err`.
///
/// # Errors
/// The failing [`Stage`].
fn defect_jacobian(
    ctx: &Context,
    pts: &Points,
    dv: &XVector,
    err: &Elements,
    settings: &Settings,
    seq: &mut Sequence,
) -> Result<super::transfer::FMatrix, Stage> {
    let mut jac = super::transfer::FMatrix::zeros();
    let columns = pts.n.saturating_mul(3);
    for (j, mut col) in jac.column_iter_mut().enumerate().take(columns) {
        if !seq.work.spend(work_units::jacobian_column(pts.n)) {
            break;
        }
        let mut probe = *dv;
        if let Some(x) = probe.get_mut(j) {
            *x += DEFECT_STEP_KM_S;
        }
        let (e, _, _) = nonlinear_error(ctx, pts, &probe, settings, seq)?;
        for ((c, a), b) in col.iter_mut().zip(e.iter()).zip(err.iter()) {
            *c = (*a - *b) / DEFECT_STEP_KM_S;
        }
    }
    Ok(jac)
}

/// The first transfer arc (1-based) of the exact propagation in `seq` whose perigee is below
/// `min_km`, with that perigee altitude: arc k < N is the deputy after impulse k (`steps[k]`'s
/// starting state), arc N the orbit after the last impulse.
fn unsafe_arc(seq: &Sequence, n: usize, min_km: f64) -> Option<(u8, f64)> {
    let after_impulses = seq
        .steps
        .iter()
        .take(n)
        .skip(1)
        .map(|s| &s.before)
        .chain(core::iter::once(&seq.end));
    for (k, el) in after_impulses.enumerate() {
        let perigee = perigee_altitude_km(el);
        // NaN fails the comparison and is caught by the non-finite scan.
        if perigee < min_km {
            return Some((index_u8(k.saturating_add(1)), perigee));
        }
    }
    None
}

/// Replace a non-finite number by 0; true when it was not finite.
fn scrub(x: &mut f64) -> bool {
    if x.is_finite() {
        false
    } else {
        *x = 0.0;
        true
    }
}

/// Every number of `out` finite: non-finite ones are written as 0. True when one was not.
fn scrub_solution(out: &mut Solution) -> bool {
    let mut bad = false;
    for imp in out.impulses.iter_mut() {
        bad |= scrub(&mut imp.time_s);
        bad |= scrub(&mut imp.arg_latitude_rad);
        bad |= scrub(&mut imp.true_arg_latitude_rad);
        for x in imp.dv_rtn_mps.iter_mut() {
            bad |= scrub(x);
        }
    }
    let e = &mut out.terminal_error_elements;
    for x in [
        &mut out.total_dv_mps,
        &mut out.min_norm_total_dv_mps,
        &mut out.linear_total_dv_mps,
        &mut out.final_time_s,
        &mut out.terminal_error_m,
        &mut out.terminal_position_error_m,
        &mut e.dsma_km,
        &mut e.decc,
        &mut e.dinc_rad,
        &mut e.draan_rad,
        &mut e.dargp_rad,
        &mut e.dmean_anomaly_rad,
        &mut out.info.condition_number,
    ] {
        bad |= scrub(x);
    }
    if let SolveStatus::Linearised { miss_m } = &mut out.info.status {
        bad |= scrub(miss_m);
    }
    if let SolveStatus::UnsafePerigee {
        perigee_altitude_km,
        ..
    } = &mut out.info.status
    {
        bad |= scrub(perigee_altitude_km);
    }
    bad
}

/// Write a report into `out`: impulses (m/s, RTN), totals, nonlinear terminal errors. The
/// status is settled here on the returned impulses: the nonlinear check is re-run on them
/// (`Solved` needs its error within `correction_tol`; `Linearised` gets its miss), every
/// transfer arc's perigee is checked, and any non-finite number makes it `NumericalFailure`.
pub(crate) fn write_solution(
    ctx: &Context,
    pts: &Points,
    settings: &Settings,
    seq: &mut Sequence,
    rep: &Report,
    evaluations: u32,
    out: &mut Solution,
) {
    let mut status = rep.status;
    let failed = |s: &SolveStatus| matches!(s, SolveStatus::NumericalFailure(_));
    // Times and latitudes from the model the impulses were solved for: the exact one when the
    // correction was applied, else the paper's linear one (left in `seq` by the solve).
    let linear_steps = seq.steps;
    let linear_final_time_s = seq.final_time_s;
    let (err, along_m, pos_m) = match nonlinear_error(ctx, pts, &rep.dv, settings, seq) {
        Ok(v) => {
            match status {
                SolveStatus::Solved
                    if scaled_error(&v.0, ctx.chief0[A])
                        .partial_cmp(&settings.correction_tol)
                        .is_none_or(core::cmp::Ordering::is_gt) =>
                {
                    status = SolveStatus::CorrectionNotConverged;
                }
                SolveStatus::Linearised { .. } => {
                    status = SolveStatus::Linearised { miss_m: v.2 };
                }
                _ => {}
            }
            if !failed(&status) {
                if let Some((arc, perigee)) =
                    unsafe_arc(seq, pts.n, settings.min_perigee_altitude_km)
                {
                    status = SolveStatus::UnsafePerigee {
                        arc,
                        perigee_altitude_km: perigee,
                    };
                }
            }
            v
        }
        Err(stage) => {
            if !failed(&status) {
                status = SolveStatus::NumericalFailure(stage);
            }
            ([f64::NAN; 6], f64::NAN, f64::NAN)
        }
    };
    if !rep.correction_used {
        seq.steps = linear_steps;
        seq.final_time_s = linear_final_time_s;
    }
    out.impulses.clear();
    for (k, (step, point)) in seq.steps.iter().zip(pts.at.iter()).enumerate().take(pts.n) {
        let c = k.saturating_mul(3);
        let comp = |j: usize| rep.dv.get(c.saturating_add(j)).copied().unwrap_or(0.0) * M_PER_KM;
        let imp = Impulse {
            time_s: step.time_s,
            arg_latitude_rad: wrap_two_pi(step.at[ARGP] + step.at[super::elements::MA]),
            true_arg_latitude_rad: wrap_two_pi(step.at[ARGP] + step.true_anomaly_rad),
            revolutions: point.revolutions,
            dv_rtn_mps: [comp(0), comp(1), comp(2)],
        };
        // Capacity equals MAX_IMPULSES and pts.n <= MAX_IMPULSES, so this cannot fail.
        let _ = out.impulses.push(imp);
    }
    out.total_dv_mps = total(&rep.dv) * M_PER_KM;
    out.min_norm_total_dv_mps = rep.min_norm_total_km_s * M_PER_KM;
    out.linear_total_dv_mps = rep.linear_total_km_s * M_PER_KM;
    out.final_time_s = seq.final_time_s;
    out.terminal_error_m = along_m;
    out.terminal_position_error_m = pos_m;
    out.terminal_error_elements = to_relative(&err);
    out.info.iterations = rep.iterations;
    out.info.min_fuel_iterations = rep.min_fuel_steps;
    out.info.min_fuel_gap_mps = if rep.min_fuel_used {
        rep.min_fuel_gap_km_s * M_PER_KM
    } else {
        0.0
    };
    out.info.correction_iterations = rep.correction_steps;
    out.info.rank = rep.conditioning.rank;
    // Rank-deficient F has no finite condition number; the largest f64 says so in a finite
    // number (the rank field carries the fact).
    out.info.condition_number = if rep.conditioning.rank < 6 {
        f64::MAX
    } else {
        rep.conditioning.condition_number
    };
    out.info.min_fuel_used = rep.min_fuel_used;
    out.info.correction_used = rep.correction_used;
    out.info.evaluations = evaluations;
    out.info.status = status;
    if scrub_solution(out) && !failed(&out.info.status) {
        out.info.status = SolveStatus::NumericalFailure(Stage::NonFinite);
    }
}

#[cfg(test)]
#[allow(clippy::unwrap_used, clippy::indexing_slicing, clippy::float_cmp)]
mod tests {
    use super::*;
    use crate::impulsive::elements::{from_mean, from_relative};
    use crate::impulsive::types::{ImpulsePoint, MeanElements, RelativeElements};

    fn deg(x: f64) -> f64 {
        x.to_radians()
    }

    pub(crate) fn paper_context() -> Context {
        let chief = MeanElements {
            sma_km: 7178.137,
            ecc: 0.0678,
            inc_rad: deg(63.4349),
            raan_rad: deg(112.0),
            argp_rad: 0.0,
            mean_anomaly_rad: 0.0,
        };
        let rel = |v: [f64; 6]| RelativeElements {
            dsma_km: v[0],
            decc: v[1],
            dinc_rad: deg(v[2]),
            draan_rad: deg(v[3]),
            dargp_rad: deg(v[4]),
            dmean_anomaly_rad: deg(v[5]),
        };
        let chief0 = from_mean(&chief);
        let initial = from_relative(&rel([
            4.0940e-4, -1.3888e-4, -1.0831e-3, 1.5409e-2, -1.6134e-2, 9.2428e-3,
        ]));
        let target = from_relative(&rel([
            -1.6389e-4, 5.5597e-4, 4.3361e-3, 7.1228e-2, -6.3572e-2, 3.1718e-2,
        ]));
        Context {
            chief0,
            deputy0: super::super::elements::add(&chief0, &initial),
            initial,
            target,
        }
    }

    #[test]
    fn fixed_point_converges_quickly_on_table_2() {
        let ctx = paper_context();
        let pts = table_2_points();
        let settings = Settings::default();
        let mut seq = Sequence::new();
        let mut dv = XVector::zeros();
        let mut changes = [0.0; 12];
        for c in changes.iter_mut() {
            let before = dv;
            fixed_point(&ctx, &pts, &settings, &mut seq, &mut dv, false, 1).unwrap();
            *c = (dv - before).amax() * 1000.0;
        }
        assert!(changes[6] < 1e-9, "{changes:?}");
        assert!((total(&dv) * 1000.0 - 8.2207).abs() < 1e-3);
    }

    fn table_2_points() -> Points {
        let mut pts = Points::new();
        for (k, (u, n)) in [(274.155, 2), (238.864, 10), (285.649, 2)]
            .iter()
            .enumerate()
        {
            pts.at[k] = ImpulsePoint {
                arg_latitude_rad: deg(*u),
                revolutions: *n,
            };
        }
        pts.n = 3;
        pts
    }

    #[test]
    fn a_transfer_arc_below_the_perigee_limit_is_unsafe_and_named() {
        let ctx = paper_context();
        let pts = table_2_points();
        let settings = Settings::default();
        let mut seq = Sequence::new();
        let rep = solve_points(&ctx, &pts, &settings, &mut seq);
        let mut out = Solution::new();
        write_solution(&ctx, &pts, &settings, &mut seq, &rep, 1, &mut out);
        assert_eq!(out.info.status, SolveStatus::Solved);
        // The exact propagation of the returned plan is left in `seq`: the arcs' perigees.
        nonlinear_error(&ctx, &pts, &rep.dv, &settings, &mut seq).unwrap();
        let arcs = [
            perigee_altitude_km(&seq.steps[1].before),
            perigee_altitude_km(&seq.steps[2].before),
            perigee_altitude_km(&seq.end),
        ];
        let start = perigee_altitude_km(&ctx.deputy0);
        // A limit between the lowest arc and everything the validation sees makes that arc
        // (and only the transfer) unsafe.
        let (lowest, value) = arcs
            .iter()
            .enumerate()
            .min_by(|a, b| a.1.partial_cmp(b.1).unwrap())
            .unwrap();
        assert!(*value < start, "{arcs:?} vs {start}");
        let strict = Settings {
            min_perigee_altitude_km: *value + 1e-6,
            ..settings
        };
        write_solution(&ctx, &pts, &strict, &mut seq, &rep, 1, &mut out);
        assert_eq!(
            out.info.status,
            SolveStatus::UnsafePerigee {
                arc: u8::try_from(lowest + 1).unwrap(),
                perigee_altitude_km: *value
            },
            "{arcs:?}"
        );
        assert!(!out.info.status.is_usable());
    }

    #[test]
    fn non_finite_numbers_never_leave_and_say_numerical_failure() {
        let ctx = paper_context();
        let pts = table_2_points();
        let settings = Settings::default();
        let mut seq = Sequence::new();
        let mut rep = solve_points(&ctx, &pts, &settings, &mut seq);
        rep.min_norm_total_km_s = f64::NAN;
        let mut out = Solution::new();
        write_solution(&ctx, &pts, &settings, &mut seq, &rep, 1, &mut out);
        assert_eq!(
            out.info.status,
            SolveStatus::NumericalFailure(Stage::NonFinite)
        );
        assert_eq!(out.min_norm_total_dv_mps, 0.0);
        assert!(out.total_dv_mps > 8.0);
    }

    #[test]
    fn solved_is_rechecked_on_the_returned_impulses() {
        let ctx = paper_context();
        let pts = table_2_points();
        let settings = Settings::default();
        let mut seq = Sequence::new();
        let mut rep = solve_points(&ctx, &pts, &settings, &mut seq);
        assert_eq!(rep.status, SolveStatus::Solved);
        // 1 mm/s off on one component: the report must not keep `Solved`.
        rep.dv[1] += 1e-6;
        let mut out = Solution::new();
        write_solution(&ctx, &pts, &settings, &mut seq, &rep, 1, &mut out);
        assert_eq!(out.info.status, SolveStatus::CorrectionNotConverged);
    }
}
