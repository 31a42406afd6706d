//! Minimum-time shooting (SPEC-hybrid.md §2 item 10, the standard form the paper leaves out):
//! full thrust throughout, the cost multiplier `λ0 > 0` and the initial costates normalised on
//! the unit sphere (Jiang et al. 2012), the time of flight free. Unknowns `p = [λ0, λ(t0)]` (8)
//! and `t_f`; equations `r(t_f) = r_f`, `v(t_f) = v_f`, `λm(t_f) = 0`, `H(t_f) + λ0 = 0` and
//! `|p| = 1`. A damped Newton iteration on the 9 × 9 system with the analytic Jacobian (the
//! state-transition matrix, the flow's derivative in time, the Hamiltonian's gradient).

use super::dynamics::{Augmented, Model, Throttle};
use super::flow::{propagate, propagate_with_stm};
use super::integrate::{Counts, Stop, Tolerance};
use super::newton::{iterate, System};
use super::shooting::{Settings, Status};
use crate::vec3::Vec3;
use nalgebra::{SMatrix, SVector};

/// A minimum-time transfer: a departure state and an arrival point.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Endpoints {
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
}

/// The unknowns: the normalised multipliers and the time of flight.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Unknowns {
    /// `[λ0, λr, λv, λm]` at the departure, `|p| = 1` at a solution.
    pub multipliers: [f64; 8],
    /// Time of flight, TU.
    pub duration_tu: f64,
}

/// The minimum-time shooting's answer.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Solution {
    /// How it ended.
    pub status: Status,
    /// The converged unknowns, or the best iterate.
    pub unknowns: Unknowns,
    /// Largest component of the residual.
    pub residual: f64,
    /// Newton iterations done.
    pub iterations: u32,
    /// The integrations' work.
    pub counts: Counts,
}

type Vector9 = SVector<f64, 9>;

impl Endpoints {
    fn initial(&self, p: &[f64; 8]) -> Augmented {
        Augmented {
            r_lu: self.departure_r_lu,
            v_vu: self.departure_v_vu,
            m_mu: self.departure_m_mu,
            lambda_r: [p[1], p[2], p[3]],
            lambda_v: [p[4], p[5], p[6]],
            lambda_m: p[7],
        }
    }

    fn residual(&self, model: &Model, p: &[f64; 8], end: &Augmented) -> Vector9 {
        let (r, v) = (end.r_lu, end.v_vu);
        let (rf, vf) = (self.arrival_r_lu, self.arrival_v_vu);
        let norm2: f64 = p.iter().map(|x| x * x).sum();
        Vector9::from([
            r[0] - rf[0],
            r[1] - rf[1],
            r[2] - rf[2],
            v[0] - vf[0],
            v[1] - vf[1],
            v[2] - vf[2],
            end.lambda_m,
            model.hamiltonian(Throttle::Full, end) + p[0],
            norm2 - 1.0,
        ])
    }
}

/// Shoot for minimum time from `guess` under `settings` (its tolerance on the residual, its
/// bounds on the iterations, halvings and integration steps, as [`super::shooting::shoot`]).
pub fn shoot(model: &Model, ends: &Endpoints, guess: &Unknowns, settings: &Settings) -> Solution {
    let system = MinimumTime {
        model,
        ends,
        tol: &settings.integration,
    };
    let o = iterate(&system, *guess, settings);
    Solution {
        status: o.status,
        unknowns: o.point,
        residual: o.residual,
        iterations: o.iterations,
        counts: o.counts,
    }
}

/// The minimum-time shooting's equations for [`iterate`].
struct MinimumTime<'a> {
    model: &'a Model,
    ends: &'a Endpoints,
    tol: &'a Tolerance,
}

