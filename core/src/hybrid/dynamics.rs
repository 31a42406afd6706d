//! The canonical system of the hybrid transfer (SPEC-hybrid.md, eq. 1–17, with the digest's
//! corrections): the CR3BP with mass and thrust, the costates of Pontryagin's principle, the
//! switching function and the optimal (smoothed) throttle. 14 unknowns: position, velocity,
//! mass and their costates.

use crate::indexed::IndexedExt;
use crate::vec3::{add, dot, norm, scale, sub, Vec3};

/// A 3×3 matrix, row-major.
pub type Mat3 = [[f64; 3]; 3];

/// The spacecraft's state and its costates: the 14 unknowns of the canonical system.
#[derive(Clone, Copy, Debug, PartialEq, Default)]
pub struct Augmented {
    /// Position in the rotating frame, LU.
    pub r_lu: Vec3,
    /// Velocity in the rotating frame, LU/TU.
    pub v_vu: Vec3,
    /// Mass, MU.
    pub m_mu: f64,
    /// Position costate.
    pub lambda_r: Vec3,
    /// Velocity costate (the primer vector is `-lambda_v`).
    pub lambda_v: Vec3,
    /// Mass costate.
    pub lambda_m: f64,
}

impl Augmented {
    /// A position and velocity with unit mass and every costate zero: the start of a
    /// ballistic flight (the halo orbit flown along itself).
    pub const fn ballistic(r_lu: Vec3, v_vu: Vec3) -> Self {
        Self {
            r_lu,
            v_vu,
            m_mu: 1.0,
            lambda_r: [0.0; 3],
            lambda_v: [0.0; 3],
            lambda_m: 0.0,
        }
    }

    /// As 14 numbers: `[r, v, m, lambda_r, lambda_v, lambda_m]`.
    pub fn to_array(&self) -> [f64; 14] {
        let (r, v, lr, lv) = (self.r_lu, self.v_vu, self.lambda_r, self.lambda_v);
        [
            r[0],
            r[1],
            r[2],
            v[0],
            v[1],
            v[2],
            self.m_mu,
            lr[0],
            lr[1],
            lr[2],
            lv[0],
            lv[1],
            lv[2],
            self.lambda_m,
        ]
    }

    /// From 14 numbers in the order of [`Self::to_array`].
    pub fn from_array(y: &[f64; 14]) -> Self {
        Self {
            r_lu: [y[0], y[1], y[2]],
            v_vu: [y[3], y[4], y[5]],
            m_mu: y[6],
            lambda_r: [y[7], y[8], y[9]],
            lambda_v: [y[10], y[11], y[12]],
            lambda_m: y[13],
        }
    }
}

/// The model: the CR3BP's mass ratio and the electric engine.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Model {
    /// μ, the smaller primary's share of the total mass.
    pub mass_ratio: f64,
    /// Largest thrust, MU LU/TU².
    pub thrust_fu: f64,
    /// Exhaust speed of the electric engine, LU/TU.
    pub exhaust_vu: f64,
}

impl Model {
    /// The paper's (Table 1): Earth–Moon μ, 10 N, a specific impulse of 3000 s.
    pub fn paper() -> Self {
        Self {
            mass_ratio: super::units::MASS_RATIO,
            thrust_fu: super::units::force_fu(10.0),
            exhaust_vu: super::units::exhaust_speed_vu(3000.0),
        }
    }

    /// The primaries as (mass share, position): the Earth at (−μ, 0, 0), the Moon at (1−μ, 0, 0).
    fn primaries(&self) -> [(f64, Vec3); 2] {
        let mu = self.mass_ratio;
        [(1.0 - mu, [-mu, 0.0, 0.0]), (mu, [1.0 - mu, 0.0, 0.0])]
    }

    /// `g(r)`: gravity and the centrifugal term in the rotating frame (eq. 1).
    pub fn gravity(&self, r_lu: &Vec3) -> Vec3 {
        self.primaries()
            .iter()
            .fold([r_lu[0], r_lu[1], 0.0], |acc, (k, at)| {
                let d = sub(r_lu, at);
                let rho = norm(&d);
                sub(&acc, &scale(&d, k / (rho * rho * rho)))
            })
    }

