//! Planner A: collision-free reconfiguration of M spacecraft by a Legendre–Gauss–Lobatto
//! pseudospectral transcription of the double integrator (Huang et al. 2012).
//!
//! ## Units
//! The paper's normalised units: a length unit LU, a time unit TU and a mass unit MU; forces in
//! FU = MU LU / TU^2. Field names carry `_lu`, `_tu`, `_mu`, `_fu`.
//!
//! ## Method
//! See `README.md` ("Planner A") for the derivation and the measured figures.

mod error;
mod problem;
mod settings;
mod solution;
mod status;

pub use error::{Boundary, Capacity, PlanError, Quantity, SettingsError};
pub use problem::{Problem, Spacecraft};
pub use settings::Settings;
pub use solution::Solution;
pub use status::{SolveInfo, SolveStatus, Stage};
