//! The analytic minimum-energy trajectory of one axis with bounded control, from Pontryagin's
//! principle (Huang 2012, eq. 24-26): `u(t) = sat(c1 t - c2)`, a cubic when the bound is
//! inactive, saturated arcs otherwise.
//!
//! The control is parametrised as `u(t) = sat(s(t))`, `s(t) = alpha + beta (2 t / T - 1)`
//! (the paper's `c1 t - c2`, rescaled so both unknowns are of the size of the force). The two
//! boundary-value equations are the gradient of the concave dual of the minimum-energy problem,
//! so a damped Newton iteration on them converges from the cubic's coefficients.

/// Halvings of a Newton step before the iteration gives up (the step is then below 1e-12 of the
/// full step).
const BACKTRACK_STEPS: u16 = 40;

/// One axis's boundary data: positions (LU), velocities (LU/TU), horizon T (TU), mass (MU),
/// bound Umax (FU).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub(crate) struct AxisBoundary {
    pub p0: f64,
    pub v0: f64,
    pub p1: f64,
    pub v1: f64,
    pub horizon: f64,
    pub mass: f64,
    pub max_control: f64,
}

/// The minimum-energy control law of one axis: `u(t) = sat_{Umax}(alpha + beta (2 t / T - 1))`.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub(crate) struct AxisLaw {
    pub alpha: f64,
    pub beta: f64,
    pub boundary: AxisBoundary,
    /// The bound is active somewhere on [0, T].
    pub saturated: bool,
}

/// Why an axis has no analytic guess.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum GuessError {
    /// The boundary conditions lie outside what bang-bang control reaches in T.
    Infeasible,
    /// Newton did not meet the boundary conditions within its iteration limit.
    NotConverged,
}

/// Integrals of the control over [0, T] for a law: `(int u, int t u)` and, over the unsaturated
/// part, `(int 1, int t, int t^2)`.
#[derive(Clone, Copy, Debug, Default)]
struct Moments {
    u0: f64,
    u1: f64,
    free0: f64,
    free1: f64,
    free2: f64,
}

fn clamp(value: f64, bound: f64) -> f64 {
    value.max(-bound).min(bound)
}

/// Integrate `sat(a + b t)` and `t sat(a + b t)` over [lo, hi] exactly, where the sign of the
/// saturation (or its absence) is constant on the piece.
fn piece(a: f64, b: f64, lo: f64, hi: f64, bound: f64, m: &mut Moments) {
    if hi <= lo {
        return;
    }
    let mid = 0.5 * (lo + hi);
    let s_mid = a + b * mid;
    let d1 = hi - lo;
    let d2 = 0.5 * (hi * hi - lo * lo);
    let d3 = (hi * hi * hi - lo * lo * lo) / 3.0;
    if s_mid > bound {
        m.u0 += bound * d1;
        m.u1 += bound * d2;
    } else if s_mid < -bound {
        m.u0 -= bound * d1;
        m.u1 -= bound * d2;
    } else {
        m.u0 += a * d1 + b * d2;
        m.u1 += a * d2 + b * d3;
        m.free0 += d1;
        m.free1 += d2;
        m.free2 += d3;
    }
}

/// The times where `a + b t` crosses `+-bound`, sorted; `None` for a constant law.
fn crossings(a: f64, b: f64, bound: f64) -> Option<[f64; 2]> {
    if b == 0.0 {
        return None;
    }
    let mut crossings = [(bound - a) / b, (-bound - a) / b];
    if crossings[0] > crossings[1] {
        crossings.swap(0, 1);
    }
    Some(crossings)
}

/// The times in (lo, hi) where the law crosses `+-bound` (`crossings`), plus the ends.
fn breakpoints(crossings: Option<[f64; 2]>, lo: f64, hi: f64) -> ([f64; 4], usize) {
    let mut points = [lo, hi, hi, hi];
    let mut count = 1usize;
    for t in crossings.into_iter().flatten() {
        if t > lo && t < hi {
            if let Some(slot) = points.get_mut(count) {
                *slot = t;
            }
            count = count.saturating_add(1);
        }
    }
    if let Some(slot) = points.get_mut(count) {
        *slot = hi;
    }
    (points, count.saturating_add(1))
}

