//! The departure (SPEC-hybrid.md eq. 4): a tangential chemical impulse on a circular, planar
//! parking orbit about the Earth multiplies the inertial speed by κ at phase θ; the state after
//! it in the rotating frame, the mass left, the chemical propellant's cost `Θ(κ)`, and their
//! derivatives in κ and θ (the shooting's Jacobian rows of eq. 24 and the transversality
//! conditions of eq. 12).

use super::units;

/// The parking orbit and the chemical engine.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Departure {
    /// μ of the CR3BP.
    pub mass_ratio: f64,
    /// Radius of the circular parking orbit about the Earth, LU.
    pub parking_radius_lu: f64,
    /// Exhaust speed of the chemical engine, LU/TU.
    pub chemical_exhaust_vu: f64,
}

/// The departure state `[r; v; m]` (7) and its derivatives.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct DepartureState {
    /// `x0(κ, θ)`.
    pub state: [f64; 7],
    /// `∂x0/∂κ`.
    pub d_kappa: [f64; 7],
    /// `∂x0/∂θ`.
    pub d_theta: [f64; 7],
    /// `∂²x0/∂κ²`.
    pub d_kappa_kappa: [f64; 7],
    /// `∂²x0/∂κ∂θ`.
    pub d_kappa_theta: [f64; 7],
    /// `∂²x0/∂θ²`.
    pub d_theta_theta: [f64; 7],
}

impl Departure {
    /// The paper's: a 6778 km parking orbit (400 km altitude), a chemical engine of 300 s.
    pub fn paper() -> Self {
        Self {
            mass_ratio: units::MASS_RATIO,
            parking_radius_lu: units::distance_lu(6778.0),
            chemical_exhaust_vu: units::exhaust_speed_vu(300.0),
        }
    }

    /// The circular speed of the parking orbit, LU/TU: `√((1 − μ)/r0)`.
    pub fn circular_speed_vu(&self) -> f64 {
        libm::sqrt((1.0 - self.mass_ratio) / self.parking_radius_lu)
    }

    /// The mass left after the impulse, MU: `exp(−(κ − 1) v_c / c1)`.
    pub fn mass_after_impulse(&self, kappa: f64) -> f64 {
        libm::exp(-(kappa - 1.0) * self.circular_speed_vu() / self.chemical_exhaust_vu)
    }

    /// The chemical propellant `Θ(κ) = 1 − m0(κ)` and its first two derivatives in κ.
    pub fn chemical_cost(&self, kappa: f64) -> (f64, f64, f64) {
        let m0 = self.mass_after_impulse(kappa);
        let k = self.circular_speed_vu() / self.chemical_exhaust_vu;
        (1.0 - m0, k * m0, -k * k * m0)
    }