    /// `G = dg/dr` (symmetric): `diag(1, 1, 0) − Σ k (I/ρ³ − 3 d dᵀ/ρ⁵)`.
    pub fn gravity_gradient(&self, r_lu: &Vec3) -> Mat3 {
        let mut g = [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 0.0]];
        for (k, at) in self.primaries() {
            let d = sub(r_lu, &at);
            let rho2 = dot(&d, &d);
            let rho3 = rho2 * libm::sqrt(rho2);
            let rho5 = rho3 * rho2;
            for (i, (row, di)) in g.iter_mut().zip(d).indexed() {
                for (j, (cell, dj)) in row.iter_mut().zip(d).indexed() {
                    let diagonal = if i == j { k / rho3 } else { 0.0 };
                    *cell += 3.0 * k * di * dj / rho5 - diagonal;
                }
            }
        }
        g
    }

    /// `d(G λ)/dr`, the third derivatives of the potential against `λ`:
    /// `Σ 3k [(λ dᵀ + d λᵀ + (d·λ) I)/ρ⁵ − 5 (d·λ) d dᵀ/ρ⁷]` (the centrifugal part adds none).
    pub fn gravity_gradient_along(&self, r_lu: &Vec3, lambda: &Vec3) -> Mat3 {
        let mut out = [[0.0; 3]; 3];
        for (k, at) in self.primaries() {
            let d = sub(r_lu, &at);
            let rho2 = dot(&d, &d);
            let rho5 = rho2 * rho2 * libm::sqrt(rho2);
            let rho7 = rho5 * rho2;
            let dl = dot(&d, lambda);
            for (i, (row, (di, li))) in out.iter_mut().zip(d.iter().zip(lambda)).indexed() {
                for (j, (cell, (dj, lj))) in row.iter_mut().zip(d.iter().zip(lambda)).indexed() {
                    let identity = if i == j { dl } else { 0.0 };
                    *cell += 3.0
                        * k
                        * ((li * dj + di * lj + identity) / rho5 - 5.0 * dl * di * dj / rho7);
                }
            }
        }
        out
    }
}

/// The throttle law: minimum time (full thrust throughout) or the smoothed minimum-fuel
/// objective of eq. 3 (`epsilon` 1: minimum energy, 0: minimum fuel, bang-bang).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Throttle {
    /// `u = 1`.
    Full,
    /// `u = 0` (a coast arc of the bang-bang law).
    Coast,
    /// `u*` of eq. 16 for the integrand `u − ε u (1 − u)`.
    Smoothed {
        /// ε in [0, 1].
        epsilon: f64,
    },
}

impl Throttle {
    /// The optimal throttle for switching function `s` (eq. 16).
    pub fn of(&self, s: f64) -> f64 {
        match *self {
            Self::Full => 1.0,
            Self::Coast => 0.0,
            Self::Smoothed { epsilon } => {
                if s > epsilon {
                    0.0
                } else if s < -epsilon {
                    1.0
                } else {
                    // |S| <= ε with ε > 0 here (ε = 0 takes one of the branches above
                    // unless S = 0 exactly, a switch instant: full thrust or none alike).
                    if epsilon > 0.0 {
                        (epsilon - s) / (2.0 * epsilon)
                    } else {
                        0.0
                    }
                }
            }
        }
    }

    /// `du/dS`: nonzero only where the smoothed throttle is between its bounds.
    pub fn slope(&self, s: f64) -> f64 {
        match *self {
            Self::Smoothed { epsilon } if epsilon > 0.0 && s.abs() <= epsilon => {
                -1.0 / (2.0 * epsilon)
            }
            _ => 0.0,
        }
    }
}

/// `|λv|`, and the thrust direction `α = −λv/|λv|` (zero when `λv` is: no direction).
pub fn primer(lambda_v: &Vec3) -> (f64, Vec3) {
    let l = norm(lambda_v);
    if l > 0.0 {
        (l, scale(lambda_v, -1.0 / l))
    } else {
        (0.0, [0.0; 3])
    }
}

impl Model {
    /// The switching function `S = 1 − |λv| c/m − λm` (eq. 15).
    pub fn switching(&self, y: &Augmented) -> f64 {
        1.0 - norm(&y.lambda_v) * self.exhaust_vu / y.m_mu - y.lambda_m
    }

    /// `dS/dt = c (λr·λv)/(m |λv|)`, the same whatever the throttle (so continuous at a
    /// switch); 0 where `λv` is.
    pub fn switching_rate(&self, y: &Augmented) -> f64 {
        let l = norm(&y.lambda_v);
        if l > 0.0 {
            self.exhaust_vu * dot(&y.lambda_r, &y.lambda_v) / (y.m_mu * l)
        } else {
            0.0
        }
    }

