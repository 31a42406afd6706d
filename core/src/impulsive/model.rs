//! The model's pieces in the working element set of a solve (`Settings::element_set`): drift,
//! impulse timing phase, anomaly, impulse matrix, state transition, exact impulse, state,
//! domain and perigee. One function per piece, dispatching to the classical modules
//! (`secular`, `gve`, `nonlinear`, the paper's set) or to the equinoctial ones.
//!
//! Impulse points: where the chief's inclination is not small the phase of an impulse point is
//! the deputy's mean argument of latitude `u = omega + M` (`lambda - Omega` in equinoctial
//! elements), as in the paper. For a (near-)equatorial chief (`|sin i| <
//! Settings::min_sin_inclination`, equinoctial set only) the node is not defined and the phase
//! is the deputy's mean longitude `lambda = M + omega + Omega` instead.

use super::elements::{Elements, A, ARGP, E, EARTH_RADIUS_KM, I, MA, RAAN};
use super::equinoctial as eq;
use super::equinoctial_drift as eq_drift;
use super::settings::{ElementSet, Settings};
use super::types::MeanElements;
use super::{gve, kepler, nonlinear, secular};
use crate::vec3::Vec3;
use nalgebra::SMatrix;

/// The phase convention of the impulse points (`ImpulsePoint::arg_latitude_rad` and
/// `Impulse::arg_latitude_rad` hold this angle): see [`point_phase`].
#[derive(Clone, Copy, Debug, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Phase {
    /// Mean argument of latitude `omega + M`.
    ArgLatitude,
    /// Mean longitude `M + omega + Omega` (equatorial chief).
    MeanLongitude,
}

/// The phase the impulse points of a problem with chief `chief` are counted in under
/// `settings`: the mean longitude for a prograde chief with `|sin i|` below
/// `settings.min_sin_inclination` in the equinoctial set (the node is not defined there), else
/// the mean argument of latitude.
pub fn point_phase(chief: &MeanElements, settings: &Settings) -> Phase {
    let (sin_i, cos_i) = (libm::sin(chief.inc_rad), libm::cos(chief.inc_rad));
    if settings.element_set == ElementSet::Equinoctial
        && cos_i > 0.0
        && libm::fabs(sin_i) < settings.min_sin_inclination
    {
        Phase::MeanLongitude
    } else {
        Phase::ArgLatitude
    }
}

/// The working set and the phase convention of one solve.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) struct Model {
    /// Working element set.
    pub set: ElementSet,
    /// Phase of the impulse points.
    pub phase: Phase,
}

impl Model {
    /// Working elements of classical ones.
    pub fn working_of_classical(&self, el: &Elements) -> Elements {
        match self.set {
            ElementSet::Classical => *el,
            ElementSet::Equinoctial => eq::from_classical(el),
        }
    }

    /// Classical elements of working ones (angles of an undefined node or perigee are 0).
    pub fn classical_of(&self, el: &Elements) -> Elements {
        match self.set {
            ElementSet::Classical => *el,
            ElementSet::Equinoctial => eq::to_classical(el),
        }
    }

    /// Equinoctial elements of working ones.
    pub fn equinoctial_of(&self, el: &Elements) -> Elements {
        match self.set {
            ElementSet::Classical => eq::from_classical(el),
            ElementSet::Equinoctial => *el,
        }
    }

    /// `el` drifted by `dt_s` with its own J2 secular rates.
    pub fn drift(&self, el: &Elements, dt_s: f64) -> Elements {
        self.drift_with(el, el, dt_s)
    }

    /// `el` drifted by `dt_s` with the rates of `rates_of` (a formation's target drifts with
    /// the chief).
    pub fn drift_with(&self, el: &Elements, rates_of: &Elements, dt_s: f64) -> Elements {
        match self.set {
            ElementSet::Classical => {
                let d = secular::rates(rates_of);
                let mut out = *el;
                for (x, r) in out.iter_mut().zip(d.iter()) {
                    *x += *r * dt_s;
                }
                out
            }
            ElementSet::Equinoctial => eq_drift::flow_with(el, &eq_drift::rates(rates_of), dt_s),
        }
    }

    /// The phase of `el` the impulse points are counted in, rad (not wrapped).
    pub fn phase_rad(&self, el: &Elements) -> f64 {
        match (self.set, self.phase) {
            (ElementSet::Classical, _) => super::elements::mean_arg_latitude_rad(el),
            (ElementSet::Equinoctial, Phase::ArgLatitude) => el[eq::LAMBDA] - eq::raan_rad(el),
            (ElementSet::Equinoctial, Phase::MeanLongitude) => el[eq::LAMBDA],
        }
    }

    /// The rate of [`Model::phase_rad`], rad/s.
    pub fn phase_rate_rad_s(&self, el: &Elements) -> f64 {
        match (self.set, self.phase) {
            (ElementSet::Classical, _) => secular::arg_latitude_rate_rad_s(el),
            (ElementSet::Equinoctial, Phase::ArgLatitude) => eq_drift::rates(el).arg_latitude,
            (ElementSet::Equinoctial, Phase::MeanLongitude) => eq_drift::rates(el).lambda,
        }
    }

    /// The true anomaly (classical) or true longitude (equinoctial) of `el`, rad;
    /// `(value, converged)`.
    pub fn anomaly(&self, el: &Elements, max_iter: u16) -> (f64, bool) {
        match self.set {
            ElementSet::Classical => kepler::true_anomaly(el[MA], el[E], max_iter),
            ElementSet::Equinoctial => eq::true_longitude(el, max_iter),
        }
    }

