//! Search for the heaviest GEO-tour requests the built-in limits accept: the most M7
//! instructions (each candidate run on the emulated Cortex-M7, the GEO image under QEMU) or
//! the most work units (host solves).
//!
//! ```sh
//! cargo run --release -p reconfig-host --example geo_worst_case -- \
//!     [--seed 1] [--rounds 12] [--batch 48] [--elite 8] [--objective m7|units] [--keep 4] [--out DIR]
//! ```
//!
//! Deterministic for a seed: candidates come from a seeded ChaCha generator and are scored by
//! deterministic counts (QEMU's instruction count under `-icount`, or the solve's work units),
//! never by a clock. Round 0 draws `batch` requests at random over everything a request may
//! choose within the limits: the client count (1-16), their layout (a row, clusters, random
//! within a window, alternating spacings), the start, the mission time (1 d - 10 y), the burn
//! cap, the sweep, the policy and every setting (the loop bounds at or below their ceilings,
//! the tolerances at or below theirs, the least radius at or above its floor, the free
//! settings anywhere in their ranges). Each later round mutates the `elite` best found so far
//! (move or add or drop a client, scale the layout, the mission time, the cap, change the
//! sweep, the policy or one setting) and adds a quarter of fresh random draws. The `keep` best
//! are written as fixtures (`--out`, default `target/geo-worst-case/best`) and printed.
//!
//! The M7 objective writes each round's candidates as fixtures into
//! `target/geo-worst-case/round`, builds the GEO image with them baked in
//! (`RECONFIG_FIXTURES_DIR`, as `cargo firmware-geo` does) and reads each solve's instruction
//! count (SysTick under `-icount shift=0`, within 40 instructions) from the QEMU run. It needs
//! `qemu-system-arm` and the `thumbv7em-none-eabihf` target (docs/firmware.md).

use anyhow::{bail, Context, Result};
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use reconfig_core::geo_tour::{self, Solution, Workspace};
use reconfig_host::fixture::geo_tour::{parse, GeoTourFixture};
use std::collections::BTreeMap;
use std::fmt::Write as _;
use std::path::{Path, PathBuf};
use std::process::Command;

/// One candidate request, in the fixture's units (degrees, days, hours).
#[derive(Clone, Debug)]
struct Candidate {
    start_deg: f64,
    targets_deg: Vec<f64>,
    days: f64,
    cap_mps: f64,
    sweep: &'static str,
    policy: &'static str,
    /// Settings overrides (fixture keys).
    settings: BTreeMap<&'static str, toml::Value>,
    /// The random draw this candidate descends from (elites are kept diverse by family).
    family: usize,
}

/// A scored candidate.
#[derive(Clone, Debug)]
struct Scored {
    name: String,
    candidate: Candidate,
    instructions: Option<u64>,
    units: Option<u64>,
    status: String,
}

fn log_uniform(rng: &mut ChaCha8Rng, lo: f64, hi: f64) -> f64 {
    (lo.ln() + rng.random::<f64>() * (hi.ln() - lo.ln())).exp()
}

fn wrap_deg(x: f64) -> f64 {
    let w = (x + 180.0).rem_euclid(360.0) - 180.0;
    // Three decimals keep the fixture readable; the search does not need more.
    (w * 1000.0).round() / 1000.0
}

