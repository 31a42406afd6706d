//! The planning model: Newtonian gravity plus the J2 zonal term, integrated by classical
//! fourth-order Runge-Kutta with a fixed step.
//!
//! Why fixed-step RK4 decides and not an analytic mean-element model: a rendezvous must end on
//! the client's *osculating* position, and over a 15-revolution arc the first-order theory
//! leaves 0.1-3 km (the neglected second-order terms); integrating the J2 force avoids any
//! mean/osculating conversion. The search ranks plans in that theory
//! ([`super::mean_j2`], much cheaper) and every returned plan is flown here. The step is a setting (`Settings::step_s`); a propagation
//! over `dt` takes `ceil(|dt| / step)` equal steps (so every end point is reached exactly) and
//! is refused beyond `Settings::max_steps` steps. Its error against the host truth model's
//! J2-only mode is in `docs/leo-tour.md`.

use crate::astro::Gravity;
use crate::vec3::{add, dot, scale, Vec3};

/// An inertial state: position km, velocity km/s.
pub type State = [f64; 6];

/// Position part of a state.
pub fn pos(s: &State) -> Vec3 {
    [s[0], s[1], s[2]]
}

/// Velocity part of a state.
pub fn vel(s: &State) -> Vec3 {
    [s[3], s[4], s[5]]
}

/// A state from a position and a velocity.
pub fn join(r: &Vec3, v: &Vec3) -> State {
    [r[0], r[1], r[2], v[0], v[1], v[2]]
}

/// Gravitational acceleration (two-body + J2), km/s^2.
pub fn acceleration(g: &Gravity, r: &Vec3) -> Vec3 {
    // One square root and one division per call (the step's four calls are most of a flight).
    let r2 = dot(r, r);
    let inv_r = 1.0 / libm::sqrt(r2);
    let inv_r2 = inv_r * inv_r;
    let inv_r3 = inv_r2 * inv_r;
    let central = scale(r, -g.mu_km3_s2 * inv_r3);
    let z2_r2 = r[2] * r[2] * inv_r2;
    let k = -1.5 * g.j2 * g.mu_km3_s2 * g.re_km * g.re_km * inv_r3 * inv_r2;
    let j2 = [
        k * r[0] * (1.0 - 5.0 * z2_r2),
        k * r[1] * (1.0 - 5.0 * z2_r2),
        k * r[2] * (3.0 - 5.0 * z2_r2),
    ];
    add(&central, &j2)
}

fn derivative(g: &Gravity, s: &State) -> State {
    let a = acceleration(g, &pos(s));
    [s[3], s[4], s[5], a[0], a[1], a[2]]
}

fn axpy(s: &State, k: f64, d: &State) -> State {
    [
        s[0] + k * d[0],
        s[1] + k * d[1],
        s[2] + k * d[2],
        s[3] + k * d[3],
        s[4] + k * d[4],
        s[5] + k * d[5],
    ]
}

/// One RK4 step of length `h` (negative steps integrate backwards).
pub fn rk4_step(g: &Gravity, s: &State, h: f64) -> State {
    let k1 = derivative(g, s);
    let k2 = derivative(g, &axpy(s, 0.5 * h, &k1));
    let k3 = derivative(g, &axpy(s, 0.5 * h, &k2));
    let k4 = derivative(g, &axpy(s, h, &k3));
    let mut out = *s;
    for (((o, a), (b, c)), d) in out
        .iter_mut()
        .zip(k1.iter())
        .zip(k2.iter().zip(k3.iter()))
        .zip(k4.iter())
    {
        *o += h / 6.0 * (a + 2.0 * b + 2.0 * c + d);
    }
    out
}

/// How many equal steps of at most `step_s` cover `dt_s`, or `None` when more than
/// `max_steps` (or a non-finite span) would be needed.
pub fn step_count(dt_s: f64, step_s: f64, max_steps: u32) -> Option<u32> {
    if !(dt_s.is_finite() && step_s.is_finite() && step_s > 0.0) {
        return None;
    }
    let n = libm::ceil(dt_s.abs() / step_s);
    if n > f64::from(max_steps) {
        return None;
    }
    // n is a whole number in [0, max_steps]: the conversion is exact.
    #[allow(clippy::cast_possible_truncation, clippy::cast_sign_loss)]
    let n = n as u32;
    Some(n)
}

/// Propagate `s` by `dt_s` in `n` equal RK4 steps (`n` from [`step_count`]); `None` if the
/// state leaves the finite numbers (e.g. a transfer through the Earth's centre).
pub fn propagate_steps(g: &Gravity, s: &State, dt_s: f64, n: u32) -> Option<State> {
    if n == 0 {
        return s.iter().all(|v| v.is_finite()).then_some(*s);
    }
    let h = dt_s / f64::from(n);
    let mut x = *s;
    for _ in 0..n {
        x = rk4_step(g, &x, h);
    }
    x.iter().all(|v| v.is_finite()).then_some(x)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::vec3::{cross, norm, sub};

    const G: Gravity = Gravity::EARTH;

    #[test]
    fn energy_and_polar_angular_momentum_are_conserved_under_j2() {
        // J2 is axisymmetric and conservative: h_z and the energy with the J2 potential stay.
        let s0: State = [6878.0, 0.0, 0.0, 0.0, 0.9 * 7.613, 0.43 * 7.613];
        let energy = |s: &State| {
            let r = pos(s);
            let rn = norm(&r);
            let v = vel(s);
            let sin_lat = r[2] / rn;
            0.5 * dot(&v, &v) - G.mu_km3_s2 / rn
                + G.mu_km3_s2 * G.j2 * G.re_km * G.re_km / (rn * rn * rn)
                    * 0.5
                    * (3.0 * sin_lat * sin_lat - 1.0)
        };
        let n = step_count(86_400.0, 20.0, 100_000).unwrap();
        let s1 = propagate_steps(&G, &s0, 86_400.0, n).unwrap();
        let hz = |s: &State| cross(&pos(s), &vel(s))[2];
        // RK4 at 20 s is not symplectic: measured drift 4.4e-7 km^2/s^2 in a day (1.5e-8
        // relative, about 0.1 m of semi-major axis).
        assert!((energy(&s1) - energy(&s0)).abs() < 1e-6, "energy");
        let dh = (hz(&s1) - hz(&s0)).abs() / hz(&s0).abs();
        assert!(dh < 1e-8, "h_z {dh}");
        // And there and back again returns to the start.
        let back = propagate_steps(&G, &s1, -86_400.0, n).unwrap();
        let err = norm(&sub(&pos(&back), &pos(&s0)));
        // RK4 at 20 s: measured 14.8 m after a day there and back (the step error of each
        // way); a wrong force or a sign error would miss by kilometres.
        assert!(err < 0.03, "{err}");
    }

    #[test]
    fn step_count_is_bounded() {
        assert_eq!(step_count(100.0, 20.0, 10), Some(5));
        assert_eq!(step_count(101.0, 20.0, 10), Some(6));
        assert_eq!(step_count(1000.0, 20.0, 10), None);
        assert_eq!(step_count(f64::NAN, 20.0, 10), None);
        assert_eq!(step_count(10.0, 0.0, 10), None);
    }
}
