//! LEO-tour arc limits: ceilings of the loop bounds (RK4 steps, Lambert, shooting, grid,
//! candidates, hops, local searches) and of the work budget, the impulse count, tolerances and
//! the search's least step no looser than the defaults. One line per setting in
//! [`Limits::check_settings`]. The physical constants, the first compass steps, the least gap
//! between impulses and the search model choose the problem or the method; the work budget
//! bounds their cost, so any value passes here (the planner validates their ranges).

use super::{at_least, at_most, LimitViolation, Setting};
use crate::leo_tour::sequence::{SequenceSettings, MAX_CLIENTS};
use crate::leo_tour::{ArcProblem, Settings, MAX_IMPULSES};
use serde::{Deserialize, Serialize};

/// LEO-tour arc limits. Field names are the settings' names; each is the most (for
/// `search_min_step_s` the least) a request may ask for. Defaults: the default settings and
/// the compiled capacity.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct Limits {
    /// Most impulses of one arc.
    pub impulses: u8,
    /// Largest RK4 step, s.
    pub step_s: f64,
    /// Most RK4 steps of one propagation.
    pub max_steps: u32,
    /// Most Householder steps per Lambert solve.
    pub lambert_max_iter: u16,
    /// Loosest Lambert tolerance.
    pub lambert_tol: f64,
    /// Most whole revolutions of a Lambert leg.
    pub max_revolutions: u16,
    /// Most aim-point iterations of one J2 shooting.
    pub shoot_max_iter: u16,
    /// Loosest arrival tolerance, km.
    pub arrival_tol_km: f64,
    /// Most grid points.
    pub grid_points: u16,
    /// Most grid candidates refined.
    pub candidates: u8,
    /// Most rounds of hops.
    pub hop_rounds: u8,
    /// Most evaluations of one local refinement.
    pub search_max_evals: u32,
    /// Least epoch step of the refinement, s (a smaller one halves the step more times).
    pub search_min_step_s: f64,
    /// Most work units of one arc.
    pub work_budget: u64,
    /// Most evaluations of the planning-model polish.
    pub polish_max_evals: u32,
    /// Most clients of a sequencing.
    pub clients: u8,
    /// Most arcs a sequencing estimates.
    pub max_arcs: u32,
    /// Least band margin of the sequencing's bound, km.
    pub band_margin_km: f64,
    /// Least inclination band margin of the bound, rad.
    pub band_margin_rad: f64,
    /// Least relative margin of the bound.
    pub bound_margin: f64,
}

/// The arcs a sequencing may estimate by default: the whole tree of five clients (320) with
/// room, about 0.4 s on the development machine at 1.7 ms an arc.
pub const DEFAULT_MAX_ARCS: u32 = 400;

impl Default for Limits {
    fn default() -> Self {
        let d = Settings::default();
        let b = crate::leo_tour::bound::BoundSettings::default();
        Self {
            impulses: MAX_IMPULSES as u8,
            step_s: d.step_s,
            max_steps: d.max_steps,
            lambert_max_iter: d.lambert_max_iter,
            lambert_tol: d.lambert_tol,
            max_revolutions: d.max_revolutions,
            shoot_max_iter: d.shoot_max_iter,
            arrival_tol_km: d.arrival_tol_km,
            grid_points: d.grid_points,
            candidates: d.candidates,
            hop_rounds: d.hop_rounds,
            search_max_evals: d.search_max_evals,
            search_min_step_s: d.search_min_step_s,
            work_budget: d.work_budget,
            polish_max_evals: d.polish_max_evals,
            clients: MAX_CLIENTS as u8,
            max_arcs: DEFAULT_MAX_ARCS,
            band_margin_km: b.band_margin_km,
            band_margin_rad: b.band_margin_rad,
            bound_margin: b.margin,
        }
    }
}

impl Limits {
    /// Check a request's arc and settings.
    ///
    /// # Errors
    /// The first [`LimitViolation`]: the problem first, then settings in declaration order.
    pub fn check(&self, problem: &ArcProblem, settings: &Settings) -> Result<(), LimitViolation> {
        self.check_impulses(problem.impulses)?;
        self.check_settings(settings)
    }

    /// Check a sequencing request: its client count, impulses, its own settings (the arc
    /// limit and the bound's margins: a smaller margin prunes more) and the arc settings.
    ///
    /// # Errors
    /// The first [`LimitViolation`].
    pub fn check_sequence(
        &self,
        clients: usize,
        impulses: u8,
        settings: &SequenceSettings,
        arc_settings: &Settings,
    ) -> Result<(), LimitViolation> {
        // Exact: at most a few digits.
        #[allow(clippy::cast_precision_loss)]
        at_most(Setting::LeoClients, clients as f64, f64::from(self.clients))?;
        self.check_impulses(impulses)?;
        let SequenceSettings {
            first: _,     // a choice of the tour, not of work
            intervals: _, // the problem (validated by the sequencing)
            bound,
            max_arcs,
        } = *settings;
        at_most(
            Setting::LeoMaxArcs,
            f64::from(max_arcs),
            f64::from(self.max_arcs),
        )?;
        at_least(
            Setting::LeoBandMarginKm,
            bound.band_margin_km,
            self.band_margin_km,
        )?;
        at_least(
            Setting::LeoBandMarginRad,
            bound.band_margin_rad,
            self.band_margin_rad,
        )?;
        at_least(Setting::LeoBoundMargin, bound.margin, self.bound_margin)?;
        self.check_settings(arc_settings)
    }

