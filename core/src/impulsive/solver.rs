//! The fixed-point solve at given impulse points (validated by [`super::validate`]): the
//! minimum-norm fixed point (Wang 2018, section 2), the min-fuel refinement, the nonlinear check
//! and correction. The returned plan's checks are in [`super::returned`].

use super::elements::{sub, Elements, A, M_PER_KM};
use super::min_fuel::{min_norm, solve_least_fuel, svd_min_norm, total};
use super::nonlinear::relative_position_rtn;
use super::pinv::{solve_full_row_rank, Conditioning};
use super::settings::ElementSet;
use super::settings::Settings;
use super::status::{SolveStatus, Stage};
use super::transfer::{
    build_system, chief_at, propagate, target_at, Context, ImpulseModel, Points, Sequence, XVector,
};
use super::work_units;
use crate::indexed::IndexedExt as _;

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
                let (x, cond) = min_norm_of_system(seq, columns, settings)?;
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

/// The nonlinear check's findings at the last impulse.
pub(crate) struct Miss {
    /// Achieved minus wanted elements in the working set, angles wrapped.
    pub err: Elements,
    /// Position error along the target's along-track direction, m.
    pub along_m: f64,
    /// Norm of the position error, m.
    pub pos_m: f64,
    /// The wanted deputy orbit (working set).
    pub wanted: Elements,
}

/// Nonlinear check: propagate with exact impulses and compare with the target at the last
/// impulse.
///
/// # Errors
/// The failing [`Stage`].
pub(crate) fn nonlinear_error(
    ctx: &Context,
    pts: &Points,
    dv: &XVector,
    settings: &Settings,
    seq: &mut Sequence,
) -> Result<Miss, Stage> {
    propagate(ctx, pts, dv, ImpulseModel::Exact, settings, seq)?;
    let model = ctx.model;
    let (mut err, wanted) = match model.set {
        ElementSet::Classical => {
            let chief = chief_at(ctx, seq.final_time_s);
            let achieved = sub(&seq.end, &chief);
            (
                sub(&achieved, &ctx.target),
                super::elements::add(&chief, &ctx.target),
            )
        }
        ElementSet::Equinoctial => {
            let wanted = target_at(ctx, seq.final_time_s);
            (sub(&seq.end, &wanted), wanted)
        }
    };
    model.wrap_angles(&mut err);
    let (f_w, ok_w) = model.anomaly(&wanted, settings.kepler_max_iter);
    let (f_a, ok_a) = model.anomaly(&seq.end, settings.kepler_max_iter);
    if !(ok_w && ok_a) {
        return Err(Stage::Kepler);
    }
    let d = relative_position_rtn(&model.state(&wanted, f_w), &model.state(&seq.end, f_a));
    Ok(Miss {
        err,
        along_m: d[1] * M_PER_KM,
        pos_m: libm::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]) * M_PER_KM,
        wanted,
    })
}