    /// `dS/dy` (14): `dS/dm = |λv| c/m²`, `dS/dλv = −(c/m) λv/|λv|`, `dS/dλm = −1`.
    pub fn switching_gradient(&self, y: &Augmented) -> [f64; 14] {
        let (l, alpha) = primer(&y.lambda_v);
        let c = self.exhaust_vu;
        let m = y.m_mu;
        // −(c/m) λv/|λv| = (c/m) α.
        let dl = scale(&alpha, c / m);
        let dm = if l > 0.0 { l * c / (m * m) } else { 0.0 };
        [
            0.0, 0.0, 0.0, 0.0, 0.0, 0.0, dm, 0.0, 0.0, 0.0, dl[0], dl[1], dl[2], -1.0,
        ]
    }

    /// The canonical system's derivative (eq. 17 with the digest's corrections).
    pub fn derivative(&self, law: Throttle, y: &Augmented) -> Augmented {
        let (l, alpha) = primer(&y.lambda_v);
        let u = law.of(self.switching(y));
        let t = self.thrust_fu;
        let m = y.m_mu;
        let coriolis = [2.0 * y.v_vu[1], -2.0 * y.v_vu[0], 0.0];
        let thrust = scale(&alpha, u * t / m);
        let g = self.gravity_gradient(&y.r_lu);
        let lv = y.lambda_v;
        // Hᵀ λv with H = dh/dv = [[0, 2, 0], [−2, 0, 0], [0, 0, 0]].
        let h_t_lv = [-2.0 * lv[1], 2.0 * lv[0], 0.0];
        Augmented {
            r_lu: y.v_vu,
            v_vu: add(&add(&self.gravity(&y.r_lu), &coriolis), &thrust),
            m_mu: -u * t / self.exhaust_vu,
            lambda_r: scale(&mat_vec(&g, &lv), -1.0),
            lambda_v: scale(&add(&y.lambda_r, &h_t_lv), -1.0),
            lambda_m: -u * t * l / (m * m),
        }
    }

    /// The Hamiltonian with the optimal throttle and direction (eq. 14): for the smoothed law
    /// `λr·v + λv·(g + h) + (T/c) u (S − ε + ε u)`; for full thrust the same without the
    /// cost (its multiplier λ0 is the minimum-time problem's, added by its shooting).
    pub fn hamiltonian(&self, law: Throttle, y: &Augmented) -> f64 {
        let s = self.switching(y);
        let u = law.of(s);
        let v = y.v_vu;
        let coriolis = [2.0 * v[1], -2.0 * v[0], 0.0];
        let drift =
            dot(&y.lambda_r, &v) + dot(&y.lambda_v, &add(&self.gravity(&y.r_lu), &coriolis));
        let engine = self.thrust_fu / self.exhaust_vu * u;
        match law {
            Throttle::Smoothed { epsilon } => drift + engine * (s - epsilon + epsilon * u),
            // The thrust and mass terms alone: −T|λv|/m − λm T/c = (T/c)(S − 1).
            Throttle::Full => drift + engine * (s - 1.0),
            // The bang-bang law's arcs (ε = 0): the minimum-fuel Hamiltonian, u S T/c.
            Throttle::Coast => drift,
        }
    }
}

/// `A x` for a 3×3 matrix.
pub fn mat_vec(a: &Mat3, x: &Vec3) -> Vec3 {
    [dot(&a[0], x), dot(&a[1], x), dot(&a[2], x)]
}

#[cfg(test)]
pub(crate) mod tests {
    use super::*;

    /// A state on a transfer from near the Earth, with costates of the size the shooting
    /// meets; `lambda_m` shifts the switching function to put the throttle where asked.
    pub(crate) fn sample(lambda_m: f64) -> Augmented {
        Augmented {
            r_lu: [0.12, -0.31, 0.02],
            v_vu: [0.9, 0.4, -0.05],
            m_mu: 0.62,
            lambda_r: [0.3, -0.7, 0.11],
            lambda_v: [0.013, 0.021, -0.004],
            lambda_m,
        }
    }

    fn central<F: Fn(f64) -> f64>(f: F, h: f64) -> f64 {
        (f(h) - f(-h)) / (2.0 * h)
    }

