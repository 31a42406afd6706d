//! Kepler's equation `M = E - e sin E` for elliptic orbits (0 <= e < 1), by a bounded Newton
//! iteration from a safe start.

use super::elements::{wrap_pi, TWO_PI};

/// The most Newton steps `eccentric_anomaly` takes at any mean anomaly and any eccentricity
/// up to the largest the planner accepts, 0.936 (semi-major axis at `MAX_SMA_KM`, perigee on
/// the Earth's surface; the limits demand 100 km above it): the test
/// `newton_steps_are_bounded_on_accepted_orbits` scans them. The default and built-in limit of
/// `kepler_max_iter` (12) leave two more for transfer arcs beyond those orbits, and planner B's
/// per-unit bound allows every Kepler solve that limit (`tests/tests/qemu_firmware/`).
pub const WORST_NEWTON_STEPS: u16 = 10;

/// Kepler solves and Newton steps taken since the last [`newton_counts_reset`], for the kernel
/// image (`firmware/src/kb_main.rs`), whose test adds to each case the steps it did not take
/// up to `kepler_max_iter`'s limit per solve. Plain loads and stores: one core, no contention.
#[cfg(feature = "kernel-counters")]
mod counters {
    use core::sync::atomic::{AtomicU32, Ordering::Relaxed};

    static SOLVES: AtomicU32 = AtomicU32::new(0);
    static STEPS: AtomicU32 = AtomicU32::new(0);

    pub(super) fn count_solve() {
        SOLVES.store(SOLVES.load(Relaxed).wrapping_add(1), Relaxed);
    }

    pub(super) fn count_step() {
        STEPS.store(STEPS.load(Relaxed).wrapping_add(1), Relaxed);
    }

    /// Zero both counts.
    pub fn newton_counts_reset() {
        SOLVES.store(0, Relaxed);
        STEPS.store(0, Relaxed);
    }

    /// `(solves, Newton steps)` since the last reset.
    pub fn newton_counts() -> (u32, u32) {
        (SOLVES.load(Relaxed), STEPS.load(Relaxed))
    }
}
#[cfg(feature = "kernel-counters")]
pub use counters::{newton_counts, newton_counts_reset};

/// Eccentric anomaly from the mean anomaly.
///
/// Units: rad in, rad out. The start `E0 = M + e sin M` (e < 0.8) or `E0 = pi sgn M`
/// (e >= 0.8) keeps Newton monotone for every e < 1, because `1 - e cos E >= 1 - e > 0`.
/// At most `max_iter` steps; returns `(E, converged)`. `E` has the sign range of `wrap_pi(M)`.
pub(crate) fn eccentric_anomaly(mean_anomaly_rad: f64, ecc: f64, max_iter: u16) -> (f64, bool) {
    let m = wrap_pi(mean_anomaly_rad);
    let mut e_anom = if ecc < 0.8 {
        m + ecc * libm::sin(m)
    } else if m < 0.0 {
        -core::f64::consts::PI
    } else {
        core::f64::consts::PI
    };
    #[cfg(feature = "kernel-counters")]
    counters::count_solve();
    for _ in 0..max_iter {
        #[cfg(feature = "kernel-counters")]
        counters::count_step();
        let f = e_anom - ecc * libm::sin(e_anom) - m;
        let fp = 1.0 - ecc * libm::cos(e_anom);
        let step = f / fp;
        e_anom -= step;
        if libm::fabs(step) <= 4.0 * f64::EPSILON * (1.0 + libm::fabs(e_anom)) {
            return (e_anom, true);
        }
    }
    (e_anom, false)
}

/// True anomaly from the eccentric anomaly, rad, in `(-pi, pi]`.
pub(crate) fn true_from_eccentric(ecc_anomaly_rad: f64, ecc: f64) -> f64 {
    let half = 0.5 * ecc_anomaly_rad;
    2.0 * libm::atan2(
        libm::sqrt(1.0 + ecc) * libm::sin(half),
        libm::sqrt(1.0 - ecc) * libm::cos(half),
    )
}

