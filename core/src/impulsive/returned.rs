//! The checks of a returned plan and its writing-out: the nonlinear check re-run on the
//! returned impulses, the transfer arcs' perigees, the terminal error in both element sets,
//! and the scrub of non-finite numbers (split from `solver`, which finds the plan).

use super::elements::{sub, to_relative, wrap_two_pi, Elements, A, M_PER_KM};
use super::min_fuel::total;
use super::model::Model;
use super::settings::{ElementSet, Settings};
use super::solution::{Impulse, Solution, TerminalError};
use super::solver::{nonlinear_error, scaled_error, Report};
use super::status::{SolveStatus, Stage};
use super::transfer::{Context, Points, Sequence};
use super::types::EquinoctialElements;
use super::validate::index_u8;
use crate::indexed::IndexedExt as _;

/// The terminal error `err` (working set; `end` achieved, `wanted` wanted) in the classical
/// and the equinoctial sets, angles wrapped.
fn both_sets(
    model: &Model,
    end: &Elements,
    wanted: &Elements,
    err: &Elements,
) -> (Elements, Elements) {
    let classical_model = Model {
        set: ElementSet::Classical,
        phase: model.phase,
    };
    let eq_model = Model {
        set: ElementSet::Equinoctial,
        phase: model.phase,
    };
    let mut classical = match model.set {
        ElementSet::Classical => *err,
        ElementSet::Equinoctial => sub(&model.classical_of(end), &model.classical_of(wanted)),
    };
    classical_model.wrap_angles(&mut classical);
    let mut equinoctial = match model.set {
        ElementSet::Classical => sub(&model.equinoctial_of(end), &model.equinoctial_of(wanted)),
        ElementSet::Equinoctial => *err,
    };
    eq_model.wrap_angles(&mut equinoctial);
    (classical, equinoctial)
}

/// The first transfer arc (1-based) of the exact propagation in `seq` whose perigee is below
/// `min_km`, with that perigee altitude: arc k < N is the deputy after impulse k (`steps[k]`'s
/// starting state), arc N the orbit after the last impulse.
fn unsafe_arc(model: &Model, seq: &Sequence, n: usize, min_km: f64) -> Option<(u8, f64)> {
    let after_impulses = seq
        .steps
        .iter()
        .take(n)
        .skip(1)
        .map(|s| &s.before)
        .chain(core::iter::once(&seq.end));
    for (k, el) in after_impulses.indexed() {
        let perigee = model.perigee_altitude_km(el);
        // NaN fails the comparison and is caught by the non-finite scan.
        if perigee < min_km {
            return Some((index_u8(k.saturating_add(1)), perigee));
        }
    }
    None
}

/// Every number of the returned plan (impulses, total, final time) and of the status finite.
fn plan_is_finite(out: &Solution) -> bool {
    let impulses = out.impulses.iter().all(|imp| {
        [imp.time_s, imp.arg_latitude_rad, imp.true_arg_latitude_rad]
            .iter()
            .chain(imp.dv_rtn_mps.iter())
            .all(|x| x.is_finite())
    });
    let status = match out.info.status {
        SolveStatus::Linearised { miss_m } => miss_m.is_finite(),
        SolveStatus::UnsafePerigee {
            perigee_altitude_km,
            ..
        } => perigee_altitude_km.is_finite(),
        _ => true,
    };
    impulses && out.total_dv_mps.is_finite() && out.final_time_s.is_finite() && status
}

