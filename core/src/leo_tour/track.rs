//! A client's trajectory over an arc in the planning model, kept as equally spaced checkpoints
//! so that its state at any epoch costs at most one checkpoint interval of RK4 steps and does
//! not depend on which epochs were asked before (the search asks in any order).

use super::flight::Flight;
use super::j2::State;
use super::types::CHECKPOINTS;
use crate::work::Meter;

/// Checkpoints of one trajectory.
#[derive(Clone, Copy, Debug)]
pub struct Track {
    states: [State; CHECKPOINTS],
    spacing_s: f64,
}

impl Track {
    /// No trajectory yet (zero checkpoints), for a workspace's initial value.
    pub const fn empty() -> Self {
        Self {
            states: [[0.0; 6]; CHECKPOINTS],
            spacing_s: 0.0,
        }
    }

    /// Make this the trajectory from `start` over `duration_s` flown by `flight` (the planning
    /// model), in place: `CHECKPOINTS` flights of `duration_s / CHECKPOINTS`. `None` when a
    /// flight is refused or not finite (the checkpoints are then partly written: unusable).
    pub fn fill(
        &mut self,
        flight: &Flight,
        start: &State,
        duration_s: f64,
        meter: &mut Meter,
    ) -> Option<()> {
        self.spacing_s = duration_s / (CHECKPOINTS as f64);
        let mut s = *start;
        for slot in self.states.iter_mut() {
            *slot = s;
            s = flight.fly(&s, self.spacing_s, meter)?;
        }
        Some(())
    }

    /// The state at `t_s` (clamped to the arc), from the checkpoint at or before it.
    pub fn state_at(&self, flight: &Flight, t_s: f64, meter: &mut Meter) -> Option<State> {
        let k = libm::floor(t_s / self.spacing_s).clamp(0.0, (CHECKPOINTS - 1) as f64);
        // k is a whole number in [0, CHECKPOINTS - 1].
        #[allow(clippy::cast_possible_truncation, clippy::cast_sign_loss)]
        let idx = k as usize;
        let base = self.states.get(idx)?;
        flight.fly(base, t_s - k * self.spacing_s, meter)
    }
}
