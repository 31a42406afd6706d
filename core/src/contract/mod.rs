//! The contract every planner keeps, written once: the settings table
//! ([`settings_table!`](crate::settings_table)) with its ranges and refusals, and the shape of
//! a planner ([`Planner`]: `Settings`, `Problem`, a caller-owned `Workspace`, a `Solution`
//! whose `info` holds a [`Status`]).

mod kind;
mod planner;
mod settings;
mod status;

pub use kind::PlannerKind;
pub use planner::{Planner, Status};
pub use settings::{
    check_limit, check_range, LimitViolation, Range, Rule, SettingError, SettingId, SettingName,
    SettingValue,
};