/// Offsets of `n` clients from the start, degrees (positive = east).
fn layout(rng: &mut ChaCha8Rng, n: usize) -> Vec<f64> {
    let mut offsets = Vec::with_capacity(n);
    match rng.random_range(0..4) {
        0 => {
            // A row.
            let s = log_uniform(rng, 0.02, 30.0);
            let first = log_uniform(rng, 0.02, 120.0);
            for k in 0..n {
                offsets.push(first + s * k as f64);
            }
        }
        1 => {
            // Random within a window.
            let w = log_uniform(rng, 0.5, 359.0);
            for _ in 0..n {
                offsets.push(rng.random::<f64>() * w);
            }
        }
        2 => {
            // Clusters of close clients, far apart.
            let clusters = rng.random_range(2..=5usize);
            let inner = log_uniform(rng, 0.02, 1.5);
            let gap = log_uniform(rng, 1.0, 90.0);
            let mut at = log_uniform(rng, 0.02, 60.0);
            for k in 0..n {
                if k > 0 && k % n.div_ceil(clusters) == 0 {
                    at += gap * (0.5 + rng.random::<f64>());
                } else if k > 0 {
                    at += inner * (0.5 + rng.random::<f64>());
                }
                offsets.push(at);
            }
        }
        _ => {
            // Alternating short and long steps.
            let short = log_uniform(rng, 0.02, 1.0);
            let long = log_uniform(rng, 1.0, 40.0);
            let mut at = log_uniform(rng, 0.02, 30.0);
            for k in 0..n {
                offsets.push(at);
                at += if k % 2 == 0 { short } else { long };
            }
        }
    }
    offsets
}

/// A random value of one setting within the built-in limits (its ceiling or floor the
/// default), in the fixture's units.
fn random_setting(rng: &mut ChaCha8Rng, key: &'static str) -> toml::Value {
    let d = geo_tour::Settings::default();
    let int_upto = |rng: &mut ChaCha8Rng, lo: i64, hi: i64| -> toml::Value {
        // Mostly the ceiling: the loops' bounds are what the worst case is made of.
        if rng.random::<f64>() < 0.6 {
            toml::Value::Integer(hi)
        } else {
            toml::Value::Integer(rng.random_range(lo..=hi))
        }
    };
    match key {
        "lambert_max_revolutions" => int_upto(rng, 0, i64::from(d.lambert_max_revolutions)),
        "lambert_max_iter" => int_upto(rng, 1, i64::from(d.lambert_max_iter)),
        "well_iterations" => int_upto(rng, 1, i64::from(d.well_iterations)),
        "root_max_iter" => int_upto(rng, 10, i64::from(d.root_max_iter)),
        "price_max_iter" => int_upto(rng, 1, i64::from(d.price_max_iter)),
        "gap_max_legs" => int_upto(rng, 0, i64::from(d.gap_max_legs)),
        "exchange_rounds" => int_upto(rng, 0, i64::from(d.exchange_rounds)),
        "lambert_tol" => toml::Value::Float(log_uniform(rng, 1e-15, d.lambert_tol)),
        "time_tol_s" => toml::Value::Float(log_uniform(rng, 1e-9, d.time_tol_s)),
        "exchange_margin_mps" => toml::Value::Float(rng.random::<f64>() * d.exchange_margin_mps),
        "min_radius_km" => toml::Value::Float(rng.random_range(d.min_radius_km..42_000.0)),
        "lambert_direct_time_h" => toml::Value::Float(log_uniform(rng, 0.02, 239.0)),
        _ => toml::Value::Float(rng.random::<f64>() * 5.0),
    }
}

/// Settings a candidate may override (fixture keys); the paper's rule thresholds are drawn
/// together (they must be ordered).
const SETTING_KEYS: [&str; 12] = [
    "lambert_max_revolutions",
    "lambert_max_iter",
    "well_iterations",
    "root_max_iter",
    "price_max_iter",
    "gap_max_legs",
    "exchange_rounds",
    "lambert_tol",
    "time_tol_s",
    "exchange_margin_mps",
    "min_radius_km",
    "lambert_direct_time_h",
];

fn rule_thresholds(rng: &mut ChaCha8Rng, settings: &mut BTreeMap<&'static str, toml::Value>) {
    let mut t = [
        rng.random::<f64>() * 5.0,
        rng.random::<f64>() * 5.0,
        rng.random::<f64>() * 5.0,
    ];
    t.sort_by(f64::total_cmp);
    let r = |x: f64| toml::Value::Float((x * 1000.0).round() / 1000.0);
    settings.insert("rule_radial_above_deg", r(t[0]));
    settings.insert("rule_hohmann_above_deg", r(t[1]));
    settings.insert("rule_drift_above_deg", r(t[2]));
}