/// True anomaly from the mean anomaly (rad); `(f, converged)`.
pub(crate) fn true_anomaly(mean_anomaly_rad: f64, ecc: f64, max_iter: u16) -> (f64, bool) {
    let (e_anom, ok) = eccentric_anomaly(mean_anomaly_rad, ecc, max_iter);
    (true_from_eccentric(e_anom, ecc), ok)
}

/// Mean anomaly from the true anomaly, rad, in `(-pi, pi]` (closed form, no iteration).
pub(crate) fn mean_from_true(true_anomaly_rad: f64, ecc: f64) -> f64 {
    let half = 0.5 * true_anomaly_rad;
    let e_anom = 2.0
        * libm::atan2(
            libm::sqrt(1.0 - ecc) * libm::sin(half),
            libm::sqrt(1.0 + ecc) * libm::cos(half),
        );
    let m = e_anom - ecc * libm::sin(e_anom);
    if m > core::f64::consts::PI {
        m - TWO_PI
    } else {
        m
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn solves_kepler_across_eccentricities() {
        for &ecc in &[0.0, 0.0678, 0.3, 0.7, 0.9, 0.99, 0.999_999] {
            for j in -50..=50 {
                let m = f64::from(j) * 0.07;
                let (e_anom, ok) = eccentric_anomaly(m, ecc, 60);
                assert!(ok, "e = {ecc}, M = {m}");
                let back = e_anom - ecc * libm::sin(e_anom);
                assert!(wrap_pi(back - m).abs() < 1e-13, "e = {ecc}, M = {m}");
            }
        }
    }

    #[test]
    fn true_and_mean_round_trip() {
        for &ecc in &[0.01, 0.0678, 0.5, 0.95] {
            for j in -30..=30 {
                let m = f64::from(j) * 0.1;
                let (f, ok) = true_anomaly(m, ecc, 60);
                assert!(ok);
                assert!(wrap_pi(mean_from_true(f, ecc) - m).abs() < 1e-12);
            }
        }
        // Known value: e = 0.0678, M = 1 rad.
        let (f, _) = true_anomaly(1.0, 0.0678, 60);
        let (e_anom, _) = eccentric_anomaly(1.0, 0.0678, 60);
        assert!((e_anom - 0.0678 * libm::sin(e_anom) - 1.0).abs() < 1e-15);
        assert!(f > e_anom && e_anom > 1.0);
    }

    use crate::astro::EARTH_RADIUS_KM;
    use crate::impulsive::settings::MAX_SMA_KM;

    /// The largest eccentricity of an orbit the planner accepts: semi-major axis at
    /// `MAX_SMA_KM`, perigee on the Earth's surface.
    const MAX_ACCEPTED_ECCENTRICITY: f64 = 1.0 - EARTH_RADIUS_KM / MAX_SMA_KM;

    /// Newton steps of one solve (to convergence, at most 60).
    fn steps(m: f64, ecc: f64) -> u16 {
        (1..=60)
            .find(|&k| eccentric_anomaly(m, ecc, k).1)
            .unwrap_or(u16::MAX)
    }

    #[test]
    fn newton_steps_are_bounded_on_accepted_orbits() {
        // Every eccentricity up to the accepted largest, every mean anomaly, denser near
        // perigee (M -> 0 at high e, where the start E = pi is farthest from the root).
        let mut worst = 0;
        for i in 0..=400u32 {
            let ecc = MAX_ACCEPTED_ECCENTRICITY * f64::from(i) / 400.0;
            for j in 0..=1500u32 {
                let x = f64::from(j) / 1500.0;
                for m in [core::f64::consts::PI * x * x * x, core::f64::consts::PI * x] {
                    worst = worst.max(steps(m, ecc)).max(steps(-m, ecc));
                }
            }
        }
        assert_eq!(
            worst, WORST_NEWTON_STEPS,
            "the scan's worst Newton step count"
        );
        assert!((MAX_ACCEPTED_ECCENTRICITY - 0.93622).abs() < 1e-5);
    }

    #[test]
    fn bounded_on_nan() {
        let (e_anom, ok) = eccentric_anomaly(f64::NAN, 0.1, 30);
        assert!(!ok);
        assert!(e_anom.is_nan());
    }
}
