//! The GEO tour request and its settings.

use crate::astro::EARTH_RADIUS_KM;
use crate::contract::{check_range, Range, SettingError};
use serde::{Deserialize, Serialize};

/// The bound on Cortex-M7 instructions per work unit over the charged kernels
/// (`work_units.rs`): the QEMU test fails when a kernel case takes more than its units times
/// this (docs/geo-tour.md, "Work budget", has the measured ratios).
pub const MAX_INSTRUCTIONS_PER_UNIT: u64 = 100;

/// The default work budget: `DEFAULT_WORK_BUDGET x MAX_INSTRUCTIONS_PER_UNIT` = 400 M
/// Cortex-M7 instructions, the most a request within the default limits may take.
pub const DEFAULT_WORK_BUDGET: u64 = 400_000_000 / MAX_INSTRUCTIONS_PER_UNIT;

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
    /// The paper's threshold rule, but a Lambert leg's transfer time is free (any time of its
    /// Lambert wells, with the time price) instead of the rule's fixed `lambert_direct_time_s`:
    /// the rule's choice of methods with the Lambert legs allocated as by cost, to compare the
    /// paper's rule with the project's allocation (issue 31).
    PaperRuleFreeLambert = 2,
}

impl MethodPolicy {
    /// Whether the paper's threshold rule chooses each leg's method.
    pub const fn follows_rule(self) -> bool {
        matches!(self, Self::PaperRule | Self::PaperRuleFreeLambert)
    }
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

/// One degree, rad.
const DEG_RAD: f64 = core::f64::consts::PI / 180.0;

crate::settings_table! {
    /// Loop bounds, tolerances, the paper's rule and the work budget. Every loop of a solve is
    /// bounded by these and the capacities, and charged to the work meter at its worst case
    /// (`work_units.rs`): a solve stops at `work_budget` units, which bounds its Cortex-M7
    /// instructions (docs/geo-tour.md, "Work budget").
    pub struct Settings;
    /// The GEO tour's settings, by name (stable codes on the wire and in the C interface).
    pub enum SettingId for GeoTour;
    {
        /// Most whole revolutions of a Lambert transfer (wells 1..=this+1), <= 8.
        lambert_max_revolutions, LambertMaxRevolutions = 0: u16 = 8,
        unit "", range Range::closed(0.0, MAX_LAMBERT_REVOLUTIONS as f64), limit AtMost;
        /// Householder steps per Lambert solve.
        lambert_max_iter, LambertMaxIter = 1: u16 = 40,
        unit "", range Range::closed(1.0, 200.0), limit AtMost;
        /// Lambert tolerance on Izzo's x.
        lambert_tol, LambertTol = 2: f64 = 1e-13,
        unit "", range Range::closed(1e-15, 1e-3), limit AtMost;
        /// Golden-section steps per Lambert well.
        well_iterations, WellIterations = 3: u16 = 20,
        unit "", range Range::closed(1.0, 200.0), limit AtMost;
        /// Bisection/secant steps of every 1-D root (drift depth, radial eccentricity).
        root_max_iter, RootMaxIter = 4: u16 = 200,
        unit "", range Range::closed(10.0, 1000.0), limit AtMost;
        /// Steps of the time-price search.
        price_max_iter, PriceMaxIter = 5: u16 = 100,
        unit "", range Range::closed(1.0, 1000.0), limit AtMost;
        /// The price search stops when the tour's time is within this of the mission time, s.
        time_tol_s, TimeTolS = 6: f64 = 1e-3,
        unit "s", range Range::closed(1e-9, 3600.0), limit AtMost;
        /// Legs switching at the critical price tried both ways, <= 6.
        gap_max_legs, GapMaxLegs = 7: u8 = 4,
        unit "", range Range::closed(0.0, MAX_GAP_LEGS as f64), limit AtMost;
        /// Rounds of the exchange search after the price (each tries every leg's options whose
        /// first-order gain at the current price is positive).
        exchange_rounds, ExchangeRounds = 8: u16 = 8,
        unit "", range Range::closed(0.0, 100.0), limit AtMost;
        /// A Lambert well is refined at the current price in the exchange search when its
        /// stored bottom's first-order effect is below this, m/s.
        exchange_margin_mps, ExchangeMarginMps = 9: f64 = 0.05,
        unit "m/s", range Range::closed(0.0, 100.0), limit AtMost;
        /// No intermediate orbit may come closer to Earth's centre than this, km.
        min_radius_km, MinRadiusKm = 10: f64 = 6578.137,
        unit "km", range Range::closed(EARTH_RADIUS_KM, 42_000.0), limit AtLeast;
        /// Paper's rule: drift above this phase offset, rad (1.2 deg). A method choice: no
        /// limit.
        rule_drift_above_rad, RuleDriftAboveRad = 11: f64 = 1.2 * DEG_RAD,
        unit "rad", range Range::closed(0.0, core::f64::consts::PI), limit Free;
        /// Paper's rule: one-revolution Hohmann above this, rad (0.25 deg), at most
        /// `rule_drift_above_rad`.
        rule_hohmann_above_rad, RuleHohmannAboveRad = 12: f64 = 0.25 * DEG_RAD,
        unit "rad", range Range::closed(0.0, core::f64::consts::PI), limit Free;
        /// Paper's rule: radial above this, rad (0.15 deg), at most `rule_hohmann_above_rad`;
        /// Lambert at or below.
        rule_radial_above_rad, RuleRadialAboveRad = 13: f64 = 0.15 * DEG_RAD,
        unit "rad", range Range::closed(0.0, core::f64::consts::PI), limit Free;
        /// Transfer time of a direct (0-revolution) Lambert leg, and of the paper's rule, s
        /// (9 h). A method choice: no limit.
        lambert_direct_time_s, LambertDirectTimeS = 14: f64 = 9.0 * 3600.0,
        unit "s", range Range::closed(60.0, 864_000.0), limit Free;
        /// Work units a solve may use (`crate::work`); when they run out the best plan so far is
        /// returned, checked, with `SolveStatus::BudgetExhausted`. Part of it is kept for the
        /// checks of the returned plan. The default bounds every request within the default
        /// limits to 400 M Cortex-M7 instructions (docs/geo-tour.md, "Work budget").
        work_budget, WorkBudget = 15: u64 = DEFAULT_WORK_BUDGET,
        unit "units", range Range::any(), limit AtMost;
    }
}

impl Settings {
    /// Check every field against its range, then the paper's rule thresholds against each
    /// other (radial <= Hohmann <= drift).
    ///
    /// # Errors
    /// [`SettingError`] naming the first setting out of range, its value and its range.
    pub fn validate(&self) -> Result<(), SettingError<SettingId>> {
        self.check_ranges()?;
        check_range(
            SettingId::RuleHohmannAboveRad,
            self.rule_hohmann_above_rad,
            Range::closed(0.0, self.rule_drift_above_rad),
        )?;
        check_range(
            SettingId::RuleRadialAboveRad,
            self.rule_radial_above_rad,
            Range::closed(0.0, self.rule_hohmann_above_rad),
        )
    }
}

/// Which point option of a leg (`table::Point`): the manoeuvres a leg's table holds, whose
/// costs `work_units` bounds.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum PointKind {
    /// Client in the same slot.
    Stay,
    /// One-revolution Hohmann-type phasing.
    Hohmann,
    /// Radial-impulse phasing.
    Radial,
    /// Direct (0-revolution) Lambert in `lambert_direct_time_s`.
    Direct,
    /// Bottom of Lambert well m (K = m - 1 revolutions).
    Well(u16),
}