fn random_candidate(rng: &mut ChaCha8Rng) -> Candidate {
    let n = if rng.random::<f64>() < 0.6 {
        16
    } else {
        rng.random_range(1..=16)
    };
    let start_deg = wrap_deg(rng.random_range(-180.0..180.0));
    let sign = if rng.random::<bool>() { 1.0 } else { -1.0 };
    let targets_deg = layout(rng, n)
        .into_iter()
        .map(|o| wrap_deg(start_deg + sign * o))
        .collect();
    let days = log_uniform(rng, 1.0, 3650.0);
    let cap_mps = if rng.random::<f64>() < 0.6 {
        log_uniform(rng, 1.0, 30.0)
    } else {
        log_uniform(rng, 0.1, 10_000.0)
    };
    let sweep = ["cheaper", "cheaper", "east", "west"][rng.random_range(0..4)];
    let policy = if rng.random::<f64>() < 0.85 {
        "by-cost"
    } else {
        "paper-rule"
    };
    let mut settings = BTreeMap::new();
    for key in SETTING_KEYS {
        if rng.random::<f64>() < 0.35 {
            settings.insert(key, random_setting(rng, key));
        }
    }
    if policy == "paper-rule" && rng.random::<bool>() {
        rule_thresholds(rng, &mut settings);
    }
    Candidate {
        start_deg,
        targets_deg,
        days: (days * 1000.0).round() / 1000.0,
        cap_mps: (cap_mps * 1000.0).round() / 1000.0,
        sweep,
        policy,
        settings,
        family: 0,
    }
}

fn mutate(rng: &mut ChaCha8Rng, parent: &Candidate, other: &Candidate) -> Candidate {
    let mut c = parent.clone();
    let changes = rng.random_range(1..=3);
    for _ in 0..changes {
        match rng.random_range(0..15) {
            10 => {
                // Jitter every client a little.
                let s = log_uniform(rng, 0.005, 1.0);
                for t in &mut c.targets_deg {
                    *t = wrap_deg(*t + s * (rng.random::<f64>() - 0.5));
                }
            }
            11 => {
                // A new layout of as many clients.
                let sign = if rng.random::<bool>() { 1.0 } else { -1.0 };
                let start = c.start_deg;
                c.targets_deg = layout(rng, c.targets_deg.len().max(1))
                    .into_iter()
                    .map(|o| wrap_deg(start + sign * o))
                    .collect();
            }
            12 => {
                // Move the servicer.
                c.start_deg = wrap_deg(
                    c.start_deg
                        + log_uniform(rng, 0.01, 90.0) * if rng.random() { 1.0 } else { -1.0 },
                );
            }
            13 => {
                // The other elite's clients (relative to its start) with this one's scalars.
                let shift = c.start_deg - other.start_deg;
                c.targets_deg = other
                    .targets_deg
                    .iter()
                    .map(|&t| wrap_deg(t + shift))
                    .collect();
            }
            14 => {
                // The other elite's settings.
                c.settings = other.settings.clone();
            }
            0 | 1 => {
                // Move one client.
                if !c.targets_deg.is_empty() {
                    let i = rng.random_range(0..c.targets_deg.len());
                    let step = log_uniform(rng, 0.01, 5.0) * if rng.random() { 1.0 } else { -1.0 };
                    c.targets_deg[i] = wrap_deg(c.targets_deg[i] + step);
                }
            }
            2 => {
                // Add or drop a client.
                if c.targets_deg.len() < 16 && (c.targets_deg.len() < 2 || rng.random()) {
                    let base = c.targets_deg.last().copied().unwrap_or(c.start_deg);
                    c.targets_deg
                        .push(wrap_deg(base + log_uniform(rng, 0.02, 10.0)));
                } else if c.targets_deg.len() > 1 {
                    let i = rng.random_range(0..c.targets_deg.len());
                    c.targets_deg.remove(i);
                }
            }
            3 => {
                // Scale the layout about the start.
                let f = (rng.random::<f64>() - 0.5).exp();
                let start = c.start_deg;
                for t in &mut c.targets_deg {
                    let off = (*t - start + 540.0).rem_euclid(360.0) - 180.0;
                    *t = wrap_deg(start + off * f);
                }
            }
            4 => {
                c.days = ((c.days * (0.4 * (rng.random::<f64>() - 0.5)).exp()).clamp(1.0, 3650.0)
                    * 1000.0)
                    .round()
                    / 1000.0
            }
            5 => {
                c.cap_mps = ((c.cap_mps * (0.6 * (rng.random::<f64>() - 0.5)).exp())
                    .clamp(0.01, 10_000.0)
                    * 1000.0)
                    .round()
                    / 1000.0
            }
            6 => c.sweep = ["cheaper", "east", "west"][rng.random_range(0..3)],
            7 => {
                c.policy = if c.policy == "by-cost" {
                    "paper-rule"
                } else {
                    "by-cost"
                };
            }
            _ => {
                let key = SETTING_KEYS[rng.random_range(0..SETTING_KEYS.len())];
                if c.settings.contains_key(key) && rng.random::<f64>() < 0.3 {
                    c.settings.remove(key);
                } else {
                    c.settings.insert(key, random_setting(rng, key));
                }
            }
        }
    }
    c
}

