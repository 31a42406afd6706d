//! A planner-B request in the form the user gave it (issue 10 item 2), converted to the
//! planner's [`Problem`] here, once, for the CLI, the flight service and the firmware alike; and
//! the plan's end state written back in the same form.
//!
//! The chief (and the deputy's own orbits) may be classical mean elements, equinoctial mean
//! elements or an osculating ECI state (first-order J2 averaging, [`super::forms`]); the
//! relative state may be element differences, quasi-nonsingular ROE in metres, or the deputy's
//! own initial and target orbits. Every conversion is a fixed number of closed-form steps plus
//! the bounded iterations of [`super::forms`] (`OSCULATING_MAX_ITER` steps of the
//! osculating-to-mean inverse, each with at most 30 Kepler steps, per state given).

use super::forms::{
    classical_of, deputy_of, equinoctial_of, mean_and_evaluations_of_osculating_state,
    osculating_state_of_mean, relative_between, relative_of_roe, roe_of, CartesianState, FormError,
    Roe,
};
use super::settings::Settings;
use super::solution::Solution;
use super::types::{EquinoctialElements, ImpulsePlan, MeanElements, Problem, RelativeElements};
use serde::{Deserialize, Serialize};

/// One orbit in any of the three forms.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub enum OrbitForm {
    /// Classical mean elements.
    Classical(MeanElements),
    /// Equinoctial mean elements.
    Equinoctial(EquinoctialElements),
    /// An osculating ECI state (converted by first-order J2 averaging).
    State(CartesianState),
}

/// The relative state in any of its forms.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub enum RelativeForm {
    /// Deputy-minus-chief classical mean elements (the [`Problem`]'s own form).
    Elements {
        /// At the epoch.
        initial: RelativeElements,
        /// Wanted after the last impulse.
        target: RelativeElements,
    },
    /// Quasi-nonsingular relative orbital elements in metres on the chief.
    Roe {
        /// At the epoch.
        initial: Roe,
        /// Wanted after the last impulse.
        target: Roe,
    },
    /// The deputy's own orbits: at the epoch, and the target orbit as it would be at the epoch
    /// (it drifts with the chief to the last impulse, like a relative target).
    Deputy {
        /// At the epoch.
        initial: OrbitForm,
        /// The target orbit, referred to the epoch.
        target: OrbitForm,
    },
}

/// A planner-B request with its orbits in the forms the user gave.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct FormProblem {
    /// The chief at the epoch.
    pub chief: OrbitForm,
    /// The deputy relative to the chief (or its own orbits).
    pub relative: RelativeForm,
    /// Impulse points or a search.
    pub plan: ImpulsePlan,
}

/// Which orbit or part of a [`FormProblem`] a conversion failed on.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[repr(u8)]
pub enum FormPart {
    /// The chief.
    Chief = 0,
    /// The initial relative state (ROE), or the deputy's initial orbit.
    Initial = 1,
    /// The target relative state (ROE), or the deputy's target orbit.
    Target = 2,
}

/// The form the plan's end state is written in: the form the user gave the target in.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[repr(u8)]
pub enum EndForm {
    /// Relative classical element differences.
    Elements = 0,
    /// ROE in metres.
    Roe = 1,
    /// The deputy's own orbit as classical mean elements.
    DeputyClassical = 2,
    /// The deputy's own orbit as equinoctial mean elements.
    DeputyEquinoctial = 3,
    /// The deputy's own orbit as an osculating ECI state.
    DeputyState = 4,
}

/// The plan's end state (the deputy after the last impulse, as flown in the nonlinear check)
/// in the form the user gave the target in. Like the target it is referred to the chief at the
/// epoch (see [`end_state`]).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub enum EndState {
    /// Achieved relative classical elements.
    Elements(RelativeElements),
    /// Achieved ROE, m.
    Roe(Roe),
    /// The deputy's achieved orbit, classical mean elements.
    DeputyClassical(MeanElements),
    /// The deputy's achieved orbit, equinoctial mean elements.
    DeputyEquinoctial(EquinoctialElements),
    /// The deputy's achieved orbit, osculating ECI state.
    DeputyState(CartesianState),
    /// The end state could not be written in the form (the plan itself is unaffected; its
    /// status says whether it is usable).
    Unavailable(FormError),
    /// The plan has no end state: its nonlinear check could not be flown (the status is a
    /// numerical failure).
    NotFlown,
}

impl OrbitForm {
    /// Classical mean elements of the orbit.
    ///
    /// # Errors
    /// [`FormError`] from the osculating-to-mean conversion of a state.
    pub fn mean(&self) -> Result<MeanElements, FormError> {
        self.mean_and_evaluations().map(|(mean, _)| mean)
    }

