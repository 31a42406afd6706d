//! reconfig-host: the std side of reconfig. Fixture files and the requests they stand for
//! (`fixture`), the planners' drivers and reports (`drivers`), the iceoryx2 flight service and
//! feeder (`harness`), the subcommands of `reconfig` (`cli`), planner A's generated problems (`families`),
//! plots, generated scenarios and the truth model.

pub mod campaign;
pub mod cli;
pub mod drivers;
pub mod families;
pub mod figure_record;
pub mod fixture;
pub mod harness;
pub mod limits;
pub mod plot;
pub mod plot_geo;
pub mod plot_hybrid;
pub mod plot_leo;
pub mod scenario;
pub mod table_record;
pub mod truth;
