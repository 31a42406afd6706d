//! Scratch: search settings sweep (ignored).
use reconfig_core::impulsive::{solve, Settings, Solution, Workspace};

#[test]
#[ignore]
fn sweep() {
    let base = Settings::default();
    let configs: Vec<(u32, u8, u32, f64)> = vec![
        (500, 8, 2000, 1e-4),
        (500, 8, 1600, 1e-4),
        (400, 8, 1600, 1e-4),
        (500, 8, 2000, 1e-3),
        (300, 6, 1500, 1e-4),
    ];
    for n in [2, 3, 4] {
        let p = reconfig_tests::impulsive_fixture(&format!("wang2018-gco-to-pco-search-{n}imp"));
        for (samples, starts, maxe, minstep) in &configs {
            let s = Settings {
                search_samples: *samples,
                search_starts: *starts,
                search_max_evaluations: *maxe,
                search_min_step_rad: *minstep,
                ..base
            };
            let mut ws = Box::new(Workspace::new());
            let mut out = Box::new(Solution::new());
            let t = std::time::Instant::now();
            solve(&p, &s, &mut ws, &mut out).unwrap();
            let dt = t.elapsed().as_secs_f64();
            let revs: Vec<i32> = out.impulses.iter().map(|i| i.revolutions).collect();
            println!(
                "n={n} {samples}/{starts}/{maxe}/{minstep:e}: total {:.5} linear {:.5} evals {} {:.3}s {:?} {:?}",
                out.total_dv_mps, out.linear_total_dv_mps, out.info.evaluations, dt, out.info.status, revs
            );
        }
    }
}