    /// [`Self::mean`] with the number of short-period evaluations the conversion made (0 for
    /// element forms), which the planner charges to its work meter.
    ///
    /// # Errors
    /// As [`Self::mean`].
    pub fn mean_and_evaluations(&self) -> Result<(MeanElements, u16), FormError> {
        match self {
            Self::Classical(el) => Ok((*el, 0)),
            Self::Equinoctial(q) => Ok((classical_of(q), 0)),
            Self::State(s) => mean_and_evaluations_of_osculating_state(s),
        }
    }

    fn deputy_end_form(&self) -> EndForm {
        match self {
            Self::Classical(_) => EndForm::DeputyClassical,
            Self::Equinoctial(_) => EndForm::DeputyEquinoctial,
            Self::State(_) => EndForm::DeputyState,
        }
    }
}

impl FormProblem {
    /// The form the end state is written in.
    pub fn end_form(&self) -> EndForm {
        match &self.relative {
            RelativeForm::Elements { .. } => EndForm::Elements,
            RelativeForm::Roe { .. } => EndForm::Roe,
            RelativeForm::Deputy { initial, .. } => initial.deputy_end_form(),
        }
    }

    /// The planner's [`Problem`]: every orbit converted to classical mean elements, the
    /// relative state to element differences. `settings.min_sin_inclination` is the least
    /// `|sin i|` of a chief that ROE may be given on (their node difference is
    /// `a di_y / (a sin i)`).
    ///
    /// # Errors
    /// The part and the [`FormError`] of the first conversion that fails.
    pub fn to_problem(&self, settings: &Settings) -> Result<Problem, (FormPart, FormError)> {
        self.to_problem_and_evaluations(settings)
            .map(|(problem, _)| problem)
    }

    /// [`Self::to_problem`] with the number of osculating-to-mean short-period evaluations the
    /// conversion made (at most 3 [`super::forms::OSCULATING_MAX_ITER`]), which
    /// [`super::solve_form`] charges to the work meter.
    ///
    /// # Errors
    /// As [`Self::to_problem`].
    pub fn to_problem_and_evaluations(
        &self,
        settings: &Settings,
    ) -> Result<(Problem, u32), (FormPart, FormError)> {
        let (chief, chief_evaluations) = self
            .chief
            .mean_and_evaluations()
            .map_err(|e| (FormPart::Chief, e))?;
        let mut evaluations = u32::from(chief_evaluations);
        let (initial, target) = match &self.relative {
            RelativeForm::Elements { initial, target } => (*initial, *target),
            RelativeForm::Roe { initial, target } => {
                let min = settings.min_sin_inclination;
                (
                    relative_of_roe(&chief, initial, min).map_err(|e| (FormPart::Initial, e))?,
                    relative_of_roe(&chief, target, min).map_err(|e| (FormPart::Target, e))?,
                )
            }
            RelativeForm::Deputy { initial, target } => {
                let (initial_mean, initial_evaluations) = initial
                    .mean_and_evaluations()
                    .map_err(|e| (FormPart::Initial, e))?;
                let (target_mean, target_evaluations) = target
                    .mean_and_evaluations()
                    .map_err(|e| (FormPart::Target, e))?;
                evaluations = evaluations
                    .saturating_add(u32::from(initial_evaluations))
                    .saturating_add(u32::from(target_evaluations));
                (
                    relative_between(&chief, &initial_mean),
                    relative_between(&chief, &target_mean),
                )
            }
        };
        Ok((
            Problem {
                chief,
                initial,
                target,
                plan: self.plan.clone(),
            },
            evaluations,
        ))
    }
}

