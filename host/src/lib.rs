//! reconfig-host: the std side of reconfig. Fixture parsing, reports, the CLI's commands, the
//! iceoryx2 flight service and feeder, timing and plots.

pub mod cli;
pub mod fixture;
pub mod harness;
pub mod limits;
pub mod plot;
pub mod plot_geo;
pub mod plot_leo;
pub mod scenario;
pub mod truth;
