//! Planner-B limits on a request in the user's input forms ([`FormProblem`]): besides the plan
//! and the settings, every orbit given as equinoctial elements or an osculating ECI state must
//! be an ellipse (eccentricity below 1) whose perigee clears `min_perigee_altitude_km`, and ROE
//! need a chief inclined enough to carry them (`|sin i| >= min_sin_inclination`). Each refusal
//! names the field, its value and the limit. Orbits given as classical mean elements are
//! validated by the planner itself ([`crate::impulsive::PlanError`] names them); a NaN or an
//! infinity, given or computed (the eccentricity of a state at 1e300 km), passes here and is
//! named by the conversion or the planner.

use super::impulsive::Limits;
use super::{at_least, below, LimitViolation, ProblemLimit, Setting};
use crate::astro::EARTH_RADIUS_KM;
use crate::impulsive::{osculating_shape, FormProblem, OrbitForm, RelativeForm, Settings};

/// The two settings an orbit's checks are named by.
struct Names {
    eccentricity: Setting,
    perigee_altitude_km: Setting,
}

const CHIEF: Names = Names {
    eccentricity: Setting::Problem(ProblemLimit::ChiefEccentricity),
    perigee_altitude_km: Setting::Problem(ProblemLimit::ChiefPerigeeAltitudeKm),
};
const DEPUTY_INITIAL: Names = Names {
    eccentricity: Setting::Problem(ProblemLimit::DeputyInitialEccentricity),
    perigee_altitude_km: Setting::Problem(ProblemLimit::DeputyInitialPerigeeAltitudeKm),
};
const DEPUTY_TARGET: Names = Names {
    eccentricity: Setting::Problem(ProblemLimit::DeputyTargetEccentricity),
    perigee_altitude_km: Setting::Problem(ProblemLimit::DeputyTargetPerigeeAltitudeKm),
};

impl Limits {
    /// Check a request in the user's forms: the plan, the settings, then the orbits as given
    /// (chief, deputy initial, deputy target) and the chief of ROE.
    ///
    /// # Errors
    /// The first [`LimitViolation`].
    pub fn check_form(
        &self,
        problem: &FormProblem,
        settings: &Settings,
    ) -> Result<(), LimitViolation> {
        self.check_plan(&problem.plan)?;
        // Settings before the orbits: the perigee floor used below is the request's own,
        // which must first clear the limits' floor.
        self.check_settings(settings)?;
        let min_alt_km = settings.min_perigee_altitude_km;
        check_orbit(&problem.chief, &CHIEF, min_alt_km)?;
        match &problem.relative {
            RelativeForm::Elements { .. } => Ok(()),
            RelativeForm::Roe { .. } => at_least(
                Setting::Problem(ProblemLimit::RoeChiefSinInclination),
                sin_inclination(&problem.chief),
                settings.min_sin_inclination,
            ),
            RelativeForm::Deputy { initial, target } => {
                check_orbit(initial, &DEPUTY_INITIAL, min_alt_km)?;
                check_orbit(target, &DEPUTY_TARGET, min_alt_km)
            }
        }
    }
}

/// Eccentricity below 1 and perigee altitude at least `min_alt_km`, of the orbit as given: the
/// osculating conic of a state (at the epoch the spacecraft flies it), the mean ellipse of
/// equinoctial elements.
fn check_orbit(orbit: &OrbitForm, names: &Names, min_alt_km: f64) -> Result<(), LimitViolation> {
    let (ecc, perigee_km) = match orbit {
        OrbitForm::Classical(_) => return Ok(()),
        OrbitForm::Equinoctial(q) => {
            let ecc = libm::sqrt(q.ex * q.ex + q.ey * q.ey);
            (ecc, q.sma_km * (1.0 - ecc))
        }
        OrbitForm::State(s) => osculating_shape(s),
    };
    below(names.eccentricity, ecc, 1.0)?;
    at_least(
        names.perigee_altitude_km,
        perigee_km - EARTH_RADIUS_KM,
        min_alt_km,
    )
}

