//! Input and output forms of planner B's orbits, converted once here for the host, the harness
//! and the firmware: classical mean elements (the `Problem`'s form), equinoctial mean elements,
//! an osculating Cartesian ECI state (by first-order J2 averaging, [`super::osculating`]),
//! quasi-nonsingular relative orbital elements in metres, and the deputy's own orbit.

use super::elements::{from_mean, wrap_pi, Elements, ARGP, E, I, MA, RAAN};
use super::equinoctial::{self as eq, from_classical, to_classical};
use super::osculating::{mean_to_osculating, osculating_to_mean};
use super::types::{EquinoctialElements, MeanElements, RelativeElements};

/// Most fixed-point steps of the osculating-to-mean inverse (it contracts by O(J2) ~ 1e-3 a
/// step: 5-6 steps reach the tolerance on LEO and GEO).
pub const OSCULATING_MAX_ITER: u16 = 20;
/// Stop of the osculating-to-mean inverse: largest change, a scaled by itself.
pub const OSCULATING_TOL: f64 = 1e-14;
/// Newton steps for Kepler's equation inside the conversions.
const KEPLER_MAX_ITER: u16 = 30;

/// An inertial (ECI) position and velocity.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct CartesianState {
    /// Position, km.
    pub pos_km: [f64; 3],
    /// Velocity, km/s.
    pub vel_km_s: [f64; 3],
}

/// Quasi-nonsingular relative orbital elements (D'Amico), each times the chief's a, in metres:
/// `a da/a`, `a (du + dOmega cos i)`, `a d(e cos omega)`, `a d(e sin omega)`, `a di`,
/// `a dOmega sin i` (u = omega + M the mean argument of latitude). Singular for an equatorial
/// chief (dOmega = d_iy / (a sin i)).
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct Roe {
    /// `a da / a`, m.
    pub da_m: f64,
    /// `a dlambda`, m.
    pub dlambda_m: f64,
    /// `a de_x`, m.
    pub dex_m: f64,
    /// `a de_y`, m.
    pub dey_m: f64,
    /// `a di_x`, m.
    pub dix_m: f64,
    /// `a di_y`, m.
    pub diy_m: f64,
}

/// Why a form could not be converted.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub enum FormError {
    /// A number is not finite.
    NotFinite,
    /// The state or elements are not an ellipse (or the normal points to -z: retrograde
    /// equatorial, outside the equinoctial set).
    NotAnEllipse,
    /// Kepler's equation did not converge.
    Kepler,
    /// The osculating-to-mean inverse did not reach [`OSCULATING_TOL`] in
    /// [`OSCULATING_MAX_ITER`] steps.
    MeanNotConverged,
    /// ROE need the chief's node: `|sin i|` of the chief is below `min`.
    RoeEquatorialChief {
        /// `|sin i|` of the chief.
        sin_inc: f64,
        /// The limit (`Settings::min_sin_inclination`).
        min: f64,
    },
}

impl core::fmt::Display for FormError {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        match self {
            Self::NotFinite => write!(f, "a number of the orbit is not finite"),
            Self::NotAnEllipse => write!(
                f,
                "the state is not an ellipse the equinoctial set covers (e < 1, not retrograde equatorial)"
            ),
            Self::Kepler => write!(f, "Kepler's equation did not converge"),
            Self::MeanNotConverged => write!(
                f,
                "osculating-to-mean conversion did not reach {OSCULATING_TOL} in {OSCULATING_MAX_ITER} steps"
            ),
            Self::RoeEquatorialChief { sin_inc, min } => write!(
                f,
                "relative orbital elements need an inclined chief: |sin i| = {sin_inc} < {min}"
            ),
        }
    }
}

fn classical(el: &Elements) -> MeanElements {
    MeanElements {
        sma_km: el[0],
        ecc: el[E],
        inc_rad: el[I],
        raan_rad: el[RAAN],
        argp_rad: el[ARGP],
        mean_anomaly_rad: el[MA],
    }
}

