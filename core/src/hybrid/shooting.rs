//! Fixed-time shooting on the initial costates (SPEC-hybrid.md eq. 18, κ and θ fixed): from a
//! given departure state, find `λ(t0)` (7) such that the flow reaches the arrival position and
//! velocity at `t_f` with `λm(t_f) = 0` (the final mass is free). A damped Newton iteration on
//! the 7 × 7 system, its Jacobian the state-transition matrix's rows `[r, v, λm]` and columns
//! `[λr, λv, λm]`, every iteration bounded by a setting.

use super::dynamics::{Augmented, Model, Throttle};
use super::flow::{propagate, propagate_with_stm};
use super::integrate::{Counts, Stop, Tolerance};
use super::newton::{iterate, System};
use crate::vec3::Vec3;
use nalgebra::{SMatrix, SVector};

/// A fixed-time transfer between a departure state and an arrival point.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Transfer {
    /// Departure position, LU.
    pub departure_r_lu: Vec3,
    /// Departure velocity, LU/TU.
    pub departure_v_vu: Vec3,
    /// Departure mass, MU.
    pub departure_m_mu: f64,
    /// Arrival position, LU.
    pub arrival_r_lu: Vec3,
    /// Arrival velocity, LU/TU.
    pub arrival_v_vu: Vec3,
    /// Time of flight, TU.
    pub duration_tu: f64,
    /// The throttle law (the smoothed law's ε; minimum time has its own shooting).
    pub law: Throttle,
}

/// The iteration's bounds.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Settings {
    /// Newton iterations at most.
    pub max_iterations: u32,
    /// Halvings of a Newton step at most, when the full step does not lower the residual.
    pub max_halvings: u32,
    /// Converged when the residual's largest component is at most this.
    pub tolerance: f64,
    /// The integrator's tolerance and step bound, per propagation.
    pub integration: Tolerance,
}

impl Default for Settings {
    fn default() -> Self {
        Self {
            max_iterations: 30,
            max_halvings: 12,
            tolerance: 1e-10,
            integration: Tolerance {
                relative: 1e-13,
                absolute: 1e-15,
                max_steps: 100_000,
            },
        }
    }
}

/// How the shooting ended.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Status {
    /// The residual is within the tolerance.
    Converged,
    /// `max_iterations` ran out first.
    IterationLimit,
    /// No step of the last Newton direction lowered the residual.
    NoDescent,
    /// The Jacobian was singular.
    Singular,
    /// A propagation stopped early.
    Integration(Stop),
}

/// The shooting's answer: the best costates found and what is known of them.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Solution {
    /// How it ended.
    pub status: Status,
    /// Initial costates `[λr, λv, λm]`: the converged ones, or the best iterate.
    pub costates: [f64; 7],
    /// Largest component of the residual at `costates`.
    pub residual: f64,
    /// Newton iterations done.
    pub iterations: u32,
    /// The integrations' work.
    pub counts: Counts,
}

type Residual = SVector<f64, 7>;

impl Transfer {
    /// The canonical system's initial state with costates `lambda`.
    pub fn initial(&self, lambda: &[f64; 7]) -> Augmented {
        Augmented {
            r_lu: self.departure_r_lu,
            v_vu: self.departure_v_vu,
            m_mu: self.departure_m_mu,
            lambda_r: [lambda[0], lambda[1], lambda[2]],
            lambda_v: [lambda[3], lambda[4], lambda[5]],
            lambda_m: lambda[6],
        }
    }

    /// `[r(t_f) − r_f, v(t_f) − v_f, λm(t_f)]`.
    fn residual(&self, end: &Augmented) -> Residual {
        let (r, v) = (end.r_lu, end.v_vu);
        let (rf, vf) = (self.arrival_r_lu, self.arrival_v_vu);
        Residual::from([
            r[0] - rf[0],
            r[1] - rf[1],
            r[2] - rf[2],
            v[0] - vf[0],
            v[1] - vf[1],
            v[2] - vf[2],
            end.lambda_m,
        ])
    }
}

/// Shoot from `guess` (initial costates) under `settings`. Its work is bounded: at most
/// `max_iterations` propagations with the state-transition matrix and
/// `max_iterations × (max_halvings + 1)` without, each of at most `integration.max_steps` steps.
pub fn shoot(
    model: &Model,
    transfer: &Transfer,
    guess: &[f64; 7],
    settings: &Settings,
) -> Solution {
    let system = FixedTime {
        model,
        transfer,
        tol: &settings.integration,
    };
    let o = iterate(&system, *guess, settings);
    Solution {
        status: o.status,
        costates: o.point,
        residual: o.residual,
        iterations: o.iterations,
        counts: o.counts,
    }
}

/// The fixed-time shooting's equations for [`iterate`].
struct FixedTime<'a> {
    model: &'a Model,
    transfer: &'a Transfer,
    tol: &'a Tolerance,
}

