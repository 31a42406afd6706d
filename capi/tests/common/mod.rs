//! Helpers shared by the C interface's integration tests.

use reconfig_core::leo_tour::elements::{state_of, Classical};

/// A circular orbit of radius `r_km`, inclination `inc_rad`, at argument of latitude `u_rad`
/// on the node at RAAN 0 (the core's `leo_tour::elements::state_of`): (position km, velocity
/// km/s).
pub fn circular(r_km: f64, inc_rad: f64, u_rad: f64) -> ([f64; 3], [f64; 3]) {
    let el = Classical {
        a_km: r_km,
        e: 0.0,
        i_rad: inc_rad,
        raan_rad: 0.0,
        argp_rad: 0.0,
        nu_rad: u_rad,
    };
    let s = state_of(reconfig_core::astro::EARTH_MU_KM3_S2, &el).unwrap();
    ([s[0], s[1], s[2]], [s[3], s[4], s[5]])
}