/// Shape of the osculating conic of an ECI state: `(eccentricity, perigee radius km)`, from
/// the eccentricity vector and `r_p = h^2 / (mu (1 + e))`, valid for every conic (so a
/// hyperbolic state is named with its eccentricity). NaN for a non-finite state.
pub fn osculating_shape(s: &CartesianState) -> (f64, f64) {
    use crate::vec3::{cross, dot, norm, scale, sub};
    let mu = super::elements::EARTH_MU_KM3_S2;
    let r = norm(&s.pos_km);
    let v2 = dot(&s.vel_km_s, &s.vel_km_s);
    let rv = dot(&s.pos_km, &s.vel_km_s);
    let e_vec = scale(
        &sub(&scale(&s.pos_km, v2 - mu / r), &scale(&s.vel_km_s, rv)),
        1.0 / mu,
    );
    let ecc = norm(&e_vec);
    let h = cross(&s.pos_km, &s.vel_km_s);
    (ecc, dot(&h, &h) / (mu * (1.0 + ecc)))
}

/// Equinoctial elements of classical mean elements.
pub fn equinoctial_of(el: &MeanElements) -> EquinoctialElements {
    let q = from_classical(&from_mean(el));
    EquinoctialElements {
        sma_km: q[0],
        mean_longitude_rad: q[1],
        ex: q[2],
        ey: q[3],
        hx: q[4],
        hy: q[5],
    }
}

/// Classical mean elements of equinoctial ones (an undefined perigee or node is 0, the mean
/// anomaly carrying the rest of the mean longitude).
pub fn classical_of(q: &EquinoctialElements) -> MeanElements {
    classical(&to_classical(&[
        q.sma_km,
        q.mean_longitude_rad,
        q.ex,
        q.ey,
        q.hx,
        q.hy,
    ]))
}

/// Mean classical elements of an osculating ECI state, by first-order J2 averaging
/// (`impulsive::osculating`; the named theory: Kozai's first-order averaging, short-period terms).
///
/// # Errors
/// [`FormError`] when the state is not finite or not an ellipse, or a step does not converge.
pub fn mean_of_osculating_state(s: &CartesianState) -> Result<MeanElements, FormError> {
    mean_and_evaluations_of_osculating_state(s).map(|(mean, _)| mean)
}

/// [`mean_of_osculating_state`] with the number of short-period evaluations it made (at most
/// [`OSCULATING_MAX_ITER`]), which the planner charges to its work meter.
///
/// # Errors
/// As [`mean_of_osculating_state`].
pub fn mean_and_evaluations_of_osculating_state(
    s: &CartesianState,
) -> Result<(MeanElements, u16), FormError> {
    if !s
        .pos_km
        .iter()
        .chain(s.vel_km_s.iter())
        .all(|x| x.is_finite())
    {
        return Err(FormError::NotFinite);
    }
    let osc = eq::from_state(&s.pos_km, &s.vel_km_s, &[0.0; 6]).ok_or(FormError::NotAnEllipse)?;
    let (mean, ok, evaluations) =
        osculating_to_mean(&osc, KEPLER_MAX_ITER, OSCULATING_MAX_ITER, OSCULATING_TOL)
            .ok_or(FormError::Kepler)?;
    if !ok {
        return Err(FormError::MeanNotConverged);
    }
    if eq::ecc_squared(&mean).partial_cmp(&1.0) != Some(core::cmp::Ordering::Less) {
        return Err(FormError::NotAnEllipse);
    }
    Ok((classical(&to_classical(&mean)), evaluations))
}

