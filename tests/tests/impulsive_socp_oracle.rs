//! The least-fuel cone program (`reconfig_core::impulsive::least_fuel_rows`) against an
//! independent conic solver, Clarabel, on seeded random instances: badly scaled rows (as F's km
//! versus rad), 1 to 6 impulses, impulses that are zero at the optimum, and rank-deficient F
//! (one impulse, repeated impulse columns) with a consistent target.
//!
//! `cargo test -p reconfig-tests --test impulsive_socp_oracle -- --nocapture` prints the worst
//! difference.

use clarabel::algebra::CscMatrix;
use clarabel::solver::{
    DefaultSettingsBuilder, DefaultSolver, IPSolver, SolverStatus, SupportedConeT,
};
use reconfig_core::impulsive::{least_fuel_rows, SocpStatus};

const INSTANCES: usize = 1200;
const COLUMNS: usize = 18;

/// Deterministic uniform in [0, 1).
struct Lcg(u64);

impl Lcg {
    fn next(&mut self) -> f64 {
        self.0 = self
            .0
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        (self.0 >> 11) as f64 / (1u64 << 53) as f64
    }
}

struct Instance {
    f: [[f64; COLUMNS]; 6],
    k: usize,
    y: [f64; 6],
}

fn instance(rng: &mut Lcg, index: usize) -> Instance {
    let k = 1 + index % 6;
    let mut f = [[0.0; COLUMNS]; 6];
    for row in f.iter_mut() {
        let scale = 10f64.powf(rng.next() * 6.0 - 3.0);
        for v in row.iter_mut().take(3 * k) {
            *v = scale * (2.0 * rng.next() - 1.0);
        }
    }
    // Every seventh instance with two or more impulses repeats impulse 0's columns (scaled) in
    // impulse 1: F loses rank.
    if k >= 2 && index % 7 == 3 {
        let gain = 0.5 + rng.next();
        for row in f.iter_mut() {
            for c in 0..3 {
                row[3 + c] = gain * row[c];
            }
        }
    }
    // A consistent target from impulses of 0.1..5 m/s, about a third of them zero.
    let mut x = [0.0; COLUMNS];
    for b in 0..k {
        if rng.next() < 0.3 {
            continue;
        }
        let mag = 0.1 + 4.9 * rng.next();
        let d = [
            2.0 * rng.next() - 1.0,
            2.0 * rng.next() - 1.0,
            2.0 * rng.next() - 1.0,
        ];
        let n = (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt().max(1e-3);
        for c in 0..3 {
            x[3 * b + c] = mag * d[c] / n;
        }
    }
    let mut y = [0.0; 6];
    for (yi, row) in y.iter_mut().zip(f.iter()) {
        *yi = row.iter().zip(x.iter()).map(|(a, b)| a * b).sum();
    }
    Instance { f, k, y }
}

/// min sum t_k  s.t.  F x = y, (t_k, x_k) in SOC(4), by Clarabel. Returns (status, objective).
fn clarabel_least_fuel(inst: &Instance) -> (SolverStatus, f64) {
    let n = 4 * inst.k;
    let m = 6 + n;
    // Columns of A: variable 4b is t_b, 4b + 1 + c is x_b[c].
    let mut colptr = vec![0usize];
    let mut rowval = Vec::new();
    let mut nzval = Vec::new();
    for b in 0..inst.k {
        for j in 0..4 {
            if j > 0 {
                for (i, row) in inst.f.iter().enumerate() {
                    let v = row[3 * b + j - 1];
                    if v != 0.0 {
                        rowval.push(i);
                        nzval.push(v);
                    }
                }
            }
            rowval.push(6 + 4 * b + j);
            nzval.push(-1.0);
            colptr.push(rowval.len());
        }
    }
    let a = CscMatrix::new(m, n, colptr, rowval, nzval);
    let p = CscMatrix::zeros((n, n));
    let mut q = vec![0.0; n];
    for b in 0..inst.k {
        q[4 * b] = 1.0;
    }
    let mut rhs = vec![0.0; m];
    rhs[..6].copy_from_slice(&inst.y);
    let mut cones = vec![SupportedConeT::ZeroConeT(6)];
    cones.extend((0..inst.k).map(|_| SupportedConeT::SecondOrderConeT(4)));
    let settings = DefaultSettingsBuilder::default()
        .verbose(false)
        .max_iter(200)
        .tol_gap_abs(1e-12)
        .tol_gap_rel(1e-12)
        .tol_feas(1e-12)
        .build()
        .unwrap();
    let mut solver = DefaultSolver::new(&p, &q, &a, &rhs, &cones, settings).unwrap();
    solver.solve();
    (solver.solution.status, solver.solution.obj_val)
}

#[test]
fn least_fuel_agrees_with_clarabel_on_random_instances() {
    let mut rng = Lcg(0x5EED_2026_1123);
    let mut worst = 0.0f64;
    let mut worst_at = 0;
    let mut rank_deficient = 0;
    let mut with_zero_impulse = 0;
    let mut iterations = 0u64;
    for index in 0..INSTANCES {
        let inst = instance(&mut rng, index);
        let ours = least_fuel_rows(&inst.f, 3 * inst.k, &inst.y, 1e-9, 1e-10, 60).unwrap();
        assert_eq!(
            ours.status,
            SocpStatus::Optimal,
            "instance {index}: {ours:?}"
        );
        assert!(ours.total.is_finite() && ours.total - ours.lower_bound <= 1e-9);
        // Our plan meets F x = y (row-relative).
        for (row, yi) in inst.f.iter().zip(inst.y.iter()) {
            let scale = row.iter().map(|v| v.abs()).fold(0.0, f64::max);
            let fx: f64 = row.iter().zip(ours.x.iter()).map(|(a, b)| a * b).sum();
            assert!(
                (fx - yi).abs() <= 1e-10 * scale * (1.0 + ours.total),
                "instance {index}"
            );
        }
        let (status, obj) = clarabel_least_fuel(&inst);
        assert!(
            matches!(status, SolverStatus::Solved | SolverStatus::AlmostSolved),
            "instance {index}: clarabel {status:?}"
        );
        let diff = (ours.total - obj).abs();
        if diff > worst {
            worst = diff;
            worst_at = index;
        }
        if ours.rank < 6 {
            rank_deficient += 1;
        }
        if ours.x[..3 * inst.k]
            .chunks(3)
            .any(|b| b.iter().all(|v| v.abs() < 1e-7))
        {
            with_zero_impulse += 1;
        }
        iterations += u64::from(ours.iterations);
        assert!(
            diff <= 1e-6,
            "instance {index} (K = {}): ours {} clarabel {obj}",
            inst.k,
            ours.total
        );
    }
    println!(
        "{INSTANCES} instances ({rank_deficient} rank-deficient, {with_zero_impulse} with a zero \
         impulse at the optimum): worst |ours - clarabel| = {worst:.3e} m/s (instance \
         {worst_at}); {:.1} interior-point iterations on average",
        iterations as f64 / INSTANCES as f64
    );
    // The worst difference rounded up to its decade: Clarabel's last bits may depend on the
    // machine's vector units, the decade does not.
    let decade = decade_above(worst);
    reconfig_host::figure_record::hold(
        "b-exact-vs-clarabel",
        &reconfig_host::figure_record::Figure {
            what: "B: exact least fuel vs Clarabel".into(),
            target: "≤ 1e-6 m/s on ≥ 1000 instances".into(),
            measured: format!("< 1e{decade} m/s, worst of {INSTANCES}"),
            met: worst <= 1e-6 && INSTANCES >= 1000,
            doc: "planner-b".into(),
            command: "cargo test -p reconfig-tests --test impulsive_socp_oracle".into(),
        },
    )
    .unwrap();
}

/// The least integer `e` with `x < 10^e` (for x > 0).
fn decade_above(x: f64) -> i32 {
    let mut e = -20;
    while 10f64.powi(e) <= x && e < 20 {
        e += 1;
    }
    e
}
