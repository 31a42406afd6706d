//! The GEO tour by cost against a brute-force optimiser of the same model on small tours (1-3
//! legs): every method, every Lambert transfer time (not only the planner's wells and 9-h
//! direct arc) with every revolution count and both branches, waiting allowed, every duration.
//! Tours without drift legs, tours where the cap binds, and mixed tours; the planner must be
//! within 1e-3 m/s of the brute force (issue 31 item 1).
//!
//! The brute force shares only the manoeuvre primitives with the planner (`lambert_phasing`,
//! `hohmann`, `radial`, `drift_for_duration`), none of its search: each leg's cost as a
//! function of its time is sampled every 60 s (Lambert) and polished by golden section at
//! every local minimum, a dynamic programme over the legs on a 300-s grid gives the basin, and
//! pairwise exchanges of time between legs on zooming grids polish the durations.
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

use reconfig_core::geo_tour::{
    drift_for_duration, hohmann, lambert_phasing, radial, solve, Direction, Geo, MethodPolicy,
    Problem, Settings, Solution, SolveStatus, SweepChoice, Workspace,
};
use reconfig_tests::golden::golden;

const DEG: f64 = std::f64::consts::PI / 180.0;
const DAY_S: f64 = 86_400.0;
/// Lambert sampling step, s.
const SCAN_S: f64 = 60.0;
/// Dynamic programme's grid, s.
const GRID_S: f64 = 300.0;

/// What one leg can do, for the brute force.
struct Leg {
    phase_rad: f64,
    cap_mps: f64,
    max_revs: u16,
    min_radius_km: f64,
    /// Point options (duration, Δv): Hohmann, radial, every local minimum of the Lambert cost.
    points: Vec<(f64, f64)>,
    /// Fastest admissible drift, s (infinite when none).
    drift_min_s: f64,
}

impl Leg {
    fn lambert(&self, g: &Geo, tau_s: f64) -> f64 {
        lambert_phasing(
            g,
            Direction::East,
            self.phase_rad,
            tau_s,
            self.max_revs,
            self.cap_mps,
            40,
            1e-13,
        )
        .map_or(f64::INFINITY, |m| m.dv_mps)
    }

    fn drift(&self, g: &Geo, t_s: f64) -> f64 {
        if t_s < self.drift_min_s {
            return f64::INFINITY;
        }
        match drift_for_duration(
            g,
            Direction::East,
            self.phase_rad,
            t_s,
            self.min_radius_km,
            200,
        ) {
            Some(m) if m.max_burn_mps <= self.cap_mps => m.dv_mps,
            _ => f64::INFINITY,
        }
    }

    /// The leg's least Δv when it may take `t_s`: a point no longer (it waits), a Lambert arc
    /// of exactly `t_s`, or the drift of `t_s`.
    fn cost(&self, g: &Geo, t_s: f64) -> f64 {
        let points = self
            .points
            .iter()
            .filter(|(tau, _)| *tau <= t_s)
            .fold(f64::INFINITY, |b, (_, dv)| b.min(*dv));
        points.min(self.lambert(g, t_s)).min(self.drift(g, t_s))
    }
}

