//! The integrator: Dormand & Prince's embedded Runge-Kutta 5(4) pair (Dormand & Prince 1980;
//! Hairer, Norsett & Wanner, *Solving ODEs I*, table 5.2) with the standard step-size control
//! on a mixed absolute and relative tolerance, stopping exactly at a given time. Deterministic:
//! the same call gives the same bits (no clock, no threads).

use anyhow::{bail, Context, Result};

/// A first-order system of six states (position km, velocity km/s).
pub type State6 = [f64; 6];

/// Tolerances and bounds of [`integrate`].
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize)]
pub struct Tolerance {
    /// Relative tolerance per step (of the larger of the state before and after).
    pub relative: f64,
    /// Absolute tolerance per step on positions, km (velocities: this over 1000 s).
    pub absolute_km: f64,
    /// Largest step, s.
    pub max_step_s: f64,
    /// Most steps (accepted and rejected) in one call: the loop's bound.
    pub max_steps: usize,
}

impl Tolerance {
    /// The truth model's setting: relative 1e-12, absolute 1 micrometre, steps <= 300 s,
    /// at most 2 million steps a call (a LEO day takes ~30,000).
    pub const TRUTH: Self = Self {
        relative: 1e-12,
        absolute_km: 1e-9,
        max_step_s: 300.0,
        max_steps: 2_000_000,
    };
}

/// What one call did.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Counters {
    /// Accepted steps.
    pub accepted: usize,
    /// Rejected steps.
    pub rejected: usize,
}

const C: [f64; 7] = [0.0, 1.0 / 5.0, 3.0 / 10.0, 4.0 / 5.0, 8.0 / 9.0, 1.0, 1.0];
const A: [[f64; 6]; 7] = [
    [0.0; 6],
    [1.0 / 5.0, 0.0, 0.0, 0.0, 0.0, 0.0],
    [3.0 / 40.0, 9.0 / 40.0, 0.0, 0.0, 0.0, 0.0],
    [44.0 / 45.0, -56.0 / 15.0, 32.0 / 9.0, 0.0, 0.0, 0.0],
    [
        19372.0 / 6561.0,
        -25360.0 / 2187.0,
        64448.0 / 6561.0,
        -212.0 / 729.0,
        0.0,
        0.0,
    ],
    [
        9017.0 / 3168.0,
        -355.0 / 33.0,
        46732.0 / 5247.0,
        49.0 / 176.0,
        -5103.0 / 18656.0,
        0.0,
    ],
    [
        35.0 / 384.0,
        0.0,
        500.0 / 1113.0,
        125.0 / 192.0,
        -2187.0 / 6784.0,
        11.0 / 84.0,
    ],
];
/// Fifth-order weights minus fourth-order weights: the error estimate.
const E: [f64; 7] = [
    71.0 / 57600.0,
    0.0,
    -71.0 / 16695.0,
    71.0 / 1920.0,
    -17253.0 / 339200.0,
    22.0 / 525.0,
    -1.0 / 40.0,
];

/// A check of each accepted state: `Err` stops the integration with that message.
pub type Guard<'a> = &'a dyn Fn(&State6) -> Result<()>;

