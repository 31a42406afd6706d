//! The contract every planner keeps, written once: the settings table
//! ([`settings_table!`](crate::settings_table)) with its ranges and refusals, and the shape of
//! a planner ([`Planner`]: `Settings`, `Problem`, a caller-owned `Workspace`, a `Solution`
//! whose `info` holds a [`Status`]).

mod planner;
mod settings;
mod status;

pub use planner::{Planner, Status};
pub use settings::{check_limit, check_range, Range, SettingError, SettingValue};