/// `|sin i|` of the chief as given (osculating for a state).
fn sin_inclination(orbit: &OrbitForm) -> f64 {
    match orbit {
        OrbitForm::Classical(el) => libm::fabs(libm::sin(el.inc_rad)),
        OrbitForm::Equinoctial(q) => {
            // tan(i/2) = |h|, sin i = 2 |h| / (1 + |h|^2).
            let t2 = q.hx * q.hx + q.hy * q.hy;
            2.0 * libm::sqrt(t2) / (1.0 + t2)
        }
        OrbitForm::State(s) => {
            let h = crate::vec3::cross(&s.pos_km, &s.vel_km_s);
            libm::sqrt(h[0] * h[0] + h[1] * h[1]) / crate::vec3::norm(&h)
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::contract::Rule;
    use crate::impulsive::{
        equinoctial_of, osculating_state_of_mean, roe_of, CartesianState, ImpulsePlan,
        MeanElements, RelativeElements,
    };

    fn chief() -> MeanElements {
        MeanElements::test_sso_chief()
    }

    fn zero() -> RelativeElements {
        RelativeElements::default()
    }

    fn problem(chief: OrbitForm, relative: RelativeForm) -> FormProblem {
        FormProblem {
            chief,
            relative,
            plan: ImpulsePlan::Search {
                impulses: 2,
                max_revolutions: 5,
            },
        }
    }

    fn state() -> CartesianState {
        osculating_state_of_mean(&chief()).unwrap()
    }

    fn elements() -> RelativeForm {
        RelativeForm::Elements {
            initial: zero(),
            target: zero(),
        }
    }

    fn check(p: &FormProblem) -> Result<(), LimitViolation> {
        Limits::default().check_form(p, &Settings::default())
    }

    #[test]
    fn every_form_passes_when_sound() {
        let c = chief();
        assert_eq!(
            check(&problem(OrbitForm::State(state()), elements())),
            Ok(())
        );
        let roe = RelativeForm::Roe {
            initial: roe_of(&c, &zero()),
            target: roe_of(&c, &zero()),
        };
        assert_eq!(
            check(&problem(OrbitForm::Equinoctial(equinoctial_of(&c)), roe)),
            Ok(())
        );
        let deputy = RelativeForm::Deputy {
            initial: OrbitForm::State(state()),
            target: OrbitForm::Equinoctial(equinoctial_of(&c)),
        };
        assert_eq!(check(&problem(OrbitForm::Classical(c), deputy)), Ok(()));
    }

    #[test]
    fn a_hyperbolic_state_is_refused_with_its_eccentricity() {
        let s = CartesianState {
            pos_km: [7000.0, 0.0, 0.0],
            vel_km_s: [0.0, 12.0, 0.0],
        };
        let e = check(&problem(OrbitForm::State(s), elements())).unwrap_err();
        assert_eq!(
            (e.setting, e.limit, e.rule),
            (
                Setting::Problem(ProblemLimit::ChiefEccentricity),
                1.0,
                Rule::Below
            )
        );
        // e = r v^2 / mu - 1 at a perigee with the velocity across the radius.
        let expected = 7000.0 * 144.0 / crate::astro::EARTH_MU_KM3_S2 - 1.0;
        assert!((e.value - expected).abs() < 1e-12, "{}", e.value);
        assert_eq!(e.setting.name(), "chief.eccentricity");
    }

    #[test]
    fn a_low_state_is_refused_with_its_perigee_altitude() {
        // Circular at 6378 + 80 km: perigee altitude 80 km, below the default 100 km.
        let r = EARTH_RADIUS_KM + 80.0;
        let v = libm::sqrt(crate::astro::EARTH_MU_KM3_S2 / r);
        let s = CartesianState {
            pos_km: [r, 0.0, 0.0],
            vel_km_s: [0.0, 0.0, v],
        };
        let deputy = RelativeForm::Deputy {
            initial: OrbitForm::State(state()),
            target: OrbitForm::State(s),
        };
        let e = check(&problem(OrbitForm::State(state()), deputy)).unwrap_err();
        assert_eq!(
            (e.setting, e.limit, e.rule),
            (
                Setting::Problem(ProblemLimit::DeputyTargetPerigeeAltitudeKm),
                100.0,
                Rule::AtLeast
            )
        );
        assert!((e.value - 80.0).abs() < 1e-9, "{}", e.value);
    }

    #[test]
    fn equinoctial_elements_are_refused_by_eccentricity_and_perigee() {
        let mut q = equinoctial_of(&chief());
        q.ex = 0.8;
        q.ey = 0.6;
        let deputy = RelativeForm::Deputy {
            initial: OrbitForm::Equinoctial(q),
            target: OrbitForm::Classical(chief()),
        };
        let e = check(&problem(OrbitForm::Classical(chief()), deputy)).unwrap_err();
        assert_eq!(
            (e.setting, e.rule),
            (
                Setting::Problem(ProblemLimit::DeputyInitialEccentricity),
                Rule::Below
            )
        );
        assert!((e.value - 1.0).abs() < 1e-15);
        let mut q = equinoctial_of(&chief());
        q.ex = 0.1;
        q.ey = 0.0;
        let e = check(&problem(OrbitForm::Equinoctial(q), elements())).unwrap_err();
        assert_eq!(
            e.setting,
            Setting::Problem(ProblemLimit::ChiefPerigeeAltitudeKm)
        );
        assert!((e.value - (7078.137 * 0.9 - EARTH_RADIUS_KM)).abs() < 1e-6);
    }

    #[test]
    fn roe_on_an_equatorial_chief_are_refused_with_its_sin_i() {
        let mut c = chief();
        c.inc_rad = 1e-4;
        let roe = RelativeForm::Roe {
            initial: roe_of(&chief(), &zero()),
            target: roe_of(&chief(), &zero()),
        };
        let e = check(&problem(OrbitForm::Equinoctial(equinoctial_of(&c)), roe)).unwrap_err();
        assert_eq!(
            (e.setting, e.limit, e.rule),
            (
                Setting::Problem(ProblemLimit::RoeChiefSinInclination),
                Settings::default().min_sin_inclination,
                Rule::AtLeast
            )
        );
        assert!((e.value - 1e-4).abs() < 1e-12, "{}", e.value);
        assert_eq!(e.setting.planner(), crate::contract::PlannerKind::Impulsive);
    }

    #[test]
    fn a_violation_carries_finite_numbers_only() {
        // Issue 29 (finite answers), found by tests/finite_answers.rs: an infinite
        // `min_sin_inclination` was the limit of a ROE chief's check (`limit: inf`), and the
        // eccentricity of a state at 1e300 km overflowed to the violation's value. Both now
        // pass here; the planner names them (the setting by its range, the state as given).
        let c = chief();
        let roe = RelativeForm::Roe {
            initial: roe_of(&c, &zero()),
            target: roe_of(&c, &zero()),
        };
        let settings = Settings {
            min_sin_inclination: f64::INFINITY,
            ..Settings::default()
        };
        let p = problem(OrbitForm::Classical(c), roe);
        assert_eq!(Limits::default().check_form(&p, &settings), Ok(()));
        let mut far = state();
        far.pos_km[0] = 1e300;
        assert_eq!(check(&problem(OrbitForm::State(far), elements())), Ok(()));
        // A finite violation is still refused.
        let e = check(&problem(
            OrbitForm::State(CartesianState {
                pos_km: [7000.0, 0.0, 0.0],
                vel_km_s: [0.0, 12.0, 0.0],
            }),
            elements(),
        ))
        .unwrap_err();
        assert!(e.value.is_finite() && e.limit.is_finite());
    }

    #[test]
    fn the_plan_and_settings_are_checked_first() {
        let l = Limits {
            search: false,
            ..Limits::default()
        };
        let e = l
            .check_form(
                &problem(OrbitForm::State(state()), elements()),
                &Settings::default(),
            )
            .unwrap_err();
        assert_eq!(e.setting, Setting::Problem(ProblemLimit::Search));
    }
}
