//! Lambert's problem, multi-revolution, general 3-D: the two-body orbit from `r1` to `r2` in a
//! given time with a given number of whole revolutions (Izzo 2015, "Revisiting Lambert's
//! problem", Householder iterations on Lancaster–Blanchard's x variable).
//!
//! Used by the GEO tour (phasing by Lambert transfer); written for any pair of positions so the
//! LEO tour can reuse it.
//!
//! ## Degenerate geometry
//! When `r1` and `r2` are (nearly) parallel the transfer plane is not defined by the positions;
//! the caller's `normal` (the wanted angular momentum direction) defines it. The end points may
//! coincide (transfer angle `2 pi K`): then `lambda = 1`, and the right branch is the tangential
//! K-revolution phasing orbit (the limit the GEO tour's Lambert wells approach), the left one
//! a rectilinear fall. Both are returned as finite numbers; no division by the chord.
//!
//! ## Bounds
//! At most `max_iter` Householder steps per branch, plus `max_iter` Halley steps for the
//! minimum time of a multi-revolution family. A hypergeometric series of at most 64 terms.

use serde::{Deserialize, Serialize};

/// 3-vector, km or km/s.
pub use crate::vec3::Vec3;
use crate::vec3::{add, cross, dot, norm, scale, sub};

/// Which of the two solutions of a multi-revolution family (K >= 1).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[repr(u8)]
pub enum Branch {
    /// Izzo's "left" (low-path, larger x) solution.
    Left = 0,
    /// Izzo's "right" solution.
    Right = 1,
}

/// Why a Lambert solve gave no orbit.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[repr(u8)]
pub enum LambertError {
    /// An input is NaN or infinite, a radius or the time of flight is not positive, or the
    /// normal has zero length.
    BadInput = 0,
    /// The time of flight is shorter than the least time of a K-revolution transfer.
    NoSolution = 1,
    /// Householder did not converge within `max_iter`.
    NotConverged = 2,
}

/// Departure and arrival velocities of a Lambert transfer, km/s.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LambertSolution {
    /// Velocity just after departure at `r1`.
    pub v1_km_s: Vec3,
    /// Velocity just before arrival at `r2`.
    pub v2_km_s: Vec3,
    /// Householder steps used.
    pub iterations: u16,
    /// Izzo's x at the solution: a starting point for a nearby solve ([`solve_from`]).
    pub x: f64,
}

fn finite(a: &Vec3) -> bool {
    a.iter().all(|v| v.is_finite())
}

/// Gauss hypergeometric 2F1(3, 1; 5/2; z) for |z| < 1 (Battin's series in Izzo's eq. 20),
/// at most 64 terms; used only near x = 1 where z is small.
fn hyp2f1b(z: f64) -> f64 {
    let mut res = 1.0;
    let mut term = 1.0;
    let mut i = 0.0;
    for _ in 0..64 {
        term = term * (3.0 + i) * (1.0 + i) / (2.5 + i) * z / (i + 1.0);
        let old = res;
        res += term;
        if (res - old).abs() <= f64::EPSILON * res.abs() {
            break;
        }
        i += 1.0;
    }
    res
}

/// `z^(2/3)` for `z >= 0`.
fn two_thirds_power(z: f64) -> f64 {
    libm::cbrt(z * z)
}

fn compute_y(x: f64, lam: f64) -> f64 {
    libm::sqrt((1.0 - lam * lam * (1.0 - x * x)).max(0.0))
}

fn compute_psi(x: f64, y: f64, lam: f64) -> f64 {
    if (-1.0..1.0).contains(&x) {
        libm::acos((x * y + lam * (1.0 - x * x)).clamp(-1.0, 1.0))
    } else if x > 1.0 {
        libm::asinh((y - x * lam) * libm::sqrt(x * x - 1.0))
    } else {
        0.0
    }
}

/// Non-dimensional time of flight at x (Izzo eq. 18 / Battin series near x = 1).
fn tof(x: f64, y: f64, lam: f64, revs: f64) -> f64 {
    if revs == 0.0 && x > libm::sqrt(0.6) && x < libm::sqrt(1.4) {
        let eta = y - lam * x;
        let s1 = (1.0 - lam - x * eta) * 0.5;
        let q = 4.0 / 3.0 * hyp2f1b(s1);
        (eta * eta * eta * q + 4.0 * lam * eta) * 0.5
    } else {
        let psi = compute_psi(x, y, lam);
        let one_m = 1.0 - x * x;
        ((psi + revs * core::f64::consts::PI) / libm::sqrt(one_m.abs()) - x + lam * y) / one_m
    }
}

