//! Second-order cone algebra for the least-fuel interior point: Jordan product, the arrow
//! solve, Nesterov-Todd scaling and the step to the cone boundary (cones of dimension 4,
//! `(t, x)` with `|x| <= t`).

use super::rows::dot;

/// One second-order cone vector `(t, x)`.
pub(super) type Cone = [f64; 4];

/// `J u` with `J = diag(1, -1, -1, -1)`.
pub(super) fn jmul(u: &Cone) -> Cone {
    [u[0], -u[1], -u[2], -u[3]]
}

/// `sqrt(u^T J u)` (0 outside the cone's interior).
pub(super) fn jnorm(u: &Cone) -> f64 {
    let n1 = libm::sqrt(u[1] * u[1] + u[2] * u[2] + u[3] * u[3]);
    let a = (u[0] - n1) * (u[0] + n1);
    if a > 0.0 {
        libm::sqrt(a)
    } else {
        0.0
    }
}

/// Jordan product `u o v = (u.v, u0 v1 + v0 u1)`.
pub(super) fn jordan(u: &Cone, v: &Cone) -> Cone {
    [
        u[0] * v[0] + u[1] * v[1] + u[2] * v[2] + u[3] * v[3],
        u[0] * v[1] + v[0] * u[1],
        u[0] * v[2] + v[0] * u[2],
        u[0] * v[3] + v[0] * u[3],
    ]
}

/// Solve `v o d = r` for `d` (`v` in the cone's interior).
pub(super) fn arrow_solve(v: &Cone, r: &Cone) -> Cone {
    let det = v[0] * v[0] - (v[1] * v[1] + v[2] * v[2] + v[3] * v[3]);
    let d0 = (v[0] * r[0] - (v[1] * r[1] + v[2] * r[2] + v[3] * r[3])) / det;
    [
        d0,
        (r[1] - d0 * v[1]) / v[0],
        (r[2] - d0 * v[2]) / v[0],
        (r[3] - d0 * v[3]) / v[0],
    ]
}

/// Nesterov-Todd scaling of one cone: `W = eta (2 q q^T - J)` with `q^T J q = 1`, so that
/// `W z = W^-1 s` (Vandenberghe, "The CVXOPT linear and quadratic cone program solvers", 2010).
#[derive(Clone, Copy, Debug, Default)]
pub(super) struct Scaling {
    pub(super) eta: f64,
    pub(super) q: Cone,
}

impl Scaling {
    /// `None` when `z` or `s` is not strictly inside the cone.
    pub(super) fn new(z: &Cone, s: &Cone) -> Option<Self> {
        let zn = jnorm(z);
        let sn = jnorm(s);
        if !(zn > 0.0 && sn > 0.0) {
            return None;
        }
        let mut zb = *z;
        let mut sb = *s;
        for x in zb.iter_mut() {
            *x /= zn;
        }
        for x in sb.iter_mut() {
            *x /= sn;
        }
        let gamma = libm::sqrt((1.0 + dot(&zb, &sb)) * 0.5);
        // w = (s_bar + J z_bar) / (2 gamma), w^T J w = 1.
        let jz = jmul(&zb);
        let mut w = [0.0; 4];
        for (wi, (si, zi)) in w.iter_mut().zip(sb.iter().zip(jz.iter())) {
            *wi = (*si + *zi) / (2.0 * gamma);
        }
        let den = libm::sqrt(2.0 * (w[0] + 1.0));
        let q = [(w[0] + 1.0) / den, w[1] / den, w[2] / den, w[3] / den];
        let eta = libm::sqrt(sn / zn);
        if eta.is_finite() && q.iter().all(|v| v.is_finite()) {
            Some(Self { eta, q })
        } else {
            None
        }
    }

    /// `W u`.
    pub(super) fn apply(&self, u: &Cone) -> Cone {
        let a = 2.0 * dot(&self.q, u);
        let ju = jmul(u);
        let mut out = [0.0; 4];
        for (o, (qi, ji)) in out.iter_mut().zip(self.q.iter().zip(ju.iter())) {
            *o = self.eta * (a * *qi - *ji);
        }
        out
    }

    /// `W^-1 u = (2 J q q^T J - J) u / eta`.
    pub(super) fn apply_inv(&self, u: &Cone) -> Cone {
        let jq = jmul(&self.q);
        let a = 2.0 * dot(&jq, u);
        let ju = jmul(u);
        let mut out = [0.0; 4];
        for (o, (qi, ji)) in out.iter_mut().zip(jq.iter().zip(ju.iter())) {
            *o = (a * *qi - *ji) / self.eta;
        }
        out
    }

