//! Impulse timing (Wang 2018, eq. 7), the propagated impulse sequence (eq. 6), and the linear
//! end condition `F dX = dY` (eq. 9-12, with the paper's `I_3` read as `I_6`).

use super::elements::{add, sub, wrap_pi, wrap_two_pi, Elements, TWO_PI};
use super::model::Model;
use super::secular::rates;
use super::settings::{ElementSet, Settings};
use super::status::Stage;
use super::types::ImpulsePoint;
use crate::capacity::MAX_IMPULSES;
use crate::indexed::IndexedExt as _;
use nalgebra::{ArrayStorage, SMatrix, SVector};

/// Unknowns at capacity: three impulse components per impulse.
pub(crate) const MAX_UNKNOWNS: usize = 3 * MAX_IMPULSES;
/// The end-condition matrix F, zero-padded to capacity.
pub(crate) type FMatrix = SMatrix<f64, 6, MAX_UNKNOWNS>;
/// All impulses stacked (km/s, RTN per impulse), zero-padded to capacity.
pub(crate) type XVector = SVector<f64, MAX_UNKNOWNS>;

/// The validated request in working units.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Context {
    /// Working element set and impulse-point phase; every element vector below is in it.
    pub model: Model,
    /// Chief at the initial epoch.
    pub chief0: Elements,
    /// Deputy at the initial epoch (chief + initial).
    pub deputy0: Elements,
    /// Initial relative elements.
    pub initial: Elements,
    /// Target relative elements (at the last impulse). Equinoctial set: the target deputy as
    /// it would be at the epoch minus the chief there; it drifts with the chief's rates (see
    /// [`target_at`]).
    pub target: Elements,
}

/// The impulse points of one solve.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Points {
    /// Number of impulses in use.
    pub n: usize,
    /// Points; only the first `n` are used.
    pub at: [ImpulsePoint; MAX_IMPULSES],
}

impl Points {
    /// No points.
    pub const fn new() -> Self {
        Self {
            n: 0,
            at: [ImpulsePoint {
                arg_latitude_rad: 0.0,
                revolutions: 0,
            }; MAX_IMPULSES],
        }
    }
}

/// One step of the propagated sequence.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Step {
    /// `sigma_{k-1}`: the deputy after the previous impulse (or at the epoch).
    pub before: Elements,
    /// `sigma_{k,0}`: the deputy just before impulse k.
    pub at: Elements,
    /// True anomaly at impulse k, rad.
    pub true_anomaly_rad: f64,
    /// Time of impulse k from the epoch, s.
    pub time_s: f64,
    /// `B(sigma_{k,0})` at the impulse (eq. 3), kept for building F.
    pub b: SMatrix<f64, 6, 3>,
}

/// The propagated sequence and the linear system built on it.
#[derive(Clone, Debug)]
pub(crate) struct Sequence {
    /// Per impulse.
    pub steps: [Step; MAX_IMPULSES],
    /// The deputy after the last impulse.
    pub end: Elements,
    /// Time of the last impulse, s.
    pub final_time_s: f64,
    /// F, columns `3k..3k+3` for impulse k (radial, along-track, normal).
    pub f: FMatrix,
    /// dY.
    pub dy: SVector<f64, 6>,
    /// The solve's work meter (here because every metered loop holds the sequence).
    pub work: crate::work::Meter,
}

impl Sequence {
    /// Zeroed.
    pub const fn new() -> Self {
        const STEP: Step = Step {
            before: [0.0; 6],
            at: [0.0; 6],
            true_anomaly_rad: 0.0,
            time_s: 0.0,
            b: SMatrix::from_array_storage(ArrayStorage([[0.0; 6]; 3])),
        };
        Self {
            steps: [STEP; MAX_IMPULSES],
            end: [0.0; 6],
            final_time_s: 0.0,
            f: SMatrix::from_array_storage(ArrayStorage([[0.0; 6]; MAX_UNKNOWNS])),
            dy: SMatrix::from_array_storage(ArrayStorage([[0.0; 6]; 1])),
            // Unmetered until a solve sets its budget (the solver's unit tests run it bare).
            work: crate::work::Meter::new(u64::MAX),
        }
    }
}