/// An axis law made ready for many evaluations (the closest-approach searches take about a
/// hundred per pair): its linear form and switching times computed once, the same arithmetic
/// as computing them at every call, so the same bits.
#[derive(Clone, Copy, Debug, Default)]
pub(crate) struct Track {
    a: f64,
    b: f64,
    bound: f64,
    crossings: Option<[f64; 2]>,
    p0: f64,
    v0: f64,
    mass: f64,
}

impl Track {
    fn moments(&self, upto: f64) -> Moments {
        let (points, count) = breakpoints(self.crossings, 0.0, upto);
        let mut m = Moments::default();
        for (&lo, &hi) in points
            .iter()
            .zip(points.iter().skip(1))
            .take(count.saturating_sub(1))
        {
            piece(self.a, self.b, lo, hi, self.bound, &mut m);
        }
        m
    }

    /// Acceleration (LU/TU^2) at time `t`: the saturated control over the mass.
    pub fn acceleration(&self, t: f64) -> f64 {
        clamp(self.a + self.b * t, self.bound) / self.mass
    }

    /// Position (LU) and velocity (LU/TU) at time `t`: `x(t) = p0 + v0 t + int_0^t (t - s)
    /// u(s) / m ds`, exact for the piecewise-linear control.
    pub fn state(&self, t: f64) -> (f64, f64) {
        let m = self.moments(t);
        let velocity = self.v0 + m.u0 / self.mass;
        let position = self.p0 + self.v0 * t + (t * m.u0 - m.u1) / self.mass;
        (position, velocity)
    }
}

impl AxisLaw {
    /// The law in the form `a + b t` (t in TU).
    fn linear(&self) -> (f64, f64) {
        let t = self.boundary.horizon;
        (self.alpha - self.beta, 2.0 * self.beta / t)
    }

    /// The law ready for repeated evaluation.
    pub fn track(&self) -> Track {
        let (a, b) = self.linear();
        let bound = self.boundary.max_control;
        Track {
            a,
            b,
            bound,
            crossings: crossings(a, b, bound),
            p0: self.boundary.p0,
            v0: self.boundary.v0,
            mass: self.boundary.mass,
        }
    }

    fn moments(&self, upto: f64) -> Moments {
        self.track().moments(upto)
    }

    /// The unconstrained cubic's control (no saturation) at `t`, FU.
    pub fn cubic_control(&self, t: f64) -> f64 {
        let (a, b) = self.linear();
        a + b * t
    }

    /// The unconstrained cubic's position (LU) at `t`: `p0 + v0 t + (a t^2/2 + b t^3/6) / m`.
    pub fn cubic_position(&self, t: f64) -> f64 {
        let (a, b) = self.linear();
        let bd = &self.boundary;
        bd.p0 + bd.v0 * t + (0.5 * a * t * t + b * t * t * t / 6.0) / bd.mass
    }

    /// Control force at time `t` (TU), FU.
    pub fn control(&self, t: f64) -> f64 {
        let (a, b) = self.linear();
        clamp(a + b * t, self.boundary.max_control)
    }
}

/// A spacecraft's three axis laws made ready for the closest-approach searches.
pub(crate) fn tracks(laws: &[AxisLaw; 3]) -> [Track; 3] {
    laws.map(|law| law.track())
}

/// The reachable position change with `|u| <= Umax` given the velocity change; returns
/// `(min, max)` of `p1 - p0 - v0 T`, or `None` if the velocity change itself is out of reach.
fn reachable(bd: &AxisBoundary) -> Option<(f64, f64)> {
    let accel = bd.max_control / bd.mass;
    let t = bd.horizon;
    let dv = bd.v1 - bd.v0;
    if libm::fabs(dv) > accel * t {
        return None;
    }
    // Full thrust forward then backward (max) or backward then forward (min).
    let t_forward = 0.5 * (t + dv / accel);
    let t_backward = 0.5 * (t - dv / accel);
    let dp_max = accel * (0.5 * t * t - (t - t_forward) * (t - t_forward));
    let dp_min = accel * ((t - t_backward) * (t - t_backward) - 0.5 * t * t);
    Some((dp_min, dp_max))
}