fn leg(g: &Geo, s: &Settings, phase_rad: f64, cap_mps: f64, t_max_s: f64) -> Leg {
    let mut l = Leg {
        phase_rad,
        cap_mps,
        max_revs: s.lambert_max_revolutions,
        min_radius_km: s.min_radius_km,
        points: Vec::new(),
        drift_min_s: f64::INFINITY,
    };
    for m in [
        hohmann(g, Direction::East, phase_rad, s.min_radius_km),
        radial(g, Direction::East, phase_rad, s.min_radius_km, 200),
    ]
    .into_iter()
    .flatten()
    {
        if m.max_burn_mps <= cap_mps {
            l.points.push((m.transfer_s, m.dv_mps));
        }
    }
    // Lambert sampled, every local minimum polished.
    let n = (t_max_s / SCAN_S).floor() as usize;
    let taus: Vec<f64> = (1..=n).map(|k| k as f64 * SCAN_S).collect();
    let costs: Vec<f64> = taus.iter().map(|&t| l.lambert(g, t)).collect();
    for k in 0..n {
        let left = if k == 0 { f64::INFINITY } else { costs[k - 1] };
        let right = costs.get(k + 1).copied().unwrap_or(f64::INFINITY);
        if costs[k].is_finite() && costs[k] <= left && costs[k] <= right {
            let lo = taus[k] - SCAN_S;
            let hi = (taus[k] + SCAN_S).min(t_max_s);
            let (t, dv) = golden(lo.max(1.0), hi, 60, |t| l.lambert(g, t));
            let (t, dv) = if dv <= costs[k] {
                (t, dv)
            } else {
                (taus[k], costs[k])
            };
            l.points.push((t, dv));
        }
    }
    // Fastest admissible drift: bisection on the duration.
    let (mut lo, mut hi) = (0.0, 400.0 * DAY_S);
    l.drift_min_s = f64::INFINITY;
    for _ in 0..100 {
        let mid = 0.5 * (lo + hi);
        let ok = drift_for_duration(g, Direction::East, phase_rad, mid, s.min_radius_km, 200)
            .is_some_and(|m| m.max_burn_mps <= cap_mps);
        if ok {
            hi = mid;
            l.drift_min_s = mid;
        } else {
            lo = mid;
        }
    }
    l
}

/// The least total Δv of the eastward tour with these phase offsets in `t_max_s`.
fn brute_optimum(g: &Geo, s: &Settings, phases: &[f64], t_max_s: f64, cap_mps: f64) -> f64 {
    let legs: Vec<Leg> = phases
        .iter()
        .map(|&p| leg(g, s, p, cap_mps, t_max_s))
        .collect();
    // Dynamic programme on the grid (every leg uses a whole number of grid steps).
    let n_grid = (t_max_s / GRID_S).floor() as usize;
    let table: Vec<Vec<f64>> = legs
        .iter()
        .map(|l| {
            let mut run = f64::INFINITY;
            (0..=n_grid)
                .map(|k| {
                    run = run.min(l.cost(g, k as f64 * GRID_S));
                    run
                })
                .collect()
        })
        .collect();
    let mut value = vec![0.0_f64; n_grid + 1];
    let mut args: Vec<Vec<usize>> = Vec::new();
    for c in &table {
        let mut next = vec![f64::INFINITY; n_grid + 1];
        let mut arg = vec![0; n_grid + 1];
        for k in 0..=n_grid {
            for i in 0..=k {
                let v = value[k - i] + c[i];
                if v < next[k] {
                    next[k] = v;
                    arg[k] = i;
                }
            }
        }
        value = next;
        args.push(arg);
    }
    let mut k = n_grid;
    let mut t = vec![0.0; legs.len()];
    for j in (0..legs.len()).rev() {
        let i = args[j][k];
        t[j] = i as f64 * GRID_S;
        k -= i;
    }
    // The time the grid left over goes to the last leg (costs never rise with time).
    let used: f64 = t.iter().sum();
    if let Some(last) = t.last_mut() {
        *last += t_max_s - used;
    }
    // Pairwise exchanges of time on zooming grids.
    let mut cost: Vec<f64> = legs.iter().zip(&t).map(|(l, &tj)| l.cost(g, tj)).collect();
    for _sweep in 0..20 {
        let before: f64 = cost.iter().sum();
        for i in 0..legs.len() {
            for j in 0..legs.len() {
                if i == j {
                    continue;
                }
                // Move d from leg j to leg i, d in [-t_i, t_j].
                let mut radius = GRID_S * 4.0;
                let mut centre = 0.0;
                for _zoom in 0..14 {
                    let mut best = (cost[i] + cost[j], 0.0, cost[i], cost[j]);
                    for q in -20..=20 {
                        let d = centre + radius * f64::from(q) / 20.0;
                        let (ti, tj) = (t[i] + d, t[j] - d);
                        if ti < 0.0 || tj < 0.0 {
                            continue;
                        }
                        let (ci, cj) = (legs[i].cost(g, ti), legs[j].cost(g, tj));
                        if ci + cj < best.0 - 1e-12 {
                            best = (ci + cj, d, ci, cj);
                        }
                    }
                    centre = best.1;
                    radius *= 0.25;
                    if best.1 != 0.0 {
                        t[i] += best.1;
                        t[j] -= best.1;
                        cost[i] = best.2;
                        cost[j] = best.3;
                        centre = 0.0;
                    }
                }
            }
        }
        let after: f64 = cost.iter().sum();
        if after > before - 1e-10 {
            break;
        }
    }
    println!(
        "  brute force: {}",
        t.iter()
            .zip(&cost)
            .map(|(tj, cj)| format!("{:.4} d {cj:.6} m/s", tj / DAY_S))
            .collect::<Vec<_>>()
            .join(", ")
    );
    cost.iter().sum()
}

