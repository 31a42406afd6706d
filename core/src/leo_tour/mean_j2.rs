//! The search model of the per-arc rendezvous: the first-order J2 theory in closed form.
//!
//! A flight maps the osculating state to mean elements (Brouwer's first-order short-period
//! terms, in Lyddane's form that stays regular at small eccentricity: Schaub & Junkins,
//! *Analytical Mechanics of Space Systems*, appendix F, without its long-period terms), moves
//! the mean node, perigee and mean anomaly at their first-order secular rates (the one
//! implementation of planner B, `impulsive::secular`), and maps back. Its cost does
//! not depend on the span: a Kepler solve and a few dozen trigonometric calls, against
//! `span / step_s` RK4 steps of the planning model ([`super::j2`]).
//!
//! Why the long-period terms are left out: they vary with `2 omega` (a few degrees a day in
//! LEO), so over one arc they are nearly constant and cancel between the two conversions; they
//! carry `1 / (1 - 5 cos^2 i)`, singular at the critical inclination, which the search must
//! not meet.
//!
//! Accuracy (unit tests, against the planning model's RK4 at 20 s): the neglected second-order
//! terms leave of the order of a kilometre after a day in LEO. The search only ranks plans
//! with it; every plan it returns is flown and shot again in the planning model
//! (`leo_tour::arc`), which decides the status.

use super::elements::{state_of, Classical};
use super::j2::{join, pos, vel, State};
use crate::astro::Gravity;
use crate::impulsive::elements::{wrap_pi, Elements, A, ARGP, E, I, MA, RAAN};
use crate::impulsive::kepler::true_anomaly;
use crate::impulsive::nonlinear::elements_and_true_anomaly_with;
use crate::impulsive::secular::rates_with;

// The secular rates are those of the last three elements (node, perigee, mean anomaly).
const _: () = assert!(RAAN + 1 == ARGP && ARGP + 1 == MA && MA == 5);

/// Newton steps of one Kepler solve: the most an orbit of eccentricity up to 0.936 needs
/// (`impulsive::kepler::WORST_NEWTON_STEPS`, scanned) and two more, planner B's limit; the
/// work units of a flight allow every solve this many (`work_units.rs`). An orbit closer to
/// parabolic may not converge: its flight fails, as any flight that leaves the model.
pub const KEPLER_MAX_ITER: u16 = crate::impulsive::WORST_NEWTON_STEPS + 2;

/// The first-order short-period J2 terms added to `el` (`sign = 1`: mean to osculating;
/// `sign = -1`: osculating to mean, to first order). `None` when Kepler's equation does not
/// converge or a result is not finite.
fn short_period(g: &Gravity, el: &Elements, sign: f64, nu: Option<f64>) -> Option<Elements> {
    let (a, e, i, raan, argp, m) = (el[A], el[E], el[I], el[RAAN], el[ARGP], el[MA]);
    let gamma = sign * 0.5 * g.j2 * (g.re_km / a) * (g.re_km / a);
    let eta2 = 1.0 - e * e;
    let eta = libm::sqrt(eta2);
    let eta3 = eta2 * eta;
    let eta6 = eta3 * eta3;
    let gamma_p = gamma / (eta2 * eta2);
    let f = match nu {
        Some(f) => f,
        None => match true_anomaly(m, e, KEPLER_MAX_ITER) {
            (f, true) => f,
            (_, false) => return None,
        },
    };
    let (sin_f, cos_f) = libm::sincos(f);
    let a_r = (1.0 + e * cos_f) / eta2;
    let a_r3 = a_r * a_r * a_r;
    let (sin_i, th) = libm::sincos(i);
    let th2 = th * th;
    let s2 = 1.0 - th2;
    // The angles 2ω + kf for k = 1, 2, 3 by the addition formulas (one sincos, not three).
    let (s_f, c_f) = libm::sincos(2.0 * argp + f);
    let (s_2f, c_2f) = (s_f * cos_f + c_f * sin_f, c_f * cos_f - s_f * sin_f);
    let (s_3f, c_3f) = (s_2f * cos_f + c_2f * sin_f, c_2f * cos_f - s_2f * sin_f);
    // The equation of the centre plus e sin f.
    let centre = wrap_pi(f - m) + e * sin_f;
    let cubic = 3.0 * cos_f + 3.0 * e * cos_f * cos_f + e * e * cos_f * cos_f * cos_f;

    let a_new = a + a * gamma * ((3.0 * th2 - 1.0) * (a_r3 - 1.0 / eta3) + 3.0 * s2 * a_r3 * c_2f);
    let de = 0.5
        * eta2
        * (gamma
            * ((3.0 * th2 - 1.0) / eta6 * (e * eta + e / (1.0 + eta) + cubic)
                + 3.0 * s2 / eta6 * (e + cubic) * c_2f)
            - gamma_p * s2 * (3.0 * c_f + c_3f));
    let di = 0.5 * gamma_p * th * sin_i * (3.0 * c_2f + 3.0 * e * c_f + e * c_3f);
    let sines = 3.0 * s_2f + 3.0 * e * s_f + e * s_3f;
    let d_raan = -0.5 * gamma_p * th * (6.0 * centre - sines);
    let d_lon =
        0.25 * gamma_p * (-6.0 * (1.0 - 5.0 * th2) * centre + (3.0 - 5.0 * th2) * sines) + d_raan;
    let aer = a_r * eta;
    let aer2 = aer * aer;
    let e_dm = -0.25
        * gamma_p
        * eta3
        * (2.0 * (3.0 * th2 - 1.0) * (aer2 + a_r + 1.0) * sin_f
            + 3.0 * s2 * ((-aer2 - a_r + 1.0) * s_f + (aer2 + a_r + 1.0 / 3.0) * s_3f));

    // Lyddane's recovery: the eccentricity and inclination vectors, not their angles.
    let (sin_m, cos_m) = libm::sincos(m);
    let d1 = (e + de) * sin_m + e_dm * cos_m;
    let d2 = (e + de) * cos_m - e_dm * sin_m;
    // Half the inclination (in [0, π/2]) from its cosine.
    let (sin_h, cos_h) = (
        libm::sqrt((0.5 * (1.0 - th)).max(0.0)),
        libm::sqrt((0.5 * (1.0 + th)).max(0.0)),
    );
    let (sin_o, cos_o) = libm::sincos(raan);
    let tilt = sin_h + 0.5 * cos_h * di;
    let d3 = tilt * sin_o + sin_h * d_raan * cos_o;
    let d4 = tilt * cos_o - sin_h * d_raan * sin_o;
    let m_new = libm::atan2(d1, d2);
    let raan_new = libm::atan2(d3, d4);
    let lon_new = m + argp + raan + d_lon;
    let out = [
        a_new,
        libm::sqrt(d1 * d1 + d2 * d2),
        2.0 * libm::asin(libm::sqrt(d3 * d3 + d4 * d4).min(1.0)),
        raan_new,
        lon_new - m_new - raan_new,
        m_new,
    ];
    (out.iter().all(|x| x.is_finite()) && out[E] < 1.0 && out[A] > 0.0).then_some(out)
}