/// How impulses change the elements while propagating.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum ImpulseModel {
    /// `sigma_k = sigma_{k,0} + B(sigma_{k,0}) dv_k` (the paper's eq. 6).
    Linear,
    /// Exact two-body impulse (verification).
    Exact,
}

/// Time from the deputy's state to the next impulse point, s (Wang 2018, eq. 7), with `u` the
/// model's phase (mean argument of latitude, or mean longitude for an equatorial chief):
/// `dt = (wrap_2pi(u_k - u_{k-1}) + 2 pi dN_k - wrap_pi(u_now - u_{k-1})) / n_J2`.
///
/// `u_{k-1}` is the previous *point* and `u_now` the deputy's mean argument of latitude after
/// the previous impulse; this equals the issue's `(wrap_2pi(u_k - u_now) + 2 pi dN_k) / n_J2`
/// except that it stays continuous when an impulse's small jump in `u` crosses `u_k` (coincident
/// points). A negative gap (the jump overshot a coincident point) is clamped to zero.
pub(crate) fn time_to_point_s(
    model: &Model,
    el: &Elements,
    prev_point_rad: f64,
    point: &ImpulsePoint,
) -> f64 {
    let u_now = model.phase_rad(el);
    let gap = wrap_two_pi(point.arg_latitude_rad - prev_point_rad)
        + TWO_PI * f64::from(point.revolutions)
        - wrap_pi(u_now - prev_point_rad);
    let gap = if gap > 0.0 { gap } else { 0.0 };
    gap / model.phase_rate_rad_s(el)
}

/// Propagate the deputy through the impulse sequence (eq. 6) with impulses `dv` (km/s, RTN).
///
/// # Errors
/// [`Stage::Kepler`] or [`Stage::SingularState`] when a step leaves the model's domain.
pub(crate) fn propagate(
    ctx: &Context,
    pts: &Points,
    dv: &XVector,
    model: ImpulseModel,
    settings: &Settings,
    seq: &mut Sequence,
) -> Result<(), Stage> {
    let mut s = ctx.deputy0;
    let mut t = 0.0;
    let working = ctx.model;
    let mut prev_point = working.phase_rad(&s);
    // One chunk of three components per impulse: `XVector` holds exactly MAX_IMPULSES of them.
    for ((step, point), dv_chunk) in seq
        .steps
        .iter_mut()
        .zip(pts.at.iter())
        .zip(dv.as_slice().chunks_exact(3))
        .take(pts.n)
    {
        let dt = time_to_point_s(&working, &s, prev_point, point);
        step.before = s;
        s = working.drift(&s, dt);
        t += dt;
        let (f, ok) = working.anomaly(&s, settings.kepler_max_iter);
        if !ok {
            return Err(Stage::Kepler);
        }
        step.at = s;
        step.true_anomaly_rad = f;
        step.time_s = t;
        let b = working.impulse_matrix(&s, f);
        step.b = b;
        // Every entry is overwritten: chunks_exact(3) yields exactly three.
        let mut dv_k = [0.0; 3];
        for (d, x) in dv_k.iter_mut().zip(dv_chunk.iter()) {
            *d = *x;
        }
        s = match model {
            ImpulseModel::Linear => {
                let mut db = SVector::<f64, 6>::zeros();
                db.gemv(1.0, &b, &SVector::<f64, 3>::from(dv_k), 0.0);
                let mut next = s;
                for (x, d) in next.iter_mut().zip(db.iter()) {
                    *x += *d;
                }
                next
            }
            ImpulseModel::Exact => working
                .apply_impulse(&s, f, &dv_k)
                .ok_or(Stage::SingularState)?,
        };
        if !working.in_domain(&s, settings) {
            return Err(Stage::SingularState);
        }
        prev_point = point.arg_latitude_rad;
    }
    seq.end = s;
    seq.final_time_s = t;
    Ok(())
}