/// The osculating ECI state of mean classical elements (the inverse of
/// [`mean_of_osculating_state`]).
///
/// # Errors
/// [`FormError`] when the elements are not finite or a Kepler solve does not converge.
pub fn osculating_state_of_mean(el: &MeanElements) -> Result<CartesianState, FormError> {
    let c = from_mean(el);
    if !c.iter().all(|x| x.is_finite()) {
        return Err(FormError::NotFinite);
    }
    let osc = mean_to_osculating(&from_classical(&c), KEPLER_MAX_ITER).ok_or(FormError::Kepler)?;
    let (l, ok) = eq::true_longitude(&osc, KEPLER_MAX_ITER);
    if !ok {
        return Err(FormError::Kepler);
    }
    let s = eq::state(&osc, l);
    Ok(CartesianState {
        pos_km: s.pos_km,
        vel_km_s: s.vel_km_s,
    })
}

/// `deputy - chief` as relative classical elements, angles wrapped into `[-pi, pi]` (the
/// deputy's own orbit as input).
pub fn relative_between(chief: &MeanElements, deputy: &MeanElements) -> RelativeElements {
    RelativeElements {
        dsma_km: deputy.sma_km - chief.sma_km,
        decc: deputy.ecc - chief.ecc,
        dinc_rad: deputy.inc_rad - chief.inc_rad,
        draan_rad: wrap_pi(deputy.raan_rad - chief.raan_rad),
        dargp_rad: wrap_pi(deputy.argp_rad - chief.argp_rad),
        dmean_anomaly_rad: wrap_pi(deputy.mean_anomaly_rad - chief.mean_anomaly_rad),
    }
}

/// `chief + rel`.
pub fn deputy_of(chief: &MeanElements, rel: &RelativeElements) -> MeanElements {
    MeanElements {
        sma_km: chief.sma_km + rel.dsma_km,
        ecc: chief.ecc + rel.decc,
        inc_rad: chief.inc_rad + rel.dinc_rad,
        raan_rad: chief.raan_rad + rel.draan_rad,
        argp_rad: chief.argp_rad + rel.dargp_rad,
        mean_anomaly_rad: chief.mean_anomaly_rad + rel.dmean_anomaly_rad,
    }
}

/// Relative classical elements of ROE on `chief`.
///
/// # Errors
/// [`FormError::RoeEquatorialChief`] when `|sin i|` of the chief is below
/// `min_sin_inclination` (the node difference is `d_iy / (a sin i)`), `NotFinite` for a NaN.
pub fn relative_of_roe(
    chief: &MeanElements,
    roe: &Roe,
    min_sin_inclination: f64,
) -> Result<RelativeElements, FormError> {
    let a = chief.sma_km * super::elements::M_PER_KM;
    let (sin_i, cos_i) = (libm::sin(chief.inc_rad), libm::cos(chief.inc_rad));
    if libm::fabs(sin_i) < min_sin_inclination {
        return Err(FormError::RoeEquatorialChief {
            sin_inc: libm::fabs(sin_i),
            min: min_sin_inclination,
        });
    }
    let draan = roe.diy_m / (a * sin_i);
    let du = roe.dlambda_m / a - draan * cos_i;
    let (ex_c, ey_c) = (
        chief.ecc * libm::cos(chief.argp_rad),
        chief.ecc * libm::sin(chief.argp_rad),
    );
    let (ex_d, ey_d) = (ex_c + roe.dex_m / a, ey_c + roe.dey_m / a);
    let ecc_d = libm::sqrt(ex_d * ex_d + ey_d * ey_d);
    // An undefined perigee (e = 0) keeps the chief's, so that u carries the phase.
    let argp_d = if ecc_d > 0.0 {
        chief.argp_rad + wrap_pi(libm::atan2(ey_d, ex_d) - chief.argp_rad)
    } else {
        chief.argp_rad
    };
    let dargp = argp_d - chief.argp_rad;
    let rel = RelativeElements {
        dsma_km: roe.da_m / super::elements::M_PER_KM,
        decc: ecc_d - chief.ecc,
        dinc_rad: roe.dix_m / a,
        draan_rad: draan,
        dargp_rad: dargp,
        dmean_anomaly_rad: du - dargp,
    };
    let all = [
        rel.dsma_km,
        rel.decc,
        rel.dinc_rad,
        rel.draan_rad,
        rel.dargp_rad,
        rel.dmean_anomaly_rad,
    ];
    if all.iter().all(|x| x.is_finite()) {
        Ok(rel)
    } else {
        Err(FormError::NotFinite)
    }
}

