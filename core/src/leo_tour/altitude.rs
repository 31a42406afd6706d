//! The lowest point of a transfer coast (issue 31: transfers kept above the atmosphere).
//!
//! A coast's lowest radius is its osculating two-body perigee when the coast passes it, else
//! the lower of its two ends (between two perigee passages the radius rises to the apogee and
//! falls back, so a coast that passes no perigee is lowest at an end). The two-body perigee of
//! the osculating orbit at the coast's start stands for the planning model's: J2 moves a LEO
//! perigee by a few kilometres over a coast, which the setting's margin must allow for.

use super::j2::{pos, vel, State};
use crate::vec3::{cross, dot, norm, scale, sub};

/// Eccentricities below this are circular here: the perigee is then the radius itself.
const CIRCULAR_E: f64 = 1e-9;

/// The lowest radius, km, of the coast from `start` (just after its burn) to `end` (just before
/// the next), `dt_s` long, under gravitational parameter `mu_km3_s2`; NaN for a state that is
/// not finite (the caller then counts the transfer as too low).
pub(crate) fn lowest_radius_km(mu_km3_s2: f64, start: &State, end: &State, dt_s: f64) -> f64 {
    let (r, v) = (pos(start), vel(start));
    let r0 = norm(&r);
    let ends = r0.min(norm(&pos(end)));
    let v2 = dot(&v, &v);
    let rv = dot(&r, &v);
    // The eccentricity vector ((v^2 - mu / r) r - (r . v) v) / mu and the perigee radius
    // h^2 / (mu (1 + e)), valid for every conic.
    let e_vec = scale(
        &sub(&scale(&r, v2 - mu_km3_s2 / r0), &scale(&v, rv)),
        1.0 / mu_km3_s2,
    );
    let e = norm(&e_vec);
    let h = norm(&cross(&r, &v));
    let perigee_km = h * h / (mu_km3_s2 * (1.0 + e));
    if !(perigee_km.is_finite() && ends.is_finite() && dt_s.is_finite()) {
        return f64::NAN;
    }
    if e < CIRCULAR_E {
        return ends.min(perigee_km);
    }
    let energy = 0.5 * v2 - mu_km3_s2 / r0;
    if energy >= 0.0 {
        // An open orbit passes its perigee once, and only while it is approaching it.
        return if rv < 0.0 { perigee_km } else { ends };
    }
    // Elliptic: the time from the start to the next perigee passage, by the start's mean
    // anomaly in (-pi, pi].
    let a = -mu_km3_s2 / (2.0 * energy);
    let n = libm::sqrt(mu_km3_s2 / (a * a * a));
    let cos_ea = (1.0 - r0 / a) / e;
    let sin_ea = rv / (e * libm::sqrt(mu_km3_s2 * a));
    let ea = libm::atan2(sin_ea, cos_ea);
    let m0 = ea - e * sin_ea;
    let two_pi = 2.0 * core::f64::consts::PI;
    let to_perigee_s = if m0 <= 0.0 { -m0 } else { two_pi - m0 } / n;
    if dt_s >= to_perigee_s {
        perigee_km
    } else {
        ends
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::astro::Gravity;
    use crate::leo_tour::j2::{join, propagate_steps};

    const MU: f64 = crate::astro::EARTH_MU_KM3_S2;

    /// A state at apogee 8000 km of an ellipse of perigee 6600 km, and the two-body flight.
    fn at_apogee() -> (State, impl Fn(&State, f64) -> State) {
        let (ra, rp) = (8000.0_f64, 6600.0_f64);
        let a = 0.5 * (ra + rp);
        let va = libm::sqrt(MU * (2.0 / ra - 1.0 / a));
        let s = join(&[ra, 0.0, 0.0], &[0.0, va, 0.0]);
        let two_body = Gravity {
            j2: 0.0,
            ..Gravity::EARTH
        };
        let fly = move |s: &State, dt: f64| propagate_steps(&two_body, s, dt, 4_000).unwrap();
        (s, fly)
    }

    #[test]
    fn a_coast_through_perigee_is_lowest_there_and_one_short_of_it_at_its_end() {
        let (s, fly) = at_apogee();
        let a: f64 = 7300.0;
        let half_period = core::f64::consts::PI * libm::sqrt(a * a * a / MU);
        // Half a period from apogee reaches the perigee (6600 km); a quarter does not: the
        // end is then the lowest point, above the perigee.
        let through = fly(&s, half_period + 60.0);
        assert!((lowest_radius_km(MU, &s, &through, half_period + 60.0) - 6600.0).abs() < 1e-6);
        let short = fly(&s, 0.5 * half_period);
        let low = lowest_radius_km(MU, &s, &short, 0.5 * half_period);
        assert!((low - norm(&pos(&short))).abs() < 1e-9, "{low}");
        assert!(low > 6700.0, "{low}");
        // Leaving from the perigee, the next passage is a period later.
        let at_perigee = fly(&s, half_period);
        let rising = fly(&at_perigee, 600.0);
        let low = lowest_radius_km(MU, &at_perigee, &rising, 600.0);
        assert!((low - 6600.0).abs() < 1e-3, "{low}");
    }

    #[test]
    fn a_circular_coast_is_at_its_radius_and_a_broken_state_is_nan() {
        let v = libm::sqrt(MU / 7000.0);
        let s = join(&[7000.0, 0.0, 0.0], &[0.0, v, 0.0]);
        assert!((lowest_radius_km(MU, &s, &s, 3000.0) - 7000.0).abs() < 1e-6);
        let broken = join(&[7000.0, f64::NAN, 0.0], &[0.0, v, 0.0]);
        assert!(lowest_radius_km(MU, &broken, &s, 10.0).is_nan());
    }
}