/// Build `F` and `dY` (eq. 11-12) on a propagated sequence.
pub(crate) fn build_system(ctx: &Context, pts: &Points, seq: &mut Sequence) {
    let t_n = seq.final_time_s;
    seq.f.fill(0.0);
    for (k, step) in seq.steps.iter().indexed().take(pts.n) {
        // P_k B_k: the impulse carried to t_N by the drift's state transition (classical: the
        // paper's I_6 + dD(sigma_{k-1}) (t_N - t_k); dD depends on (a, e, i) only, which do not
        // drift, so sigma_{k-1} and sigma_{k,0} give the same P).
        let p_b = ctx
            .model
            .transition_times(&step.before, &step.at, t_n - step.time_s, &step.b);
        let c = k.saturating_mul(3);
        if c < MAX_UNKNOWNS {
            seq.f.fixed_view_mut::<6, 3>(0, c).copy_from(&p_b);
        }
    }
    let dy = match ctx.model.set {
        ElementSet::Classical => {
            let drift = sub(&rates(&ctx.deputy0), &rates(&ctx.chief0));
            sub(
                &sub(&ctx.target, &ctx.initial),
                &[
                    drift[0] * t_n,
                    drift[1] * t_n,
                    drift[2] * t_n,
                    drift[3] * t_n,
                    drift[4] * t_n,
                    drift[5] * t_n,
                ],
            )
        }
        // The target at t_N minus the deputy drifted there without impulses.
        ElementSet::Equinoctial => sub(&target_at(ctx, t_n), &ctx.model.drift(&ctx.deputy0, t_n)),
    };
    seq.dy = SVector::<f64, 6>::from(dy);
}

/// The chief at time `t_s` (J2 secular drift only).
pub(crate) fn chief_at(ctx: &Context, t_s: f64) -> Elements {
    ctx.model.drift(&ctx.chief0, t_s)
}

/// The deputy's target orbit at time `t_s`: the target relative elements on the chief there.
pub(crate) fn target_at(ctx: &Context, t_s: f64) -> Elements {
    match ctx.model.set {
        ElementSet::Classical => add(&chief_at(ctx, t_s), &ctx.target),
        ElementSet::Equinoctial => {
            ctx.model
                .drift_with(&add(&ctx.chief0, &ctx.target), &ctx.chief0, t_s)
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::impulsive::model::Phase;
    use crate::impulsive::secular::arg_latitude_rate_rad_s;

    const CLASSICAL: Model = Model {
        set: ElementSet::Classical,
        phase: Phase::ArgLatitude,
    };

    #[test]
    fn timing_counts_revolutions_and_wraps() {
        let el = [7178.137, 0.0678, 1.1071, 1.95, 0.0, 0.0];
        let n = arg_latitude_rate_rad_s(&el);
        let p = ImpulsePoint {
            arg_latitude_rad: 1.0,
            revolutions: 2,
        };
        assert!(
            (time_to_point_s(&CLASSICAL, &el, 0.0, &p) - (1.0 + 2.0 * TWO_PI) / n).abs() < 1e-9
        );
        // Point behind the current u: wraps forward.
        let el2 = [7178.137, 0.0678, 1.1071, 1.95, 0.0, 2.0];
        let p = ImpulsePoint {
            arg_latitude_rad: 1.0,
            revolutions: 0,
        };
        assert!((time_to_point_s(&CLASSICAL, &el2, 2.0, &p) - (TWO_PI - 1.0) / n).abs() < 1e-9);
        // Coincident point just overshot by the impulse: zero, not a revolution.
        let el3 = [7178.137, 0.0678, 1.1071, 1.95, 0.0, 1.0 + 1e-9];
        assert_eq!(time_to_point_s(&CLASSICAL, &el3, 1.0, &p), 0.0);
    }
}
