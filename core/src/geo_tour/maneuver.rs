//! What one phasing manoeuvre is: its method, its burns and the time it needs.

use serde::{Deserialize, Serialize};

/// Most burns of one manoeuvre (the drift method's four).
pub const MAX_BURNS: usize = 4;

/// The four phasing methods (and the empty leg to a client in the same slot).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[repr(u8)]
pub enum Method {
    /// Client in the same slot: no burn, no time.
    #[default]
    None = 0,
    /// Drift phasing: Hohmann transfer to a drift orbit, drift, Hohmann transfer back (4 burns).
    Drift = 1,
    /// One-revolution Hohmann-type phasing: two tangential burns one phasing period apart.
    Hohmann = 2,
    /// Radial-impulse phasing: two radial burns half an (eccentric) revolution apart.
    Radial = 3,
    /// Lambert transfer from the servicer to the client's arrival position (2 burns).
    Lambert = 4,
}

/// Direction of motion along the ring.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[repr(u8)]
pub enum Direction {
    /// Towards increasing longitude (the servicer gains phase: drift orbits below GEO).
    East = 0,
    /// Towards decreasing longitude (drift orbits above GEO).
    West = 1,
}

impl Direction {
    /// +1 east, -1 west.
    pub fn sign(self) -> f64 {
        match self {
            Self::East => 1.0,
            Self::West => -1.0,
        }
    }
}

/// One burn of a manoeuvre.
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct Burn {
    /// Time after the start of the manoeuvre (of the leg), s.
    pub offset_s: f64,
    /// Velocity change in the servicer's local frame just before the burn: radial (away from
    /// Earth), along-track (in the orbit plane, perpendicular to radial, positive eastward),
    /// normal (along the orbit's angular momentum); m/s.
    pub dv_rtn_mps: [f64; 3],
}

impl Burn {
    /// Size of the burn, m/s.
    pub fn size_mps(&self) -> f64 {
        let [r, t, n] = self.dv_rtn_mps;
        libm::sqrt(r * r + t * t + n * n)
    }
}

/// A phasing manoeuvre for one leg: the burns and the time from the first to the arrival.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct Maneuver {
    /// The method.
    pub method: Method,
    /// Time from the leg's start to the arrival at the client (the last burn), s. A leg given
    /// more time waits the rest co-located with the client after the arrival.
    pub transfer_s: f64,
    /// Sum of the burn sizes, m/s.
    pub dv_mps: f64,
    /// Largest single burn, m/s.
    pub max_burn_mps: f64,
    /// Semi-major axis of the intermediate orbit (drift orbit, phasing orbit, radial ellipse;
    /// for Lambert the transfer orbit's), km; 0 for `Method::None`.
    pub orbit_sma_km: f64,
    /// Whole revolutions of a Lambert transfer (0 otherwise).
    pub revolutions: u16,
    /// The burns in time order.
    pub burns: heapless::Vec<Burn, MAX_BURNS>,
}

impl Maneuver {
    /// Build from burns (sizes summed here, so the totals always agree with the burns).
    pub(crate) fn from_burns(
        method: Method,
        transfer_s: f64,
        orbit_sma_km: f64,
        revolutions: u16,
        burns: &[Burn],
    ) -> Self {
        let mut out = Self {
            method,
            transfer_s,
            orbit_sma_km,
            revolutions,
            ..Self::default()
        };
        for b in burns.iter().take(MAX_BURNS) {
            let s = b.size_mps();
            out.dv_mps += s;
            out.max_burn_mps = out.max_burn_mps.max(s);
            // `take(MAX_BURNS)` keeps the push within capacity.
            let _ = out.burns.push(*b);
        }
        out
    }

    /// The empty manoeuvre (client in the same slot).
    pub(crate) fn none() -> Self {
        Self::default()
    }
}