/// First three derivatives of the time of flight with respect to x (Izzo eq. 22).
fn tof_derivatives(x: f64, y: f64, t: f64, lam: f64) -> (f64, f64, f64) {
    let one_m = 1.0 - x * x;
    let l2 = lam * lam;
    let l3 = l2 * lam;
    let d1 = (3.0 * t * x - 2.0 + 2.0 * l3 * x / y) / one_m;
    let d2 = (3.0 * t + 5.0 * x * d1 + 2.0 * (1.0 - l2) * l3 / (y * y * y)) / one_m;
    let d3 =
        (7.0 * x * d2 + 8.0 * d1 - 6.0 * (1.0 - l2) * l2 * l3 * x / (y * y * y * y * y)) / one_m;
    (d1, d2, d3)
}

/// One Halley step of the least-time search on dT/dx = 0 from `x`: the next x (clamped
/// inside (-1, 1)) and whether the step was within the tolerance; `None` when the step is not
/// defined. Exposed (hidden) so that its cost can be measured alone (`geo_tour::kernels`).
#[doc(hidden)]
#[inline(always)]
pub fn halley_step(x: f64, lam: f64, revs: f64, tol: f64) -> Option<(f64, bool)> {
    let y = compute_y(x, lam);
    let t = tof(x, y, lam, revs);
    let (d1, d2, d3) = tof_derivatives(x, y, t, lam);
    let den = 2.0 * d2 * d2 - d1 * d3;
    if den == 0.0 || !den.is_finite() {
        return None;
    }
    let next = x - 2.0 * d1 * d2 / den;
    let done = (next - x).abs() <= tol * (1.0 + x.abs());
    Some((next.clamp(-0.999_999, 0.999_999), done))
}

/// One Householder step (Izzo eq. 22-23) on T(x) = `t_nd` from `x`: the next x and the
/// step's size; `None` when the step is not defined. Exposed (hidden) so that its cost can be
/// measured alone (`geo_tour::kernels`).
#[doc(hidden)]
#[inline(always)]
pub fn householder_step(x: f64, lam: f64, m: f64, t_nd: f64) -> Option<(f64, f64)> {
    let y = compute_y(x, lam);
    let t = tof(x, y, lam, m);
    let f = t - t_nd;
    let (d1, d2, d3) = tof_derivatives(x, y, t, lam);
    let den = d1 * (d1 * d1 - f * d2) + d3 * f * f / 6.0;
    if den == 0.0 || !den.is_finite() {
        return None;
    }
    let next = x - f * (d1 * d1 - f * d2 * 0.5) / den;
    Some((next, (next - x).abs()))
}

/// Least non-dimensional time of a `revs`-revolution family (Halley on dT/dx = 0).
fn min_tof<S: FnMut() -> bool>(
    lam: f64,
    revs: f64,
    max_iter: u16,
    tol: f64,
    step: &mut S,
) -> Option<f64> {
    let mut x = 0.1;
    if lam >= 1.0 {
        x = 0.0;
    } else {
        for _ in 0..max_iter {
            if !step() {
                return None;
            }
            let (next, done) = halley_step(x, lam, revs, tol)?;
            x = next;
            if done {
                break;
            }
        }
    }
    let t = tof(x, compute_y(x, lam), lam, revs);
    t.is_finite().then_some(t)
}

