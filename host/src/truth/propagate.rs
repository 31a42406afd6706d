//! Propagate one spacecraft through impulsive burns in the force model.

use super::forces::ForceModel;
use super::integrator::{integrate, Counters, State6, Tolerance};
use anyhow::{bail, Context, Result};

/// An impulsive burn.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Burn {
    /// Time from the epoch, s.
    pub time_s: f64,
    /// Velocity change in the spacecraft's local frame at that instant: radial (away from the
    /// Earth), along-track (normal x radial), normal (along the orbit's angular momentum); m/s.
    pub dv_rtn_mps: [f64; 3],
}

/// An inertial state, km and km/s.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize)]
pub struct EciState {
    /// Position, km.
    pub pos_km: [f64; 3],
    /// Velocity, km/s.
    pub vel_km_s: [f64; 3],
}

impl EciState {
    /// `[x, y, z, vx, vy, vz]`, km and km/s.
    pub fn to_array(self) -> State6 {
        let (p, v) = (self.pos_km, self.vel_km_s);
        [p[0], p[1], p[2], v[0], v[1], v[2]]
    }

    /// From `[x, y, z, vx, vy, vz]`, km and km/s.
    pub fn from_array(y: &State6) -> Self {
        Self {
            pos_km: [y[0], y[1], y[2]],
            vel_km_s: [y[3], y[4], y[5]],
        }
    }

    /// The local frame (radial, along-track, normal unit vectors) of this state.
    pub fn rtn_axes(&self) -> [[f64; 3]; 3] {
        let r = unit(&self.pos_km);
        let n = unit(&cross(&self.pos_km, &self.vel_km_s));
        let t = cross(&n, &r);
        [r, t, n]
    }
}

/// Cross product.
pub fn cross(a: &[f64; 3], b: &[f64; 3]) -> [f64; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

fn unit(a: &[f64; 3]) -> [f64; 3] {
    let n = (a[0] * a[0] + a[1] * a[1] + a[2] * a[2]).sqrt();
    [a[0] / n, a[1] / n, a[2] / n]
}

/// Below this geocentric distance (the equatorial radius plus 80 km, where the exponential
/// atmosphere's drag makes an orbit re-enter within a revolution) a propagation stops with an
/// error rather than fly on through a model that no longer describes an orbit.
pub const MIN_RADIUS_KM: f64 = super::atmosphere::EARTH_RADIUS_KM + 80.0;

/// `Err` naming the altitude when `y` is below [`MIN_RADIUS_KM`].
fn check_altitude(y: &State6) -> Result<()> {
    let r_km = (y[0] * y[0] + y[1] * y[1] + y[2] * y[2]).sqrt();
    if r_km < MIN_RADIUS_KM {
        bail!(
            "altitude {:.1} km below the {:.0} km the truth model flies",
            r_km - super::atmosphere::EARTH_RADIUS_KM,
            MIN_RADIUS_KM - super::atmosphere::EARTH_RADIUS_KM
        );
    }
    Ok(())
}

/// The end of a propagation.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Propagated {
    /// The state at the end time.
    pub end: EciState,
    /// Integrator steps.
    pub counters: Counters,
}

/// Propagate `start` (at `t = 0`) to `end_s` under `model`, applying `burns` (in time order,
/// each within `[0, end_s]`) at their instants. Bounded: one integration per burn interval, each
/// bounded by `tol.max_steps`.
///
/// # Errors
/// Burns out of order or outside `[0, end_s]`, a non-finite burn, an integration error, or the
/// spacecraft below [`MIN_RADIUS_KM`] at the start or at any accepted step.
pub fn propagate(
    model: &ForceModel,
    start: &EciState,
    burns: &[Burn],
    end_s: f64,
    tol: &Tolerance,
) -> Result<Propagated> {
    if !(end_s.is_finite() && end_s >= 0.0) {
        bail!("end time {end_s} s is not a finite time >= 0");
    }
    let f = |t: f64, y: &State6| -> State6 {
        let a = model.acceleration(t, &[y[0], y[1], y[2]], &[y[3], y[4], y[5]]);
        [y[3], y[4], y[5], a[0], a[1], a[2]]
    };
    let mut y = start.to_array();
    check_altitude(&y).context("at the start")?;
    let mut t = 0.0;
    let mut h = 10.0;
    let mut counters = Counters::default();
    for (k, burn) in burns.iter().enumerate() {
        let in_order = burn.time_s >= t && burn.time_s <= end_s;
        if !(in_order && burn.dv_rtn_mps.iter().all(|x| x.is_finite())) {
            bail!(
                "burn {} at {} s: not in time order within [0, {end_s}] s, or not finite",
                k + 1,
                burn.time_s
            );
        }
        integrate(
            &f,
            &check_altitude,
            t,
            burn.time_s,
            &mut y,
            &mut h,
            tol,
            &mut counters,
        )
        .with_context(|| format!("coasting to burn {}", k + 1))?;
        let state = EciState::from_array(&y);
        let axes = state.rtn_axes();
        for (axis, dv) in axes.iter().zip(burn.dv_rtn_mps.iter()) {
            for (j, u) in axis.iter().enumerate() {
                y[3 + j] += dv * 1e-3 * u;
            }
        }
        t = burn.time_s;
    }
    integrate(
        &f,
        &check_altitude,
        t,
        end_s,
        &mut y,
        &mut h,
        tol,
        &mut counters,
    )
    .context("coasting to the end")?;
    Ok(Propagated {
        end: EciState::from_array(&y),
        counters,
    })
}