/// The unconstrained minimum-energy law (a cubic): `int u = m dv`, `int (T - t) u = m dp`.
/// With `u = alpha + beta (2t/T - 1)`: `int u = alpha T`, `int (T - t) u = alpha T^2/2 - beta T^2/6`.
pub(crate) fn unconstrained(bd: AxisBoundary) -> AxisLaw {
    let t = bd.horizon;
    let dv = bd.v1 - bd.v0;
    let dp = bd.p1 - bd.p0 - bd.v0 * t;
    let alpha = bd.mass * dv / t;
    let beta = 6.0 * (alpha * t * t / 2.0 - bd.mass * dp) / (t * t);
    AxisLaw {
        alpha,
        beta,
        boundary: bd,
        saturated: false,
    }
}

/// Solve one axis. `max_newton` bounds the Newton iterations of the saturated case.
pub(crate) fn solve_axis(bd: AxisBoundary, max_newton: u16) -> Result<AxisLaw, GuessError> {
    let t = bd.horizon;
    let dv = bd.v1 - bd.v0;
    let dp = bd.p1 - bd.p0 - bd.v0 * t;
    let mut law = unconstrained(bd);
    if libm::fabs(law.alpha) + libm::fabs(law.beta) <= bd.max_control {
        return Ok(law);
    }
    law.saturated = true;
    let Some((dp_min, dp_max)) = reachable(&bd) else {
        return Err(GuessError::Infeasible);
    };
    let slack = 1e-12 * (1.0 + libm::fabs(dp));
    if dp < dp_min - slack || dp > dp_max + slack {
        return Err(GuessError::Infeasible);
    }
    // Residuals of the two boundary conditions, scaled to force units.
    let residual = |law: &AxisLaw| -> (f64, f64, Moments) {
        let m = law.moments(t);
        let r0 = m.u0 / t - bd.mass * dv / t;
        let r1 = (t * m.u0 - m.u1) / (t * t) - bd.mass * dp / (t * t);
        (r0, r1, m)
    };
    let tolerance = 1e-13 * bd.max_control;
    let (mut r0, mut r1, mut m) = residual(&law);
    for _ in 0..max_newton {
        let norm = libm::fabs(r0) + libm::fabs(r1);
        if norm <= tolerance {
            return Ok(law);
        }
        // Jacobian of (r0, r1) w.r.t. (a, b) of s = a + b t on the unsaturated set, then
        // chained to (alpha, beta): a = alpha - beta, b = 2 beta / T.
        let j00 = m.free0 / t;
        let j01 = m.free1 / t;
        let j10 = (t * m.free0 - m.free1) / (t * t);
        let j11 = (t * m.free1 - m.free2) / (t * t);
        let k00 = j00;
        let k01 = -j00 + 2.0 * j01 / t;
        let k10 = j10;
        let k11 = -j10 + 2.0 * j11 / t;
        let det = k00 * k11 - k01 * k10;
        let (mut d_alpha, mut d_beta);
        if libm::fabs(det) > 1e-14 * (k00 * k00 + k11 * k11 + 1e-300) {
            d_alpha = -(k11 * r0 - k01 * r1) / det;
            d_beta = -(-k10 * r0 + k00 * r1) / det;
        } else {
            // Fully saturated: move the switching line toward the unsaturated region.
            d_alpha = -r0;
            d_beta = -r1;
            if libm::fabs(law.alpha) > bd.max_control {
                d_alpha -= 0.5 * (law.alpha - clamp(law.alpha, bd.max_control));
            }
            if libm::fabs(law.beta) > 2.0 * bd.max_control {
                d_beta -= 0.5 * (law.beta - clamp(law.beta, 2.0 * bd.max_control));
            }
        }
        // Backtracking on the residual norm (the residual is the dual gradient: monotone).
        let mut step = 1.0;
        let mut accepted = false;
        for _ in 0..BACKTRACK_STEPS {
            let trial = AxisLaw {
                alpha: law.alpha + step * d_alpha,
                beta: law.beta + step * d_beta,
                ..law
            };
            let (t0, t1, tm) = residual(&trial);
            if libm::fabs(t0) + libm::fabs(t1) < norm {
                law = trial;
                (r0, r1, m) = (t0, t1, tm);
                accepted = true;
                break;
            }
            step *= 0.5;
        }
        if !accepted {
            break;
        }
    }
    if libm::fabs(r0) + libm::fabs(r1) <= 1e-9 * bd.max_control {
        Ok(law)
    } else {
        Err(GuessError::NotConverged)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn bd(p0: f64, v0: f64, p1: f64, v1: f64, umax: f64) -> AxisBoundary {
        AxisBoundary {
            p0,
            v0,
            p1,
            v1,
            horizon: 10.0,
            mass: 1.0,
            max_control: umax,
        }
    }

    #[test]
    fn rest_to_rest_cubic_matches_closed_form() {
        // x(t) = D (3 s^2 - 2 s^3), u = 6 D / T^2 (1 - 2 s), J = 6 D^2 / T^3.
        let law = solve_axis(bd(0.0, 0.0, 12.0, 0.0, 1.0), 50).unwrap();
        assert!(!law.saturated);
        assert!((law.control(0.0) - 0.72).abs() < 1e-14);
        assert!((law.control(10.0) + 0.72).abs() < 1e-14);
        let (x, v) = law.track().state(4.0);
        assert!((x - 12.0 * (3.0 * 0.16 - 2.0 * 0.064)).abs() < 1e-12);
        assert!((v - 12.0 * (6.0 * 0.4 - 6.0 * 0.16) / 10.0).abs() < 1e-12);
        let (x1, v1) = law.track().state(10.0);
        assert!((x1 - 12.0).abs() < 1e-12 && v1.abs() < 1e-12);
    }

    #[test]
    fn saturated_case_meets_boundary_conditions() {
        // D = 20 needs 1.2 > 1: saturated arcs at both ends.
        let law = solve_axis(bd(0.0, 0.0, 20.0, 0.0, 1.0), 60).unwrap();
        assert!(law.saturated);
        assert!((law.control(0.0) - 1.0).abs() < 1e-12);
        assert!((law.control(10.0) + 1.0).abs() < 1e-12);
        let (x1, v1) = law.track().state(10.0);
        assert!((x1 - 20.0).abs() < 1e-9, "{x1}");
        assert!(v1.abs() < 1e-9, "{v1}");
    }

    #[test]
    fn moving_boundaries_saturated() {
        let law = solve_axis(bd(1.0, 1.5, -3.0, -0.5, 0.6), 60).unwrap();
        let (x1, v1) = law.track().state(10.0);
        assert!((x1 + 3.0).abs() < 1e-9 && (v1 + 0.5).abs() < 1e-9);
        for k in 0..=100 {
            assert!(law.control(k as f64 * 0.1).abs() <= 0.6 + 1e-15);
        }
    }

    #[test]
    fn bang_bang_limit_is_feasible_and_beyond_is_infeasible() {
        // Rest to rest with Umax = 1, T = 10: the most is a T^2 / 4 = 25.
        assert!(solve_axis(bd(0.0, 0.0, 24.9, 0.0, 1.0), 80).is_ok());
        assert_eq!(
            solve_axis(bd(0.0, 0.0, 25.1, 0.0, 1.0), 80),
            Err(GuessError::Infeasible)
        );
        assert_eq!(
            solve_axis(bd(0.0, 0.0, 0.0, 11.0, 1.0), 80),
            Err(GuessError::Infeasible)
        );
    }
}
