//! One module per subcommand of `reconfig`, and nothing else: what they share lives in
//! `crate::drivers` (answering and reporting a fixture's requests), `crate::harness` (the
//! flight service, the feeders and their checks) and `crate::fixture`.

pub mod campaign;
pub mod demo;
pub mod fairness;
pub mod feed;
pub mod montecarlo;
pub mod pareto;
pub mod placement;
pub mod plot;
pub mod reconverge;
pub mod serve;
pub mod solve;
pub mod sweep;
pub mod truth;