/// Izzo's initial guess of x (eq. 30 and the multi-revolution guesses).
fn izzo_guess(lam: f64, t_nd: f64, revs: u16, branch: Branch) -> f64 {
    let m = f64::from(revs);
    let pi = core::f64::consts::PI;
    if revs == 0 {
        let t0 = libm::acos(lam) + lam * libm::sqrt((1.0 - lam * lam).max(0.0));
        let t1 = 2.0 * (1.0 - lam * lam * lam) / 3.0;
        // z^(2/3) as cbrt(z^2) and lambda^5 as a product: several times cheaper than pow,
        // and only the starting point moves (the iteration converges to the same root).
        if t_nd >= t0 {
            two_thirds_power(t0 / t_nd) - 1.0
        } else if t_nd < t1 {
            let l2 = lam * lam;
            2.5 * t1 / t_nd * (t1 - t_nd) / (1.0 - l2 * l2 * lam) + 1.0
        } else {
            libm::pow(t0 / t_nd, libm::log2(t1 / t0)) - 1.0
        }
    } else {
        let a = two_thirds_power((m * pi + pi) / (8.0 * t_nd));
        let xl = (a - 1.0) / (a + 1.0);
        let b = two_thirds_power(8.0 * t_nd / (m * pi));
        let xr = (b - 1.0) / (b + 1.0);
        match branch {
            Branch::Left => xl.max(xr),
            Branch::Right => xl.min(xr),
        }
    }
}

/// Solve Lambert's problem.
///
/// * `mu_km3_s2`: gravitational parameter.
/// * `r1_km`, `r2_km`: positions at departure and arrival.
/// * `tof_s`: time of flight, s, > 0.
/// * `revs`: whole revolutions K before arrival (0 = direct).
/// * `branch`: which solution of a K >= 1 family (ignored for K = 0).
/// * `normal`: the wanted angular-momentum direction (prograde motion about it); defines the
///   plane when `r1` and `r2` are parallel and picks the short or long way otherwise.
/// * `max_iter`, `tol`: Householder bound and tolerance on x.
///
/// # Errors
/// [`LambertError`] saying why no orbit was returned.
#[allow(clippy::too_many_arguments)]
pub fn solve(
    mu_km3_s2: f64,
    r1_km: &Vec3,
    r2_km: &Vec3,
    tof_s: f64,
    revs: u16,
    branch: Branch,
    normal: &Vec3,
    max_iter: u16,
    tol: f64,
) -> Result<LambertSolution, LambertError> {
    solve_from(
        mu_km3_s2, r1_km, r2_km, tof_s, revs, branch, normal, max_iter, tol, None,
    )
}

/// Work units of one Householder step of a direct (0-revolution) solve
/// ([`householder_step`]) on its dearest branch (the hypergeometric series of a near-parabolic
/// transfer), with the loop's bookkeeping and the meter's check, for the planners that meter
/// a solve step by step ([`solve_from_stepped`]: the GEO and LEO tours, whose unit is at most
/// 100 Cortex-M7 instructions): the M7 instructions measured by the GEO tour's kernel cases
/// (`geo_tour/kernels.rs`), divided by 90 and rounded up.
pub(crate) const STEP_UNITS_DIRECT: u64 = 21;
/// One Householder or Halley step of a multi-revolution solve ([`householder_step`],
/// [`halley_step`]; no series), likewise.
pub(crate) const STEP_UNITS: u64 = 15;

/// The units of one step of a solve of `revs` revolutions.
pub(crate) const fn step_units(revs: u16) -> u64 {
    if revs == 0 {
        STEP_UNITS_DIRECT
    } else {
        STEP_UNITS
    }
}

/// [`solve`] started from `guess` (the `x` of a solution of a nearby problem, e.g. the same
/// family a little earlier or later) instead of Izzo's initial guess: the same root to the
/// tolerance in fewer Householder steps. The guess is kept only when the iteration converges
/// from it on the requested branch (K >= 1: the left solution is where the time of flight
/// grows with x, the right one where it falls); otherwise the solve starts again from Izzo's
/// guess, so the answer is the one [`solve`] gives, to the tolerance, at most `2 max_iter`
/// Householder steps.
///
/// # Errors
/// As [`solve`].
#[allow(clippy::too_many_arguments)]
pub fn solve_from(
    mu_km3_s2: f64,
    r1_km: &Vec3,
    r2_km: &Vec3,
    tof_s: f64,
    revs: u16,
    branch: Branch,
    normal: &Vec3,
    max_iter: u16,
    tol: f64,
    guess: Option<f64>,
) -> Result<LambertSolution, LambertError> {
    solve_from_stepped(
        mu_km3_s2,
        r1_km,
        r2_km,
        tof_s,
        revs,
        branch,
        normal,
        (max_iter, tol),
        guess,
        &mut || true,
    )
}