    /// `x' = dH/dλ` and `λ' = −dH/dx` for every component, by central differences of the
    /// Hamiltonian (the optimal throttle and direction substituted: their own derivative
    /// terms vanish, Pontryagin's envelope), with the throttle off, full and in between.
    #[test]
    fn the_canonical_system_is_the_hamiltonians_gradient() {
        let model = Model::paper();
        let smoothed = Throttle::Smoothed { epsilon: 0.4 };
        let probe = sample(0.0);
        let s0 = model.switching(&probe);
        // λm moves S by −1 per unit: S = 0.9 (off), −0.9 (full), 0.1 (in between); and the
        // minimum-time law (full thrust whatever S).
        for (law, target_s) in [
            (smoothed, 0.9),
            (smoothed, -0.9),
            (smoothed, 0.1),
            (Throttle::Full, 0.9),
        ] {
            let y = sample(s0 - target_s);
            assert!((model.switching(&y) - target_s).abs() < 1e-12);
            let f = model.derivative(law, &y).to_array();
            let base = y.to_array();
            let h_at = |k: usize, dx: f64| {
                let mut z = base;
                z[k] += dx;
                model.hamiltonian(law, &Augmented::from_array(&z))
            };
            for k in 0..7 {
                let dh_dx = central(|dx| h_at(k, dx), 1e-6);
                let dh_dl = central(|dx| h_at(k + 7, dx), 1e-6);
                assert!(
                    (f[k] - dh_dl).abs() < 1e-6 * (1.0 + f[k].abs()),
                    "S {target_s}: x'[{k}]"
                );
                assert!(
                    (f[k + 7] + dh_dx).abs() < 1e-6 * (1.0 + f[k + 7].abs()),
                    "S {target_s}: λ'[{k}] = {} against −dH/dx = {}",
                    f[k + 7],
                    -dh_dx
                );
            }
        }
    }

    #[test]
    fn the_throttle_is_off_full_or_the_quadratics_vertex() {
        let law = Throttle::Smoothed { epsilon: 0.5 };
        assert_eq!(law.of(0.6), 0.0);
        assert_eq!(law.of(-0.6), 1.0);
        assert!((law.of(0.0) - 0.5).abs() < 1e-15);
        assert!((law.of(0.25) - 0.25).abs() < 1e-15);
        assert_eq!(Throttle::Smoothed { epsilon: 0.0 }.of(-1e-9), 1.0);
        assert_eq!(Throttle::Smoothed { epsilon: 0.0 }.of(1e-9), 0.0);
        assert_eq!(Throttle::Full.of(3.0), 1.0);
        // It minimises the smoothed integrand's share of H, u (S − ε + ε u), over [0, 1].
        for s in [-0.7, -0.2, 0.0, 0.3, 0.8] {
            let best = law.of(s);
            let cost = |u: f64| u * (s - 0.5 + 0.5 * u);
            for k in 0..=100 {
                assert!(cost(best) <= cost(f64::from(k) / 100.0) + 1e-15, "S {s}");
            }
        }
    }

    #[test]
    fn gravity_vanishes_at_the_l1_point_and_its_gradient_is_its_derivative() {
        let model = Model::paper();
        // The L1 point between the primaries, where g_x changes sign: at 0.8369 LU for the
        // Earth–Moon μ (the textbook's 0.836915), with g = 0 there.
        let (mut lo, mut hi) = (0.5, 0.98);
        for _ in 0..60 {
            let mid = 0.5 * (lo + hi);
            if model.gravity(&[mid, 0.0, 0.0])[0] < 0.0 {
                lo = mid;
            } else {
                hi = mid;
            }
        }
        assert!((lo - 0.836_915).abs() < 2e-6, "L1 at {lo}");
        assert!(norm(&model.gravity(&[lo, 0.0, 0.0])) < 1e-12);
        let r = [0.5, 0.3, -0.1];
        let gg = model.gravity_gradient(&r);
        let lambda = [0.4, -1.1, 0.7];
        let third = model.gravity_gradient_along(&r, &lambda);
        for j in 0..3 {
            let at = |dx: f64| {
                let mut q = r;
                q[j] += dx;
                q
            };
            for i in 0..3 {
                let dg = central(|dx| model.gravity(&at(dx))[i], 1e-6);
                assert!((gg[i][j] - dg).abs() < 1e-7, "G[{i}][{j}]");
                let dgl = central(
                    |dx| mat_vec(&model.gravity_gradient(&at(dx)), &lambda)[i],
                    1e-6,
                );
                assert!((third[i][j] - dgl).abs() < 1e-6, "d(Gλ)/dr[{i}][{j}]");
            }
        }
        for (i, row) in gg.iter().enumerate() {
            for (j, x) in row.iter().enumerate() {
                assert!((x - gg[j][i]).abs() < 1e-12, "G symmetric");
            }
        }
    }
}