fn fixture_text(name: &str, c: &Candidate, comment: &str) -> Result<String> {
    let mut t = String::new();
    for line in comment.lines() {
        let _ = writeln!(t, "# {line}");
    }
    let mut table = toml::Table::new();
    table.insert("name".into(), name.into());
    table.insert("planner".into(), "geo-tour".into());
    table.insert("start_lon_deg".into(), c.start_deg.into());
    table.insert(
        "targets_lon_deg".into(),
        toml::Value::Array(c.targets_deg.iter().map(|&x| x.into()).collect()),
    );
    table.insert("mission_time_days".into(), c.days.into());
    table.insert("max_burn_mps".into(), c.cap_mps.into());
    table.insert("sweep".into(), c.sweep.into());
    table.insert("policy".into(), c.policy.into());
    if !c.settings.is_empty() {
        let s: toml::Table = c
            .settings
            .iter()
            .map(|(k, v)| ((*k).to_owned(), v.clone()))
            .collect();
        table.insert("settings".into(), toml::Value::Table(s));
    }
    t.push_str(&toml::to_string(&table).context("fixture as TOML")?);
    Ok(t)
}

/// The candidate as the fixture parser reads it, if the built-in limits accept it.
fn accepted(name: &str, c: &Candidate) -> Option<GeoTourFixture> {
    let f = parse(&fixture_text(name, c, "").ok()?).ok()?;
    let limits = reconfig_core::limits::geo_tour::Limits::default();
    f.settings.validate().ok()?;
    limits.check(&f.problem, &f.settings).ok()?;
    let mut ws = Box::new(Workspace::new());
    let mut out = Box::new(Solution::new());
    geo_tour::solve(&f.problem, &f.settings, &mut ws, &mut out).ok()?;
    Some(f)
}

/// Host solve: status and the work units.
fn host_eval(f: &GeoTourFixture) -> (String, Option<u64>) {
    let mut ws = Box::new(Workspace::new());
    let mut out = Box::new(Solution::new());
    let _ = geo_tour::solve(&f.problem, &f.settings, &mut ws, &mut out);
    (format!("{:?}", out.info.status), Some(out.info.work_units))
}

fn root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .parent()
        .map_or_else(|| PathBuf::from("."), Path::to_path_buf)
}

