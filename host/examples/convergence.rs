//! Prints the cost after k convex subproblems (no verification) for a fixture: how fast the
//! convex-concave sequence converges. `cargo run --release --example convergence -- FILE`
use reconfig_core::pseudospectral::{self, Settings, Solution, Workspace};
fn main() {
    let path = std::env::args().nth(1).expect("usage: convergence FIXTURE");
    let reconfig_host::fixture::Fixture::Pseudospectral(f) =
        reconfig_host::fixture::load(path.as_ref()).expect("fixture")
    else {
        panic!("planner A fixture")
    };
    let mut ws = Box::new(Workspace::new());
    let mut out = Box::new(Solution::new());
    let mut previous = 0.0;
    for k in 1..=60u16 {
        let settings = Settings {
            sqp_max_iter: k,
            verify_max_rounds: 0,
            ..Settings::default()
        };
        pseudospectral::solve(&f.problem, &settings, &mut ws, &mut out).expect("solve");
        println!(
            "{k:3} J = {:.12} dJ = {:.3e} min_sep = {:.9?} {:?}",
            out.cost,
            out.cost - previous,
            out.min_separation_lu,
            out.info.status
        );
        previous = out.cost;
    }
}