    /// Check an arc's impulse count (a tour's arcs all have the same).
    ///
    /// # Errors
    /// [`Setting::LeoImpulses`] above its limit.
    pub fn check_impulses(&self, impulses: u8) -> Result<(), LimitViolation> {
        at_most(
            Setting::LeoImpulses,
            f64::from(impulses),
            f64::from(self.impulses),
        )
    }

    /// Check every setting, one line each.
    ///
    /// # Errors
    /// The first [`LimitViolation`].
    pub fn check_settings(&self, s: &Settings) -> Result<(), LimitViolation> {
        // No `..`: a new setting does not compile until it has its line here.
        let Settings {
            mu_km3_s2: _, // the problem's physics
            re_km: _,     // the problem's physics
            j2: _,        // the problem's physics
            step_s,
            max_steps,
            lambert_max_iter,
            lambert_tol,
            max_revolutions,
            shoot_max_iter,
            arrival_tol_km,
            grid_points,
            candidates,
            hop_rounds,
            search_max_evals,
            search_step_s: _,    // method choice only
            search_step_km_s: _, // method choice only
            search_min_step_s,
            min_gap_s: _, // the problem's operations constraint
            work_budget,
            search_model: _, // method choice only (the work budget bounds either)
            polish_max_evals,
        } = *s;
        use Setting as S;
        let l = self;
        let n = |v: u32| f64::from(v);
        at_most(S::LeoStepS, step_s, l.step_s)?;
        at_most(S::LeoMaxSteps, n(max_steps), n(l.max_steps))?;
        at_most(
            S::LeoLambertMaxIter,
            n(lambert_max_iter.into()),
            n(l.lambert_max_iter.into()),
        )?;
        at_most(S::LeoLambertTol, lambert_tol, l.lambert_tol)?;
        at_most(
            S::LeoMaxRevolutions,
            n(max_revolutions.into()),
            n(l.max_revolutions.into()),
        )?;
        at_most(
            S::LeoShootMaxIter,
            n(shoot_max_iter.into()),
            n(l.shoot_max_iter.into()),
        )?;
        at_most(S::LeoArrivalTolKm, arrival_tol_km, l.arrival_tol_km)?;
        at_most(
            S::LeoGridPoints,
            n(grid_points.into()),
            n(l.grid_points.into()),
        )?;
        at_most(
            S::LeoCandidates,
            n(candidates.into()),
            n(l.candidates.into()),
        )?;
        at_most(
            S::LeoHopRounds,
            n(hop_rounds.into()),
            n(l.hop_rounds.into()),
        )?;
        at_most(
            S::LeoSearchMaxEvals,
            n(search_max_evals),
            n(l.search_max_evals),
        )?;
        at_least(S::LeoSearchMinStepS, search_min_step_s, l.search_min_step_s)?;
        // Exact up to 2^53 units, far above any budget a flight computer gives.
        #[allow(clippy::cast_precision_loss)]
        at_most(S::LeoWorkBudget, work_budget as f64, l.work_budget as f64)?;
        at_most(
            S::LeoPolishMaxEvals,
            n(polish_max_evals),
            n(l.polish_max_evals),
        )
    }
}

#[cfg(test)]
#[allow(clippy::unwrap_used, clippy::float_cmp)]
mod tests {
    use super::*;
    use crate::limits::Rule;

    #[test]
    fn defaults_pass_and_a_loosened_setting_is_named() {
        let l = Limits::default();
        assert_eq!(l.check_settings(&Settings::default()), Ok(()));
        let e = l
            .check_settings(&Settings {
                hop_rounds: 50,
                ..Settings::default()
            })
            .unwrap_err();
        assert_eq!(
            (e.setting, e.value, e.limit, e.rule),
            (Setting::LeoHopRounds, 50.0, 6.0, Rule::AtMost)
        );
        assert_eq!(e.setting.name(), "hop_rounds");
        assert_eq!(e.setting.planner(), crate::wire::Planner::LeoArc);
        let e = l
            .check_settings(&Settings {
                search_min_step_s: 1e-3,
                ..Settings::default()
            })
            .unwrap_err();
        assert_eq!(
            (e.setting, e.rule),
            (Setting::LeoSearchMinStepS, Rule::AtLeast)
        );
        let e = l
            .check_settings(&Settings {
                work_budget: 1 << 40,
                ..Settings::default()
            })
            .unwrap_err();
        assert_eq!(e.setting, Setting::LeoWorkBudget);
        let tighter = Settings {
            grid_points: 32,
            hop_rounds: 0,
            work_budget: 1_000_000,
            ..Settings::default()
        };
        assert_eq!(l.check_settings(&tighter), Ok(()));
    }

    #[test]
    fn impulses_above_the_limit_are_named() {
        let l = Limits {
            impulses: 3,
            ..Limits::default()
        };
        let p = ArcProblem {
            from: [7000.0, 0.0, 0.0, 0.0, 7.5, 0.0],
            to: [7100.0, 0.0, 0.0, 0.0, 7.4, 0.0],
            duration_s: 86_400.0,
            impulses: 4,
        };
        let e = l.check(&p, &Settings::default()).unwrap_err();
        assert_eq!(
            (e.setting, e.value, e.limit),
            (Setting::LeoImpulses, 4.0, 3.0)
        );
        assert_eq!(e.setting.name(), "impulses");
    }
}
