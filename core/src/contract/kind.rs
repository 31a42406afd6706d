//! The planners by kind: the one list every front end and the wire share.

use serde::{Deserialize, Serialize};

/// Which planner a request, an answer or a setting belongs to (its code on the wire and in
/// the C interface).
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash, Serialize, Deserialize)]
#[repr(u8)]
pub enum PlannerKind {
    /// Planner A.
    Pseudospectral = 0,
    /// Planner B.
    Impulsive = 1,
    /// The GEO servicing tour.
    GeoTour = 2,
    /// One arc of the LEO tour.
    LeoArc = 3,
    /// The LEO tour's order.
    LeoSequence = 4,
    /// The hybrid chemical + electric transfer to a libration-point orbit.
    Hybrid = 5,
}

impl PlannerKind {
    /// The planner's name in reports, records and fixture files.
    pub const fn name(self) -> &'static str {
        match self {
            Self::Pseudospectral => "pseudospectral",
            Self::Impulsive => "impulsive",
            Self::GeoTour => "geo-tour",
            Self::LeoArc => "leo-arc",
            Self::LeoSequence => "leo-sequence",
            Self::Hybrid => "hybrid",
        }
    }
}