fn plan(
    start_deg: f64,
    targets_deg: &[f64],
    days: f64,
    cap_mps: f64,
    s: &Settings,
) -> Box<Solution> {
    let mut targets = heapless::Vec::new();
    for &lon in targets_deg {
        targets.push(lon * DEG).unwrap();
    }
    let p = Problem {
        start_lon_rad: start_deg * DEG,
        targets_lon_rad: targets,
        mission_time_s: days * DAY_S,
        max_burn_mps: cap_mps,
        sweep: SweepChoice::East,
        policy: MethodPolicy::ByCost,
    };
    let mut ws = Box::new(Workspace::new());
    let mut out = Box::new(Solution::new());
    solve(&p, s, &mut ws, &mut out).expect("accepted");
    out
}

/// Each leg's phase offset, rad: the eastward tour from `start_deg` through `targets_deg`.
fn phases_rad(start_deg: f64, targets_deg: &[f64]) -> Vec<f64> {
    std::iter::once(start_deg)
        .chain(targets_deg.iter().copied())
        .collect::<Vec<_>>()
        .windows(2)
        .map(|w| (w[1] - w[0]) * DEG)
        .collect()
}

/// Planner against brute force on one tour; returns (planner, brute).
fn compare(start_deg: f64, targets_deg: &[f64], days: f64, cap_mps: f64) -> (f64, f64) {
    let s = Settings::default();
    let g = Geo::standard();
    let out = plan(start_deg, targets_deg, days, cap_mps, &s);
    assert_eq!(
        out.info.status,
        SolveStatus::Solved,
        "{start_deg} {targets_deg:?} {days} d {cap_mps} m/s"
    );
    let brute = brute_optimum(
        &g,
        &s,
        &phases_rad(start_deg, targets_deg),
        days * DAY_S,
        cap_mps,
    );
    println!(
        "{start_deg} -> {targets_deg:?}, {days} d, cap {cap_mps}: planner {:.6} brute {brute:.6} m/s ({})",
        out.total_dv_mps,
        out.legs
            .iter()
            .map(|l| format!("{:?} {:.4} d", l.method, l.duration_s / DAY_S))
            .collect::<Vec<_>>()
            .join(", ")
    );
    (out.total_dv_mps, brute)
}

fn assert_agrees(start_deg: f64, targets_deg: &[f64], days: f64, cap_mps: f64) {
    let (planner, brute) = compare(start_deg, targets_deg, days, cap_mps);
    assert!(
        planner <= brute + 1e-3,
        "{start_deg} -> {targets_deg:?} in {days} d, cap {cap_mps}: planner {planner} m/s, brute force {brute}"
    );
}

/// Issue 31's tour without a drift leg: both Lambert legs must move off their wells' bottoms
/// to fit 1.5 days (1.7400 m/s with a radial leg before; 1.2891 possible).
#[test]
fn two_lambert_legs_that_must_share_the_time() {
    let (planner, brute) = compare(75.0, &[75.05, 75.12], 1.5, 5.0);
    assert!(planner <= 1.2891 + 1e-4, "{planner}");
    assert!(planner <= brute + 1e-3, "{planner} {brute}");
}

/// The cap binds: one client 2 degrees east in 3 days, 2 m/s per burn (the two-revolution
/// well's bottom is within the cap, its window's ends are not).
#[test]
fn cap_binding_single_leg() {
    assert_agrees(48.0, &[50.0], 3.0, 2.0);
}