/// [`solve_from`] with `step` asked before every Householder and Halley step: when it
/// returns `false` the solve stops (`NotConverged`). A caller meters the solve's work this
/// way (the GEO tour charges each step to its work budget); the answer is otherwise the one
/// [`solve_from`] gives, bit for bit.
///
/// # Errors
/// As [`solve`].
#[allow(clippy::too_many_arguments)]
pub fn solve_from_stepped<S: FnMut() -> bool>(
    mu_km3_s2: f64,
    r1_km: &Vec3,
    r2_km: &Vec3,
    tof_s: f64,
    revs: u16,
    branch: Branch,
    normal: &Vec3,
    (max_iter, tol): (u16, f64),
    guess: Option<f64>,
    step: &mut S,
) -> Result<LambertSolution, LambertError> {
    let r1n = norm(r1_km);
    let r2n = norm(r2_km);
    let nn = norm(normal);
    let valid = finite(r1_km)
        && finite(r2_km)
        && finite(normal)
        && mu_km3_s2.is_finite()
        && mu_km3_s2 > 0.0
        && tof_s.is_finite()
        && tof_s > 0.0
        && r1n > 0.0
        && r2n > 0.0
        && nn > 0.0;
    if !valid {
        return Err(LambertError::BadInput);
    }
    let ir1 = scale(r1_km, 1.0 / r1n);
    let ir2 = scale(r2_km, 1.0 / r2n);
    let ihat = scale(normal, 1.0 / nn);
    let chord = sub(r2_km, r1_km);
    let c = norm(&chord);
    let s = 0.5 * (r1n + r2n + c);
    // Plane normal: from the positions when they span one, else the caller's; oriented with
    // the caller's so the motion is prograde about `normal`.
    let h_raw = cross(&ir1, &ir2);
    let hn = norm(&h_raw);
    let (ih, long_way) = if hn > 1e-12 {
        let h = scale(&h_raw, 1.0 / hn);
        if dot(&h, &ihat) >= 0.0 {
            (h, false)
        } else {
            (scale(&h, -1.0), true)
        }
    } else {
        // Parallel positions: same direction (angle 0 mod 2 pi) or opposite (pi).
        (ihat, false)
    };
    let mut lam = libm::sqrt((1.0 - (c / s).min(1.0)).max(0.0));
    if long_way {
        lam = -lam;
    }
    let it1 = cross(&ih, &ir1);
    let it2 = cross(&ih, &ir2);
    let t_nd = libm::sqrt(2.0 * mu_km3_s2 / (s * s * s)) * tof_s;
    let m = f64::from(revs);
    let pi = core::f64::consts::PI;
    // Householder from x0 (Izzo eq. 22-23): the converged x, or None.
    let householder = |x0: f64, used: &mut u16, step: &mut S| -> Option<f64> {
        let mut x = x0;
        for _ in 0..max_iter {
            if !step() {
                return None;
            }
            *used = used.saturating_add(1);
            let (next, step) = householder_step(x, lam, m, t_nd)?;
            x = next;
            if !x.is_finite() {
                return None;
            }
            if step <= tol * (1.0 + x.abs()) {
                return (x > -1.0 || revs == 0).then_some(x);
            }
        }
        None
    };
    let mut used = 0u16;
    // A warm start is kept when it converged on the requested branch: the time of flight
    // grows with x at the left solution and falls at the right one (a converged root also
    // shows the K-revolution family reaches this time, so no least-time search is needed).
    let warm = guess
        .filter(|g| g.is_finite() && *g > -1.0)
        .and_then(|g| householder(g, &mut used, step))
        .filter(|&x| {
            revs == 0 || {
                let y = compute_y(x, lam);
                let (d1, _, _) = tof_derivatives(x, y, tof(x, y, lam, m), lam);
                match branch {
                    Branch::Left => d1 > 0.0,
                    Branch::Right => d1 < 0.0,
                }
            }
        });
    let x = match warm {
        Some(x) => x,
        None => {
            // T(x = 0) = acos(lambda) + lambda sqrt(1 - lambda^2) + K pi bounds the least
            // time of the K-revolution family from above: only shorter times need the Halley
            // search for it.
            // Every K-revolution transfer takes more than K pi (non-dimensional): the time
            // is the direct part (positive) plus K pi / (1 - x^2)^(3/2). Equivalently K
            // periods of the least-energy orbit (a = s/2) fit in the time of flight. Shorter
            // times are refused before the least-time search.
            if revs > 0 && t_nd <= m * pi {
                return Err(LambertError::NoSolution);
            }
            let t_00 = libm::acos(lam) + lam * libm::sqrt((1.0 - lam * lam).max(0.0)) + m * pi;
            if revs > 0 && t_nd < t_00 {
                let t_min =
                    min_tof(lam, m, max_iter, tol, step).ok_or(LambertError::NotConverged)?;
                if t_nd < t_min {
                    return Err(LambertError::NoSolution);
                }
            }
            householder(izzo_guess(lam, t_nd, revs, branch), &mut used, step)
                .ok_or(LambertError::NotConverged)?
        }
    };
    let y = compute_y(x, lam);
    let gamma = libm::sqrt(mu_km3_s2 * s / 2.0);
    // rho = (r1 - r2) / c; with equal radii it is 0 however small the chord (GEO phasing).
    let dr = r1n - r2n;
    let rho = if c > 0.0 {
        (dr / c).clamp(-1.0, 1.0)
    } else {
        0.0
    };
    let sigma = libm::sqrt((1.0 - rho * rho).max(0.0));
    let vr1 = gamma * ((lam * y - x) - rho * (lam * y + x)) / r1n;
    let vr2 = -gamma * ((lam * y - x) + rho * (lam * y + x)) / r2n;
    let vt1 = gamma * sigma * (y + lam * x) / r1n;
    let vt2 = gamma * sigma * (y + lam * x) / r2n;
    let v1 = add(&scale(&ir1, vr1), &scale(&it1, vt1));
    let v2 = add(&scale(&ir2, vr2), &scale(&it2, vt2));
    if finite(&v1) && finite(&v2) {
        Ok(LambertSolution {
            v1_km_s: v1,
            v2_km_s: v2,
            iterations: used,
            x,
        })
    } else {
        Err(LambertError::NotConverged)
    }
}