/// The mean elements of osculating ones: the short-period terms evaluated at the osculating
/// elements and subtracted (first order: the conversions are inverse to each other up to
/// J2^2 terms, a few metres; fixed-point corrections that make them exact were measured to
/// change the flights by less than their own error and cost a third of a flight each).
fn to_mean(g: &Gravity, osc: &Elements, nu: f64) -> Option<Elements> {
    short_period(g, osc, -1.0, Some(nu))
}

/// Brouwer's second-order (J2^2) secular rates of the node, the perigee and the mean anomaly
/// of mean elements `el`, rad/s: `n (3/8) g'^2 [...]` with `g' = J2 Re^2 / (2 p^2)` (Brouwer
/// 1959; at e = 0 they are SGP4's). At low inclination they move the satellite by about half
/// a kilometre per revolution, ten times the first-order theory's other errors.
fn second_order_rates(g: &Gravity, el: &Elements) -> [f64; 3] {
    let (a, e, i) = (el[A], el[E], el[I]);
    let eta2 = 1.0 - e * e;
    let eta = libm::sqrt(eta2);
    let p = a * eta2;
    let gp = 0.5 * g.j2 * (g.re_km / p) * (g.re_km / p);
    let n = libm::sqrt(g.mu_km3_s2 / (a * a * a));
    let th = libm::cos(i);
    let th2 = th * th;
    let th4 = th2 * th2;
    let k = n * gp * gp;
    let raan = 0.375
        * k
        * ((-5.0 + 12.0 * eta + 9.0 * eta2) * th + (-35.0 - 36.0 * eta - 5.0 * eta2) * th2 * th);
    let argp = 0.093_75
        * k
        * (-35.0
            + 24.0 * eta
            + 25.0 * eta2
            + (90.0 - 192.0 * eta - 126.0 * eta2) * th2
            + (385.0 + 360.0 * eta + 45.0 * eta2) * th4);
    let mean_anomaly = 0.093_75
        * k
        * eta
        * (-15.0
            + 16.0 * eta
            + 25.0 * eta2
            + (30.0 - 96.0 * eta - 90.0 * eta2) * th2
            + (105.0 + 144.0 * eta + 25.0 * eta2) * th4);
    [raan, argp, mean_anomaly]
}

/// An orbit as its mean elements at an epoch: flown to any time by the secular rates and
/// the short-period terms (the conversion from the osculating state made once).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct MeanOrbit {
    mean: Elements,
    rates: [f64; 3],
}

impl MeanOrbit {
    /// The mean orbit of an osculating `state`; `None` for a state that is not a
    /// non-degenerate ellipse or a conversion that does not converge.
    pub fn of_state(g: &Gravity, state: &State) -> Option<Self> {
        let (osc, nu) =
            elements_and_true_anomaly_with(g.mu_km3_s2, &pos(state), &vel(state), &[0.0; 6])?;
        let mean = to_mean(g, &osc, nu)?;
        let d = rates_with(g, &mean);
        let d2 = second_order_rates(g, &mean);
        // The angle rows RAAN, ARGP, MA are the last three of an element vector.
        let mut rates = [0.0; 3];
        for (r, (dk, d2k)) in rates.iter_mut().zip(d.iter().skip(RAAN).zip(d2)) {
            *r = dk + d2k;
        }
        rates
            .iter()
            .all(|r| r.is_finite())
            .then_some(Self { mean, rates })
    }