/// ROE (metres) of relative classical elements on `chief` (the inverse of [`relative_of_roe`]).
pub fn roe_of(chief: &MeanElements, rel: &RelativeElements) -> Roe {
    let a = chief.sma_km * super::elements::M_PER_KM;
    let d = deputy_of(chief, rel);
    let (sin_i, cos_i) = (libm::sin(chief.inc_rad), libm::cos(chief.inc_rad));
    let du = rel.dargp_rad + rel.dmean_anomaly_rad;
    Roe {
        da_m: rel.dsma_km * super::elements::M_PER_KM,
        dlambda_m: a * (du + rel.draan_rad * cos_i),
        dex_m: a * (d.ecc * libm::cos(d.argp_rad) - chief.ecc * libm::cos(chief.argp_rad)),
        dey_m: a * (d.ecc * libm::sin(d.argp_rad) - chief.ecc * libm::sin(chief.argp_rad)),
        dix_m: a * rel.dinc_rad,
        diy_m: a * rel.draan_rad * sin_i,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn paper_chief() -> MeanElements {
        MeanElements::test_paper_chief()
    }

    #[test]
    fn roe_round_trip() {
        let chief = paper_chief();
        let rel = RelativeElements {
            dsma_km: 0.1,
            decc: 1e-4,
            dinc_rad: 2e-4,
            draan_rad: -3e-4,
            dargp_rad: 0.01,
            dmean_anomaly_rad: -0.012,
        };
        let roe = roe_of(&chief, &rel);
        let back = relative_of_roe(&chief, &roe, 1e-3).unwrap();
        assert!((back.dsma_km - rel.dsma_km).abs() < 1e-12);
        assert!((back.decc - rel.decc).abs() < 1e-15);
        assert!((back.dinc_rad - rel.dinc_rad).abs() < 1e-15);
        assert!((back.draan_rad - rel.draan_rad).abs() < 1e-15);
        assert!((back.dargp_rad - rel.dargp_rad).abs() < 1e-12);
        assert!((back.dmean_anomaly_rad - rel.dmean_anomaly_rad).abs() < 1e-12);
        let mut eq_chief = chief;
        eq_chief.inc_rad = 0.0;
        assert!(matches!(
            relative_of_roe(&eq_chief, &roe, 1e-3),
            Err(FormError::RoeEquatorialChief { .. })
        ));
    }

    #[test]
    fn osculating_state_round_trip() {
        for el in [
            paper_chief(),
            MeanElements {
                sma_km: 7078.137,
                ecc: 0.0,
                inc_rad: 98.2f64.to_radians(),
                raan_rad: 0.5,
                argp_rad: 0.0,
                mean_anomaly_rad: 1.0,
            },
        ] {
            let s = osculating_state_of_mean(&el).unwrap();
            let back = mean_of_osculating_state(&s).unwrap();
            let (q0, q1) = (equinoctial_of(&el), equinoctial_of(&back));
            assert!((q0.sma_km - q1.sma_km).abs() < 1e-9);
            for (x, y) in [
                (q0.ex, q1.ex),
                (q0.ey, q1.ey),
                (q0.hx, q1.hx),
                (q0.hy, q1.hy),
            ] {
                assert!((x - y).abs() < 1e-13);
            }
            assert!(wrap_pi(q0.mean_longitude_rad - q1.mean_longitude_rad).abs() < 1e-13);
            // The osculating a differs from the mean one by the J2 short-period term (km).
            let osc_r = crate::vec3::norm(&s.pos_km);
            assert!(osc_r > 6378.0 && osc_r < 7700.0);
        }
    }
}
