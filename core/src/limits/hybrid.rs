//! Hybrid-transfer limits: the settings' limits alone (each setting's rule is in its settings
//! table, `hybrid::SettingId::limit_rule`: ceilings of the Newton iterations, the halvings, the
//! check flight's pieces and the work budget; tolerances no looser than the defaults). The
//! problem has no size: its work is bounded by the settings.

use super::{LimitViolation, Setting};
use crate::hybrid::{Problem, Settings};
use serde::{Deserialize, Serialize};

planner_limits! {
    /// Hybrid-transfer limits. Defaults: the default settings.
    pub struct Limits {
        /// The most work and the least safety a request's settings may ask for.
        settings: Settings = Settings::DEFAULT,
    }
}

impl Limits {
    /// Check a request's settings (the problem has no size to limit).
    ///
    /// # Errors
    /// The first [`LimitViolation`], in declaration order.
    pub fn check(&self, _problem: &Problem, settings: &Settings) -> Result<(), LimitViolation> {
        settings
            .check_limits(&self.settings)
            .map_err(|v| v.naming(Setting::from))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::contract::Rule;
    use crate::hybrid::SettingId;

    #[test]
    fn defaults_pass_and_a_loosened_setting_is_named() {
        let l = Limits::default();
        let problem = Problem {
            objective: crate::hybrid::Objective::MinFuel,
            kappa: 1.4,
            theta_rad: -2.0,
            free_kappa: false,
            free_theta: false,
            duration_days: 4.38,
            thrust_n: 10.0,
            specific_impulse_s: 3000.0,
            chemical_specific_impulse_s: 300.0,
            parking_radius_km: 6778.0,
            departure_offset: [0.0; 7],
            arrival_r_lu: [0.823_385_182_067, 0.0, -0.022_277_556_273],
            arrival_v_vu: [0.0, 0.134_184_170_262, 0.0],
            halo_period_tu: 2.746_337,
            costates: [0.0; 7],
            cost_multiplier: 0.0,
            design_duration_days: 4.38,
            design_thrust_n: 10.0,
        };
        assert_eq!(l.check(&problem, &Settings::default()), Ok(()));
        let e = l
            .check(
                &problem,
                &Settings {
                    hamiltonian_tol: 1e-6,
                    ..Settings::default()
                },
            )
            .unwrap_err();
        assert_eq!(e.setting, Setting::Hybrid(SettingId::HamiltonianTol));
        assert_eq!((e.value, e.limit, e.rule), (1e-6, 1e-10, Rule::AtMost));
        let e = l
            .check(
                &problem,
                &Settings {
                    work_budget: 10_000_000,
                    ..Settings::default()
                },
            )
            .unwrap_err();
        assert_eq!(e.setting, Setting::Hybrid(SettingId::WorkBudget));
    }
}