/// Build the GEO image with the fixtures of `dir` baked in, run it in QEMU and return each
/// fixture's instruction count (SysTick under `-icount shift=0`) by name.
fn m7_instructions(dir: &Path) -> Result<BTreeMap<String, u64>> {
    let cargo = std::env::var("CARGO").unwrap_or_else(|_| "cargo".into());
    let output = Command::new(cargo)
        .current_dir(root())
        .args([
            "build",
            "--release",
            "--target",
            "thumbv7em-none-eabihf",
            "-p",
            "reconfig-firmware",
            "--bin",
            "reconfig-firmware-geo",
            "--no-default-features",
            "--features",
            "geo_tour",
            "--message-format=json-render-diagnostics",
        ])
        .env("RECONFIG_FIXTURES_DIR", dir)
        .env_remove("RUSTFLAGS")
        .env_remove("CARGO_ENCODED_RUSTFLAGS")
        .output()
        .context("cannot run cargo")?;
    if !output.status.success() {
        bail!(
            "building the GEO image failed:\n{}",
            String::from_utf8_lossy(&output.stderr)
        );
    }
    let elf = String::from_utf8_lossy(&output.stdout)
        .lines()
        .filter_map(|l| serde_json::from_str::<serde_json::Value>(l).ok())
        .filter(|m| {
            m["reason"] == "compiler-artifact" && m["target"]["name"] == "reconfig-firmware-geo"
        })
        .find_map(|m| m["executable"].as_str().map(PathBuf::from))
        .context("cargo did not report the GEO image")?;
    let run = Command::new("qemu-system-arm")
        .args([
            "-cpu",
            "cortex-m7",
            "-machine",
            "mps2-an500",
            "-nographic",
            "-semihosting-config",
            "enable=on,target=native",
            "-icount",
            "shift=0",
            "-kernel",
        ])
        .arg(&elf)
        .output()
        .context("cannot run qemu-system-arm")?;
    if !run.status.success() {
        bail!(
            "the GEO image failed in QEMU:\n{}",
            String::from_utf8_lossy(&run.stdout)
        );
    }
    let mut counts = BTreeMap::new();
    for line in String::from_utf8_lossy(&run.stdout).lines() {
        let Some(rest) = line.strip_prefix("fixture ") else {
            continue;
        };
        let fields: BTreeMap<&str, &str> = rest
            .split_whitespace()
            .filter_map(|kv| kv.split_once('='))
            .collect();
        if let (Some(name), Some(n)) = (fields.get("name"), fields.get("systick_instructions")) {
            counts.insert((*name).to_owned(), n.parse()?);
        }
    }
    Ok(counts)
}

struct Options {
    seed: u64,
    rounds: usize,
    batch: usize,
    elite: usize,
    objective: String,
    keep: usize,
    out: PathBuf,
}

fn options() -> Result<Options> {
    let mut o = Options {
        seed: 1,
        rounds: 12,
        batch: 48,
        elite: 8,
        objective: "m7".into(),
        keep: 4,
        out: root().join("target/geo-worst-case/best"),
    };
    let mut args = std::env::args().skip(1);
    while let Some(flag) = args.next() {
        let value = args
            .next()
            .with_context(|| format!("{flag} needs a value"))?;
        match flag.as_str() {
            "--seed" => o.seed = value.parse()?,
            "--rounds" => o.rounds = value.parse()?,
            "--batch" => o.batch = value.parse()?,
            "--elite" => o.elite = value.parse()?,
            "--objective" => o.objective = value,
            "--keep" => o.keep = value.parse()?,
            "--out" => o.out = PathBuf::from(value),
            other => bail!("unknown option {other}"),
        }
    }
    if o.objective != "m7" && o.objective != "units" {
        bail!("--objective is m7 or units");
    }
    Ok(o)
}

fn score(s: &Scored, objective: &str) -> u64 {
    if objective == "m7" {
        s.instructions.unwrap_or(0)
    } else {
        s.units.unwrap_or(0)
    }
}

fn describe(c: &Candidate) -> String {
    let settings: Vec<String> = c.settings.iter().map(|(k, v)| format!("{k}={v}")).collect();
    format!(
        "{} clients, {} d, cap {} m/s, {}, {}{}{}",
        c.targets_deg.len(),
        c.days,
        c.cap_mps,
        c.sweep,
        c.policy,
        if settings.is_empty() { "" } else { ", " },
        settings.join(" ")
    )
}