/// Two-body propagation by universal variables (bounded Newton on Kepler's universal
/// equation, at most `max_iter` steps): state after `dt_s` from `(r, v)`. Used to check
/// Lambert arcs and the GEO tour's legs; `None` if it did not converge.
pub fn propagate(
    mu_km3_s2: f64,
    r_km: &Vec3,
    v_km_s: &Vec3,
    dt_s: f64,
    max_iter: u16,
) -> Option<(Vec3, Vec3)> {
    let r0 = norm(r_km);
    let v0 = norm(v_km_s);
    let sqmu = libm::sqrt(mu_km3_s2);
    let rv = dot(r_km, v_km_s) / sqmu;
    let alpha = 2.0 / r0 - v0 * v0 / mu_km3_s2;
    let mut chi = sqmu * alpha.abs() * dt_s;
    if alpha <= 0.0 {
        chi = sqmu * dt_s / r0;
    }
    let stumpff = |z: f64| -> (f64, f64) {
        if z > 1e-8 {
            let sz = libm::sqrt(z);
            (
                (1.0 - libm::cos(sz)) / z,
                (sz - libm::sin(sz)) / (sz * sz * sz),
            )
        } else if z < -1e-8 {
            let sz = libm::sqrt(-z);
            (
                (libm::cosh(sz) - 1.0) / -z,
                (libm::sinh(sz) - sz) / (sz * sz * sz),
            )
        } else {
            (0.5 - z / 24.0, 1.0 / 6.0 - z / 120.0)
        }
    };
    let mut ok = false;
    for _ in 0..max_iter {
        let z = alpha * chi * chi;
        let (c2, c3) = stumpff(z);
        let r = chi * chi * c2 + rv * chi * (1.0 - z * c3) + r0 * (1.0 - z * c2);
        let f = rv * chi * chi * c2 + (1.0 - alpha * r0) * chi * chi * chi * c3 + r0 * chi
            - sqmu * dt_s;
        let step = f / r;
        chi -= step;
        if step.abs() <= 1e-14 * (1.0 + chi.abs()) {
            ok = true;
            break;
        }
    }
    if !ok {
        return None;
    }
    let z = alpha * chi * chi;
    let (c2, c3) = stumpff(z);
    let f = 1.0 - chi * chi / r0 * c2;
    let g = dt_s - chi * chi * chi / sqmu * c3;
    let r = add(&scale(r_km, f), &scale(v_km_s, g));
    let rn = norm(&r);
    let fdot = sqmu / (rn * r0) * (alpha * chi * chi * chi * c3 - chi);
    let gdot = 1.0 - chi * chi / rn * c2;
    let v = add(&scale(r_km, fdot), &scale(v_km_s, gdot));
    (finite(&r) && finite(&v)).then_some((r, v))
}