    /// The lower-right 3 x 3 block of `W^-2` as `(I + c qbar qbar^T) / eta^2`, returned as
    /// `(1 / eta^2, c)` with `qbar = q[1..4]`: with `a = J q`, `(2 a a^T - J)^2 = 4 (a.a) a a^T
    /// - 2 a q^T - 2 q a^T + I`, whose lower block is `(4 |q|^2 + 4) qbar qbar^T + I`.
    pub(super) fn inv_squared_block(&self) -> (f64, f64) {
        let qq = dot(&self.q, &self.q);
        (1.0 / (self.eta * self.eta), 4.0 * qq + 4.0)
    }

    /// `W^-2` as a dense 4 x 4 (symmetric).
    #[cfg(test)]
    pub(super) fn inv_squared(&self) -> [[f64; 4]; 4] {
        let mut m = [[0.0; 4]; 4];
        for (j, col) in m.iter_mut().enumerate() {
            let mut e = [0.0; 4];
            if let Some(x) = e.get_mut(j) {
                *x = 1.0;
            }
            *col = self.apply_inv(&self.apply_inv(&e));
        }
        m
    }
}

/// Largest `alpha` with `u + alpha du` in the cone (infinite when the ray stays inside): the
/// first positive root of `(u + a du)^T J (u + a du)`.
pub(super) fn max_step(u: &Cone, du: &Cone) -> f64 {
    let a = du[0] * du[0] - (du[1] * du[1] + du[2] * du[2] + du[3] * du[3]);
    let b = u[0] * du[0] - (u[1] * du[1] + u[2] * du[2] + u[3] * du[3]);
    let n1 = libm::sqrt(u[1] * u[1] + u[2] * u[2] + u[3] * u[3]);
    let c = (u[0] - n1) * (u[0] + n1);
    if c <= 0.0 {
        return 0.0;
    }
    let disc = b * b - a * c;
    if disc < 0.0 {
        // No real root: the quadratic keeps its sign, the ray never meets the boundary.
        return f64::INFINITY;
    }
    let sq = libm::sqrt(disc);
    // Roots (-b +- sq) / a, computed without cancellation: t1 = q / a, t2 = c / q.
    let qv = if b >= 0.0 { -(b + sq) } else { -b + sq };
    let mut best = f64::INFINITY;
    for root in [
        if a != 0.0 { qv / a } else { f64::INFINITY },
        if qv != 0.0 { c / qv } else { f64::INFINITY },
    ] {
        if root > 0.0 && root < best {
            best = root;
        }
    }
    best
}

#[cfg(test)]
#[allow(clippy::needless_range_loop)]
mod tests {
    use super::*;

    #[test]
    fn scaling_maps_both_points_to_the_same_scaled_point() {
        let z = [2.0, 0.3, -0.5, 1.1];
        let s = [0.7, -0.2, 0.1, 0.4];
        let w = Scaling::new(&z, &s).unwrap();
        let a = w.apply(&z);
        let b = w.apply_inv(&s);
        for (x, y) in a.iter().zip(b.iter()) {
            assert!((x - y).abs() < 1e-14, "{a:?} {b:?}");
        }
        let u = [0.3, 1.0, -2.0, 0.5];
        let back = w.apply(&w.apply_inv(&u));
        for (x, y) in back.iter().zip(u.iter()) {
            assert!((x - y).abs() < 1e-13);
        }
        assert!(Scaling::new(&[1.0, 1.0, 0.0, 0.0], &s).is_none());
    }

    #[test]
    fn closed_form_block_of_the_inverse_squared_scaling() {
        let w = Scaling::new(&[2.0, 0.3, -0.5, 1.1], &[0.7, -0.2, 0.1, 0.4]).unwrap();
        let full = w.inv_squared();
        let (inv_eta2, c) = w.inv_squared_block();
        for i in 1..4 {
            for j in 1..4 {
                let want = inv_eta2 * (if i == j { 1.0 } else { 0.0 } + c * w.q[i] * w.q[j]);
                assert!((full[j][i] - want).abs() < 1e-13, "{i} {j}");
            }
        }
    }

    #[test]
    fn step_to_the_cone_boundary() {
        let u = [1.0, 0.0, 0.0, 0.0];
        // Towards (0, 1, 0, 0): boundary where 1 - a = a, a = 0.5.
        assert!((max_step(&u, &[-1.0, 1.0, 0.0, 0.0]) - 0.5).abs() < 1e-15);
        // Inside the cone: no limit.
        assert!(max_step(&u, &[1.0, 0.5, 0.0, 0.0]).is_infinite());
        // Straight down the axis: the apex at 1.
        assert!((max_step(&u, &[-1.0, 0.0, 0.0, 0.0]) - 1.0).abs() < 1e-15);
        // Sideways: the boundary at |a| = 1.
        assert!((max_step(&u, &[0.0, 0.0, 1.0, 0.0]) - 1.0).abs() < 1e-15);
    }
}