// nalgebra's f64 vectors: the integer-overflow lint does not apply.
#[allow(clippy::arithmetic_side_effects)]
impl System<7> for FixedTime<'_> {
    type Point = [f64; 7];

    fn linearised(
        &self,
        lambda: &[f64; 7],
        counts: &mut Counts,
    ) -> Result<(Residual, Option<Residual>), Stop> {
        let t = self.transfer;
        let y0 = t.initial(lambda);
        let (end, phi) =
            propagate_with_stm(self.model, t.law, &y0, t.duration_tu, self.tol, counts)?;
        let f = t.residual(&end);
        // Rows r, v (0..6) and λm (13) of Φ; columns λr, λv, λm (7..14).
        let mut jac = SMatrix::<f64, 7, 7>::zeros();
        jac.fixed_view_mut::<6, 7>(0, 0)
            .copy_from(&phi.fixed_view::<6, 7>(0, 7));
        jac.fixed_view_mut::<1, 7>(6, 0)
            .copy_from(&phi.fixed_view::<1, 7>(13, 7));
        let step = super::linear::solve(&jac, &(-f));
        Ok((f, step))
    }

    fn residual(&self, lambda: &[f64; 7], counts: &mut Counts) -> Option<Residual> {
        let t = self.transfer;
        let y = t.initial(lambda);
        let end = propagate(self.model, t.law, &y, t.duration_tu, self.tol, counts).ok()?;
        Some(t.residual(&end))
    }

    fn moved(&self, lambda: &[f64; 7], step: &Residual, fraction: f64) -> Option<[f64; 7]> {
        let mut trial = *lambda;
        for (x, d) in trial.iter_mut().zip(step.iter()) {
            *x += fraction * d;
        }
        Some(trial)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::hybrid::units::{distance_lu, time_tu};

    /// A transfer whose answer is known: from an arrival state with `λm(t_f) = 0` and chosen
    /// costates, flown backwards over `duration_tu` to a departure state. Shooting from that
    /// departure to that arrival must find the costates again.
    fn manufactured(law: Throttle, duration_tu: f64) -> (Transfer, [f64; 7]) {
        let model = Model::paper();
        let arrival = Augmented {
            r_lu: [0.823_385_182_067, 0.0, -0.022_277_556_273],
            v_vu: [0.0, 0.134_184_170_262, 0.0],
            m_mu: 0.35,
            lambda_r: [0.02, -0.015, 0.004],
            lambda_v: [0.006, 0.011, -0.002],
            lambda_m: 0.0,
        };
        let mut counts = Counts::default();
        let tol = Settings::default().integration;
        let start = propagate(&model, law, &arrival, -duration_tu, &tol, &mut counts).unwrap();
        let lambda = [
            start.lambda_r[0],
            start.lambda_r[1],
            start.lambda_r[2],
            start.lambda_v[0],
            start.lambda_v[1],
            start.lambda_v[2],
            start.lambda_m,
        ];
        let transfer = Transfer {
            departure_r_lu: start.r_lu,
            departure_v_vu: start.v_vu,
            departure_m_mu: start.m_mu,
            arrival_r_lu: arrival.r_lu,
            arrival_v_vu: arrival.v_vu,
            duration_tu,
            law,
        };
        (transfer, lambda)
    }

    #[test]
    fn the_shooting_finds_the_costates_of_a_known_transfer() {
        let model = Model::paper();
        for law in [
            Throttle::Smoothed { epsilon: 1.0 },
            Throttle::Smoothed { epsilon: 0.3 },
        ] {
            let (transfer, truth) = manufactured(law, time_tu(1.5));
            // The engine worked on the way (else the test shoots a ballistic arc).
            assert!(
                transfer.departure_m_mu > 0.351,
                "{law:?}: {}",
                transfer.departure_m_mu
            );
            // Start 5 % off every costate.
            let guess = truth.map(|x| x * 1.05);
            let s = shoot(&model, &transfer, &guess, &Settings::default());
            assert_eq!(s.status, Status::Converged, "{law:?}: {s:?}");
            assert!(s.residual <= 1e-10 && s.iterations <= 12, "{law:?}: {s:?}");
            for (x, t) in s.costates.iter().zip(truth) {
                assert!(
                    (x - t).abs() < 1e-7 * (1.0 + t.abs()),
                    "{law:?}: {x} against {t}"
                );
            }
        }
        // The departure of the paper's parking orbit is far from this arrival in 1.5 d: no
        // costates reach it, and the shooting says so within its bounds.
        let (mut far, truth) = manufactured(Throttle::Smoothed { epsilon: 1.0 }, time_tu(1.5));
        far.departure_r_lu = [
            distance_lu(6778.0) - crate::hybrid::units::MASS_RATIO,
            0.0,
            0.0,
        ];
        let settings = Settings {
            max_iterations: 4,
            ..Settings::default()
        };
        let s = shoot(&model, &far, &truth, &settings);
        assert_ne!(s.status, Status::Converged);
        assert!(s.iterations <= 4 && s.residual > 1e-3, "{s:?}");
    }
}