    /// `x0(κ, θ)` and its derivatives (eq. 4): position `r0 (cos θ, sin θ) − (μ, 0)`, rotating
    /// velocity `s (−sin θ, cos θ)` with `s = κ v_c − r0` (the inertial speed less the frame's
    /// rotation), mass `m0(κ)`.
    pub fn state(&self, kappa: f64, theta_rad: f64) -> DepartureState {
        let r0 = self.parking_radius_lu;
        let vc = self.circular_speed_vu();
        let s = kappa * vc - r0;
        let (sin, cos) = (libm::sin(theta_rad), libm::cos(theta_rad));
        let m0 = self.mass_after_impulse(kappa);
        let k = vc / self.chemical_exhaust_vu;
        DepartureState {
            state: [
                r0 * cos - self.mass_ratio,
                r0 * sin,
                0.0,
                -s * sin,
                s * cos,
                0.0,
                m0,
            ],
            d_kappa: [0.0, 0.0, 0.0, -vc * sin, vc * cos, 0.0, -k * m0],
            d_theta: [-r0 * sin, r0 * cos, 0.0, -s * cos, -s * sin, 0.0, 0.0],
            d_kappa_kappa: [0.0, 0.0, 0.0, 0.0, 0.0, 0.0, k * k * m0],
            d_kappa_theta: [0.0, 0.0, 0.0, -vc * cos, -vc * sin, 0.0, 0.0],
            d_theta_theta: [-r0 * cos, -r0 * sin, 0.0, s * sin, -s * cos, 0.0, 0.0],
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Table 2's third column, the mass after the impulse, follows from κ alone (the digest
    /// checked it; some printed entries are truncated rather than rounded).
    #[test]
    fn the_mass_after_the_impulse_is_table_2s() {
        let d = Departure::paper();
        let printed = [
            (1.00, 1.0000),
            (1.04, 0.9011),
            (1.08, 0.8119),
            (1.12, 0.7316),
            (1.16, 0.6593),
            (1.20, 0.5941),
            (1.24, 0.5353),
            (1.28, 0.4824),
            (1.32, 0.4347),
            (1.36, 0.3917),
            (1.40, 0.3529),
        ];
        for (kappa, mass) in printed {
            let m = d.mass_after_impulse(kappa);
            assert!(
                m >= mass - 5e-5 && m < mass + 1e-4,
                "κ {kappa}: {m} against {mass}"
            );
        }
    }

    /// The rotating-frame state is the inertial circular orbit sped up by κ; the derivatives
    /// are the state's, by central differences.
    #[test]
    fn the_departure_and_its_derivatives() {
        let d = Departure::paper();
        let (kappa, theta) = (1.4, -2.0);
        let x = d.state(kappa, theta);
        // Inertial velocity = rotating velocity + ω × r (ω = ẑ, r from the barycentre).
        let r = [x.state[0], x.state[1]];
        let inertial = [x.state[3] - r[1], x.state[4] + r[0]];
        let about_earth = [r[0] + d.mass_ratio, r[1]];
        let speed = libm::sqrt(inertial[0] * inertial[0] + inertial[1] * inertial[1]);
        // The Earth moves at μ about the barycentre: the speed relative to the Earth is κ v_c.
        let earth_v = [0.0, -d.mass_ratio];
        let rel = [inertial[0] - earth_v[0], inertial[1] - earth_v[1]];
        let rel_speed = libm::sqrt(rel[0] * rel[0] + rel[1] * rel[1]);
        assert!(
            (rel_speed - kappa * d.circular_speed_vu()).abs() < 1e-12,
            "{rel_speed}"
        );
        assert!(speed > 0.0);
        // Tangential: the velocity relative to the Earth is normal to the radius.
        assert!((rel[0] * about_earth[0] + rel[1] * about_earth[1]).abs() < 1e-12);
        let h = 1e-5;
        let fd = |f: &dyn Fn(f64, f64) -> [f64; 7], dk: f64, dt: f64| {
            let (p, m) = (f(kappa + dk, theta + dt), f(kappa - dk, theta - dt));
            let mut out = [0.0; 7];
            for i in 0..7 {
                out[i] = (p[i] - m[i]) / (2.0 * h);
            }
            out
        };
        let state = |k: f64, t: f64| d.state(k, t).state;
        let dk = |k: f64, t: f64| d.state(k, t).d_kappa;
        let dt = |k: f64, t: f64| d.state(k, t).d_theta;
        for (analytic, numeric) in [
            (x.d_kappa, fd(&state, h, 0.0)),
            (x.d_theta, fd(&state, 0.0, h)),
            (x.d_kappa_kappa, fd(&dk, h, 0.0)),
            (x.d_kappa_theta, fd(&dk, 0.0, h)),
            (x.d_theta_theta, fd(&dt, 0.0, h)),
        ] {
            for (a, n) in analytic.iter().zip(numeric) {
                assert!(
                    (a - n).abs() < 1e-7 * (1.0 + n.abs()),
                    "{analytic:?} against {numeric:?}"
                );
            }
        }
        let (_, d1, d2) = d.chemical_cost(kappa);
        let cost = |k: f64| d.chemical_cost(k).0;
        assert!((d1 - (cost(kappa + h) - cost(kappa - h)) / (2.0 * h)).abs() < 1e-8);
        let slope = |k: f64| d.chemical_cost(k).1;
        assert!((d2 - (slope(kappa + h) - slope(kappa - h)) / (2.0 * h)).abs() < 1e-8);
    }
}
