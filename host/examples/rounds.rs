//! Prints the solution after r verification rounds. `cargo run --release --example rounds -- FILE [sqp_tol_cost]`
use reconfig_core::pseudospectral::{self, Settings, Solution, Workspace};
fn main() {
    let path = std::env::args().nth(1).expect("fixture path");
    let tol: f64 = std::env::args()
        .nth(2)
        .map(|s| s.parse().expect("tol"))
        .unwrap_or(1e-8);
    let reconfig_host::fixture::Fixture::Pseudospectral(f) =
        reconfig_host::fixture::load(path.as_ref()).expect("fixture")
    else {
        panic!("planner A fixture")
    };
    let mut ws = Box::new(Workspace::new());
    let mut out = Box::new(Solution::new());
    for r in 0..=8u8 {
        let settings = Settings {
            verify_max_rounds: r,
            sqp_tol_cost: tol,
            ..Settings::default()
        };
        pseudospectral::solve(&f.problem, &settings, &mut ws, &mut out).expect("solve");
        println!(
            "{r} J = {:.9} min_sep = {:.9} pair {:?} t = {:.5} sqp = {} {:?}",
            out.cost,
            out.min_separation_lu,
            out.min_separation_pair,
            out.min_separation_time_tu,
            out.info.sqp_iterations,
            out.info.status
        );
    }
}
