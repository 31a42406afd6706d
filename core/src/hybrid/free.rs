//! Shooting with the impulse free (SPEC-hybrid.md eq. 12 and 24): the impulse ratio κ and/or
//! the phase θ join the 7 initial costates as unknowns, with their transversality conditions
//! `∂Θ/∂κ + λ(t0)·∂x0/∂κ = 0` and `λ(t0)·∂x0/∂θ = 0` (λ the costate, the cost-to-go's
//! gradient: so the departure's sensitivities enter with a plus sign). The departure state is
//! `x0(κ, θ)` of eq. 4; the rest is the fixed-time shooting's.

use super::departure::Departure;
use super::dynamics::{Augmented, Model, Throttle};
use super::flow::{propagate, propagate_with_stm};
use super::integrate::{Counts, Stop, Tolerance};
use super::newton::{iterate, System};
use super::shooting::{Settings, Status};
use crate::vec3::Vec3;
use nalgebra::{SMatrix, SVector};

/// Which of the impulse's parameters are free.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Free {
    /// κ free (else held at its start value).
    pub kappa: bool,
    /// θ free.
    pub theta: bool,
}

/// A fixed-time transfer from the parking orbit through the impulse to the arrival point.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ImpulseTransfer {
    /// The parking orbit and the chemical engine.
    pub departure: Departure,
    /// Arrival position, LU.
    pub arrival_r_lu: Vec3,
    /// Arrival velocity, LU/TU.
    pub arrival_v_vu: Vec3,
    /// Time of flight, TU.
    pub duration_tu: f64,
    /// The throttle law.
    pub law: Throttle,
    /// Which parameters are free.
    pub free: Free,
    /// Added to the state after the impulse, `[r (LU), v (LU/TU), m (MU)]`: a navigation
    /// update of the departure (zero for the planned one). Its derivatives in κ and θ are 0.
    pub offset: [f64; 7],
}

/// The unknowns: costates, κ, θ (a parameter not free stays as given).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Point {
    /// Initial costates `[λr, λv, λm]`.
    pub costates: [f64; 7],
    /// Impulse ratio.
    pub kappa: f64,
    /// Phase of the impulse on the parking orbit, rad.
    pub theta_rad: f64,
}

/// The answer.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Solution {
    /// How it ended.
    pub status: Status,
    /// The converged unknowns, or the best iterate.
    pub point: Point,
    /// Largest component of the residual (9 equations; those of a fixed parameter are 0).
    pub residual: f64,
    /// Newton iterations done.
    pub iterations: u32,
    /// The integrations' work.
    pub counts: Counts,
}

type Vector9 = SVector<f64, 9>;

impl ImpulseTransfer {
    fn initial(&self, p: &Point) -> Augmented {
        let mut x = self.departure.state(p.kappa, p.theta_rad).state;
        for (xi, di) in x.iter_mut().zip(self.offset) {
            *xi += di;
        }
        let l = p.costates;
        Augmented {
            r_lu: [x[0], x[1], x[2]],
            v_vu: [x[3], x[4], x[5]],
            m_mu: x[6],
            lambda_r: [l[0], l[1], l[2]],
            lambda_v: [l[3], l[4], l[5]],
            lambda_m: l[6],
        }
    }

    /// `[r − r_f, v − v_f, λm(t_f), transversality in κ, in θ]`; a fixed parameter's row 0.
    fn residual(&self, p: &Point, end: &Augmented) -> Vector9 {
        let d = self.departure.state(p.kappa, p.theta_rad);
        let dot7 = |a: &[f64; 7], b: &[f64; 7]| a.iter().zip(b).map(|(x, y)| x * y).sum::<f64>();
        let (_, theta_k, _) = self.departure.chemical_cost(p.kappa);
        let (r, v) = (end.r_lu, end.v_vu);
        let (rf, vf) = (self.arrival_r_lu, self.arrival_v_vu);
        Vector9::from([
            r[0] - rf[0],
            r[1] - rf[1],
            r[2] - rf[2],
            v[0] - vf[0],
            v[1] - vf[1],
            v[2] - vf[2],
            end.lambda_m,
            if self.free.kappa {
                theta_k + dot7(&p.costates, &d.d_kappa)
            } else {
                0.0
            },
            if self.free.theta {
                dot7(&p.costates, &d.d_theta)
            } else {
                0.0
            },
        ])
    }
}

/// Shoot from `start` under `settings` (as [`super::shooting::shoot`]; a fixed parameter's
/// column is the identity, so the 9 × 9 system stays square).
pub fn shoot(
    model: &Model,
    transfer: &ImpulseTransfer,
    start: &Point,
    settings: &Settings,
) -> Solution {
    let system = ImpulseFree {
        model,
        transfer,
        tol: &settings.integration,
    };
    let o = iterate(&system, *start, settings);
    Solution {
        status: o.status,
        point: o.point,
        residual: o.residual,
        iterations: o.iterations,
        counts: o.counts,
    }
}