#[cfg(test)]
mod tests {
    use super::*;

    const MU: f64 = crate::astro::EARTH_MU_KM3_S2;

    fn check_arc(r1: Vec3, r2: Vec3, tof_s: f64, revs: u16, branch: Branch) -> LambertSolution {
        let sol = solve(
            MU,
            &r1,
            &r2,
            tof_s,
            revs,
            branch,
            &[0.0, 0.0, 1.0],
            40,
            1e-13,
        )
        .unwrap();
        let (r, _) = propagate(MU, &r1, &sol.v1_km_s, tof_s, 60).unwrap();
        let miss = norm(&sub(&r, &r2));
        assert!(miss < 1e-6, "miss {miss} km (revs {revs}, {branch:?})");
        sol
    }

    #[test]
    fn zero_and_multi_revolution_arcs_reach_the_target() {
        let r1 = [7000.0, 0.0, 0.0];
        let r2 = [-2000.0, 6500.0, 1200.0];
        check_arc(r1, r2, 2000.0, 0, Branch::Left);
        check_arc(r1, r2, 6000.0, 0, Branch::Left);
        for revs in 1..=3 {
            for branch in [Branch::Left, Branch::Right] {
                check_arc(r1, r2, 7000.0 * f64::from(revs) + 9000.0, revs, branch);
            }
        }
    }

    #[test]
    fn coincident_end_points_give_the_tangential_phasing_orbit() {
        // r1 = r2 on a 42164 km circle, 1 revolution of period 0.99 T0: tangential burn.
        let a0 = 42_164.17;
        let r = [a0, 0.0, 0.0];
        let t0 = 2.0 * core::f64::consts::PI * libm::sqrt(a0 * a0 * a0 / MU);
        let tof_s = 0.99 * t0;
        let left = solve(
            MU,
            &r,
            &r,
            tof_s,
            1,
            Branch::Left,
            &[0.0, 0.0, 1.0],
            40,
            1e-13,
        );
        let right = solve(
            MU,
            &r,
            &r,
            tof_s,
            1,
            Branch::Right,
            &[0.0, 0.0, 1.0],
            40,
            1e-13,
        );
        let (left, right) = (left.unwrap(), right.unwrap());
        // One branch is the tangential phasing orbit, the other the rectilinear fall.
        let sol = if left.v1_km_s[0].abs() < right.v1_km_s[0].abs() {
            left
        } else {
            right
        };
        assert!(sol.v1_km_s[0].abs() < 1e-9, "radial {}", sol.v1_km_s[0]);
        let a_m = libm::cbrt(MU * (tof_s / (2.0 * core::f64::consts::PI)).powi(2));
        let v_apo = libm::sqrt(MU * (2.0 / a0 - 1.0 / a_m));
        assert!((sol.v1_km_s[1] - v_apo).abs() < 1e-9);
    }

    #[test]
    fn too_short_for_the_revolutions_and_bad_input_are_errors() {
        let quarter = |tof_s: f64, revs: u16, normal: Vec3| {
            let (r1, r2) = ([7000.0, 0.0, 0.0], [0.0, 7000.0, 0.0]);
            solve(MU, &r1, &r2, tof_s, revs, Branch::Left, &normal, 40, 1e-13)
        };
        let z = [0.0, 0.0, 1.0];
        assert_eq!(quarter(3000.0, 2, z), Err(LambertError::NoSolution));
        assert_eq!(quarter(f64::NAN, 0, z), Err(LambertError::BadInput));
        assert_eq!(quarter(100.0, 0, [0.0; 3]), Err(LambertError::BadInput));
    }
}
