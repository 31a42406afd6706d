//! One module per subcommand of `reconfig`.

pub mod montecarlo;
pub mod solve;
pub mod solve_impulsive;
pub mod solve_pseudospectral;