    /// The osculating state `dt_s` after the epoch; `None` when the result is not finite.
    pub fn state_at(&self, g: &Gravity, dt_s: f64) -> Option<State> {
        let mut mean = self.mean;
        for (angle, r) in mean.iter_mut().skip(RAAN).zip(self.rates) {
            *angle = wrap_pi(*angle + r * dt_s);
        }
        let el = short_period(g, &mean, 1.0, None)?;
        let (nu, ok) = true_anomaly(el[MA], el[E], KEPLER_MAX_ITER);
        if !ok {
            return None;
        }
        let s = state_of(
            g.mu_km3_s2,
            &Classical {
                a_km: el[A],
                e: el[E],
                i_rad: el[I],
                raan_rad: el[RAAN],
                argp_rad: el[ARGP],
                nu_rad: nu,
            },
        )?;
        let out = join(&pos(&s), &vel(&s));
        out.iter().all(|x| x.is_finite()).then_some(out)
    }
}

/// `state` flown for `dt_s` in the first-order J2 theory; `None` for a state that is not a
/// non-degenerate ellipse, or a result that is not finite.
pub fn fly(g: &Gravity, state: &State, dt_s: f64) -> Option<State> {
    MeanOrbit::of_state(g, state)?.state_at(g, dt_s)
}

#[cfg(test)]
mod tests {
    extern crate std;
    use super::*;
    use crate::leo_tour::j2::{propagate_steps, step_count};
    use crate::vec3::{norm, sub};

    const G: Gravity = Gravity::EARTH;

    fn orbit(a_km: f64, e: f64, i_deg: f64, raan_deg: f64, argp_deg: f64, nu_deg: f64) -> State {
        state_of(
            G.mu_km3_s2,
            &Classical {
                a_km,
                e,
                i_rad: i_deg.to_radians(),
                raan_rad: raan_deg.to_radians(),
                argp_rad: argp_deg.to_radians(),
                nu_rad: nu_deg.to_radians(),
            },
        )
        .unwrap()
    }

    fn rk4(s: &State, dt: f64) -> State {
        let n = step_count(dt, 20.0, 1_000_000).unwrap();
        propagate_steps(&G, s, dt, n).unwrap()
    }

    /// (position error after one revolution, after a day), km.
    fn errors(s: &State) -> (f64, f64) {
        let one = 5900.0;
        let day = 86_400.0;
        let e1 = norm(&sub(&pos(&fly(&G, s, one).unwrap()), &pos(&rk4(s, one))));
        let e2 = norm(&sub(&pos(&fly(&G, s, day).unwrap()), &pos(&rk4(s, day))));
        (e1, e2)
    }

    #[test]
    fn a_flight_of_zero_span_returns_near_its_start() {
        // The two conversions are inverse to first order: measured 4.9 m and 4.6 mm/s for
        // this orbit; without the short-period terms' sign flip it would be kilometres.
        let s = orbit(7078.0, 0.0, 98.2, 30.0, 0.0, 40.0);
        let back = fly(&G, &s, 0.0).unwrap();
        let dr = norm(&sub(&pos(&back), &pos(&s)));
        let dv = norm(&sub(&vel(&back), &vel(&s)));
        std::println!("zero span: {dr} km, {dv} km/s");
        assert!(dr < 0.02 && dv < 2e-5, "{dr} km {dv} km/s");
    }

    #[test]
    fn the_first_order_theory_follows_the_planning_model() {
        // Measured (km after one revolution / after a day): circular SSO 0.007 / 0.10,
        // transfer e = 0.02 0.20 / 3.1, e = 0.01 at 60 deg 0.009 / 0.15, low inclination
        // 0.13 / 1.9. Without the second-order secular rates the low-inclination orbit is
        // 0.51 / 7.6 km off, and without the short-period terms (osculating taken as mean)
        // every orbit is tens to hundreds of km off after a day.
        for (label, s, one_max, day_max) in [
            (
                "circular SSO 700 km",
                orbit(7078.0, 0.0, 98.2, 30.0, 0.0, 40.0),
                0.02,
                0.2,
            ),
            (
                "transfer e = 0.02",
                orbit(7000.0, 0.02, 97.5, 10.0, 70.0, 200.0),
                0.4,
                5.0,
            ),
            (
                "e = 0.01, 60 deg",
                orbit(7200.0, 0.01, 60.0, 100.0, 30.0, 5.0),
                0.02,
                0.3,
            ),
            (
                "low inclination",
                orbit(6900.0, 0.005, 10.0, 300.0, 120.0, 250.0),
                0.2,
                3.0,
            ),
        ] {
            let (one, day) = errors(&s);
            std::println!("{label}: {one:.4} km after one revolution, {day:.3} km after a day");
            assert!(one < one_max && day < day_max, "{label}: {one} {day}");
        }
    }
}
