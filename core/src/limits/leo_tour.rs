//! LEO-tour limits: the impulse count of an arc, the client count of a sequencing, and the
//! settings' limits of both (each setting's rule is in its settings table: ceilings of the loop
//! bounds and of the work budget, tolerances and the search's least step no looser than the
//! defaults; the physical constants, the first compass steps, the least gap between impulses
//! and the search model choose the problem or the method and have no limit).

use super::{at_most, LimitViolation, ProblemLimit, Setting};
use crate::leo_tour::sequence::{SequenceProblem, SequenceSettings, MAX_CLIENTS};
use crate::leo_tour::{ArcProblem, Settings, MAX_IMPULSES};
use serde::{Deserialize, Serialize};

planner_limits! {
    /// LEO-tour limits. Defaults: the compiled capacities and the default settings.
    pub struct Limits {
        /// Most impulses of one arc.
        impulses: u8 = MAX_IMPULSES as u8,
        /// Most clients of a sequencing.
        clients: u8 = MAX_CLIENTS as u8,
        /// The most work and the least safety an arc's settings may ask for (also those of a
        /// sequencing's arc estimates).
        arc: Settings = Settings::DEFAULT,
        /// The most work and the least safety a sequencing's settings may ask for.
        sequence: SequenceSettings = SequenceSettings::DEFAULT,
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
        problem: &SequenceProblem,
        settings: &SequenceSettings,
        arc_settings: &Settings,
    ) -> Result<(), LimitViolation> {
        at_most(
            Setting::Problem(ProblemLimit::Clients),
            problem.clients.len() as f64,
            f64::from(self.clients),
        )?;
        self.check_impulses(problem.impulses)?;
        settings
            .check_limits(&self.sequence)
            .map_err(|v| v.naming(Setting::from))?;
        self.check_settings(arc_settings)
    }

    /// Check an arc's impulse count (a tour's arcs all have the same).
    ///
    /// # Errors
    /// [`ProblemLimit::ArcImpulses`] above its limit.
    pub fn check_impulses(&self, impulses: u8) -> Result<(), LimitViolation> {
        at_most(
            Setting::Problem(ProblemLimit::ArcImpulses),
            f64::from(impulses),
            f64::from(self.impulses),
        )
    }

    /// Check every arc setting against its limit.
    ///
    /// # Errors
    /// The first [`LimitViolation`], in declaration order.
    pub fn check_settings(&self, s: &Settings) -> Result<(), LimitViolation> {
        s.check_limits(&self.arc)
            .map_err(|v| v.naming(Setting::from))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::contract::Rule;
    use crate::leo_tour::SettingId;

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
            (
                Setting::LeoArc(SettingId::HopRounds),
                50.0,
                6.0,
                Rule::AtMost
            )
        );
        assert_eq!(e.setting.name(), "hop_rounds");
        assert_eq!(e.setting.planner(), crate::contract::PlannerKind::LeoArc);
        let e = l
            .check_settings(&Settings {
                search_min_step_s: 1e-3,
                ..Settings::default()
            })
            .unwrap_err();
        assert_eq!(
            (e.setting, e.rule),
            (Setting::LeoArc(SettingId::SearchMinStepS), Rule::AtLeast)
        );
        let e = l
            .check_settings(&Settings {
                work_budget: 1 << 40,
                ..Settings::default()
            })
            .unwrap_err();
        assert_eq!(e.setting, Setting::LeoArc(SettingId::WorkBudget));
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
            (Setting::Problem(ProblemLimit::ArcImpulses), 4.0, 3.0)
        );
        assert_eq!(e.setting.name(), "impulses");
    }
}
