//! One flight of a coasting state, in the model the search is using: the planning model
//! (fixed-step RK4 of two-body + J2, [`super::j2`]) or the search model (the first-order J2
//! theory in closed form, [`super::mean_j2`]). Both are charged to the work meter
//! ([`super::work_units`]): RK4 by its steps, the closed form by the flight whatever its span.

use super::j2::{propagate_steps, step_count, State};
use super::{mean_j2, work_units};
use crate::astro::Gravity;
use crate::work::Meter;
use serde::{Deserialize, Serialize};

/// The model of a flight.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[repr(u8)]
pub enum Model {
    /// Two-body + J2 by fixed-step RK4: the planning model, which decides every status.
    Planning = 0,
    /// The first-order J2 theory in closed form: the search model.
    MeanElements = 1,
}

impl crate::contract::SettingValue for Model {
    fn to_f64(self) -> f64 {
        f64::from(self as u8)
    }
    fn from_f64(value: f64) -> Option<Self> {
        match u8::from_f64(value)? {
            0 => Some(Self::Planning),
            1 => Some(Self::MeanElements),
            _ => None,
        }
    }
}

/// A flight model with its constants and step bounds.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Flight {
    /// The physical constants.
    pub g: Gravity,
    /// Which model.
    pub model: Model,
    /// Largest RK4 step, s.
    pub step_s: f64,
    /// Most RK4 steps of one flight.
    pub max_steps: u32,
}

impl Flight {
    /// `s` flown for `dt_s`; `None` when the meter refuses, more than `max_steps` steps
    /// would be needed, or the state leaves the finite numbers.
    pub fn fly(&self, s: &State, dt_s: f64, meter: &mut Meter) -> Option<State> {
        match self.model {
            Model::Planning => {
                let n = step_count(dt_s, self.step_s, self.max_steps)?;
                if !meter.spend(work_units::flight(n)) {
                    return None;
                }
                propagate_steps(&self.g, s, dt_s, n)
            }
            Model::MeanElements => {
                if !dt_s.is_finite() || !meter.spend(work_units::MEAN_FLIGHT) {
                    return None;
                }
                mean_j2::fly(&self.g, s, dt_s)
            }
        }
    }

    /// The same model with J2 scaled by `fraction` (continuation in J2).
    pub fn with_j2_fraction(&self, fraction: f64) -> Self {
        Self {
            g: Gravity {
                j2: self.g.j2 * fraction,
                ..self.g
            },
            ..*self
        }
    }
}
