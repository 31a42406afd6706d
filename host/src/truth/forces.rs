//! The force model: which accelerations act, and their sum at an instant.

use super::atmosphere::drag_km_s2;
use super::ephemeris::{gmst_rad, moon_position_km, sun_position_km, DAY_S};
use super::gravity::{acceleration_km_s2, FieldTerms};
use super::gravity_model::GravityModel;

/// Gravitational parameter of the Sun, km^3/s^2 (DE440).
pub const SUN_GM_KM3_S2: f64 = 1.327_124_400_18e11;
/// Gravitational parameter of the Moon, km^3/s^2 (DE440).
pub const MOON_GM_KM3_S2: f64 = 4_902.800_066;

/// What acts on the spacecraft.
#[derive(Clone, Debug, PartialEq)]
pub struct ForceModel {
    /// The Earth's field (JGM-3, vendored).
    pub gravity: GravityModel,
    /// The field's terms.
    pub terms: FieldTerms,
    /// Drag with this ballistic coefficient `Cd A / m`, m^2/kg (exponential atmosphere);
    /// `None`: no drag.
    pub drag_cd_area_per_mass_m2_kg: Option<f64>,
    /// The Sun's third-body attraction.
    pub sun: bool,
    /// The Moon's third-body attraction.
    pub moon: bool,
    /// Julian date (TT) of `t = 0`: places the Earth's rotation, the Sun and the Moon. (A LEO
    /// tour passes its UTC epoch here, `drivers::leo_truth`: within the series' accuracy.)
    pub epoch_jd: f64,
}

impl ForceModel {
    /// Two-body motion in the model's central field.
    pub fn two_body(gravity: GravityModel, epoch_jd: f64) -> Self {
        Self {
            gravity,
            terms: FieldTerms::CENTRAL,
            drag_cd_area_per_mass_m2_kg: None,
            sun: false,
            moon: false,
            epoch_jd,
        }
    }

    /// The whole model: the field to degree and order 8, drag, Sun and Moon.
    pub fn full(gravity: GravityModel, epoch_jd: f64, cd_area_per_mass_m2_kg: f64) -> Self {
        Self {
            gravity,
            terms: FieldTerms::FULL,
            drag_cd_area_per_mass_m2_kg: Some(cd_area_per_mass_m2_kg),
            sun: true,
            moon: true,
            epoch_jd,
        }
    }

    /// One line naming what acts (for reports).
    pub fn describe(&self) -> String {
        let mut parts = vec![format!(
            "{} degree {} order {}",
            self.gravity.name, self.terms.degree, self.terms.order
        )];
        if let Some(b) = self.drag_cd_area_per_mass_m2_kg {
            parts.push(format!(
                "drag (exponential atmosphere, Cd A/m = {b} m^2/kg)"
            ));
        }
        if self.sun {
            parts.push("Sun".into());
        }
        if self.moon {
            parts.push("Moon".into());
        }
        parts.join(", ")
    }

    /// Acceleration, km/s^2, at `t_s` from the epoch, inertial position `r_km`, velocity `v_km_s`.
    pub fn acceleration(&self, t_s: f64, r_km: &[f64; 3], v_km_s: &[f64; 3]) -> [f64; 3] {
        let jd = self.epoch_jd + t_s / DAY_S;
        // Inertial -> Earth-fixed: a rotation by the sidereal angle about z.
        let (s, c) = gmst_rad(jd).sin_cos();
        let fixed = [
            c * r_km[0] + s * r_km[1],
            -s * r_km[0] + c * r_km[1],
            r_km[2],
        ];
        let g = acceleration_km_s2(&self.gravity, self.terms, &fixed);
        let mut a = [c * g[0] - s * g[1], s * g[0] + c * g[1], g[2]];
        if let Some(b) = self.drag_cd_area_per_mass_m2_kg {
            add(&mut a, &drag_km_s2(b, r_km, v_km_s));
        }
        if self.sun {
            add(
                &mut a,
                &third_body(SUN_GM_KM3_S2, &sun_position_km(jd), r_km),
            );
        }
        if self.moon {
            add(
                &mut a,
                &third_body(MOON_GM_KM3_S2, &moon_position_km(jd), r_km),
            );
        }
        a
    }
}

fn add(a: &mut [f64; 3], b: &[f64; 3]) {
    for (x, y) in a.iter_mut().zip(b.iter()) {
        *x += *y;
    }
}

/// Tidal acceleration of a body of parameter `gm` at geocentric `s_km` on a spacecraft at
/// `r_km`: the body's pull on the spacecraft less its pull on the Earth.
fn third_body(gm: f64, s_km: &[f64; 3], r_km: &[f64; 3]) -> [f64; 3] {
    let d = [s_km[0] - r_km[0], s_km[1] - r_km[1], s_km[2] - r_km[2]];
    let dn3 = (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).powf(1.5);
    let sn3 = (s_km[0] * s_km[0] + s_km[1] * s_km[1] + s_km[2] * s_km[2]).powf(1.5);
    [
        gm * (d[0] / dn3 - s_km[0] / sn3),
        gm * (d[1] / dn3 - s_km[1] / sn3),
        gm * (d[2] / dn3 - s_km[2] / sn3),
    ]
}

#[cfg(test)]
#[allow(clippy::unwrap_used)]
mod tests {
    use super::*;
    use crate::truth::ephemeris::julian_date;

    #[test]
    fn third_body_tides_have_their_textbook_size() {
        let g = GravityModel::jgm3().unwrap();
        let mut m = ForceModel::two_body(g, julian_date(2025, 3, 20, 0, 0, 0.0));
        let r = [7000.0, 0.0, 0.0];
        let v = [0.0, 7.5, 0.0];
        let base = m.acceleration(0.0, &r, &v);
        // The change of the acceleration with the third body on, km/s^2.
        let with = |m: &ForceModel| {
            let a = m.acceleration(0.0, &r, &v);
            (0..3).map(|k| (a[k] - base[k]).powi(2)).sum::<f64>().sqrt()
        };
        m.moon = true;
        let d = with(&m);
        // ~ GM_moon r / d^3 ... 2 GM_moon r / d^3 = 0.6e-9 .. 1.2e-9 km/s^2 (~1e-6 m/s^2).
        assert!(d > 2e-10 && d < 2e-9, "moon {d}");
        m.moon = false;
        m.sun = true;
        let d = with(&m);
        // GM_sun r / au^3 = 2.8e-10 .. twice that.
        assert!(d > 1e-10 && d < 8e-10, "sun {d}");
    }
}
