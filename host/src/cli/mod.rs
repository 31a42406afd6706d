//! One module per subcommand of `reconfig`.

pub mod demo;
pub mod demo_leo_onboard;
pub mod fairness;
pub mod feed;
pub mod leo_tour_rounds;
pub mod leo_tour_sequence;
pub mod montecarlo;
pub mod plot;
pub mod serve;
pub mod solve;
pub mod solve_geo_tour;
pub mod solve_impulsive;
pub mod solve_leo_tour;
pub mod solve_pseudospectral;
pub mod sweep;
pub mod sweep_oracle;
pub mod truth;