    /// The true phase at the anomaly [`Model::anomaly`] returned: `omega + f`, or the true
    /// longitude minus the node, or the true longitude (see [`Phase`]), rad (not wrapped).
    pub fn true_phase_rad(&self, el: &Elements, anomaly_rad: f64) -> f64 {
        match (self.set, self.phase) {
            (ElementSet::Classical, _) => el[ARGP] + anomaly_rad,
            (ElementSet::Equinoctial, Phase::ArgLatitude) => anomaly_rad - eq::raan_rad(el),
            (ElementSet::Equinoctial, Phase::MeanLongitude) => anomaly_rad,
        }
    }

    /// The impulse matrix `B` at `anomaly_rad`.
    pub fn impulse_matrix(&self, el: &Elements, anomaly_rad: f64) -> SMatrix<f64, 6, 3> {
        match self.set {
            ElementSet::Classical => gve::impulse_matrix(el, anomaly_rad),
            ElementSet::Equinoctial => eq::impulse_matrix(el, anomaly_rad),
        }
    }

    /// `Phi B`: the impulse matrix `b` carried to the end by the drift's state transition over
    /// `dt_s` from `before` (the deputy before the impulse). Classical: the paper's
    /// `(I_6 + dD(sigma_{k-1}) dt) B` (eq. 11); equinoctial: the exact Jacobian of the flow.
    pub fn transition_times(
        &self,
        before: &Elements,
        at: &Elements,
        dt_s: f64,
        b: &SMatrix<f64, 6, 3>,
    ) -> SMatrix<f64, 6, 3> {
        match self.set {
            ElementSet::Classical => {
                let mut p_b = *b;
                p_b.gemm(dt_s, &secular::rates_jacobian(before), b, 1.0);
                p_b
            }
            ElementSet::Equinoctial => {
                let mut p_b = SMatrix::<f64, 6, 3>::zeros();
                p_b.gemm(1.0, &eq_drift::flow_jacobian(at, dt_s), b, 0.0);
                p_b
            }
        }
    }

    /// The elements after the exact impulse `dv` (km/s, RTN) at `anomaly_rad`.
    pub fn apply_impulse(&self, el: &Elements, anomaly_rad: f64, dv: &Vec3) -> Option<Elements> {
        match self.set {
            ElementSet::Classical => nonlinear::apply_impulse(el, anomaly_rad, dv),
            ElementSet::Equinoctial => eq::apply_impulse(el, anomaly_rad, dv),
        }
    }

    /// Position, velocity and local frame at `anomaly_rad`.
    pub fn state(&self, el: &Elements, anomaly_rad: f64) -> nonlinear::State {
        match self.set {
            ElementSet::Classical => nonlinear::state(el, anomaly_rad),
            ElementSet::Equinoctial => eq::state(el, anomaly_rad),
        }
    }

    /// Eccentricity of `el`.
    pub fn ecc(&self, el: &Elements) -> f64 {
        match self.set {
            ElementSet::Classical => el[E],
            ElementSet::Equinoctial => libm::sqrt(eq::ecc_squared(el)),
        }
    }

    /// Perigee altitude `a (1 - e) - Re`, km.
    pub fn perigee_altitude_km(&self, el: &Elements) -> f64 {
        el[A] * (1.0 - self.ecc(el)) - EARTH_RADIUS_KM
    }

    /// `(sin i, cos i)` of `el`.
    pub fn sin_cos_inc(&self, el: &Elements) -> (f64, f64) {
        match self.set {
            ElementSet::Classical => (libm::sin(el[I]), libm::cos(el[I])),
            ElementSet::Equinoctial => {
                let t2 = eq::tan_half_inc_squared(el);
                (2.0 * libm::sqrt(t2) / (1.0 + t2), (1.0 - t2) / (1.0 + t2))
            }
        }
    }

    /// `el` is inside the domain the model is valid on (thresholds from the settings):
    /// finite, above Earth's radius, elliptic, and away from the set's singularities (e = 0 and
    /// sin i = 0 for the classical set, retrograde equatorial for the equinoctial set).
    pub fn in_domain(&self, el: &Elements, settings: &Settings) -> bool {
        if !(el.iter().all(|x| x.is_finite()) && el[A] > EARTH_RADIUS_KM) {
            return false;
        }
        let e = self.ecc(el);
        let (sin_i, cos_i) = self.sin_cos_inc(el);
        match self.set {
            ElementSet::Classical => {
                e >= settings.min_eccentricity
                    && e < 1.0
                    && libm::fabs(sin_i) >= settings.min_sin_inclination
            }
            ElementSet::Equinoctial => {
                e < 1.0 && !(cos_i < 0.0 && sin_i < settings.min_sin_inclination)
            }
        }
    }

    /// The angle rows of an element difference wrapped into `[-pi, pi]`.
    pub fn wrap_angles(&self, err: &mut Elements) {
        let rows: &[usize] = match self.set {
            ElementSet::Classical => &[RAAN, ARGP, MA],
            ElementSet::Equinoctial => &[eq::LAMBDA],
        };
        for k in rows {
            if let Some(x) = err.get_mut(*k) {
                *x = super::elements::wrap_pi(*x);
            }
        }
    }
}