fn main() -> Result<()> {
    let o = options()?;
    let mut rng = ChaCha8Rng::seed_from_u64(o.seed);
    let work = root().join("target/geo-worst-case/round");
    let mut best: Vec<Scored> = Vec::new();
    let mut families = 0usize;
    for round in 0..=o.rounds {
        // Candidates of this round: random draws in round 0, then mutants of the elite and a
        // quarter of fresh draws.
        let mut batch: Vec<(String, Candidate, GeoTourFixture)> = Vec::new();
        let mut attempts = 0usize;
        while batch.len() < o.batch && attempts < 100 * o.batch {
            attempts += 1;
            let fresh = round == 0 || best.is_empty() || batch.len() % 4 == 3;
            let c = if fresh {
                let mut c = random_candidate(&mut rng);
                families += 1;
                c.family = families;
                c
            } else {
                // Parents by rank: the best most often.
                let k = best.len().min(o.elite);
                let i = rng.random_range(0..k).min(rng.random_range(0..k));
                let j = rng.random_range(0..k);
                mutate(&mut rng, &best[i].candidate, &best[j].candidate)
            };
            let name = format!("cand-r{round:02}-{:03}", batch.len());
            if let Some(f) = accepted(&name, &c) {
                batch.push((name, c, f));
            }
        }
        let counts = if o.objective == "m7" {
            if work.exists() {
                std::fs::remove_dir_all(&work)?;
            }
            std::fs::create_dir_all(&work)?;
            for (name, c, _) in &batch {
                std::fs::write(
                    work.join(format!("{name}.toml")),
                    fixture_text(name, c, "")?,
                )?;
            }
            m7_instructions(&work)?
        } else {
            BTreeMap::new()
        };
        for (name, c, f) in batch {
            let (status, units) = host_eval(&f);
            best.push(Scored {
                instructions: counts.get(&name).copied(),
                name,
                candidate: c,
                units,
                status,
            });
        }
        best.sort_by(|a, b| {
            score(b, &o.objective)
                .cmp(&score(a, &o.objective))
                .then_with(|| a.name.cmp(&b.name))
        });
        // Keep the best, at most a quarter of the elite from one family (diversity), and never
        // the same request twice.
        let per_family = (o.elite / 4).max(1);
        let mut kept: Vec<Scored> = Vec::new();
        for s in best {
            let same_family = kept
                .iter()
                .filter(|k| k.candidate.family == s.candidate.family)
                .count();
            let duplicate = kept
                .iter()
                .any(|k| score(k, &o.objective) == score(&s, &o.objective));
            if same_family < per_family && !duplicate && kept.len() < o.elite.max(o.keep) {
                kept.push(s);
            }
        }
        best = kept;
        if let Some(top) = best.first() {
            println!(
                "round {round:2}: best {} = {:?} instructions, {:?} units, {} ({})",
                top.name,
                top.instructions,
                top.units,
                top.status,
                describe(&top.candidate)
            );
        }
    }
    std::fs::create_dir_all(&o.out)?;
    println!("\nbest {} by {}:", o.keep, o.objective);
    for (rank, s) in best.iter().take(o.keep).enumerate() {
        let name = format!("geo-worst-{}-{}", o.objective, rank + 1);
        let comment = format!(
            "Found by `cargo run --release -p reconfig-host --example geo_worst_case -- --seed {} \
             --rounds {} --batch {} --elite {} --objective {}` ({}).\nM7 instructions {:?}, work \
             units {:?}, status {}.",
            o.seed,
            o.rounds,
            o.batch,
            o.elite,
            o.objective,
            s.name,
            s.instructions,
            s.units,
            s.status
        );
        std::fs::write(
            o.out.join(format!("{name}.toml")),
            fixture_text(&name, &s.candidate, &comment)?,
        )?;
        println!(
            "{:>2}. {name}: {:?} instructions, {:?} units, {}: {}",
            rank + 1,
            s.instructions,
            s.units,
            s.status,
            describe(&s.candidate)
        );
    }
    Ok(())
}
