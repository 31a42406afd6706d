//! The truth-model check of a planner-B plan: fly the plan's impulses from the osculating states
//! of the chief and the deputy in the truth model and measure where the deputy ends against the
//! formation the plan promised.
//!
//! * Start: the chief's mean elements and the deputy's (chief + initial relative elements), each
//!   turned into an osculating inertial state by the core's first-order J2 conversion
//!   (`reconfig_core::impulsive::osculating_state_of_mean`).
//! * Flight: the chief coasts; the deputy gets each impulse (its RTN components, in its own local
//!   frame of that instant) at the plan's epoch; both are propagated to the last impulse.
//! * Miss against the target: the deputy's position relative to the chief in the truth model,
//!   in the chief's local frame (radial, along-track, normal), minus the target formation's at
//!   the same instant in the planner's model (`formation_position_rtn_km`: the target relative
//!   elements formed at the last impulse); the same for the velocity seen in the chief's
//!   rotating frame (the model's by a central difference over +-0.5 s).
//! * Miss against the planner's J2 model: the same truth relative position minus the one the
//!   planner's model predicts for the flown plan (`relative_position_rtn_km`); it differs from
//!   the miss against the target by the planner's own terminal error (micrometres).
//! * The planner's model treats mean elements as two-body elements at each instant, so even a
//!   perfect J2 plan shows the short-period J2 differential of the formation here (metres for
//!   a formation of kilometres); the J2-only run measures that part alone.

use super::forces::ForceModel;
use super::gravity::FieldTerms;
use super::gravity_model::GravityModel;
use super::integrator::Tolerance;
use super::propagate::{propagate, Burn, EciState};
use crate::fixture::impulsive::ImpulsiveFixture;
use anyhow::{anyhow, bail, Result};
use reconfig_core::astro::{EARTH_J2, EARTH_MU_KM3_S2, EARTH_RADIUS_KM};
use reconfig_core::impulsive::{
    deputy_of, formation_position_rtn_km, osculating_state_of_mean, relative_position_rtn_km,
    solve, CartesianState, MeanElements, Solution, Workspace,
};
use std::time::Instant;

/// How the truth model is set up for a check.
#[derive(Clone, Debug, PartialEq)]
pub struct TruthSettings {
    /// Julian date (TT) of the plan's epoch (t = 0).
    pub epoch_jd: f64,
    /// The chief's ballistic coefficient `Cd A / m`, m^2/kg.
    pub chief_ballistic_m2_kg: f64,
    /// The deputy's ballistic coefficient, m^2/kg.
    pub deputy_ballistic_m2_kg: f64,
}

impl TruthSettings {
    /// The stated defaults: epoch 2025-01-01T00:00:00 TT, `Cd A / m = 0.022 m^2/kg` for both
    /// (Cd 2.2, 0.01 m^2/kg: a small satellite of 100 kg and 1 m^2).
    pub fn default_settings() -> Self {
        Self {
            epoch_jd: super::ephemeris::julian_date(2025, 1, 1, 0, 0, 0.0),
            chief_ballistic_m2_kg: 0.022,
            deputy_ballistic_m2_kg: 0.022,
        }
    }
}

/// Where the deputy ended in one model.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize)]
pub struct Miss {
    /// Relative position minus the target formation's, chief's local frame, m.
    pub target_rtn_m: [f64; 3],
    /// Norm of `target_rtn_m`, m.
    pub target_m: f64,
    /// Relative velocity minus the target formation's, in the chief's rotating local frame,
    /// mm/s.
    pub target_vel_rtn_mm_s: [f64; 3],
    /// Truth relative position minus the planner model's, chief's local frame, m.
    pub j2_model_rtn_m: [f64; 3],
    /// Norm of `j2_model_rtn_m`, m.
    pub j2_model_m: f64,
    /// Integrator steps of the chief and of the deputy.
    pub steps: [usize; 2],
    /// Host wall time of the chief's and of the deputy's propagation, s (not deterministic).
    pub time_s: [f64; 2],
}

