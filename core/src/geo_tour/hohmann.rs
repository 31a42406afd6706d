//! One-revolution Hohmann-type phasing: a tangential burn puts the servicer on a phasing
//! orbit of period `T_m = (2 pi - s du) / n0` (s = +1 east: a shorter period, apoapsis on the
//! ring); after one revolution it is back at the burn point with the client, and the opposite
//! burn recircularises. Digest eqs. (1)-(4), exact in two-body.

use super::geo::Geo;
use super::maneuver::{Burn, Direction, Maneuver, Method};
use crate::astro::{M_PER_KM, TWO_PI};

/// The manoeuvre, or `None` when the phasing orbit would dip below `min_radius_km` or the
/// phase cannot be made in one revolution.
pub fn hohmann(g: &Geo, dir: Direction, phase_rad: f64, min_radius_km: f64) -> Option<Maneuver> {
    let tm = (TWO_PI - dir.sign() * phase_rad) / g.n0;
    if !(tm.is_finite() && tm > 0.0) {
        return None;
    }
    let am = libm::cbrt(g.mu * (tm / TWO_PI) * (tm / TWO_PI));
    // The other apse of the phasing orbit.
    if 2.0 * am - g.a0 < min_radius_km {
        return None;
    }
    let b = (g.vis_viva(g.a0, am) - g.v0) * M_PER_KM;
    let burns = [
        Burn {
            offset_s: 0.0,
            dv_rtn_mps: [0.0, b, 0.0],
        },
        Burn {
            offset_s: tm,
            dv_rtn_mps: [0.0, -b, 0.0],
        },
    ];
    Some(Maneuver::from_burns(Method::Hohmann, tm, am, 0, &burns))
}
