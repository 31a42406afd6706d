//! A client's trajectory over an arc in the planning model, kept as equally spaced checkpoints
//! so that its state at any epoch costs at most one checkpoint interval of RK4 steps and does
//! not depend on which epochs were asked before (the search asks in any order).

use super::j2::{propagate_steps, step_count, Gravity, State};
use super::types::{Settings, CHECKPOINTS};
use crate::work::Meter;

/// Checkpoints of one trajectory.
#[derive(Clone, Copy, Debug)]
pub struct Track {
    states: [State; CHECKPOINTS],
    spacing_s: f64,
}

impl Track {
    /// The trajectory from `start` over `duration_s`: `CHECKPOINTS` propagations of
    /// `duration_s / CHECKPOINTS`. `None` when a propagation is refused or not finite.
    pub fn new(
        g: &Gravity,
        settings: &Settings,
        start: &State,
        duration_s: f64,
        meter: &mut Meter,
    ) -> Option<Self> {
        let spacing_s = duration_s / (CHECKPOINTS as f64);
        let n = step_count(spacing_s, settings.step_s, settings.max_steps)?;
        let mut states = [*start; CHECKPOINTS];
        let mut s = *start;
        for slot in states.iter_mut() {
            *slot = s;
            if !meter.spend(u64::from(n)) {
                return None;
            }
            s = propagate_steps(g, &s, spacing_s, n)?;
        }
        Some(Self { states, spacing_s })
    }

    /// The state at the arc start.
    pub fn start(&self) -> State {
        let [first, ..] = self.states;
        first
    }

    /// The state at `t_s` (clamped to the arc), from the checkpoint at or before it.
    pub fn state_at(
        &self,
        g: &Gravity,
        settings: &Settings,
        t_s: f64,
        meter: &mut Meter,
    ) -> Option<State> {
        let k = libm::floor(t_s / self.spacing_s).clamp(0.0, (CHECKPOINTS - 1) as f64);
        // k is a whole number in [0, CHECKPOINTS - 1].
        #[allow(clippy::cast_possible_truncation, clippy::cast_sign_loss)]
        let idx = k as usize;
        let base = self.states.get(idx)?;
        let dt = t_s - k * self.spacing_s;
        let n = step_count(dt, settings.step_s, settings.max_steps)?;
        if !meter.spend(u64::from(n)) {
            return None;
        }
        propagate_steps(g, base, dt, n)
    }
}
