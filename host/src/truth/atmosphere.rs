//! Atmospheric drag: the exponential atmosphere of Vallado (*Fundamentals of Astrodynamics and
//! Applications*, 4th ed., 2013, table 8-4: CIRA-72 fitted piecewise, 0 km to above 1000 km;
//! no solar or geomagnetic activity, so nothing to download) and a co-rotating atmosphere.
//! Altitude is above a sphere of the Earth's equatorial radius (the flattening moves a polar
//! orbit's altitude by up to 21 km: a density factor of ~1.5 at 300 km, within the table's own
//! error against a real atmosphere, which varies by ~10 over a solar cycle).

/// Equatorial radius for the altitude, km (WGS-84).
pub const EARTH_RADIUS_KM: f64 = 6378.137;
/// Earth rotation rate, rad/s (IERS).
pub const EARTH_ROTATION_RAD_S: f64 = 7.292_115e-5;

/// (base altitude km, density kg/m^3 at the base, scale height km), rows in ascending altitude.
const TABLE: [(f64, f64, f64); 28] = [
    (0.0, 1.225, 7.249),
    (25.0, 3.899e-2, 6.349),
    (30.0, 1.774e-2, 6.682),
    (40.0, 3.972e-3, 7.554),
    (50.0, 1.057e-3, 8.382),
    (60.0, 3.206e-4, 7.714),
    (70.0, 8.770e-5, 6.549),
    (80.0, 1.905e-5, 5.799),
    (90.0, 3.396e-6, 5.382),
    (100.0, 5.297e-7, 5.877),
    (110.0, 9.661e-8, 7.263),
    (120.0, 2.438e-8, 9.473),
    (130.0, 8.484e-9, 12.636),
    (140.0, 3.845e-9, 16.149),
    (150.0, 2.070e-9, 22.523),
    (180.0, 5.464e-10, 29.740),
    (200.0, 2.789e-10, 37.105),
    (250.0, 7.248e-11, 45.546),
    (300.0, 2.418e-11, 53.628),
    (350.0, 9.518e-12, 53.298),
    (400.0, 3.725e-12, 58.515),
    (450.0, 1.585e-12, 60.828),
    (500.0, 6.967e-13, 63.822),
    (600.0, 1.454e-13, 71.835),
    (700.0, 3.614e-14, 88.667),
    (800.0, 1.170e-14, 124.64),
    (900.0, 5.245e-15, 181.05),
    (1000.0, 3.019e-15, 268.00),
];

/// Density at geometric altitude `alt_km`, kg/m^3 (the lowest row below 0 km; the last row's
/// exponential above 1000 km).
pub fn density_kg_m3(alt_km: f64) -> f64 {
    let row = TABLE
        .iter()
        .rev()
        .find(|(base, _, _)| alt_km >= *base)
        .unwrap_or(&TABLE[0]);
    let (base, rho0, scale) = *row;
    rho0 * (-(alt_km - base) / scale).exp()
}

/// Drag acceleration, km/s^2, on a body with ballistic coefficient `cd_area_per_mass_m2_kg`
/// (`Cd A / m`) at inertial position `r_km` and velocity `v_km_s`: `-1/2 (Cd A/m) rho |v_rel|
/// v_rel`, with `v_rel = v - omega x r` (the atmosphere turns with the Earth).
pub fn drag_km_s2(cd_area_per_mass_m2_kg: f64, r_km: &[f64; 3], v_km_s: &[f64; 3]) -> [f64; 3] {
    let alt_km =
        (r_km[0] * r_km[0] + r_km[1] * r_km[1] + r_km[2] * r_km[2]).sqrt() - EARTH_RADIUS_KM;
    let rho = density_kg_m3(alt_km);
    let rel = [
        v_km_s[0] + EARTH_ROTATION_RAD_S * r_km[1],
        v_km_s[1] - EARTH_ROTATION_RAD_S * r_km[0],
        v_km_s[2],
    ];
    let speed = (rel[0] * rel[0] + rel[1] * rel[1] + rel[2] * rel[2]).sqrt();
    // rho [kg/m^3] * B [m^2/kg] * v^2 [(km/s)^2 = 1e6 m^2/s^2] gives m/s^2: 1e3 km/s^2 per unit.
    let k = -0.5 * cd_area_per_mass_m2_kg * rho * speed * 1e3;
    [k * rel[0], k * rel[1], k * rel[2]]
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn density_follows_the_table_and_is_continuous_enough() {
        assert_eq!(density_kg_m3(400.0), 3.725e-12);
        // Vallado example 8-4 style check: 300 km -> 2.418e-11; 350 km from the 300 km row.
        let at_350_from_below = 2.418e-11 * (-50.0f64 / 53.628).exp();
        assert!((at_350_from_below / density_kg_m3(350.0) - 1.0).abs() < 0.05);
        // Monotone over LEO.
        let mut last = f64::INFINITY;
        for h in (150..1200).step_by(5) {
            let rho = density_kg_m3(f64::from(h));
            assert!(rho < last && rho > 0.0, "{h} km");
            last = rho;
        }
    }

    #[test]
    fn drag_opposes_the_relative_velocity_with_its_size() {
        let r = [6778.137, 0.0, 0.0];
        let v = [0.0, 7.6686, 0.0];
        let a = drag_km_s2(0.022, &r, &v);
        let vrel = 7.6686 - EARTH_ROTATION_RAD_S * 6778.137;
        // 1/2 0.022 3.725e-12 (vrel 1e3)^2 m/s^2 at 400 km.
        let want_mps2 = 0.5 * 0.022 * 3.725e-12 * (vrel * 1e3).powi(2);
        assert!(a[0] == 0.0 && a[2] == 0.0);
        assert!((-a[1] * 1e3 / want_mps2 - 1.0).abs() < 1e-12, "{a:?}");
    }
}
