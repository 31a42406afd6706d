//! `reconfig plot` for LEO tour fixtures (issue 13): Δv per arc and each arc's relative
//! geometry, the chaser flown through the plan in the core's planning model.

use reconfig_host::fixture::leo_tour::load;
use reconfig_host::plot_leo::tour_svg;
use reconfig_tests::fixtures_dir;

#[test]
fn the_tour_plot_draws_every_arc_from_the_start_offset_to_the_rendezvous() {
    let f = load(&fixtures_dir().join("leo-tour-example1-printed.toml")).unwrap();
    let out = std::env::temp_dir().join(format!("reconfig-leo-plot-{}.svg", std::process::id()));
    let drawn = tour_svg(&f, &out).unwrap();
    let svg = std::fs::read_to_string(&out).unwrap();
    std::fs::remove_file(&out).ok();
    assert!(svg.contains("leo-tour-example1-printed"));
    assert!(
        svg.contains("total dv 1209.528 m/s (published 1293.651)"),
        "caption"
    );
    assert_eq!(drawn.arcs.len(), 4);
    for (arc, pts) in drawn.arcs.iter().zip(&drawn.geometry) {
        assert!(svg.contains(&format!("chaser seen from client {}", arc.to + 1)));
        // Starts where the previous client is, seen from the next: the radii's difference and
        // the height above the next client's plane, computed here from the states.
        let (a, b) = (&arc.problem.from, &arc.problem.to);
        let r = |s: &[f64; 6]| (s[0] * s[0] + s[1] * s[1] + s[2] * s[2]).sqrt();
        let h = [
            b[1] * b[5] - b[2] * b[4],
            b[2] * b[3] - b[0] * b[5],
            b[0] * b[4] - b[1] * b[3],
        ];
        let hn = (h[0] * h[0] + h[1] * h[1] + h[2] * h[2]).sqrt();
        let height = (a[0] * h[0] + a[1] * h[1] + a[2] * h[2]) / hn;
        let first = pts.first().unwrap();
        assert!((first.radial_km - (r(a) - r(b))).abs() < 1e-9);
        assert!((first.cross_km - height).abs() < 1e-9);
        // Ends at the rendezvous (the planning model's arrival is within 1e-6 km; the plot's
        // own flight of the same burns is another sequence of RK4 steps).
        let last = pts.last().unwrap();
        let miss = (last.radial_km.powi(2) + last.along_km.powi(2) + last.cross_km.powi(2)).sqrt();
        assert!(
            miss < 1e-3,
            "arc {} -> {}: {miss} km",
            arc.from + 1,
            arc.to + 1
        );
        // One marked point per burn, and time runs forward over the arc.
        let burns = pts.iter().filter(|p| p.before_burn).count();
        assert_eq!(burns, usize::from(arc.solution.impulses));
        assert!(pts.windows(2).all(|w| w[1].t_h >= w[0].t_h));
        assert!((last.t_h * 3600.0 - arc.problem.duration_s).abs() < 1e-6);
    }
}
