//! The GEO tour request and its settings.

use serde::{Deserialize, Serialize};

/// Most clients of one tour.
pub const MAX_TARGETS: usize = 16;
/// Highest Lambert revolution limit the settings accept.
pub const MAX_LAMBERT_REVOLUTIONS: u16 = 8;
/// Most legs whose method switches at the critical time price that the gap enumeration
/// tries both ways (2^this assignments).
pub const MAX_GAP_LEGS: u8 = 6;

/// Which way the servicer sweeps the ring.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[repr(u8)]
pub enum SweepChoice {
    /// Plan both sweeps and keep the cheaper (east on a tie).
    #[default]
    Cheaper = 0,
    /// Eastward only.
    East = 1,
    /// Westward only.
    West = 2,
}

/// How each leg's method is chosen.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[repr(u8)]
pub enum MethodPolicy {
    /// Every method (and Lambert well) of every leg competes on Δv under the time price.
    #[default]
    ByCost = 0,
    /// The paper's threshold rule on the leg's phase offset: drift above
    /// `rule_drift_above_rad`, one-revolution Hohmann down to `rule_hohmann_above_rad`,
    /// radial down to `rule_radial_above_rad`, Lambert in `rule_lambert_time_s` below. Only
    /// the drift legs' durations are then free.
    PaperRule = 1,
}

/// A servicing tour: one servicer in a geostationary slot visits clients in other slots, in
/// one sweep, within a mission time, every burn under a cap.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Problem {
    /// The servicer's slot: Earth-fixed longitude, rad (east positive).
    pub start_lon_rad: f64,
    /// The clients' slots, rad, in any order (the sweep sorts them).
    pub targets_lon_rad: heapless::Vec<f64, MAX_TARGETS>,
    /// Time for the whole tour, s.
    pub mission_time_s: f64,
    /// Largest single burn allowed, m/s.
    pub max_burn_mps: f64,
    /// Sweep direction.
    pub sweep: SweepChoice,
    /// Method choice.
    pub policy: MethodPolicy,
}

/// Loop bounds, tolerances and the paper's rule. Worst case of a solve (per sweep, M legs,
/// W = `lambert_max_revolutions + 1` wells): table building M (W (`well_iterations` + 3) + 2)
/// Lambert pairs (<= 2 `lambert_max_iter` Householder steps each) and 4 M `root_max_iter`
/// drift/radial bisection steps; allocation (1 + 2^`gap_max_legs`) `price_max_iter` price
/// steps of M drift roots of at most `root_max_iter` steps each; the exchange search at most
/// `exchange_rounds` x M x (`MAX_POINTS` + 1) exact re-allocations (each `price_max_iter` x M
/// drift roots) and M x W well searches.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct Settings {
    /// Most whole revolutions of a Lambert transfer (wells 1..=this+1), <= 8.
    pub lambert_max_revolutions: u16,
    /// Householder steps per Lambert solve.
    pub lambert_max_iter: u16,
    /// Lambert tolerance on Izzo's x.
    pub lambert_tol: f64,
    /// Golden-section steps per Lambert well.
    pub well_iterations: u16,
    /// Bisection/secant steps of every 1-D root (drift depth, radial eccentricity).
    pub root_max_iter: u16,
    /// Steps of the time-price search.
    pub price_max_iter: u16,
    /// The price search stops when the tour's time is within this of the mission time, s.
    pub time_tol_s: f64,
    /// Legs switching at the critical price tried both ways, <= 6.
    pub gap_max_legs: u8,
    /// Rounds of the exchange search after the price (each tries every leg's options whose
    /// first-order gain at the current price is positive).
    pub exchange_rounds: u16,
    /// A Lambert well is refined at the current price in the exchange search when its stored
    /// bottom's first-order effect is below this, m/s.
    pub exchange_margin_mps: f64,
    /// No intermediate orbit may come closer to Earth's centre than this, km.
    pub min_radius_km: f64,
    /// Paper's rule: drift above this phase offset, rad (1.2 deg).
    pub rule_drift_above_rad: f64,
    /// Paper's rule: one-revolution Hohmann above this, rad (0.25 deg).
    pub rule_hohmann_above_rad: f64,
    /// Paper's rule: radial above this, rad (0.15 deg); Lambert at or below.
    pub rule_radial_above_rad: f64,
    /// Transfer time of a direct (0-revolution) Lambert leg, and of the paper's rule, s (9 h).
    pub lambert_direct_time_s: f64,
}

impl Default for Settings {
    fn default() -> Self {
        let deg = core::f64::consts::PI / 180.0;
        Self {
            lambert_max_revolutions: 3,
            lambert_max_iter: 40,
            lambert_tol: 1e-13,
            well_iterations: 20,
            root_max_iter: 200,
            price_max_iter: 100,
            time_tol_s: 1e-3,
            gap_max_legs: 4,
            exchange_rounds: 8,
            exchange_margin_mps: 0.05,
            min_radius_km: 6578.137,
            rule_drift_above_rad: 1.2 * deg,
            rule_hohmann_above_rad: 0.25 * deg,
            rule_radial_above_rad: 0.15 * deg,
            lambert_direct_time_s: 9.0 * 3600.0,
        }
    }
}
