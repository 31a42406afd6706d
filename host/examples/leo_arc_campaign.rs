//! The LEO arc planner on generated arcs: one JSON line per arc (seed, kind, impulses, status,
//! Δv, work units, evaluations, the problem's two states and the plan's burns, which
//! `tests/oracle/leo_arc_optimum.py` restarts from), then a summary line. The search's settings are chosen on the
//! tuning seeds (0..40) and its figures reported on held-out seeds (1000..1040), which add a
//! kind the tuning set never has (`eccentric`).
//!
//! `cargo run --release -p reconfig-host --example leo_arc_campaign -- FIRST LAST [WORK_BUDGET]`
//!
//! Kinds (clients on near-circular LEO orbits, arcs of 0.3-2 days):
//! * `sso-pair`: two sun-synchronous-like orbits, up to 150 km apart in height and 3 degrees in
//!   node (the published tours' kind);
//! * `inclined`: 45-75 degree orbits, up to 0.5 degree apart in inclination and 1.5 in node;
//! * `phasing`: one plane, up to 60 km apart in height, any phase;
//! * `eccentric` (held-out seeds only): as `sso-pair` with eccentricities up to 0.02.

use anyhow::{anyhow, Context, Result};
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use reconfig_core::astro::EARTH_MU_KM3_S2;
use reconfig_core::leo_tour::elements::{state_of, Classical};
use reconfig_core::leo_tour::{
    solve_arc, ArcProblem, ArcSolution, Settings, SolveStatus, Workspace,
};

/// The first held-out seed: seeds from here on may draw the `eccentric` kind.
const HELD_OUT_FROM: u64 = 1000;

fn client(rng: &mut ChaCha8Rng, a_km: f64, e: f64, i_deg: f64, raan_deg: f64) -> Result<Classical> {
    Ok(Classical {
        a_km,
        e,
        i_rad: i_deg.to_radians(),
        raan_rad: raan_deg.to_radians(),
        argp_rad: rng.random_range(0.0..360.0_f64).to_radians(),
        nu_rad: rng.random_range(0.0..360.0_f64).to_radians(),
    })
}

/// The arc of `seed`: its kind and problem.
fn arc(seed: u64) -> Result<(&'static str, ArcProblem)> {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let kinds: &[&str] = if seed >= HELD_OUT_FROM {
        &["sso-pair", "inclined", "phasing", "eccentric"]
    } else {
        &["sso-pair", "inclined", "phasing"]
    };
    let kind = kinds[rng.random_range(0..kinds.len())];
    let a0 = 6678.0 + rng.random_range(0.0..600.0);
    let (a, b) = match kind {
        "sso-pair" | "eccentric" => {
            let e_max = if kind == "eccentric" { 0.02 } else { 0.001 };
            let a1 = a0 + rng.random_range(-150.0..150.0);
            // Sun-synchronous inclination, to first order, for each radius.
            let sso = |a_km: f64| 97.0 + (a_km - 6678.0) * 0.0040;
            let raan = rng.random_range(0.0..360.0);
            let e0 = rng.random_range(0.0..e_max);
            let e1 = rng.random_range(0.0..e_max);
            let d_raan = rng.random_range(-3.0..3.0);
            (
                client(&mut rng, a0, e0, sso(a0), raan)?,
                client(&mut rng, a1, e1, sso(a1), raan + d_raan)?,
            )
        }
        "inclined" => {
            let i = rng.random_range(45.0..75.0);
            let raan = rng.random_range(0.0..360.0);
            let di = rng.random_range(-0.5..0.5);
            let d_raan = rng.random_range(-1.5..1.5);
            let a1 = a0 + rng.random_range(-100.0..100.0);
            (
                client(&mut rng, a0, 0.0005, i, raan)?,
                client(&mut rng, a1, 0.0005, i + di, raan + d_raan)?,
            )
        }
        _ => {
            let i = rng.random_range(0.0..100.0);
            let raan = rng.random_range(0.0..360.0);
            let a1 = a0 + rng.random_range(-60.0..60.0);
            (
                client(&mut rng, a0, 0.0002, i, raan)?,
                client(&mut rng, a1, 0.0002, i, raan)?,
            )
        }
    };
    let duration_s = rng.random_range(0.3..2.0) * 86_400.0;
    let impulses = rng.random_range(2..=4u8);
    let from = state_of(EARTH_MU_KM3_S2, &a).ok_or_else(|| anyhow!("seed {seed}: client A"))?;
    let to = state_of(EARTH_MU_KM3_S2, &b).ok_or_else(|| anyhow!("seed {seed}: client B"))?;
    Ok((
        kind,
        ArcProblem {
            from,
            to,
            duration_s,
            impulses,
        },
    ))
}

fn main() -> Result<()> {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let [first, last, rest @ ..] = args.as_slice() else {
        return Err(anyhow!("usage: leo_arc_campaign FIRST LAST [WORK_BUDGET]"));
    };
    let first: u64 = first.parse().context("FIRST")?;
    let last: u64 = last.parse().context("LAST")?;
    let mut settings = Settings::default();
    if let Some(b) = rest.first() {
        settings.work_budget = b.parse().context("WORK_BUDGET")?;
    }
    let mut workspace = Box::new(Workspace::new());
    let (mut n, mut usable, mut solved, mut units_max) = (0u32, 0u32, 0u32, 0u64);
    for seed in first..last {
        let (kind, problem) = arc(seed)?;
        let mut out = ArcSolution::new();
        let status = match solve_arc(&problem, &settings, &mut workspace, &mut out) {
            Ok(()) => format!("{:?}", out.info.status),
            Err(e) => format!("refused {e:?}"),
        };
        n += 1;
        usable += u32::from(out.info.status.is_usable());
        solved += u32::from(out.info.status == SolveStatus::Solved);
        units_max = units_max.max(out.info.work_units);
        println!(
            "{}",
            serde_json::json!({
                "seed": seed, "kind": kind, "impulses": problem.impulses,
                "duration_s": problem.duration_s, "status": status,
                "dv_mps": out.total_dv_mps, "work_units": out.info.work_units,
                "evaluations": out.info.evaluations,
                "from": problem.from, "to": problem.to,
                "burns": out.burns.iter().take(usize::from(out.impulses))
                    .map(|b| serde_json::json!({"epoch_s": b.epoch_s, "dv_km_s": b.dv_km_s}))
                    .collect::<Vec<_>>(),
            })
        );
    }
    println!(
        "{}",
        serde_json::json!({
            "arcs": n, "solved": solved, "usable": usable, "work_units_max": units_max,
            "work_budget": settings.work_budget,
        })
    );
    Ok(())
}