// nalgebra's f64 vectors and matrices: the integer-overflow lint does not apply.
#[allow(clippy::arithmetic_side_effects)]
impl System<9> for MinimumTime<'_> {
    type Point = Unknowns;

    fn linearised(
        &self,
        x: &Unknowns,
        counts: &mut Counts,
    ) -> Result<(Vector9, Option<Vector9>), Stop> {
        let (model, law) = (self.model, Throttle::Full);
        let y0 = self.ends.initial(&x.multipliers);
        let (end, phi) = propagate_with_stm(model, law, &y0, x.duration_tu, self.tol, counts)?;
        let f = self.ends.residual(model, &x.multipliers, &end);
        // Columns: λ0, λ(t0) (7), t_f.
        let mut jac = SMatrix::<f64, 9, 9>::zeros();
        let lambda_cols = phi.fixed_view::<14, 7>(0, 7);
        // r, v and λm at t_f against λ(t0); against t_f, the flow's derivative.
        jac.fixed_view_mut::<6, 7>(0, 1)
            .copy_from(&lambda_cols.fixed_view::<6, 7>(0, 0));
        jac.fixed_view_mut::<1, 7>(6, 1)
            .copy_from(&lambda_cols.fixed_view::<1, 7>(13, 0));
        let rate = SVector::<f64, 14>::from(model.derivative(law, &end).to_array());
        jac.fixed_view_mut::<6, 1>(0, 8)
            .copy_from(&rate.fixed_view::<6, 1>(0, 0));
        jac.fixed_view_mut::<1, 1>(6, 8)
            .copy_from(&rate.fixed_view::<1, 1>(13, 0));
        // H(t_f) against λ(t0): its gradient (−λ', x') through Φ; against λ0, 1; against t_f,
        // none (H is constant along the flow).
        let mut grad = SVector::<f64, 14>::zeros();
        grad.fixed_view_mut::<7, 1>(0, 0)
            .copy_from(&(-rate.fixed_view::<7, 1>(7, 0)));
        grad.fixed_view_mut::<7, 1>(7, 0)
            .copy_from(&rate.fixed_view::<7, 1>(0, 0));
        jac.fixed_view_mut::<1, 7>(7, 1)
            .copy_from(&(grad.transpose() * lambda_cols));
        jac.fixed_view_mut::<1, 1>(7, 0).fill(1.0);
        // |p|² − 1 against p.
        let p = SVector::<f64, 8>::from(x.multipliers);
        jac.fixed_view_mut::<1, 8>(8, 0)
            .copy_from(&(p.transpose() * 2.0));
        let step = super::linear::solve(&jac, &(-f));
        Ok((f, step))
    }

    fn residual(&self, x: &Unknowns, counts: &mut Counts) -> Option<Vector9> {
        let y = self.ends.initial(&x.multipliers);
        let end = propagate(
            self.model,
            Throttle::Full,
            &y,
            x.duration_tu,
            self.tol,
            counts,
        )
        .ok()?;
        Some(self.ends.residual(self.model, &x.multipliers, &end))
    }

    /// `None` for a time of flight that is not positive.
    fn moved(&self, x: &Unknowns, step: &Vector9, fraction: f64) -> Option<Unknowns> {
        let mut trial = *x;
        for (v, d) in trial.multipliers.iter_mut().zip(step.iter()) {
            *v += fraction * d;
        }
        trial.duration_tu += fraction * step.fixed_rows::<1>(8).x;
        (trial.duration_tu > 0.0).then_some(trial)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::hybrid::integrate::Counts;

    /// A full-thrust transfer whose answer is known: from the halo point with chosen costates
    /// (`λm(t_f) = 0`), flown backwards; its cost multiplier `λ0 = −H` (positive), the
    /// multipliers normalised.
    #[test]
    fn the_minimum_time_shooting_finds_a_known_extremal() {
        let model = Model::paper();
        let arrival = Augmented {
            r_lu: [0.823_385_182_067, 0.0, -0.022_277_556_273],
            v_vu: [0.0, 0.134_184_170_262, 0.0],
            m_mu: 0.32,
            lambda_r: [0.01, -0.012, 0.003],
            lambda_v: [0.006, 0.011, -0.002],
            lambda_m: 0.0,
        };
        let lambda0 = -model.hamiltonian(Throttle::Full, &arrival);
        assert!(
            lambda0 > 0.0,
            "a minimum-time extremal has λ0 > 0: {lambda0}"
        );
        let duration = 0.4;
        let settings = Settings::default();
        let mut counts = Counts::default();
        let start = propagate(
            &model,
            Throttle::Full,
            &arrival,
            -duration,
            &settings.integration,
            &mut counts,
        )
        .unwrap();
        let raw = [
            lambda0,
            start.lambda_r[0],
            start.lambda_r[1],
            start.lambda_r[2],
            start.lambda_v[0],
            start.lambda_v[1],
            start.lambda_v[2],
            start.lambda_m,
        ];
        let norm = libm::sqrt(raw.iter().map(|x| x * x).sum::<f64>());
        let truth = raw.map(|x| x / norm);
        let ends = Endpoints {
            departure_r_lu: start.r_lu,
            departure_v_vu: start.v_vu,
            departure_m_mu: start.m_mu,
            arrival_r_lu: arrival.r_lu,
            arrival_v_vu: arrival.v_vu,
        };
        // 3 % off every multiplier, the time of flight 2 % long.
        let guess = Unknowns {
            multipliers: truth.map(|x| x * 1.03),
            duration_tu: duration * 1.02,
        };
        let s = shoot(&model, &ends, &guess, &settings);
        assert_eq!(s.status, Status::Converged, "{s:?}");
        assert!(s.residual <= 1e-10 && s.iterations <= 15, "{s:?}");
        assert!((s.unknowns.duration_tu - duration).abs() < 1e-9, "{s:?}");
        for (x, t) in s.unknowns.multipliers.iter().zip(truth) {
            assert!((x - t).abs() < 1e-7, "{x} against {t}");
        }
    }
}
