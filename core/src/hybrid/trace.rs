//! Flying a transfer once more after its shooting: the trajectory at evenly spaced times, every
//! switch of the bang-bang law located, the thrust arcs counted and the Hamiltonian's drift
//! measured. It is the check of a returned plan (its end against the arrival, H constant) and
//! the source of the host's reports and plots, so that both show one computation.

use super::dynamics::{Augmented, Model, Throttle};
use super::flow::{bang_bang, propagate_observed};
use super::integrate::{Counts, Stop, Tolerance};

/// Switch times a flight keeps (the count goes on beyond them).
pub const MAX_SWITCH_TIMES: usize = 32;

/// The state at one sample time.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Sample {
    /// Time from the departure, TU.
    pub time_tu: f64,
    /// The canonical system's state.
    pub state: Augmented,
    /// The throttle there, in [0, 1].
    pub throttle: f64,
    /// The switching function there.
    pub switching: f64,
    /// The Hamiltonian there.
    pub hamiltonian: f64,
}

/// What a flight found.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Flight {
    /// The state at the end.
    pub end: Augmented,
    /// Switches of the bang-bang law (all of them; 0 for another law).
    pub switches: u32,
    /// The first [`MAX_SWITCH_TIMES`] switch times, TU from the departure (the rest 0).
    pub switch_times_tu: [f64; MAX_SWITCH_TIMES],
    /// Arcs of full thrust: for the bang-bang law counted at its switches; for the smoothed
    /// law the runs of samples with the throttle above one half; for full thrust 1.
    pub thrust_arcs: u32,
    /// Largest `|H(t) − H(0)|` over the samples and the switches.
    pub hamiltonian_drift: f64,
}

/// How long to fly and in how many pieces.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Span {
    /// The flight's duration, TU (either sign).
    pub duration_tu: f64,
    /// Pieces of equal duration (at least 1 is flown): a sample at the end of each.
    pub segments: u32,
}

/// Fly `law` from `y0` over `span`, calling `visit` at the start and at the end of each
/// piece; the integrations count into `counts` and stop at `tol.max_steps` step trials.
///
/// # Errors
/// The integrator's [`Stop`].
pub fn fly(
    model: &Model,
    law: Throttle,
    y0: &Augmented,
    span: Span,
    tol: &Tolerance,
    counts: &mut Counts,
    visit: &mut dyn FnMut(&Sample),
) -> Result<Flight, Stop> {
    let (duration_tu, segments) = (span.duration_tu, span.segments.max(1));
    let sample = |time_tu: f64, y: &Augmented| {
        let switching = model.switching(y);
        Sample {
            time_tu,
            state: *y,
            throttle: law.of(switching),
            switching,
            hamiltonian: model.hamiltonian(law, y),
        }
    };
    let first = sample(0.0, y0);
    visit(&first);
    let h0 = first.hamiltonian;
    let mut flight = Flight {
        end: *y0,
        switches: 0,
        switch_times_tu: [0.0; MAX_SWITCH_TIMES],
        thrust_arcs: 0,
        hamiltonian_drift: 0.0,
    };
    let bang_bang = bang_bang(law);
    let mut thrusting = first.throttle > 0.5;
    if thrusting {
        flight.thrust_arcs = 1;
    }
    let mut y = *y0;
    let mut reached = 0.0;
    for k in 1..=segments {
        let target = duration_tu * f64::from(k) / f64::from(segments);
        let start = reached;
        let mut on_switch = |offset: f64, at: &Augmented| {
            let time = start + offset;
            if let Some(slot) = usize::try_from(flight.switches)
                .ok()
                .and_then(|i| flight.switch_times_tu.get_mut(i))
            {
                *slot = time;
            }
            flight.switches = flight.switches.saturating_add(1);
            // The law switches on where it was off: the switching function falls through 0.
            if model.switching_rate(at) < 0.0 {
                flight.thrust_arcs = flight.thrust_arcs.saturating_add(1);
            }
            let drift = libm::fabs(model.hamiltonian(law, at) - h0);
            flight.hamiltonian_drift = flight.hamiltonian_drift.max(drift);
        };
        y = propagate_observed(model, law, &y, target - start, tol, counts, &mut on_switch)?;
        reached = target;
        let s = sample(target, &y);
        visit(&s);
        flight.hamiltonian_drift = flight.hamiltonian_drift.max(libm::fabs(s.hamiltonian - h0));
        if !bang_bang {
            let on = s.throttle > 0.5;
            if on && !thrusting {
                flight.thrust_arcs = flight.thrust_arcs.saturating_add(1);
            }
            thrusting = on;
        }
    }
    flight.end = y;
    Ok(flight)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::hybrid::flow::propagate;
    use crate::hybrid::units::time_tu;

    const TOL: Tolerance = Tolerance {
        relative: 1e-13,
        absolute: 1e-15,
        max_steps: 200_000,
    };

    /// A point near the halo with costates that make the bang-bang law switch a few times.
    fn start() -> Augmented {
        Augmented {
            r_lu: [0.823_385_182_067, 0.0, -0.022_277_556_273],
            v_vu: [0.0, 0.134_184_170_262, 0.0],
            m_mu: 0.35,
            lambda_r: [0.02, -0.015, 0.004],
            lambda_v: [0.006, 0.011, -0.002],
            lambda_m: 0.0,
        }
    }

    #[test]
    fn a_flight_in_pieces_ends_where_one_propagation_does_and_finds_its_switches() {
        let model = Model::paper();
        let law = Throttle::Smoothed { epsilon: 0.0 };
        let duration = time_tu(-1.5);
        let mut counts = Counts::default();
        let whole = propagate(&model, law, &start(), duration, &TOL, &mut counts).unwrap();
        let mut samples = 0;
        let mut last_time = 0.0;
        let flight = fly(
            &model,
            law,
            &start(),
            Span {
                duration_tu: duration,
                segments: 16,
            },
            &TOL,
            &mut counts,
            &mut |s| {
                samples += 1;
                last_time = s.time_tu;
            },
        )
        .unwrap();
        assert_eq!(samples, 17);
        assert_eq!(last_time.to_bits(), duration.to_bits());
        for (a, b) in flight.end.to_array().iter().zip(whole.to_array()) {
            assert!((a - b).abs() < 1e-9 * (1.0 + b.abs()), "{a} against {b}");
        }
        // It switched, every switch time lies inside the flight, in order.
        assert!(flight.switches >= 1, "{flight:?}");
        let count = usize::try_from(flight.switches)
            .unwrap()
            .min(MAX_SWITCH_TIMES);
        let times = &flight.switch_times_tu[..count];
        assert!(times.windows(2).all(|w| w[1] < w[0]), "{times:?}");
        assert!(times.iter().all(|t| *t < 0.0 && *t > duration));
        // The switching function is zero at each switch: H is continuous there, and constant.
        assert!(flight.hamiltonian_drift < 1e-10, "{flight:?}");
        assert!(flight.thrust_arcs >= 1);
    }

    #[test]
    fn a_step_bound_stops_the_flight_and_says_so() {
        let model = Model::paper();
        let tight = Tolerance {
            max_steps: 5,
            ..TOL
        };
        let mut counts = Counts::default();
        let stop = fly(
            &model,
            Throttle::Full,
            &start(),
            Span {
                duration_tu: time_tu(1.0),
                segments: 4,
            },
            &tight,
            &mut counts,
            &mut |_| {},
        );
        assert!(matches!(stop, Err(Stop::StepLimit { .. })), "{stop:?}");
        assert!(counts.step_trials() <= 5);
    }
}