/// Three short legs, no drift, time binding.
#[test]
fn three_short_legs_without_drift() {
    assert_agrees(10.0, &[10.1, 10.3, 10.45], 2.5, 5.0);
}

/// A drift leg and a Lambert leg sharing the time.
#[test]
fn a_drift_leg_and_a_lambert_leg() {
    assert_agrees(48.0, &[51.0, 51.08], 4.0, 5.0);
}

/// The cap binds on a tour with time to spare.
#[test]
fn cap_binding_tour_with_slack() {
    assert_agrees(100.0, &[100.6, 101.4], 6.0, 1.0);
}

/// Tours from `examples/geo_revolutions.rs` where more Lambert revolutions once planned
/// dearer tours than fewer (tuning seed 15: a drift leg was never offered at a zero price;
/// held-out seed 1036: a leg turned to a drift left the other wells where the wells' own price
/// had put them).
#[test]
fn tours_where_more_revolutions_once_planned_worse() {
    assert_agrees(285.704321, &[285.761091, 285.771403], 3.578214, 5.0);
    assert_agrees(
        333.085385,
        &[333.229426, 333.259799, 333.364232],
        5.668568,
        2.760213,
    );
}

/// Tours whose optimum needs more than one leg's method changed, or a well moved far from its
/// bottom, which the one-leg exchange once missed (issue 31): three Lambert legs squeezed into
/// 1.2 days (4.901356 against 4.895621 m/s, +0.12 %: the middle leg kept its radial transfer
/// where the brute force flies a 0.48-day arc of its 0-revolution well, whose bottom at 0.99 d
/// ranked it 2 m/s dear); tuning seed 82 (0.337405 against 0.334912 m/s, +0.74 %: a drift and
/// a three-revolution well, where a four-revolution well and the drift on the other leg are
/// cheaper; neither change alone is, the pair stage tries both).
#[test]
fn tours_whose_optimum_needs_two_legs_changed_or_a_well_moved_far() {
    assert_agrees(20.0, &[20.04, 20.1, 20.13], 1.2, 5.0);
    assert_agrees(52.239754, &[52.360497, 52.451771], 7.660245, 5.0);
}

/// Every small tour of this file, for the README's line: (start, clients, days, cap).
const SMALL_TOURS: [(f64, &[f64], f64, f64); 9] = [
    (75.0, &[75.05, 75.12], 1.5, 5.0),
    (48.0, &[50.0], 3.0, 2.0),
    (10.0, &[10.1, 10.3, 10.45], 2.5, 5.0),
    (48.0, &[51.0, 51.08], 4.0, 5.0),
    (100.0, &[100.6, 101.4], 6.0, 1.0),
    (285.704321, &[285.761091, 285.771403], 3.578214, 5.0),
    (
        333.085385,
        &[333.229426, 333.259799, 333.364232],
        5.668568,
        2.760213,
    ),
    (20.0, &[20.04, 20.1, 20.13], 1.2, 5.0),
    (52.239754, &[52.360497, 52.451771], 7.660245, 5.0),
];

/// The README's line: how many of the small tours the planner plans within 1e-3 m/s of the
/// brute force, and by how much it stays above on the others.
#[test]
fn the_readme_figure_counts_the_small_tours() {
    let mut within = 0;
    let mut gaps = Vec::new();
    for (start, targets, days, cap) in SMALL_TOURS {
        let (planner, brute) = compare(start, targets, days, cap);
        if planner <= brute + 1e-3 {
            within += 1;
        } else {
            gaps.push(format!("+{:.2} %", 100.0 * (planner / brute - 1.0)));
        }
    }
    let n = SMALL_TOURS.len();
    let measured = if gaps.is_empty() {
        format!("{within} of {n} tours")
    } else {
        format!(
            "{within} of {n} tours; above it by {}: {}",
            gaps.len(),
            gaps.join(", ")
        )
    };
    reconfig_host::figure_record::hold(
        "geo-brute-small-tours",
        &reconfig_host::figure_record::Figure {
            what: "GEO: by cost vs a brute force over every Lambert time, small tours (issue 31)"
                .into(),
            target: "within 1e-3 m/s".into(),
            measured,
            met: within == n,
            doc: "geo-tour".into(),
            command: "cargo test -p reconfig-tests --test geo_tour_brute".into(),
        },
    )
    .unwrap();
}