/// A [`Miss`] and the deputy's end state it came from.
struct Flown {
    miss: Miss,
    deputy_end: EciState,
}

impl Miss {
    fn with_deputy(self, deputy_end: EciState) -> Flown {
        Flown {
            miss: self,
            deputy_end,
        }
    }
}

/// The check of one fixture's plan.
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub struct PlanCheck {
    /// The fixture's name.
    pub name: String,
    /// The planner's status.
    pub status: String,
    /// The plan's total dv, m/s.
    pub total_dv_mps: f64,
    /// The last impulse, s from the epoch (the end of the check).
    pub final_time_s: f64,
    /// The plan's own terminal position error in its model, m (absent when its nonlinear check
    /// could not be flown).
    pub planner_terminal_error_m: Option<f64>,
    /// The deputy's end position in the full model minus the J2-only one, norm, m: what the
    /// forces beyond J2 move it by (absolute, not relative to the chief).
    pub deputy_full_minus_j2_only_m: f64,
    /// In the full truth model (field 8 x 8, drag, Sun, Moon).
    pub full: Miss,
    /// In the truth model with J2 alone, with the core's constants (the planner's physics,
    /// without its first-order averaging).
    pub j2_only: Miss,
}

/// The full truth model with these settings' epoch and a ballistic coefficient.
pub fn full_model(settings: &TruthSettings, ballistic_m2_kg: f64) -> Result<ForceModel> {
    Ok(ForceModel::full(
        GravityModel::jgm3()?,
        settings.epoch_jd,
        ballistic_m2_kg,
    ))
}

/// J2 alone with the core's mu, radius and J2: the planner's own force.
pub fn j2_model(settings: &TruthSettings) -> Result<ForceModel> {
    let mut g = GravityModel::jgm3()?;
    g.name = "core J2".into();
    g.gm_km3_s2 = EARTH_MU_KM3_S2;
    g.radius_km = EARTH_RADIUS_KM;
    g.c = [[0.0; super::gravity_model::ROWS]; super::gravity_model::ROWS];
    g.s = g.c;
    g.c[0][0] = 1.0;
    g.c[2][0] = -EARTH_J2;
    let mut model = ForceModel::two_body(g, settings.epoch_jd);
    model.terms = FieldTerms::J2;
    Ok(model)
}

fn eci(s: &CartesianState) -> EciState {
    EciState {
        pos_km: s.pos_km,
        vel_km_s: s.vel_km_s,
    }
}

fn project(axes: &[[f64; 3]; 3], d: &[f64; 3]) -> [f64; 3] {
    std::array::from_fn(|k| (0..3).map(|j| axes[k][j] * d[j]).sum())
}

