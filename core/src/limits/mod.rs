//! Service-side limits: the most work and the least safety a request may ask for.
//!
//! Every loop of a solve is bounded by a setting of the request (or by a problem size), so a
//! request alone decides how long a worker is held. The flight service, `reconfig solve` and
//! the firmware check each request against one [`Limits`] value before solving: a request may
//! tighten any setting, never loosen it past its limit. A request outside the limits is refused
//! with a [`LimitViolation`] that names the setting, its value and the limit; it is never solved
//! with silently clamped values.
//!
//! The built-in limits ([`Limits::default`]) are each planner's default settings and the
//! compiled capacities: the default request of either planner passes, and nothing may ask for
//! more iterations, looser tolerances or a safety check switched off.
//!
//! Planner settings gain fields over time: `pseudospectral::Limits::check_settings` and
//! `impulsive::Limits::check_settings` destructure `Settings` without `..`, so a new field
//! fails to compile until it has its one line (and its [`Setting`] name).

/// Declare a planner's `Limits`: the struct (each field with the value of the built-in
/// limits), its `BUILT_IN` constant and `Default` (the built-in limits), so every planner's
/// limits are built the one way.
macro_rules! planner_limits {
    (
        $(#[$meta:meta])*
        pub struct Limits {
            $( $(#[$fmeta:meta])* $field:ident : $ty:ty = $built_in:expr ),* $(,)?
        }
    ) => {
        // The derive first: a caller's `#[serde(...)]` needs its helper in scope.
        #[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
        $(#[$meta])*
        pub struct Limits {
            $( $(#[$fmeta])* pub $field: $ty ),*
        }

        impl Limits {
            /// The built-in limits, as a constant: a flight image's limits can sit in flash,
            /// not in RAM.
            pub const BUILT_IN: Self = Self {
                $( $field: $built_in ),*
            };
        }

        impl Default for Limits {
            fn default() -> Self {
                Self::BUILT_IN
            }
        }
    };
}

pub mod geo_tour;
pub mod hybrid;
pub mod impulsive;
mod impulsive_forms;
pub mod leo_tour;
pub mod pseudospectral;

use crate::contract::{PlannerKind, Rule};
use crate::wire::Request;
use serde::{Deserialize, Serialize};

/// A setting, or a problem quantity, that a limit or a range applies to: every refusal names
/// one. A planner's settings are named by its settings table's id (one name per field, the
/// fixture key and the limits-file key); the problem quantities the limits bound by
/// [`ProblemLimit`].
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub enum Setting {
    /// A planner-A setting.
    Pseudospectral(crate::pseudospectral::SettingId),
    /// A planner-B setting.
    Impulsive(crate::impulsive::SettingId),
    /// A GEO-tour setting.
    GeoTour(crate::geo_tour::SettingId),
    /// A LEO-arc setting.
    LeoArc(crate::leo_tour::SettingId),
    /// A LEO-sequencing setting.
    LeoSequence(crate::leo_tour::sequence::SettingId),
    /// A hybrid-transfer setting.
    Hybrid(crate::hybrid::SettingId),
    /// A problem quantity the limits bound.
    Problem(ProblemLimit),
}

impl Setting {
    /// The setting's name: its field, fixture key and limits-file key.
    pub const fn name(self) -> &'static str {
        match self {
            Self::Pseudospectral(id) => id.name(),
            Self::Impulsive(id) => id.name(),
            Self::GeoTour(id) => id.name(),
            Self::LeoArc(id) => id.name(),
            Self::LeoSequence(id) => id.name(),
            Self::Hybrid(id) => id.name(),
            Self::Problem(p) => p.name(),
        }
    }

    /// The planner the setting belongs to.
    pub const fn planner(self) -> PlannerKind {
        match self {
            Self::Pseudospectral(_) => PlannerKind::Pseudospectral,
            Self::Impulsive(_) => PlannerKind::Impulsive,
            Self::GeoTour(_) => PlannerKind::GeoTour,
            Self::LeoArc(_) => PlannerKind::LeoArc,
            Self::LeoSequence(_) => PlannerKind::LeoSequence,
            Self::Hybrid(_) => PlannerKind::Hybrid,
            Self::Problem(p) => p.planner(),
        }
    }

    /// The setting's code within its planner (the settings id's code; a problem quantity's
    /// code plus [`ProblemLimit::CODE_BASE`]): with the planner, it names the setting in the C
    /// interface's refusals (`error.index`).
    pub const fn code(self) -> u8 {
        match self {
            Self::Pseudospectral(id) => id as u8,
            Self::Impulsive(id) => id as u8,
            Self::GeoTour(id) => id as u8,
            Self::LeoArc(id) => id as u8,
            Self::LeoSequence(id) => id as u8,
            Self::Hybrid(id) => id as u8,
            Self::Problem(p) => ProblemLimit::CODE_BASE.saturating_add(p as u8),
        }
    }
}

/// A problem quantity the limits bound (the sizes that bound a solve's loops, and the orbits
/// of planner B's input forms).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[repr(u8)]
pub enum ProblemLimit {
    /// Planner A: spacecraft count M.
    Spacecraft = 0,
    /// Planner A: polynomial degree N (the fixture key `nodes`).
    Degree = 1,
    /// Planner B: impulses (fixed points, or a search's count).
    Impulses = 2,
    /// Planner B: the problem asks for an impulse-point search.
    Search = 3,
    /// Planner B, input forms: eccentricity of the chief as given (the osculating conic of an
    /// ECI state, or the equinoctial mean elements' `sqrt(ex^2 + ey^2)`).
    ChiefEccentricity = 4,
    /// Planner B, input forms: perigee altitude of the chief as given, km.
    ChiefPerigeeAltitudeKm = 5,
    /// Planner B, input forms: eccentricity of the deputy's initial orbit as given.
    DeputyInitialEccentricity = 6,
    /// Planner B, input forms: perigee altitude of the deputy's initial orbit as given, km.
    DeputyInitialPerigeeAltitudeKm = 7,
    /// Planner B, input forms: eccentricity of the deputy's target orbit as given.
    DeputyTargetEccentricity = 8,
    /// Planner B, input forms: perigee altitude of the deputy's target orbit as given, km.
    DeputyTargetPerigeeAltitudeKm = 9,
    /// Planner B, input forms: `|sin i|` of the chief a relative state in ROE is given on.
    RoeChiefSinInclination = 10,
    /// GEO tour: client count.
    Targets = 11,
    /// LEO arc (and every arc of a sequencing): impulse count.
    ArcImpulses = 12,
    /// LEO sequencing: client count.
    Clients = 13,
}

impl ProblemLimit {
    /// The C code of a problem quantity is this plus its own (settings ids stay below).
    pub const CODE_BASE: u8 = 128;

    /// The quantity's name (its fixture key where it has one).
    pub const fn name(self) -> &'static str {
        match self {
            Self::Spacecraft => "spacecraft",
            Self::Degree => "nodes",
            Self::Impulses | Self::ArcImpulses => "impulses",
            Self::Search => "search",
            Self::ChiefEccentricity => "chief.eccentricity",
            Self::ChiefPerigeeAltitudeKm => "chief.perigee_altitude_km",
            Self::DeputyInitialEccentricity => "deputy.initial.eccentricity",
            Self::DeputyInitialPerigeeAltitudeKm => "deputy.initial.perigee_altitude_km",
            Self::DeputyTargetEccentricity => "deputy.target.eccentricity",
            Self::DeputyTargetPerigeeAltitudeKm => "deputy.target.perigee_altitude_km",
            Self::RoeChiefSinInclination => "relative.roe chief |sin i|",
            Self::Targets => "targets",
            Self::Clients => "clients",
        }
    }

    /// The planner the quantity belongs to.
    pub const fn planner(self) -> PlannerKind {
        match self {
            Self::Spacecraft | Self::Degree => PlannerKind::Pseudospectral,
            Self::Targets => PlannerKind::GeoTour,
            Self::ArcImpulses => PlannerKind::LeoArc,
            Self::Clients => PlannerKind::LeoSequence,
            _ => PlannerKind::Impulsive,
        }
    }
}

/// A request outside the limits, naming any planner's setting or problem quantity.
pub type LimitViolation = crate::contract::LimitViolation<Setting>;

impl crate::contract::SettingName for Setting {
    fn setting_name(self) -> &'static str {
        self.name()
    }
}

/// A planner's settings id names its setting on the request path.
macro_rules! setting_of_planner {
    ($($Variant:ident($Id:ty)),+ $(,)?) => {$(
        impl From<$Id> for Setting {
            fn from(id: $Id) -> Self {
                Self::$Variant(id)
            }
        }
    )+};
}

setting_of_planner!(
    Pseudospectral(crate::pseudospectral::SettingId),
    Impulsive(crate::impulsive::SettingId),
    GeoTour(crate::geo_tour::SettingId),
    LeoArc(crate::leo_tour::SettingId),
    LeoSequence(crate::leo_tour::sequence::SettingId),
    Hybrid(crate::hybrid::SettingId),
);

planner_limits! {
    /// The limits of every planner (built in: each planner's default settings and compiled
    /// capacities).
    #[serde(default, deny_unknown_fields)]
    pub struct Limits {
        /// Planner A.
        pseudospectral: pseudospectral::Limits = pseudospectral::Limits::BUILT_IN,
        /// Planner B.
        impulsive: impulsive::Limits = impulsive::Limits::BUILT_IN,
        /// The GEO servicing tour.
        geo_tour: geo_tour::Limits = geo_tour::Limits::BUILT_IN,
        /// The LEO tour's arcs and sequencing.
        leo_tour: leo_tour::Limits = leo_tour::Limits::BUILT_IN,
        /// The hybrid transfer.
        hybrid: hybrid::Limits = hybrid::Limits::BUILT_IN,
    }
}

impl Limits {
    /// Check a request against the limits of its planner.
    ///
    /// # Errors
    /// The first [`LimitViolation`], in the order the settings are declared.
    pub fn check(&self, request: &Request) -> Result<(), LimitViolation> {
        match request {
            Request::Pseudospectral { problem, settings } => {
                self.pseudospectral.check(problem, settings)
            }
            Request::Impulsive { problem, settings } => self.impulsive.check(problem, settings),
            Request::GeoTour { problem, settings } => self.geo_tour.check(problem, settings),
            Request::LeoArc { problem, settings } => self.leo_tour.check(problem, settings),
            Request::LeoSequence {
                problem,
                settings,
                arc_settings,
            } => self
                .leo_tour
                .check_sequence(problem, settings, arc_settings),
            Request::ImpulsiveForm { problem, settings } => {
                self.impulsive.check_form(problem, settings)
            }
            Request::Hybrid { problem, settings } => self.hybrid.check(problem, settings),
        }
    }
}

/// `value <= limit`. A NaN or an infinity passes here (`contract::check_limit`): the
/// planner's own validation names it.
fn at_most(setting: Setting, value: f64, limit: f64) -> Result<(), LimitViolation> {
    crate::contract::check_limit(setting, Rule::AtMost, value, limit)
}

/// `value >= limit`. A NaN or an infinity passes here (`contract::check_limit`): the
/// planner's own validation names it.
fn at_least(setting: Setting, value: f64, limit: f64) -> Result<(), LimitViolation> {
    crate::contract::check_limit(setting, Rule::AtLeast, value, limit)
}

/// `value < limit`. A NaN or an infinity passes here (`contract::check_limit`): the
/// planner's own validation names it.
fn below(setting: Setting, value: f64, limit: f64) -> Result<(), LimitViolation> {
    crate::contract::check_limit(setting, Rule::Below, value, limit)
}

/// A work-adding flag: unless `allowed`, `value` must be off.
fn allowed(setting: Setting, value: bool, allowed: bool) -> Result<(), LimitViolation> {
    if value && !allowed {
        Err(LimitViolation {
            setting,
            value: 1.0,
            limit: 0.0,
            rule: Rule::MustBeOff,
        })
    } else {
        Ok(())
    }
}