/// Largest of `|da|/a, |de|, |di|, |dOmega|, |domega|, |dM|`.
pub(crate) fn scaled_error(err: &Elements, sma_km: f64) -> f64 {
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

impl Report {
    /// A fresh solve's report holding the plan `dv`: `Solved`, no steps taken yet.
    pub(crate) fn holding(dv: XVector) -> Self {
        Self {
            dv,
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
        }
    }
}

/// The full fixed-point solve at the points in `pts`.
pub(crate) fn solve_points(
    ctx: &Context,
    pts: &Points,
    settings: &Settings,
    seq: &mut Sequence,
) -> Report {
    let mut rep = Report::holding(XVector::zeros());
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
pub(super) fn conditioning_at(
    ctx: &Context,
    pts: &Points,
    dv: &XVector,
    settings: &Settings,
    seq: &mut Sequence,
) -> Result<Conditioning, Stage> {
    propagate(ctx, pts, dv, ImpulseModel::Linear, settings, seq)?;
    build_system(ctx, pts, seq);
    let columns = pts.n.saturating_mul(3);
    let (_, c) = min_norm_of_system(seq, columns, settings)?;
    Ok(c)
}

/// The minimum-norm solution and conditioning (by the SVD, charged once done) of the system
/// `F x = dy` built in `seq`, over its first `columns` unknowns.
///
/// # Errors
/// [`Stage::Svd`] when the SVD fails.
fn min_norm_of_system(
    seq: &mut Sequence,
    columns: usize,
    settings: &Settings,
) -> Result<(XVector, Conditioning), Stage> {
    svd_min_norm(&seq.f, columns, &seq.dy, settings, &mut seq.work)
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
pub(super) fn correct(
    ctx: &Context,
    pts: &Points,
    settings: &Settings,
    seq: &mut Sequence,
    rep: &mut Report,
) -> Result<bool, Stage> {
    let columns = pts.n.saturating_mul(3);
    let mut dv = rep.dv;
    let err = nonlinear_error(ctx, pts, &dv, settings, seq)?.err;
    if scaled_error(&err, ctx.chief0[A]) <= settings.correction_tol {
        return Ok(true);
    }
    let mut e = nalgebra::SVector::<f64, 6>::from(err);
    let mut jac = defect_jacobian(ctx, pts, &dv, &err, settings, seq)?;
    for _ in 0..settings.correction_max_iter {
        if !seq.work.spend(work_units::correction_step(pts.n)) {
            break;
        }
        let d = min_norm(&jac, columns, &e, settings, &mut seq.work)?;
        dv.axpy(-1.0, &d, 1.0);
        rep.correction_steps = rep.correction_steps.saturating_add(1);
        rep.correction_used = true;
        rep.dv = dv;
        let err = nonlinear_error(ctx, pts, &dv, settings, seq)?.err;
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
    for (j, mut col) in jac.column_iter_mut().indexed().take(columns) {
        if !seq.work.spend(work_units::jacobian_column(pts.n)) {
            break;
        }
        let mut probe = *dv;
        if let Some(x) = probe.get_mut(j) {
            *x += DEFECT_STEP_KM_S;
        }
        let e = nonlinear_error(ctx, pts, &probe, settings, seq)?.err;
        for ((c, a), b) in col.iter_mut().zip(e.iter()).zip(err.iter()) {
            *c = (*a - *b) / DEFECT_STEP_KM_S;
        }
    }
    Ok(jac)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::impulsive::elements::{from_mean, from_relative};
    use crate::impulsive::returned::write_solution;
    use crate::impulsive::solution::Solution;
    use crate::impulsive::types::{ImpulsePoint, MeanElements, RelativeElements};
    use crate::impulsive::validate::perigee_altitude_km;

    fn deg(x: f64) -> f64 {
        x.to_radians()
    }

    pub(crate) fn paper_context() -> Context {
        let chief = MeanElements::test_paper_chief();
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
            model: crate::impulsive::model::Model {
                set: ElementSet::Classical,
                phase: crate::impulsive::model::Phase::ArgLatitude,
            },
            chief0,
            deputy0: super::super::elements::add(&chief0, &initial),
            initial,
            target,
        }
    }

    #[test]
    fn fixed_point_converges_quickly_on_table_2() {
        let (ctx, pts, settings, mut seq) = paper_case();
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

    /// The paper's case: its context, Table 2's impulse points, its settings, a sequence.
    fn paper_case() -> (Context, Points, Settings, Sequence) {
        let settings = Settings::paper_classical();
        (paper_context(), table_2_points(), settings, Sequence::new())
    }

    /// The solution written for `rep`: one evaluation, a fresh `Solution`.
    fn written(
        ctx: &Context,
        pts: &Points,
        settings: &Settings,
        seq: &mut Sequence,
        rep: &Report,
    ) -> Solution {
        let mut out = Solution::new();
        write_solution(ctx, pts, settings, seq, rep, 1, &mut out);
        out
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
        let (ctx, pts, settings, mut seq) = paper_case();
        let rep = solve_points(&ctx, &pts, &settings, &mut seq);
        let out = written(&ctx, &pts, &settings, &mut seq, &rep);
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
        let out = written(&ctx, &pts, &strict, &mut seq, &rep);
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
        let (ctx, pts, settings, mut seq) = paper_case();
        let mut rep = solve_points(&ctx, &pts, &settings, &mut seq);
        rep.min_norm_total_km_s = f64::NAN;
        let out = written(&ctx, &pts, &settings, &mut seq, &rep);
        // A figure that came out non-finite is absent; the plan itself is finite and kept.
        assert_eq!(out.min_norm_total_dv_mps, None);
        assert!(out.total_dv_mps > 8.0);
        assert!(out.terminal_error.is_some());
        // A plan number that came out non-finite: no plan at all, and the status says so.
        rep.dv[0] = f64::INFINITY;
        let out = written(&ctx, &pts, &settings, &mut seq, &rep);
        assert!(matches!(out.info.status, SolveStatus::NumericalFailure(_)));
        assert!(out.impulses.is_empty());
        assert_eq!(out.total_dv_mps, 0.0);
    }

    #[test]
    fn solved_is_rechecked_on_the_returned_impulses() {
        let (ctx, pts, settings, mut seq) = paper_case();
        let mut rep = solve_points(&ctx, &pts, &settings, &mut seq);
        assert_eq!(rep.status, SolveStatus::Solved);
        // 1 mm/s off on one component: the report must not keep `Solved`.
        rep.dv[1] += 1e-6;
        let out = written(&ctx, &pts, &settings, &mut seq, &rep);
        assert_eq!(out.info.status, SolveStatus::CorrectionNotConverged);
    }
}