fn norm(v: &[f64; 3]) -> f64 {
    (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt()
}

fn sub(a: &[f64; 3], b: &[f64; 3]) -> [f64; 3] {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

/// Fly `solution` for `fixture` in the models `chief_model` and `deputy_model` (they differ
/// only by the ballistic coefficient).
fn fly(
    fixture: &ImpulsiveFixture,
    solution: &Solution,
    chief_model: &ForceModel,
    deputy_model: &ForceModel,
) -> Result<Flown> {
    let p = &fixture.problem;
    let form_err = |what: &str, e: reconfig_core::impulsive::FormError| anyhow!("{what}: {e}");
    let chief0 = osculating_state_of_mean(&p.chief).map_err(|e| form_err("chief", e))?;
    let deputy_mean0: MeanElements = deputy_of(&p.chief, &p.initial);
    let deputy0 = osculating_state_of_mean(&deputy_mean0).map_err(|e| form_err("deputy", e))?;
    let burns: Vec<Burn> = solution
        .impulses
        .iter()
        .map(|i| Burn {
            time_s: i.time_s,
            dv_rtn_mps: i.dv_rtn_mps,
        })
        .collect();
    let end_s = solution.final_time_s;
    let tol = Tolerance::TRUTH;
    let started = Instant::now();
    let chief = propagate(chief_model, &eci(&chief0), &[], end_s, &tol)?;
    let chief_time_s = started.elapsed().as_secs_f64();
    let started = Instant::now();
    let deputy = propagate(deputy_model, &eci(&deputy0), &burns, end_s, &tol)?;
    let deputy_time_s = started.elapsed().as_secs_f64();
    let axes = chief.end.rtn_axes();
    let rel_km = project(&axes, &sub(&deputy.end.pos_km, &chief.end.pos_km));
    // Velocity seen in the chief's rotating frame: inertial difference less omega x rho, with
    // omega = |h| / r^2 about the normal (the frame's turn about the radial is a perturbation's,
    // ~1e-9 rad/s, left out).
    let h = super::propagate::cross(&chief.end.pos_km, &chief.end.vel_km_s);
    let r2: f64 = chief.end.pos_km.iter().map(|x| x * x).sum();
    let omega = norm(&h) / r2;
    let dv_km_s = project(&axes, &sub(&deputy.end.vel_km_s, &chief.end.vel_km_s));
    let rel_vel_km_s = [
        dv_km_s[0] + omega * rel_km[1],
        dv_km_s[1] - omega * rel_km[0],
        dv_km_s[2],
    ];
    let formation = |t_s: f64| {
        formation_position_rtn_km(&p.chief, &p.target, end_s, t_s, &fixture.settings)
            .map_err(|e| anyhow!("the target formation at {t_s} s: {e}"))
    };
    let target_km = formation(end_s)?;
    let (ahead, behind) = (formation(end_s + 0.5)?, formation(end_s - 0.5)?);
    let target_vel_km_s = sub(&ahead, &behind);
    let target_rtn_m = sub(&rel_km, &target_km).map(|x| x * 1e3);
    let target_vel_rtn_mm_s = sub(&rel_vel_km_s, &target_vel_km_s).map(|x| x * 1e6);
    let model_rel_km = relative_position_rtn_km(p, &fixture.settings, solution, end_s)
        .map_err(|e| anyhow!("the planner's model at the end: {e}"))?;
    let j2_model_rtn_m = sub(&rel_km, &model_rel_km).map(|x| x * 1e3);
    let deputy_end = deputy.end;
    Ok(Miss {
        target_rtn_m,
        target_m: norm(&target_rtn_m),
        target_vel_rtn_mm_s,
        j2_model_rtn_m,
        j2_model_m: norm(&j2_model_rtn_m),
        steps: [chief.counters.accepted, deputy.counters.accepted],
        time_s: [chief_time_s, deputy_time_s],
    }
    .with_deputy(deputy_end))
}

/// Plan `fixture` with planner B and check the plan in the truth model (full, and J2 alone).
///
/// # Errors
/// The planner rejects the input, or a conversion or propagation fails.
pub fn check(fixture: &ImpulsiveFixture, settings: &TruthSettings) -> Result<PlanCheck> {
    let mut workspace = Box::new(Workspace::new());
    let mut solution = Box::new(Solution::new());
    solve(
        &fixture.problem,
        &fixture.settings,
        &mut workspace,
        &mut solution,
    )
    .map_err(|e| anyhow!("{}: the planner rejects the input: {e}", fixture.name))?;
    if solution.impulses.is_empty() {
        bail!("{}: the planner returned no impulses", fixture.name);
    }
    let full = fly(
        fixture,
        &solution,
        &full_model(settings, settings.chief_ballistic_m2_kg)?,
        &full_model(settings, settings.deputy_ballistic_m2_kg)?,
    )?;
    let j2 = j2_model(settings)?;
    let j2_only = fly(fixture, &solution, &j2, &j2)?;
    let deputy_full_minus_j2_only_m =
        norm(&sub(&full.deputy_end.pos_km, &j2_only.deputy_end.pos_km)) * 1e3;
    Ok(PlanCheck {
        name: fixture.name.clone(),
        status: format!("{:?}", solution.info.status),
        total_dv_mps: solution.total_dv_mps,
        final_time_s: solution.final_time_s,
        planner_terminal_error_m: solution.terminal_error.map(|t| t.position_m),
        deputy_full_minus_j2_only_m,
        full: full.miss,
        j2_only: j2_only.miss,
    })
}
