//! The damped Newton iteration every shooting shares (fixed time, minimum time, the impulse
//! free): linearise at the iterate (a propagation with the state-transition matrix), stop when
//! the residual's largest component is within the tolerance or the iterations run out, else
//! take the Newton step, halved until the residual falls (each trial a propagation without the
//! matrix). Each shooting supplies its residual, its Jacobian's solve and how a step moves its
//! unknowns ([`System`]).

use super::integrate::{Counts, Stop};
use super::shooting::{Settings, Status};
use nalgebra::SVector;

/// A shooting's equations, as the iteration sees them.
pub(crate) trait System<const K: usize> {
    /// The unknowns.
    type Point: Copy;

    /// The residual at `p` and the Newton step there (`None`: the Jacobian is singular).
    ///
    /// # Errors
    /// The propagation's [`Stop`].
    #[allow(clippy::type_complexity)]
    fn linearised(
        &self,
        p: &Self::Point,
        counts: &mut Counts,
    ) -> Result<(SVector<f64, K>, Option<SVector<f64, K>>), Stop>;

    /// The residual at `p`; `None` where it cannot be flown.
    fn residual(&self, p: &Self::Point, counts: &mut Counts) -> Option<SVector<f64, K>>;

    /// `p` moved by `fraction` of `step`; `None` where that leaves the unknowns' domain.
    fn moved(&self, p: &Self::Point, step: &SVector<f64, K>, fraction: f64) -> Option<Self::Point>;
}

/// How the iteration ended and where.
pub(crate) struct Outcome<P> {
    /// How it ended.
    pub status: Status,
    /// The converged unknowns, or the best iterate.
    pub point: P,
    /// Largest component of the residual at `point` (infinite when it could not be flown).
    pub residual: f64,
    /// Newton iterations done.
    pub iterations: u32,
    /// The integrations' work.
    pub counts: Counts,
}

/// Iterate from `start` under `settings`: at most `max_iterations` linearisations and
/// `max_iterations × (max_halvings + 1)` trial residuals.
pub(crate) fn iterate<const K: usize, S: System<K>>(
    system: &S,
    start: S::Point,
    settings: &Settings,
) -> Outcome<S::Point> {
    let mut counts = Counts::default();
    let mut point = start;
    let mut iterations = 0;
    let end = |status, point, residual, iterations, counts| Outcome {
        status,
        point,
        residual,
        iterations,
        counts,
    };
    loop {
        let (f, step) = match system.linearised(&point, &mut counts) {
            Ok(v) => v,
            Err(stop) => {
                return end(
                    Status::Integration(stop),
                    point,
                    f64::INFINITY,
                    iterations,
                    counts,
                )
            }
        };
        let size = f.amax();
        if size <= settings.tolerance {
            return end(Status::Converged, point, size, iterations, counts);
        }
        if iterations >= settings.max_iterations {
            return end(Status::IterationLimit, point, size, iterations, counts);
        }
        iterations = iterations.saturating_add(1);
        let Some(step) = step else {
            return end(Status::Singular, point, size, iterations, counts);
        };
        // Halve the step until the residual falls (a damped Newton iteration).
        let mut fraction = 1.0;
        let mut accepted = false;
        for _ in 0..=settings.max_halvings {
            if let Some(trial) = system.moved(&point, &step, fraction) {
                if let Some(r) = system.residual(&trial, &mut counts) {
                    if r.amax() < size {
                        point = trial;
                        accepted = true;
                        break;
                    }
                }
            }
            fraction *= 0.5;
        }
        if !accepted {
            return end(Status::NoDescent, point, size, iterations, counts);
        }
    }
}