/// Integrate `y' = f(t, y)` from `t0_s` to `t1_s >= t0_s` starting at `y`, with a first step of
/// `*step_s` (updated to the controller's next step, to carry on in the next call); `guard`
/// checks every accepted state.
///
/// # Errors
/// A non-finite state or step, more than `tol.max_steps` steps, or the guard's error.
#[allow(clippy::too_many_arguments)]
pub fn integrate(
    f: &dyn Fn(f64, &State6) -> State6,
    guard: Guard<'_>,
    t0_s: f64,
    t1_s: f64,
    y: &mut State6,
    step_s: &mut f64,
    tol: &Tolerance,
    counters: &mut Counters,
) -> Result<()> {
    if t0_s.is_nan() || t1_s.is_nan() || t1_s < t0_s {
        bail!("cannot integrate backwards from {t0_s} s to {t1_s} s");
    }
    let mut t = t0_s;
    let mut h = step_s.clamp(1e-3, tol.max_step_s);
    let mut k = [[0.0; 6]; 7];
    k[0] = f(t, y);
    let mut steps = 0usize;
    while t < t1_s {
        steps += 1;
        if steps > tol.max_steps {
            bail!(
                "more than {} integration steps between {t0_s} s and {t1_s} s (stopped at {t} s)",
                tol.max_steps
            );
        }
        let last = t + h >= t1_s;
        let h_now = if last { t1_s - t } else { h };
        for stage in 1..7 {
            let mut ys = *y;
            for (i, yi) in ys.iter_mut().enumerate() {
                let mut sum = 0.0;
                for (a, ks) in A[stage].iter().zip(k.iter()).take(stage) {
                    sum += a * ks[i];
                }
                *yi += h_now * sum;
            }
            k[stage] = f(t + C[stage] * h_now, &ys);
        }
        // Fifth-order solution (the last stage's argument, FSAL) and the error estimate.
        let mut y_new = *y;
        for (i, yi) in y_new.iter_mut().enumerate() {
            let mut sum = 0.0;
            for (a, ks) in A[6].iter().zip(k.iter()) {
                sum += a * ks[i];
            }
            *yi += h_now * sum;
        }
        let mut err2 = 0.0;
        for i in 0..6 {
            let mut e = 0.0;
            for (w, ks) in E.iter().zip(k.iter()) {
                e += w * ks[i];
            }
            let abs = if i < 3 {
                tol.absolute_km
            } else {
                tol.absolute_km / 1000.0
            };
            let scale = abs + tol.relative * y[i].abs().max(y_new[i].abs());
            err2 += (h_now * e / scale).powi(2);
        }
        let err = (err2 / 6.0).sqrt();
        if !err.is_finite() || !y_new.iter().all(|x| x.is_finite()) {
            bail!("the state stopped being finite at {t} s");
        }
        // Standard controller: safety 0.9, exponent 1/5, growth in [0.2, 5].
        let factor = (0.9 * err.powf(-0.2)).clamp(0.2, 5.0);
        if err <= 1.0 {
            t = if last { t1_s } else { t + h_now };
            guard(&y_new).with_context(|| format!("at {} s", t))?;
            *y = y_new;
            k[0] = k[6];
            counters.accepted += 1;
            if !last {
                h = (h_now * factor).min(tol.max_step_s);
            }
        } else {
            counters.rejected += 1;
            h = h_now * factor.min(1.0);
        }
    }
    *step_s = h;
    Ok(())
}

#[cfg(test)]
#[allow(clippy::unwrap_used)]
mod tests {
    use super::*;

    /// A harmonic oscillator in each axis: the exact solution is a rotation.
    #[test]
    fn the_pair_is_fifth_order_accurate_on_an_oscillator() {
        let w = 1e-3;
        let f = |_t: f64, y: &State6| -> State6 {
            [
                y[3],
                y[4],
                y[5],
                -w * w * y[0],
                -w * w * y[1],
                -w * w * y[2],
            ]
        };
        let mut y = [7000.0, 0.0, 100.0, 0.0, 7.0, 0.0];
        let mut h = 10.0;
        let mut c = Counters::default();
        let t1 = 86_400.0;
        integrate(
            &f,
            &|_| Ok(()),
            0.0,
            t1,
            &mut y,
            &mut h,
            &Tolerance::TRUTH,
            &mut c,
        )
        .unwrap();
        let want = [
            7000.0 * (w * t1).cos(),
            7.0 / w * (w * t1).sin(),
            100.0 * (w * t1).cos(),
        ];
        super::super::assert_close(&y, &want, 1e-6);
        assert!(c.accepted > 100 && c.accepted < 100_000, "{c:?}");
    }

    #[test]
    fn too_many_steps_or_backwards_is_an_error() {
        let f = |_t: f64, y: &State6| -> State6 { [y[3], y[4], y[5], -y[0], -y[1], -y[2]] };
        let mut y = [1.0, 0.0, 0.0, 0.0, 1.0, 0.0];
        let mut h = 1.0;
        let tight = Tolerance {
            max_steps: 10,
            ..Tolerance::TRUTH
        };
        let mut c = Counters::default();
        let err =
            integrate(&f, &|_| Ok(()), 0.0, 1000.0, &mut y, &mut h, &tight, &mut c).unwrap_err();
        assert!(err.to_string().contains("more than 10"), "{err}");
        assert!(integrate(&f, &|_| Ok(()), 5.0, 1.0, &mut y, &mut h, &tight, &mut c).is_err());
    }
}