/// SplitMix64: the held-out tours' generator (no state shared with any tuning set).
struct SplitMix(u64);

impl SplitMix {
    fn next(&mut self) -> f64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^= z >> 31;
        (z >> 11) as f64 / (1u64 << 53) as f64
    }

    fn range(&mut self, lo: f64, hi: f64) -> f64 {
        lo + (hi - lo) * self.next()
    }
}

/// Held-out small tours, generated after the exchange's pair stage and re-pricing bound were
/// chosen on the tours above (seeds 1-16, never looked at before): 1-3 clients 0.02-0.3 deg
/// apart, 1-6 days, a cap of 1-5 m/s. The tours the planner cannot fit (faster than its fastest
/// tour) are skipped and counted. The README's held-out line: how many agree within 1e-3 m/s.
#[test]
fn held_out_small_tours_agree_with_the_brute_force() {
    let s = Settings::default();
    let g = Geo::standard();
    let mut within = 0;
    let mut planned = 0;
    let mut worst = 0.0_f64;
    for seed in 1..=16_u64 {
        let mut r = SplitMix(seed);
        let start = r.range(0.0, 360.0);
        let legs = 1 + (r.next() * 3.0) as usize;
        let mut lon = start;
        let targets: Vec<f64> = (0..legs)
            .map(|_| {
                lon += r.range(0.02, 0.3);
                lon
            })
            .collect();
        let days = r.range(1.0, 6.0);
        let cap = r.range(1.0, 5.0);
        let out = plan(start, &targets, days, cap, &s);
        if out.info.status != SolveStatus::Solved {
            println!("seed {seed}: {:?}, skipped", out.info.status);
            continue;
        }
        planned += 1;
        let brute = brute_optimum(&g, &s, &phases_rad(start, &targets), days * DAY_S, cap);
        let gap = out.total_dv_mps - brute;
        println!(
            "seed {seed}: {start:.3} -> {targets:?}, {days:.3} d, cap {cap:.3}: planner {:.6} brute {brute:.6} ({})",
            out.total_dv_mps,
            out.legs
                .iter()
                .map(|l| format!("{:?} {:.4} d {:.6}", l.method, l.duration_s / DAY_S, l.dv_mps))
                .collect::<Vec<_>>()
                .join(", ")
        );
        assert!(
            gap >= -1e-3,
            "seed {seed}: the brute force is the optimum ({gap})"
        );
        worst = worst.max(gap / brute);
        if gap <= 1e-3 {
            within += 1;
        }
    }
    println!(
        "held out: {within} of {planned} within 1e-3 m/s, worst +{:.3} %",
        100.0 * worst
    );
    // Every held-out tour within 2 % (the one-leg exchange left 10-13 % on some generated
    // tours of examples/geo_revolutions.rs), and most to the brute force's resolution.
    assert!(worst < 0.02, "worst +{:.3} %", 100.0 * worst);
    assert!(2 * within > planned, "{within} of {planned}");
    let measured = if within == planned {
        format!("{within} of {planned} tours (seeds 1-16)")
    } else {
        format!(
            "{within} of {planned} tours (seeds 1-16); the others within +{:.2} %",
            100.0 * worst
        )
    };
    reconfig_host::figure_record::hold(
        "geo-brute-held-out",
        &reconfig_host::figure_record::Figure {
            what: "GEO: by cost vs the brute force, held-out small tours (1-3 clients \
                   0.02-0.3 deg apart, 1-6 d, cap 1-5 m/s)"
                .into(),
            target: "within 1e-3 m/s".into(),
            measured,
            met: within == planned,
            doc: "geo-tour".into(),
            command: "cargo test -p reconfig-tests --test geo_tour_brute held_out".into(),
        },
    )
    .unwrap();
}