/// The equations with the impulse free, for [`iterate`].
struct ImpulseFree<'a> {
    model: &'a Model,
    transfer: &'a ImpulseTransfer,
    tol: &'a Tolerance,
}

// nalgebra's f64 vectors and matrices: the integer-overflow lint does not apply.
#[allow(clippy::arithmetic_side_effects)]
impl System<9> for ImpulseFree<'_> {
    type Point = Point;

    fn linearised(
        &self,
        p: &Point,
        counts: &mut Counts,
    ) -> Result<(Vector9, Option<Vector9>), Stop> {
        let t = self.transfer;
        let y0 = t.initial(p);
        let (end, phi) =
            propagate_with_stm(self.model, t.law, &y0, t.duration_tu, self.tol, counts)?;
        let f = t.residual(p, &end);
        let d = t.departure.state(p.kappa, p.theta_rad);
        let (_, _, theta_kk) = t.departure.chemical_cost(p.kappa);
        let dk = SVector::<f64, 7>::from(d.d_kappa);
        let dt = SVector::<f64, 7>::from(d.d_theta);
        let lam = SVector::<f64, 7>::from(p.costates);
        // λ·∂²x0/∂κ∂θ, the cross term of both conditions.
        let cross = lam.dot(&SVector::<f64, 7>::from(d.d_kappa_theta));
        // Rows r, v (0..6) and λm (13) of Φ, against the costates (columns 7..14) and against
        // the departure state (columns 0..7, through x0's derivatives).
        let mut rows = SMatrix::<f64, 7, 14>::zeros();
        rows.fixed_view_mut::<6, 14>(0, 0)
            .copy_from(&phi.fixed_view::<6, 14>(0, 0));
        rows.fixed_view_mut::<1, 14>(6, 0)
            .copy_from(&phi.fixed_view::<1, 14>(13, 0));
        let by_state = rows.fixed_view::<7, 7>(0, 0);
        let mut jac = SMatrix::<f64, 9, 9>::zeros();
        jac.fixed_view_mut::<7, 7>(0, 0)
            .copy_from(&rows.fixed_view::<7, 7>(0, 7));
        if t.free.kappa {
            jac.fixed_view_mut::<7, 1>(0, 7).copy_from(&(by_state * dk));
            jac.fixed_view_mut::<1, 7>(7, 0).copy_from(&dk.transpose());
            let dkk = SVector::<f64, 7>::from(d.d_kappa_kappa);
            jac.fixed_view_mut::<1, 1>(7, 7)
                .fill(theta_kk + lam.dot(&dkk));
            if t.free.theta {
                jac.fixed_view_mut::<1, 1>(7, 8).fill(cross);
            }
        } else {
            jac.fixed_view_mut::<1, 1>(7, 7).fill(1.0);
        }
        if t.free.theta {
            jac.fixed_view_mut::<7, 1>(0, 8).copy_from(&(by_state * dt));
            jac.fixed_view_mut::<1, 7>(8, 0).copy_from(&dt.transpose());
            let dtt = SVector::<f64, 7>::from(d.d_theta_theta);
            jac.fixed_view_mut::<1, 1>(8, 8).fill(lam.dot(&dtt));
            if t.free.kappa {
                jac.fixed_view_mut::<1, 1>(8, 7).fill(cross);
            }
        } else {
            jac.fixed_view_mut::<1, 1>(8, 8).fill(1.0);
        }
        let step = super::linear::solve(&jac, &(-f));
        Ok((f, step))
    }

    fn residual(&self, p: &Point, counts: &mut Counts) -> Option<Vector9> {
        let t = self.transfer;
        let y = t.initial(p);
        let end = propagate(self.model, t.law, &y, t.duration_tu, self.tol, counts).ok()?;
        Some(t.residual(p, &end))
    }

    /// A fixed parameter stays where it is.
    fn moved(&self, p: &Point, step: &Vector9, fraction: f64) -> Option<Point> {
        let mut trial = *p;
        for (v, s) in trial.costates.iter_mut().zip(step.iter()) {
            *v += fraction * s;
        }
        if self.transfer.free.kappa {
            trial.kappa += fraction * step.fixed_rows::<1>(7).x;
        }
        if self.transfer.free.theta {
            trial.theta_rad += fraction * step.fixed_rows::<1>(8).x;
        }
        Some(trial)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::hybrid::ladder::{descend, walk_duration};
    use crate::hybrid::shooting::{shoot as shoot_fixed, Transfer};
    use crate::hybrid::units::time_tu;

    /// Table 3's first group with κ free (θ = −2), as the digest read the paper's "κ, θ
    /// free" column: from the fixed-κ minimum-fuel solution (the ladder at 4.38 d, then t_f
    /// walked at ε = 0), the shooting with κ's transversality condition. First the condition
    /// itself: at the fixed-κ solution its value is the derivative of the cost `1 − m_f` in κ,
    /// found by differences of two fixed-κ solves (the envelope theorem; it checks the sign).
    #[test]
    fn freeing_kappa_reaches_table_3s_free_column() {
        let model = Model::paper();
        let settings = Settings {
            max_iterations: 40,
            max_halvings: 20,
            ..Settings::default()
        };
        let zero = Throttle::Smoothed { epsilon: 0.0 };
        let fixed = |kappa: f64, days: f64, law: Throttle| {
            let x = Departure::paper().state(kappa, -2.0).state;
            Transfer {
                departure_r_lu: [x[0], x[1], x[2]],
                departure_v_vu: [x[3], x[4], x[5]],
                departure_m_mu: x[6],
                arrival_r_lu: [0.823_385_182_067, 0.0, -0.022_277_556_273],
                arrival_v_vu: [0.0, 0.134_184_170_262, 0.0],
                duration_tu: time_tu(days),
                law,
            }
        };
        let energy = [
            1.635, 7.972, -0.069_96, -0.020_72, 0.016_16, 9.53e-6, 0.066_14,
        ];
        let smooth = fixed(1.4, 4.38, Throttle::Smoothed { epsilon: 1.0 });
        let fuel = descend(&model, &smooth, &energy, 0.0, 12, &settings).unwrap();
        let final_mass = |t: &Transfer, costates: &[f64; 7]| {
            let mut c = Counts::default();
            let tol = &settings.integration;
            propagate(
                &model,
                t.law,
                &t.initial(costates),
                t.duration_tu,
                tol,
                &mut c,
            )
            .unwrap()
            .m_mu
        };
        for (days, printed, kappa_near) in [
            (4.3800, 0.3437, 1.3839),
            (4.0431, 0.3398, 1.3865),
            (3.7061, 0.3334, 1.3917),
        ] {
            let walk = walk_duration(
                &model,
                &fixed(1.4, 4.38, zero),
                &fuel.solution.costates,
                time_tu(days),
                time_tu(0.05),
                40,
                &settings,
            )
            .unwrap();
            assert!(walk.reached, "{days} d: {walk:?}");
            let lam = walk.solution.costates;
            let transfer = ImpulseTransfer {
                departure: Departure::paper(),
                arrival_r_lu: [0.823_385_182_067, 0.0, -0.022_277_556_273],
                arrival_v_vu: [0.0, 0.134_184_170_262, 0.0],
                duration_tu: time_tu(days),
                law: zero,
                free: Free {
                    kappa: true,
                    theta: false,
                },
                offset: [0.0; 7],
            };
            // The envelope: d(1 − m_f)/dκ by fixed-κ solves at κ ± 1e-4.
            let h = 1e-4;
            let mass_at = |kappa: f64| {
                let t = fixed(kappa, days, zero);
                let s = shoot_fixed(&model, &t, &lam, &settings);
                assert_eq!(s.status, Status::Converged);
                final_mass(&t, &s.costates)
            };
            let slope = -(mass_at(1.4 + h) - mass_at(1.4 - h)) / (2.0 * h);
            let at = Point {
                costates: lam,
                kappa: 1.4,
                theta_rad: -2.0,
            };
            let mut counts = Counts::default();
            let tol = &settings.integration;
            let end = propagate(
                &model,
                zero,
                &transfer.initial(&at),
                transfer.duration_tu,
                tol,
                &mut counts,
            )
            .unwrap();
            let condition = transfer.residual(&at, &end)[7];
            assert!(
                (condition - slope).abs() < 1e-4 * slope.abs(),
                "{days} d: {condition} against {slope}"
            );
            // κ free: the paper's free column.
            let s = shoot(&model, &transfer, &at, &settings);
            assert_eq!(s.status, Status::Converged, "{days} d: {s:?}");
            assert!(
                (s.point.kappa - kappa_near).abs() < 1e-4,
                "{days} d: κ {}",
                s.point.kappa
            );
            let t = fixed(s.point.kappa, days, zero);
            let m_f = final_mass(&t, &s.point.costates);
            assert!(
                (m_f - printed).abs() < 1e-4,
                "{days} d: m_f {m_f} against {printed}"
            );
        }
    }
}
