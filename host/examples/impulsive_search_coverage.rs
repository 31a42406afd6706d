//! Basin coverage of the impulse-point search on eccentric, strongly inclined orbits (issue 10):
//! the search's least-fuel total against a brute-force reference, a dense grid over the
//! cumulative phases of 3 impulses (every `phi_1 < phi_2 < phi_3` on a 20-degree grid within
//! the revolution limit) whose 12 best cells are polished by a coordinate search. The reference
//! is an upper bound on the best basin's value, so a negative gap means the search did better
//! than the grid.
//!
//! A measurement, not a regression test (a few seconds in release):
//! `cargo run --release -p reconfig-host --example impulsive_search_coverage`

use reconfig_core::astro::TWO_PI;
use reconfig_core::impulsive::{
    solve, ImpulsePlan, ImpulsePoint, MeanElements, Problem, RelativeElements, Settings, Solution,
    SolveStatus, Workspace,
};

const IMPULSES: usize = 3;
const MAX_REVS: i32 = 4;
const GRID_PER_REV: usize = 18;

fn deg(x: f64) -> f64 {
    x.to_radians()
}

fn wrap(x: f64) -> f64 {
    x.rem_euclid(TWO_PI)
}

struct Case {
    name: &'static str,
    chief: MeanElements,
}

fn cases() -> Vec<Case> {
    let chief = |a: f64, e: f64, i: f64, raan: f64, argp: f64| MeanElements {
        sma_km: a,
        ecc: e,
        inc_rad: deg(i),
        raan_rad: deg(raan),
        argp_rad: deg(argp),
        mean_anomaly_rad: 0.0,
    };
    vec![
        Case {
            name: "a 9000 km, e 0.25, i 80 deg",
            chief: chief(9000.0, 0.25, 80.0, 40.0, 30.0),
        },
        Case {
            name: "a 12000 km, e 0.4, i 100 deg",
            chief: chief(12000.0, 0.4, 100.0, 200.0, 120.0),
        },
        Case {
            name: "a 26560 km, e 0.7, i 63.4 deg (Molniya)",
            chief: chief(26560.0, 0.7, 63.4, 300.0, 270.0),
        },
    ]
}

/// Wang 2018's GCO -> PCO relative elements (km, -, deg).
fn problem(chief: MeanElements, plan: ImpulsePlan) -> Problem {
    let rel = |v: [f64; 6]| RelativeElements {
        dsma_km: v[0],
        decc: v[1],
        dinc_rad: deg(v[2]),
        draan_rad: deg(v[3]),
        dargp_rad: deg(v[4]),
        dmean_anomaly_rad: deg(v[5]),
    };
    Problem {
        chief,
        initial: rel([
            4.0940e-4, -1.3888e-4, -1.0831e-3, 1.5409e-2, -1.6134e-2, 9.2428e-3,
        ]),
        target: rel([
            -1.6389e-4, 5.5597e-4, 4.3361e-3, 7.1228e-2, -6.3572e-2, 3.1718e-2,
        ]),
        plan,
    }
}

/// Impulse points of cumulative phases (as the search maps them), or `None` when infeasible.
fn points(u0: f64, phi: &[f64]) -> Option<heapless::Vec<ImpulsePoint, 6>> {
    let mut out = heapless::Vec::new();
    let (mut prev_phi, mut prev_u, mut sum) = (0.0, wrap(u0), 0);
    for p in phi {
        let gap = p - prev_phi;
        if gap < 0.0 {
            return None;
        }
        let u = wrap(u0 + p);
        let revs = (((gap - wrap(u - prev_u)) / TWO_PI).round() as i32).max(0);
        sum += revs;
        out.push(ImpulsePoint {
            arg_latitude_rad: u,
            revolutions: revs,
        })
        .ok()?;
        prev_phi = *p;
        prev_u = u;
    }
    (sum <= MAX_REVS).then_some(out)
}

/// Linear least-fuel total at the points of `phi` (infinite when infeasible or unsolved).
fn cost(chief: MeanElements, u0: f64, phi: &[f64], ws: &mut Workspace, out: &mut Solution) -> f64 {
    let Some(pts) = points(u0, phi) else {
        return f64::INFINITY;
    };
    let settings = Settings {
        nonlinear_correction: false,
        ..Settings::default()
    };
    match solve(&problem(chief, ImpulsePlan::Fixed(pts)), &settings, ws, out) {
        Ok(()) if out.info.status == SolveStatus::Solved => {
            out.linear_total_dv_mps.unwrap_or(f64::INFINITY)
        }
        _ => f64::INFINITY,
    }
}

fn reference(case: &Case, u0: f64) -> f64 {
    let mut ws = Box::new(Workspace::new());
    let mut out = Box::new(Solution::new());
    let h = TWO_PI / GRID_PER_REV as f64;
    let cells = GRID_PER_REV * (MAX_REVS as usize + 1);
    let mut scored: Vec<(f64, [f64; IMPULSES])> = Vec::new();
    for a in 0..cells {
        for b in a + 1..cells {
            for c in b + 1..cells {
                let phi = [a as f64 * h, b as f64 * h, c as f64 * h];
                let v = cost(case.chief, u0, &phi, &mut ws, &mut out);
                if v.is_finite() {
                    scored.push((v, phi));
                }
            }
        }
    }
    scored.sort_by(|x, y| x.0.total_cmp(&y.0));
    let mut best = f64::INFINITY;
    for (v0, phi0) in scored.iter().take(12) {
        let (mut v, mut phi) = (*v0, *phi0);
        let mut step = h / 2.0;
        while step > 1e-4 {
            let mut improved = false;
            for k in 0..IMPULSES {
                for d in [step, -step] {
                    let mut cand = phi;
                    cand[k] += d;
                    let c = cost(case.chief, u0, &cand, &mut ws, &mut out);
                    if c < v {
                        (v, phi, improved) = (c, cand, true);
                        break;
                    }
                }
            }
            if !improved {
                step /= 2.0;
            }
        }
        best = best.min(v);
    }
    best
}

fn searched(case: &Case, budget_factor: u32) -> (f64, u32) {
    let d = Settings::default();
    let settings = Settings {
        search_samples: d.search_samples * budget_factor,
        search_max_evaluations: d.search_max_evaluations * budget_factor,
        ..d
    };
    let p = problem(
        case.chief,
        ImpulsePlan::Search {
            impulses: IMPULSES as u8,
            max_revolutions: MAX_REVS,
        },
    );
    let mut ws = Box::new(Workspace::new());
    let mut out = Box::new(Solution::new());
    solve(&p, &settings, &mut ws, &mut out).expect("an accepted request");
    (
        out.linear_total_dv_mps.unwrap_or(f64::INFINITY),
        out.info.evaluations,
    )
}

fn main() {
    for case in cases() {
        let c = &case.chief;
        let u0 = c.argp_rad + deg(-1.6134e-2) + c.mean_anomaly_rad + deg(9.2428e-3);
        let best = reference(&case, u0);
        for factor in [1, 10] {
            let (total, evaluations) = searched(&case, factor);
            println!(
                "{}: grid+polish {best:.5} m/s, search x{factor} {total:.5} m/s \
                 ({evaluations} evaluations), gap {:+.3} %",
                case.name,
                100.0 * (total - best) / best
            );
        }
    }
}