/// The plan's end state in `form`. `chief` and `target` are the converted problem's; the
/// achieved relative elements are the target plus the solution's nonlinear terminal error. Like
/// the target it is referred to the chief at the epoch (the chief's drift to the last impulse
/// subtracted), so that it compares with the target entry by entry: ROE and the deputy's own
/// orbit are not invariant under the J2 drift of the chief's perigee and node, relative
/// classical elements are.
pub fn end_state(
    chief: &MeanElements,
    target: &RelativeElements,
    solution: &Solution,
    form: EndForm,
) -> EndState {
    let Some(terminal) = &solution.terminal_error else {
        return EndState::NotFlown;
    };
    let e = &terminal.elements;
    let achieved = RelativeElements {
        dsma_km: target.dsma_km + e.dsma_km,
        decc: target.decc + e.decc,
        dinc_rad: target.dinc_rad + e.dinc_rad,
        draan_rad: target.draan_rad + e.draan_rad,
        dargp_rad: target.dargp_rad + e.dargp_rad,
        dmean_anomaly_rad: target.dmean_anomaly_rad + e.dmean_anomaly_rad,
    };
    let deputy = deputy_of(chief, &achieved);
    match form {
        EndForm::Elements => EndState::Elements(achieved),
        EndForm::Roe => EndState::Roe(roe_of(chief, &achieved)),
        EndForm::DeputyClassical => EndState::DeputyClassical(deputy),
        EndForm::DeputyEquinoctial => EndState::DeputyEquinoctial(equinoctial_of(&deputy)),
        EndForm::DeputyState => match osculating_state_of_mean(&deputy) {
            Ok(s) => EndState::DeputyState(s),
            Err(e) => EndState::Unavailable(e),
        },
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn chief() -> MeanElements {
        MeanElements::test_sso_chief()
    }

    fn rel(scale: f64) -> RelativeElements {
        RelativeElements {
            dsma_km: 0.1 * scale,
            decc: 1e-5 * scale,
            dinc_rad: 2e-5 * scale,
            draan_rad: -3e-5 * scale,
            dargp_rad: 1e-3 * scale,
            dmean_anomaly_rad: -1.2e-3 * scale,
        }
    }

    #[test]
    fn every_form_converts_to_the_same_problem() {
        let c = chief();
        let s = Settings::default();
        let plan = ImpulsePlan::Search {
            impulses: 2,
            max_revolutions: 5,
        };
        let base = FormProblem {
            chief: OrbitForm::Classical(c),
            relative: RelativeForm::Elements {
                initial: rel(1.0),
                target: rel(-1.0),
            },
            plan: plan.clone(),
        };
        let p0 = base.to_problem(&s).unwrap();
        assert_eq!(base.end_form(), EndForm::Elements);
        let roe = FormProblem {
            relative: RelativeForm::Roe {
                initial: roe_of(&c, &rel(1.0)),
                target: roe_of(&c, &rel(-1.0)),
            },
            ..base.clone()
        };
        assert_eq!(roe.end_form(), EndForm::Roe);
        let p1 = roe.to_problem(&s).unwrap();
        assert!((p1.initial.dsma_km - p0.initial.dsma_km).abs() < 1e-12);
        assert!((p1.target.dinc_rad - p0.target.dinc_rad).abs() < 1e-15);
        let deputy = FormProblem {
            chief: OrbitForm::Equinoctial(equinoctial_of(&c)),
            relative: RelativeForm::Deputy {
                initial: OrbitForm::State(
                    osculating_state_of_mean(&deputy_of(&c, &rel(1.0))).unwrap(),
                ),
                target: OrbitForm::Classical(deputy_of(&c, &rel(-1.0))),
            },
            plan,
        };
        assert_eq!(deputy.end_form(), EndForm::DeputyState);
        let p2 = deputy.to_problem(&s).unwrap();
        assert!((p2.chief.sma_km - c.sma_km).abs() < 1e-9);
        assert!((p2.initial.dsma_km - p0.initial.dsma_km).abs() < 1e-8);
        assert!((p2.target.decc - p0.target.decc).abs() < 1e-12);
    }

    #[test]
    fn conversion_failures_name_the_part() {
        let mut c = chief();
        c.inc_rad = 0.0;
        let p = FormProblem {
            chief: OrbitForm::Classical(c),
            relative: RelativeForm::Roe {
                initial: roe_of(&chief(), &rel(1.0)),
                target: roe_of(&chief(), &rel(1.0)),
            },
            plan: ImpulsePlan::Search {
                impulses: 2,
                max_revolutions: 5,
            },
        };
        assert!(matches!(
            p.to_problem(&Settings::default()),
            Err((FormPart::Initial, FormError::RoeEquatorialChief { .. }))
        ));
        let hyperbolic = FormProblem {
            chief: OrbitForm::State(CartesianState {
                pos_km: [7000.0, 0.0, 0.0],
                vel_km_s: [0.0, 12.0, 0.0],
            }),
            ..p
        };
        assert_eq!(
            hyperbolic.to_problem(&Settings::default()),
            Err((FormPart::Chief, FormError::NotAnEllipse))
        );
    }

    #[test]
    fn end_state_of_a_perfect_plan_is_the_target_in_its_form() {
        let c = chief();
        let mut sol = Solution::new();
        assert_eq!(
            end_state(&chief(), &rel(1.0), &sol, EndForm::Roe),
            EndState::NotFlown
        );
        sol.terminal_error = Some(crate::impulsive::TerminalError {
            along_track_m: 0.0,
            position_m: 0.0,
            elements: rel(0.0),
            equinoctial: EquinoctialElements {
                sma_km: 0.0,
                mean_longitude_rad: 0.0,
                ex: 0.0,
                ey: 0.0,
                hx: 0.0,
                hy: 0.0,
            },
        });
        let t = rel(1.0);
        match end_state(&c, &t, &sol, EndForm::Roe) {
            EndState::Roe(r) => assert_eq!(r, roe_of(&c, &t)),
            other => panic!("{other:?}"),
        }
        match end_state(&c, &t, &sol, EndForm::DeputyEquinoctial) {
            EndState::DeputyEquinoctial(q) => assert_eq!(q, equinoctial_of(&deputy_of(&c, &t))),
            other => panic!("{other:?}"),
        }
        assert!(matches!(
            end_state(&c, &t, &sol, EndForm::DeputyState),
            EndState::DeputyState(_)
        ));
    }
}