/// `Some(x)` when `x` is finite: a figure that came out NaN or infinite is absent.
fn finite(x: f64) -> Option<f64> {
    x.is_finite().then_some(x)
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
    // The terminal error in the classical and the equinoctial sets, and the position misses.
    let terminal = match nonlinear_error(ctx, pts, &rep.dv, settings, seq) {
        Ok(miss) => {
            let (classical, equinoctial) = both_sets(&ctx.model, &seq.end, &miss.wanted, &miss.err);
            match status {
                SolveStatus::Solved
                    if scaled_error(&miss.err, ctx.chief0[A])
                        .partial_cmp(&settings.correction_tol)
                        .is_none_or(core::cmp::Ordering::is_gt) =>
                {
                    status = SolveStatus::CorrectionNotConverged;
                }
                SolveStatus::Linearised { .. } => {
                    status = SolveStatus::Linearised { miss_m: miss.pos_m };
                }
                _ => {}
            }
            if !failed(&status) {
                if let Some((arc, perigee)) =
                    unsafe_arc(&ctx.model, seq, pts.n, settings.min_perigee_altitude_km)
                {
                    status = SolveStatus::UnsafePerigee {
                        arc,
                        perigee_altitude_km: perigee,
                    };
                }
            }
            Some(TerminalError {
                along_track_m: miss.along_m,
                position_m: miss.pos_m,
                elements: to_relative(&classical),
                equinoctial: EquinoctialElements {
                    sma_km: equinoctial[0],
                    mean_longitude_rad: equinoctial[1],
                    ex: equinoctial[2],
                    ey: equinoctial[3],
                    hx: equinoctial[4],
                    hy: equinoctial[5],
                },
            })
        }
        Err(stage) => {
            if !failed(&status) {
                status = SolveStatus::NumericalFailure(stage);
            }
            None
        }
    };
    if !rep.correction_used {
        seq.steps = linear_steps;
        seq.final_time_s = linear_final_time_s;
    }
    out.impulses.clear();
    for ((step, point), dv_chunk) in seq
        .steps
        .iter()
        .zip(pts.at.iter())
        .zip(rep.dv.as_slice().chunks_exact(3))
        .take(pts.n)
    {
        // Every component is overwritten: chunks_exact(3) yields exactly three.
        let mut dv_rtn_mps = [0.0; 3];
        for (d, x) in dv_rtn_mps.iter_mut().zip(dv_chunk.iter()) {
            *d = *x * M_PER_KM;
        }
        let imp = Impulse {
            time_s: step.time_s,
            arg_latitude_rad: wrap_two_pi(ctx.model.phase_rad(&step.at)),
            true_arg_latitude_rad: wrap_two_pi(
                ctx.model.true_phase_rad(&step.at, step.true_anomaly_rad),
            ),
            revolutions: point.revolutions,
            dv_rtn_mps,
        };
        // Capacity equals MAX_IMPULSES and pts.n <= MAX_IMPULSES, so this cannot fail.
        let _ = out.impulses.push(imp);
    }
    out.total_dv_mps = total(&rep.dv) * M_PER_KM;
    out.min_norm_total_dv_mps = finite(rep.min_norm_total_km_s * M_PER_KM);
    out.linear_total_dv_mps = finite(rep.linear_total_km_s * M_PER_KM);
    out.final_time_s = seq.final_time_s;
    out.terminal_error = terminal.filter(|t| {
        [t.along_track_m, t.position_m]
            .iter()
            .chain(t.elements.as_array().iter())
            .chain(t.equinoctial.as_array().iter())
            .all(|x| x.is_finite())
    });
    out.info.iterations = rep.iterations;
    out.info.min_fuel_iterations = rep.min_fuel_steps;
    out.info.min_fuel_gap_mps = if rep.min_fuel_used {
        rep.min_fuel_gap_km_s * M_PER_KM
    } else {
        0.0
    };
    out.info.correction_iterations = rep.correction_steps;
    out.info.rank = rep.conditioning.rank;
    // Rank-deficient F has no finite condition number: absent (the rank says why).
    out.info.condition_number = if rep.conditioning.rank < 6 {
        None
    } else {
        finite(rep.conditioning.condition_number)
    };
    out.info.min_fuel_used = rep.min_fuel_used;
    out.info.correction_used = rep.correction_used;
    out.info.evaluations = evaluations;
    out.info.status = status;
    if !plan_is_finite(out) {
        // No plan with a non-finite number leaves: none at all, and the status says why.
        out.impulses.clear();
        out.total_dv_mps = 0.0;
        out.final_time_s = 0.0;
        if !failed(&out.info.status) {
            out.info.status = SolveStatus::NumericalFailure(Stage::NonFinite);
        }
    }
}
