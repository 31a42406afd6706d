//! The hybrid transfer's units and constants (SPEC-hybrid.md, Table 1): the Earth–Moon
//! circular restricted three-body problem in the rotating frame, non-dimensional in distance
//! (LU, the Earth–Moon distance), time (TU, 27.32 d / 2π, the paper's: only it reproduces
//! Table 2's masses), and mass (MU, the spacecraft's 3000 kg before the impulse). A force is
//! then in MU LU / TU² (`_fu`), a speed in LU / TU (`_vu`).

/// μ, the Moon's share of the Earth–Moon mass.
pub const MASS_RATIO: f64 = 1.215_066_83e-2;
/// LU, km.
pub const LU_KM: f64 = 3.844_05e5;
/// TU, s.
pub const TU_S: f64 = 3.756_769_67e5;
/// MU, kg: the spacecraft before the chemical impulse.
pub const MU_KG: f64 = 3000.0;
/// Standard gravity, m/s², for exhaust speeds from specific impulses.
pub const G0_MPS2: f64 = 9.806_65;
/// One day, s.
pub const DAY_S: f64 = 86_400.0;

/// VU = LU / TU, km/s.
pub fn vu_kmps() -> f64 {
    LU_KM / TU_S
}

/// A thrust in newtons as MU LU / TU².
pub fn force_fu(thrust_n: f64) -> f64 {
    thrust_n / (MU_KG * LU_KM * 1e3 / (TU_S * TU_S))
}

/// An exhaust speed from a specific impulse (s), in LU / TU.
pub fn exhaust_speed_vu(specific_impulse_s: f64) -> f64 {
    specific_impulse_s * G0_MPS2 * 1e-3 / vu_kmps()
}

/// A distance in km as LU.
pub fn distance_lu(km: f64) -> f64 {
    km / LU_KM
}

/// A time in TU as days.
pub fn days(time_tu: f64) -> f64 {
    time_tu * TU_S / DAY_S
}

/// A time in days as TU.
pub fn time_tu(days: f64) -> f64 {
    days * DAY_S / TU_S
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Table 1's non-dimensional values, as SPEC-hybrid.md derived and checked them.
    #[test]
    fn the_papers_constants_come_out_as_the_digest_derived_them() {
        assert!((force_fu(10.0) - 1.223_824).abs() < 1e-6);
        assert!((exhaust_speed_vu(300.0) - 2.875_196).abs() < 1e-6);
        assert!((exhaust_speed_vu(3000.0) - 28.751_96).abs() < 1e-5);
        assert!((vu_kmps() - 1.023_232_81).abs() < 1e-8);
        assert!((distance_lu(6778.0) - 0.017_632_44).abs() < 1e-8);
        // The circular speed of the parking orbit, 7.658850 km/s = 7.484953 VU.
        let vc = libm::sqrt((1.0 - MASS_RATIO) / distance_lu(6778.0));
        assert!((vc - 7.484_953).abs() < 1e-6);
        assert!((vc * vu_kmps() - 7.658_850).abs() < 1e-6);
        assert!((days(time_tu(3.3692)) - 3.3692).abs() < 1e-12);
    }
}
