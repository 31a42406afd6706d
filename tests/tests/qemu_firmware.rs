//! The core on the emulated Cortex-M7 (QEMU `mps2-an500`): bit-identical results and budgets.
//!
//! Both tests share one run of the firmware (`firmware/`), built for `thumbv7em-none-eabihf` and
//! run in `qemu-system-arm` with the instruction-counting plugin `tools/qemu-insn-plugin/`
//! (built here with `gcc`):
//! * `results_are_bit_identical_to_the_host` compares every fixture's postcard-encoded
//!   `Result<Solution, PlanError>` byte for byte with the host build's, solved from the same
//!   problem bytes the firmware baked in;
//! * `figures_are_within_budget` checks the instructions per solve, stack high-water, RAM and
//!   section sizes against the budgets in `fixtures/golden/m7-figures.toml`.
//!   Every measured figure must also be within 1 % of the record (drift check); accept a new
//!   record (budgets are kept, the docs' tables are regenerated from it) with
//!   `RECONFIG_UPDATE_FIGURES=1 cargo test -p reconfig-tests --test qemu_firmware`.
//! * `no_fused_multiply_add_in_the_firmware` disassembles the firmware and rejects `vfma`-family
//!   instructions, which would break bit-identity with the host.
//!
//! Without `qemu-system-arm`, the thumb target, `gcc` or `arm-none-eabi-objdump` these tests say
//! that they were skipped, why and how to install what is missing, and pass; with
//! `RECONFIG_REQUIRE_QEMU=1` (set by `.ci/run`) they fail instead.

#[path = "../../firmware/fixture_set.rs"]
mod fixture_set;

use std::collections::BTreeMap;
use std::fmt::Write as _;
use std::io::Write as _;
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::sync::{Mutex, OnceLock};
use std::time::{Duration, Instant};

use fixture_set::Planner;
use reconfig_core::{geo_tour, impulsive, pseudospectral};

const TARGET: &str = "thumbv7em-none-eabihf";
const FIGURES_FILE: &str = "fixtures/golden/m7-figures.toml";
const UPDATE_COMMAND: &str =
    "RECONFIG_UPDATE_FIGURES=1 cargo test -p reconfig-tests --test qemu_firmware";
/// A measured figure further than this (relative) from the record fails the drift check.
const DRIFT_TOLERANCE: f64 = 0.01;

/// Default budgets for a figure with no entry in the figures file (the on-board budgets of
/// docs/firmware.md; a fixture's entry may set its own).
const BUDGET_INSTRUCTIONS_PSEUDOSPECTRAL: u64 = 40_000_000;
const BUDGET_INSTRUCTIONS_IMPULSIVE: u64 = 2_000_000;
const BUDGET_RAM_BYTES: u64 = 256 * 1024;
const BUDGET_STACK_BYTES: u64 = 64 * 1024;
/// `static_ram_bytes` holds both planners' workspaces and solutions (the firmware carries
/// both); the per-planner figures say what each costs alone.
const BINARY_FIGURES: [(&str, u64); 9] = [
    ("text_bytes", 1024 * 1024),
    ("rodata_bytes", 256 * 1024),
    ("data_bytes", 16 * 1024),
    ("bss_bytes", 256 * 1024),
    ("static_ram_bytes", 256 * 1024),
    ("pseudospectral_workspace_bytes", 256 * 1024),
    ("pseudospectral_solution_bytes", 64 * 1024),
    ("impulsive_workspace_bytes", 64 * 1024),
    ("impulsive_solution_bytes", 16 * 1024),
];

fn root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .parent()
        .expect("tests/ sits in the workspace")
        .to_path_buf()
}

/// Print to the real stderr, past the test harness's capture, so a skip is always seen.
fn notice(text: &str) {
    let _ = writeln!(std::io::stderr(), "{text}");
}

/// Skip (say so and pass) or, with `RECONFIG_REQUIRE_QEMU=1`, fail.
fn skip(test: &str, why: &str) {
    if std::env::var("RECONFIG_REQUIRE_QEMU").as_deref() == Ok("1") {
        panic!("{test}: {why}\n(RECONFIG_REQUIRE_QEMU=1, so this is a failure, not a skip)");
    }
    notice(&format!(
        "SKIPPED {test}: {why}\n  (set RECONFIG_REQUIRE_QEMU=1 to make this a failure)"
    ));
}

fn tool_runs(program: &str, arg: &str) -> bool {
    Command::new(program)
        .arg(arg)
        .stdout(Stdio::null())
        .stderr(Stdio::null())
        .status()
        .is_ok_and(|s| s.success())
}

/// What the QEMU run needs, or why it cannot happen here.
fn check_prerequisites() -> Result<(), String> {
    if !tool_runs("qemu-system-arm", "--version") {
        return Err("qemu-system-arm is not installed. Install it with \
                    `sudo apt-get install qemu-system-arm` (Debian/Ubuntu) or your system's \
                    QEMU package (it needs TCG plugin support, as Debian's has)."
            .into());
    }
    let rustc = std::env::var("RUSTC").unwrap_or_else(|_| "rustc".into());
    let sysroot = Command::new(&rustc)
        .args(["--print", "sysroot"])
        .output()
        .map_err(|e| format!("cannot run {rustc}: {e}"))?;
    let sysroot = String::from_utf8_lossy(&sysroot.stdout).trim().to_owned();
    if !Path::new(&sysroot)
        .join("lib/rustlib")
        .join(TARGET)
        .is_dir()
    {
        return Err(format!(
            "the Rust target {TARGET} is not installed. Install it with \
             `rustup target add {TARGET}`."
        ));
    }
    Ok(())
}

/// One fixture's line pair in the firmware output.
#[derive(Debug, Clone)]
struct FixtureReport {
    name: String,
    planner: String,
    stack_bytes: u64,
    /// The firmware's own SysTick estimate (to within 40 instructions).
    systick_instructions: u64,
    /// Work units the solve reported (`SolveInfo::work_units`); the GEO tour has none.
    work_units: Option<u64>,
    hex: String,
}

/// Everything one firmware run produced.
#[derive(Debug)]
struct Run {
    elf: PathBuf,
    binary: BTreeMap<String, u64>,
    fixtures: Vec<FixtureReport>,
    /// Instructions per solve, by fixture index; `None` without the plugin.
    instructions: Option<Vec<u64>>,
    /// The one-planner images' runs (default image only; empty for the others).
    images: Vec<OnePlannerImage>,
}

/// A one-planner image (docs/firmware.md, "One image per planner"): its planner's key, the
/// cargo features and alias that build it.
const ONE_PLANNER_IMAGES: [(&str, &str, &str); 2] = [
    ("pseudospectral", "pseudospectral", "cargo firmware-a"),
    ("impulsive", "impulsive", "cargo firmware-b"),
];
/// RAM (static + stack high-water) of each one-planner image: 230 KiB, 90 % of 256 KiB.
const BUDGET_ONE_PLANNER_IMAGE_RAM_BYTES: u64 = 230 * 1024;

/// One one-planner image's run, without the instruction plugin (its figures of interest are its
/// RAM: the solves are the default image's, compared byte for byte).
#[derive(Debug)]
struct OnePlannerImage {
    planner: &'static str,
    command: &'static str,
    run: Run,
}

impl OnePlannerImage {
    /// Static RAM, as the image prints it from its linker symbols (`__euninit - __sdata`).
    fn static_ram_bytes(&self) -> u64 {
        self.run
            .binary
            .get("static_ram_bytes")
            .copied()
            .unwrap_or(0)
    }

    /// The largest stack high-water over the image's fixtures.
    fn stack_bytes(&self) -> u64 {
        self.run
            .fixtures
            .iter()
            .map(|f| f.stack_bytes)
            .max()
            .unwrap_or(0)
    }
}

/// Build and run one one-planner image (no plugin: about a second of QEMU), in a folder of its
/// own so that its QEMU output does not meet the default image's.
fn one_planner_image(
    (planner, features, command): (&'static str, &str, &'static str),
) -> Result<OnePlannerImage, String> {
    let built = build_image("reconfig-firmware", features)?;
    let dir = built
        .parent()
        .ok_or("odd target path")?
        .join(format!("{planner}-image"));
    std::fs::create_dir_all(&dir).map_err(|e| format!("{}: {e}", dir.display()))?;
    let elf = dir.join("reconfig-firmware");
    std::fs::copy(&built, &elf).map_err(|e| format!("{}: {e}", elf.display()))?;
    let run = run_firmware(&elf, None)?;
    Ok(OnePlannerImage {
        planner,
        command,
        run,
    })
}

static RUN: OnceLock<Result<Run, String>> = OnceLock::new();

/// The shared firmware run, or why there is none (`Err` starting with "SKIP: " for a missing
/// prerequisite).
fn firmware_run() -> &'static Result<Run, String> {
    RUN.get_or_init(|| {
        check_prerequisites().map_err(|e| format!("SKIP: {e}"))?;
        // The one-planner images first: they share the default image's output path, so the
        // default image is built last and its ELF stays in place for the other tests.
        let images = ONE_PLANNER_IMAGES
            .into_iter()
            .map(one_planner_image)
            .collect::<Result<Vec<_>, String>>()?;
        let elf = build_firmware()?;
        let plugin = match build_plugin(&elf) {
            Ok(p) => Some(p),
            Err(e) => {
                notice(&format!("note: no instruction counts: {e}"));
                None
            }
        };
        let mut run = match run_firmware(&elf, plugin.as_deref()) {
            // A QEMU built without TCG plugin support: run again without counting.
            Err(e) if e.starts_with("PLUGIN: ") => {
                notice(&format!("note: no instruction counts: {}", &e[8..]));
                run_firmware(&elf, None)
            }
            other => other,
        }?;
        run.images = images;
        Ok(run)
    })
}

fn cargo() -> String {
    std::env::var("CARGO").unwrap_or_else(|_| "cargo".into())
}

/// Build the firmware exactly as `cargo firmware` does; the path of the ELF.
fn build_firmware() -> Result<PathBuf, String> {
    let output = Command::new(cargo())
        .current_dir(root())
        .args([
            "build",
            "--release",
            "--target",
            TARGET,
            "-p",
            "reconfig-firmware",
            "--message-format=json-render-diagnostics",
        ])
        // Flags from the environment would replace .cargo/config.toml's link flags.
        .env_remove("RUSTFLAGS")
        .env_remove("CARGO_ENCODED_RUSTFLAGS")
        .env_remove("CARGO_BUILD_RUSTFLAGS")
        .stderr(Stdio::inherit())
        .output()
        .map_err(|e| format!("cannot run cargo: {e}"))?;
    if !output.status.success() {
        return Err(format!(
            "building the firmware failed ({}); see the compiler output above",
            output.status
        ));
    }
    let mut elf = None;
    for line in String::from_utf8_lossy(&output.stdout).lines() {
        let Ok(message) = serde_json::from_str::<serde_json::Value>(line) else {
            continue;
        };
        if message["reason"] == "compiler-artifact"
            && message["target"]["name"] == "reconfig-firmware"
        {
            if let Some(path) = message["executable"].as_str() {
                elf = Some(PathBuf::from(path));
            }
        }
    }
    elf.ok_or_else(|| "cargo did not report the firmware executable".into())
}

/// Build the instruction-counting plugin next to the firmware's target folder.
fn build_plugin(elf: &Path) -> Result<PathBuf, String> {
    let source_dir = root().join("tools/qemu-insn-plugin");
    let out_dir = elf
        .ancestors()
        .nth(3)
        .ok_or("odd target path")?
        .join("qemu-insn-plugin");
    std::fs::create_dir_all(&out_dir).map_err(|e| e.to_string())?;
    let plugin = out_dir.join("libinsn_count.so");
    let status = Command::new("gcc")
        .args(["-shared", "-fPIC", "-O2", "-Wall", "-Wextra", "-Werror", "-o"])
        .arg(&plugin)
        .arg(source_dir.join("insn_count.c"))
        .status()
        .map_err(|e| {
            format!("gcc is needed to build the QEMU plugin ({e}); install it with `sudo apt-get install gcc`")
        })?;
    if !status.success() {
        return Err(format!("gcc failed to build the QEMU plugin ({status})"));
    }
    Ok(plugin)
}

/// Addresses of named symbols in a 32-bit little-endian ELF file.
fn elf32_symbols(elf: &Path, names: &[&str]) -> Result<Vec<u32>, String> {
    let data = std::fs::read(elf).map_err(|e| format!("{}: {e}", elf.display()))?;
    let bad = || format!("{} is not a 32-bit little-endian ELF file", elf.display());
    let u16_at = |at: usize| -> Result<usize, String> {
        let b = data.get(at..at + 2).ok_or_else(bad)?;
        Ok(usize::from(u16::from_le_bytes([b[0], b[1]])))
    };
    let u32_at = |at: usize| -> Result<usize, String> {
        let b = data.get(at..at + 4).ok_or_else(bad)?;
        Ok(u32::from_le_bytes([b[0], b[1], b[2], b[3]]) as usize)
    };
    if data.get(..6) != Some(&[0x7f, b'E', b'L', b'F', 1, 1][..]) {
        return Err(bad());
    }
    let (shoff, shentsize, shnum) = (u32_at(0x20)?, u16_at(0x2e)?, u16_at(0x30)?);
    let section = |i: usize| shoff + i * shentsize;
    let mut found = vec![None; names.len()];
    for i in 0..shnum {
        if u32_at(section(i) + 4)? != 2 {
            continue; // not SHT_SYMTAB
        }
        let (offset, size, link) = (
            u32_at(section(i) + 16)?,
            u32_at(section(i) + 20)?,
            u32_at(section(i) + 24)?,
        );
        let strtab = u32_at(section(link) + 16)?;
        for sym in (offset..offset + size).step_by(16) {
            let name_at = strtab + u32_at(sym)?;
            let end = data[name_at..]
                .iter()
                .position(|&b| b == 0)
                .ok_or_else(bad)?;
            let name = &data[name_at..name_at + end];
            for (slot, wanted) in found.iter_mut().zip(names) {
                if name == wanted.as_bytes() {
                    *slot = Some(u32_at(sym + 4)? as u32);
                }
            }
        }
    }
    found
        .into_iter()
        .zip(names)
        .map(|(f, n)| f.ok_or_else(|| format!("symbol {n} not in {}", elf.display())))
        .collect()
}

fn run_firmware(elf: &Path, plugin: Option<&Path>) -> Result<Run, String> {
    let out_dir = elf.parent().ok_or("odd target path")?;
    let stdout_path = out_dir.join("qemu-stdout.txt");
    let stderr_path = out_dir.join("qemu-stderr.txt");
    let mut command = Command::new("qemu-system-arm");
    // The runner of .cargo/config.toml, plus the plugin.
    command.args([
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
    ]);
    command.arg(elf);
    if let Some(plugin) = plugin {
        let markers = elf32_symbols(elf, &["reconfig_measure_start", "reconfig_measure_stop"])?;
        command.arg("-plugin").arg(format!(
            "{},start={:#x},stop={:#x}",
            plugin.display(),
            markers[0],
            markers[1]
        ));
        command.args(["-d", "plugin"]);
    }
    let file = |p: &Path| std::fs::File::create(p).map_err(|e| format!("{}: {e}", p.display()));
    let mut child = command
        .stdin(Stdio::null())
        .stdout(file(&stdout_path)?)
        .stderr(file(&stderr_path)?)
        .spawn()
        .map_err(|e| format!("cannot start qemu-system-arm: {e}"))?;
    let limit = Duration::from_secs(
        std::env::var("RECONFIG_QEMU_TIMEOUT_S")
            .ok()
            .and_then(|s| s.parse().ok())
            .unwrap_or(600),
    );
    let started = Instant::now();
    let status = loop {
        if let Some(status) = child.try_wait().map_err(|e| e.to_string())? {
            break status;
        }
        if started.elapsed() > limit {
            let _ = child.kill();
            let _ = child.wait();
            return Err(format!(
                "the firmware did not finish within {} s (RECONFIG_QEMU_TIMEOUT_S)",
                limit.as_secs()
            ));
        }
        std::thread::sleep(Duration::from_millis(20));
    };
    let stdout = std::fs::read_to_string(&stdout_path).map_err(|e| e.to_string())?;
    let stderr = std::fs::read_to_string(&stderr_path).map_err(|e| e.to_string())?;
    let tail = |s: &str| -> String {
        let lines: Vec<&str> = s.lines().collect();
        let from = lines.len().saturating_sub(20);
        lines[from..]
            .iter()
            .map(|l| l.chars().take(300).collect::<String>())
            .collect::<Vec<_>>()
            .join("\n")
    };
    if !status.success() && stdout.is_empty() && plugin.is_some() {
        return Err(format!(
            "PLUGIN: QEMU did not start with the instruction-counting plugin ({status}); this \
             QEMU may lack TCG plugin support (Debian's qemu-system-arm has it):\n{}",
            tail(&stderr)
        ));
    }
    if !status.success() {
        return Err(format!(
            "the firmware failed in QEMU ({status}). Last output:\n{}\nstderr:\n{}",
            tail(&stdout),
            tail(&stderr)
        ));
    }
    let mut run = parse_output(elf, &stdout)?;
    if plugin.is_some() {
        let mut counts = BTreeMap::new();
        for line in stderr.lines() {
            if let Some(fields) = line.strip_prefix("reconfig-insns ") {
                let f = fields_of(fields);
                counts.insert(number(&f, "measurement")?, number(&f, "instructions")?);
            }
        }
        let counts: Vec<u64> = counts.into_values().collect();
        if counts.len() != run.fixtures.len() {
            return Err(format!(
                "the plugin reported {} measurements for {} fixtures; stderr:\n{}",
                counts.len(),
                run.fixtures.len(),
                tail(&stderr)
            ));
        }
        run.instructions = Some(counts);
    }
    Ok(run)
}

fn fields_of(text: &str) -> BTreeMap<&str, &str> {
    text.split_whitespace()
        .filter_map(|kv| kv.split_once('='))
        .collect()
}

fn number(fields: &BTreeMap<&str, &str>, key: &str) -> Result<u64, String> {
    fields
        .get(key)
        .and_then(|v| v.parse().ok())
        .ok_or_else(|| format!("missing or bad `{key}` in the firmware output"))
}

fn parse_output(elf: &Path, stdout: &str) -> Result<Run, String> {
    let mut binary = BTreeMap::new();
    let mut fixtures: Vec<FixtureReport> = Vec::new();
    let mut done = false;
    for line in stdout.lines() {
        let (kind, rest) = line.split_once(' ').unwrap_or((line, ""));
        let f = fields_of(rest);
        match kind {
            "binary" | "planners" => {
                for (k, v) in &f {
                    binary.insert(
                        (*k).to_owned(),
                        v.parse().map_err(|_| format!("bad {k} in {line}"))?,
                    );
                }
            }
            "fixture" => {
                if number(&f, "index")? != fixtures.len() as u64 {
                    return Err(format!("fixture lines out of order at {line}"));
                }
                fixtures.push(FixtureReport {
                    name: f.get("name").ok_or("fixture without name")?.to_string(),
                    planner: f
                        .get("planner")
                        .ok_or("fixture without planner")?
                        .to_string(),
                    stack_bytes: number(&f, "stack_bytes")?,
                    systick_instructions: number(&f, "systick_instructions")?,
                    work_units: match f.get("work_units") {
                        Some(_) => Some(number(&f, "work_units")?),
                        None => None,
                    },
                    hex: String::new(),
                });
            }
            "result" => {
                let index = number(&f, "index")? as usize;
                let report = fixtures
                    .get_mut(index)
                    .ok_or("result line before its fixture line")?;
                report.hex = f.get("hex").ok_or("result without hex")?.to_string();
            }
            "done" => done = true,
            _ => {}
        }
    }
    if !done {
        return Err("the firmware output has no `done` line".into());
    }
    Ok(Run {
        elf: elf.to_path_buf(),
        binary,
        fixtures,
        instructions: None,
        images: Vec::new(),
    })
}

/// The run, or `None` after reporting a skip.
fn run_or_skip(test: &str) -> Option<&'static Run> {
    match firmware_run() {
        Ok(run) => Some(run),
        Err(e) => match e.strip_prefix("SKIP: ") {
            Some(why) => {
                skip(test, why);
                None
            }
            None => panic!("{test}: {e}"),
        },
    }
}

fn hex(bytes: &[u8]) -> String {
    bytes.iter().fold(String::new(), |mut s, b| {
        let _ = write!(s, "{b:02x}");
        s
    })
}

/// The host's encoded result for one fixture: the same problem bytes the firmware decoded, the
/// same settings, a fresh workspace and output buffer.
fn host_result(planner: Planner, problem: &[u8]) -> Vec<u8> {
    match planner {
        Planner::Pseudospectral => {
            let problem: pseudospectral::Problem =
                postcard::from_bytes(problem).expect("the baked problem decodes");
            let mut workspace = Box::new(pseudospectral::Workspace::new());
            let mut solution = Box::new(pseudospectral::Solution::new());
            let result = pseudospectral::solve(
                &problem,
                &pseudospectral::Settings::default(),
                &mut workspace,
                &mut solution,
            );
            let encoded: Result<&pseudospectral::Solution, pseudospectral::PlanError> =
                result.map(|()| &*solution);
            postcard::to_stdvec(&encoded).expect("encode")
        }
        Planner::Impulsive | Planner::ImpulsiveFixedPoint => {
            let settings = if planner == Planner::ImpulsiveFixedPoint {
                impulsive::Settings::fixed_point_only()
            } else {
                impulsive::Settings::default()
            };
            let problem: impulsive::Problem =
                postcard::from_bytes(problem).expect("the baked problem decodes");
            let mut workspace = Box::new(impulsive::Workspace::new());
            let mut solution = Box::new(impulsive::Solution::new());
            let result = impulsive::solve(&problem, &settings, &mut workspace, &mut solution);
            let encoded: Result<&impulsive::Solution, impulsive::PlanError> =
                result.map(|()| &*solution);
            postcard::to_stdvec(&encoded).expect("encode")
        }
        Planner::ImpulsiveForm | Planner::ImpulsiveFormFixedPoint => {
            let settings = if planner == Planner::ImpulsiveFormFixedPoint {
                impulsive::Settings::fixed_point_only()
            } else {
                impulsive::Settings::default()
            };
            let problem: impulsive::FormProblem =
                postcard::from_bytes(problem).expect("the baked problem decodes");
            let mut workspace = Box::new(impulsive::Workspace::new());
            let mut solution = Box::new(impulsive::Solution::new());
            let result = impulsive::solve_form(&problem, &settings, &mut workspace, &mut solution);
            let encoded: Result<(&impulsive::Solution, impulsive::EndState), impulsive::PlanError> =
                result.map(|end| (&*solution, end));
            postcard::to_stdvec(&encoded).expect("encode")
        }
        Planner::GeoTour => geo_host_result(problem),
    }
}

#[test]
fn results_are_bit_identical_to_the_host() {
    let Some(run) = run_or_skip("results_are_bit_identical_to_the_host") else {
        return;
    };
    let fixtures = fixture_set::encode_all(&root().join("fixtures")).expect("fixtures load");
    // The GEO tour runs in its own image (geo_results_are_bit_identical_to_the_host).
    let fixtures: Vec<_> = fixtures
        .into_iter()
        .filter(|f| f.planner != Planner::GeoTour)
        .collect();
    let host_names: Vec<&str> = fixtures.iter().map(|f| f.name.as_str()).collect();
    let m7_names: Vec<&str> = run.fixtures.iter().map(|f| f.name.as_str()).collect();
    assert_eq!(
        m7_names, host_names,
        "the firmware ran a different fixture set than fixtures/ holds"
    );
    assert!(!fixtures.is_empty(), "no fixtures to compare");
    let mut mismatches = Vec::new();
    for (fixture, m7) in fixtures.iter().zip(&run.fixtures) {
        assert_eq!(m7.planner, fixture.planner.key(), "{}", fixture.name);
        let host = hex(&host_result(fixture.planner, &fixture.problem));
        if host != m7.hex {
            let first = host
                .bytes()
                .zip(m7.hex.bytes())
                .position(|(a, b)| a != b)
                .unwrap_or(host.len().min(m7.hex.len()));
            mismatches.push(format!(
                "{}: host {} bytes, M7 {} bytes, first difference at byte {}",
                fixture.name,
                host.len() / 2,
                m7.hex.len() / 2,
                first / 2
            ));
        }
    }
    assert!(
        mismatches.is_empty(),
        "results differ between the host and the emulated Cortex-M7:\n{}",
        mismatches.join("\n")
    );
}

#[test]
fn one_planner_images_give_the_default_images_results() {
    let Some(run) = run_or_skip("one_planner_images_give_the_default_images_results") else {
        return;
    };
    assert_eq!(run.images.len(), ONE_PLANNER_IMAGES.len());
    for image in &run.images {
        // Exactly its planner's fixtures, in the default image's order, with the same bytes.
        let expected: Vec<&FixtureReport> = run
            .fixtures
            .iter()
            .filter(|f| f.planner == image.planner)
            .collect();
        let names =
            |fs: &[&FixtureReport]| -> Vec<String> { fs.iter().map(|f| f.name.clone()).collect() };
        let got: Vec<&FixtureReport> = image.run.fixtures.iter().collect();
        assert_eq!(
            names(&got),
            names(&expected),
            "{} ran another fixture set than the default image's {} fixtures",
            image.command,
            image.planner
        );
        for (one, both) in got.iter().zip(&expected) {
            assert!(
                one.hex == both.hex,
                "{}: {} and the default image give different results",
                one.name,
                image.command
            );
        }
    }
}

/// One figure: what was measured and what it may be.
struct Figure {
    what: String,
    measured: u64,
    recorded: Option<u64>,
    budget: u64,
}

/// One firmware image's RAM figures (static RAM, its largest stack, their sum), written under
/// the image's table in `text` with their budgets (the recorded ones, else the one-planner-image
/// defaults) and pushed as figures labelled `"{planner} image {key}"`.
fn record_image_ram(
    text: &mut String,
    figures: &mut Vec<Figure>,
    recorded: Option<&toml::Table>,
    planner: &str,
    static_ram: u64,
    stack: u64,
) {
    for (key, measured, default_budget) in [
        (
            "static_ram_bytes",
            static_ram,
            BUDGET_ONE_PLANNER_IMAGE_RAM_BYTES,
        ),
        ("stack_bytes", stack, BUDGET_STACK_BYTES),
        (
            "ram_bytes",
            static_ram + stack,
            BUDGET_ONE_PLANNER_IMAGE_RAM_BYTES,
        ),
    ] {
        let budget = table_u64(recorded, &format!("{key}_budget")).unwrap_or(default_budget);
        let _ = writeln!(text, "{key} = {measured}\n{key}_budget = {budget}");
        figures.push(Figure {
            what: format!("{planner} image {key}"),
            measured,
            recorded: table_u64(recorded, key),
            budget,
        });
    }
}

fn table_u64(table: Option<&toml::Table>, key: &str) -> Option<u64> {
    table?
        .get(key)?
        .as_integer()
        .and_then(|v| u64::try_from(v).ok())
}

#[test]
fn figures_are_within_budget() {
    let test = "figures_are_within_budget";
    let Some(run) = run_or_skip(test) else {
        return;
    };
    let Some(instructions) = &run.instructions else {
        skip(
            test,
            "the QEMU instruction-counting plugin could not be built or loaded; the note above \
             says why and what to install",
        );
        return;
    };
    // The plugin's exact count and the firmware's own SysTick estimate (40-instruction ticks,
    // plus the few instructions of the SysTick reads) measure the same span: they must agree.
    for (fixture, &exact) in run.fixtures.iter().zip(instructions) {
        let estimate = fixture.systick_instructions;
        assert!(
            estimate.abs_diff(exact) <= 200 + exact / 1000,
            "{}: the plugin counted {exact} instructions, the firmware's SysTick {estimate}",
            fixture.name
        );
    }
    let path = root().join(FIGURES_FILE);
    let file: toml::Table = match std::fs::read_to_string(&path) {
        Ok(text) => toml::from_str(&text).unwrap_or_else(|e| panic!("{FIGURES_FILE}: {e}")),
        Err(_) => toml::Table::new(),
    };
    let recorded_binary = file.get("binary").and_then(|v| v.as_table());
    let recorded_fixtures: BTreeMap<String, &toml::Table> = file
        .get("fixture")
        .and_then(|v| v.as_array())
        .into_iter()
        .flatten()
        .filter_map(|v| v.as_table())
        .filter_map(|t| Some((t.get("name")?.as_str()?.to_owned(), t)))
        .collect();

    let mut figures = Vec::new();
    let mut text = format!(
        "# Figures of the firmware on the emulated Cortex-M7 (QEMU mps2-an500), each with its budget.\n\
         # The tests fail when a measured figure exceeds its budget (tests/tests/qemu_firmware.rs).\n\
         # Regenerate the measured values (budgets are kept; edit them by hand):\n\
         #   {UPDATE_COMMAND}\n\
         # instructions: guest instructions executed by the solve alone (QEMU plugin\n\
         #   tools/qemu-insn-plugin; deterministic). stack_bytes: stack high-water during the fixture,\n\
         #   from the top of the stack. ram_bytes = static_ram_bytes + stack_bytes. Sizes in bytes.\n\
         \n[binary]\n"
    );
    for (key, default_budget) in BINARY_FIGURES {
        let measured = *run
            .binary
            .get(key)
            .unwrap_or_else(|| panic!("firmware output lacks {key}"));
        let budget = table_u64(recorded_binary, &format!("{key}_budget")).unwrap_or(default_budget);
        let _ = writeln!(text, "{key} = {measured}\n{key}_budget = {budget}");
        figures.push(Figure {
            what: format!("binary {key}"),
            measured,
            recorded: table_u64(recorded_binary, key),
            budget,
        });
    }
    let static_ram = run.binary["static_ram_bytes"];
    for (index, fixture) in run.fixtures.iter().enumerate() {
        let recorded = recorded_fixtures.get(&fixture.name).copied();
        let (default_instructions, work_budget) = if fixture.planner == Planner::Impulsive.key() {
            (
                BUDGET_INSTRUCTIONS_IMPULSIVE,
                reconfig_core::impulsive::Settings::default().work_budget,
            )
        } else {
            (
                BUDGET_INSTRUCTIONS_PSEUDOSPECTRAL,
                reconfig_core::pseudospectral::Settings::default().work_budget,
            )
        };
        let _ = write!(
            text,
            "\n[[fixture]]\nname = {:?}\nplanner = {:?}\n",
            fixture.name, fixture.planner
        );
        for (key, measured, default_budget) in [
            ("instructions", instructions[index], default_instructions),
            // The work units beside the instructions (the calibration in docs/firmware.md);
            // their budget is the planner's default `work_budget`.
            (
                "work_units",
                fixture.work_units.unwrap_or_else(|| {
                    panic!("{}: the firmware printed no work_units", fixture.name)
                }),
                work_budget,
            ),
            ("stack_bytes", fixture.stack_bytes, BUDGET_STACK_BYTES),
            (
                "ram_bytes",
                static_ram + fixture.stack_bytes,
                BUDGET_RAM_BYTES,
            ),
        ] {
            let budget = table_u64(recorded, &format!("{key}_budget")).unwrap_or(default_budget);
            let _ = writeln!(text, "{key} = {measured}\n{key}_budget = {budget}");
            figures.push(Figure {
                what: format!("{} {key}", fixture.name),
                measured,
                recorded: table_u64(recorded, key),
                budget,
            });
        }
    }

    // The one-planner images' RAM (static + the largest stack over their fixtures), each
    // measured in its own image: its `main` frame differs from the default image's.
    let recorded_images: BTreeMap<String, &toml::Table> = file
        .get("image")
        .and_then(|v| v.as_array())
        .into_iter()
        .flatten()
        .filter_map(|v| v.as_table())
        .filter_map(|t| Some((t.get("planner")?.as_str()?.to_owned(), t)))
        .collect();
    if !run.images.is_empty() {
        text.push_str(
            "\n# One-planner images (docs/firmware.md): static RAM from the image's linker \
             symbols,\n# stack_bytes the largest over its fixtures in its own run, ram_bytes \
             their sum.\n",
        );
    }
    for image in &run.images {
        let recorded = recorded_images.get(image.planner).copied();
        let _ = write!(
            text,
            "\n[[image]]\nplanner = {:?}\ncommand = {:?}\n",
            image.planner, image.command
        );
        record_image_ram(
            &mut text,
            &mut figures,
            recorded,
            image.planner,
            image.static_ram_bytes(),
            image.stack_bytes(),
        );
    }

    let mut report = String::from("figure | measured | recorded | budget\n");
    for f in &figures {
        let recorded = f.recorded.map_or("-".to_owned(), |r| r.to_string());
        let _ = writeln!(
            report,
            "{} | {} | {recorded} | {}{}",
            f.what,
            f.measured,
            f.budget,
            if f.measured > f.budget {
                "  OVER BUDGET"
            } else {
                ""
            }
        );
    }
    println!("{report}");
    // Every run writes what it measured beside the firmware; the record is that file accepted.
    let measured_path = run.elf.with_file_name("m7-figures-measured.toml");
    let _ = std::fs::write(&measured_path, &text);
    let updating = std::env::var("RECONFIG_UPDATE_FIGURES").as_deref() == Ok("1");
    if updating {
        let _lock = RECORD_LOCK.lock().unwrap_or_else(|e| e.into_inner());
        // The GEO image's part of the record is its own test's (geo_figures_are_within_budget).
        let existing = std::fs::read_to_string(&path).unwrap_or_default();
        let geo_part = geo_record_part(&existing);
        if !geo_part.is_empty() {
            text.push('\n');
            text.push_str(geo_part);
        }
        std::fs::create_dir_all(path.parent().expect("has a parent")).expect("create folder");
        std::fs::write(&path, &text).unwrap_or_else(|e| panic!("{FIGURES_FILE}: {e}"));
        notice(&format!("wrote the measured figures to {FIGURES_FILE}"));
        let changed = reconfig_tests::m7_record::update_docs().expect("regenerate the docs");
        let images = reconfig_tests::m7_record::update_images_docs().expect("regenerate the docs");
        if changed || images {
            notice("regenerated the tables of docs/firmware.md from the record");
        }
    }
    // Drift: a figure more than 1 % away from the record (or not in it) fails, so a change
    // toward a budget is seen when it happens, not when the budget breaks.
    let drifted: Vec<String> = figures
        .iter()
        // Accepting a new record is exactly what the update run does.
        .filter(|_| !updating)
        .filter_map(|f| match f.recorded {
            None => Some(format!(
                "{}: measured {}, not in the record",
                f.what, f.measured
            )),
            Some(r) if (f.measured as f64 - r as f64).abs() > DRIFT_TOLERANCE * r as f64 => {
                Some(format!(
                    "{}: measured {}, recorded {} ({:+.2} %)",
                    f.what,
                    f.measured,
                    r,
                    100.0 * (f.measured as f64 - r as f64) / (r as f64).max(1.0)
                ))
            }
            Some(_) => None,
        })
        .collect();
    assert!(
        drifted.is_empty(),
        "M7 figures drifted more than {:.0} % from {FIGURES_FILE}:\n{}\nIf the change is \
         intended, accept the new record (and say why in the commit message):\n  {UPDATE_COMMAND}\n\
         (the measured figures are in {})",
        DRIFT_TOLERANCE * 100.0,
        drifted.join("\n"),
        measured_path.display()
    );
    let over: Vec<&Figure> = figures.iter().filter(|f| f.measured > f.budget).collect();
    assert!(
        over.is_empty(),
        "figures over budget on the emulated Cortex-M7:\n{}\nfirmware: {}",
        over.iter()
            .map(|f| format!("{}: {} > {}", f.what, f.measured, f.budget))
            .collect::<Vec<_>>()
            .join("\n"),
        run.elf.display()
    );
}

#[test]
fn no_fused_multiply_add_in_the_firmware() {
    let test = "no_fused_multiply_add_in_the_firmware";
    let Some(run) = run_or_skip(test) else {
        return;
    };
    let objdump = "arm-none-eabi-objdump";
    let output = match Command::new(objdump).arg("-d").arg(&run.elf).output() {
        Ok(o) if o.status.success() => o,
        _ => {
            skip(
                test,
                "arm-none-eabi-objdump is not installed. Install it with \
                 `sudo apt-get install binutils-arm-none-eabi`.",
            );
            return;
        }
    };
    let mut function = String::new();
    let mut fused = Vec::new();
    for line in String::from_utf8_lossy(&output.stdout).lines() {
        if line.ends_with(">:") {
            function = line.to_owned();
        }
        let mnemonic = line.split('\t').nth(2).unwrap_or("").trim();
        if ["vfma", "vfms", "vfnma", "vfnms"]
            .iter()
            .any(|m| mnemonic.starts_with(m))
        {
            fused.push(format!("{function} {}", line.trim()));
        }
    }
    assert!(
        fused.is_empty(),
        "fused multiply-add in the firmware breaks bit-identity with the host:\n{}",
        fused.join("\n")
    );
}

// The GEO servicing tour's image (`cargo firmware-geo`): its own build and a short QEMU run of the
// GEO fixtures alone, so that the default two-planner image keeps its RAM. Its figures are the
// record's GEO part (after `GEO_RECORD_MARKER`), written by its own test.

/// The GEO image's binary.
const GEO_BIN: &str = "reconfig-firmware-geo";
/// First line of the record's GEO part; everything after it belongs to the GEO image.
const GEO_RECORD_MARKER: &str =
    "# GEO servicing tour image (cargo firmware-geo): written by geo_figures_are_within_budget.";
/// Instructions per GEO tour solve (issue 12: at most 20 M for 16 clients).
const BUDGET_INSTRUCTIONS_GEO_TOUR: u64 = 20_000_000;
const GEO_BINARY_FIGURES: [(&str, u64); 4] = [
    ("text_bytes", 1024 * 1024),
    ("static_ram_bytes", 256 * 1024),
    ("geo_tour_workspace_bytes", 64 * 1024),
    ("geo_tour_solution_bytes", 16 * 1024),
];

/// Both tests that may rewrite the record take this first.
static RECORD_LOCK: Mutex<()> = Mutex::new(());
static GEO_RUN: OnceLock<Result<Run, String>> = OnceLock::new();

/// The record's GEO part (from its marker to the end; empty when absent).
fn geo_record_part(record: &str) -> &str {
    record
        .find(GEO_RECORD_MARKER)
        .map_or("", |at| &record[at..])
}

/// Build one image (`bin`, with exactly `features`) as its cargo alias does; the ELF's path.
fn build_image(bin: &str, features: &str) -> Result<PathBuf, String> {
    let output = Command::new(cargo())
        .current_dir(root())
        .args([
            "build",
            "--release",
            "--target",
            TARGET,
            "-p",
            "reconfig-firmware",
            "--bin",
            bin,
            "--no-default-features",
            "--features",
            features,
            "--message-format=json-render-diagnostics",
        ])
        // Flags from the environment would replace .cargo/config.toml's link flags.
        .env_remove("RUSTFLAGS")
        .env_remove("CARGO_ENCODED_RUSTFLAGS")
        .env_remove("CARGO_BUILD_RUSTFLAGS")
        .stderr(Stdio::inherit())
        .output()
        .map_err(|e| format!("cannot run cargo: {e}"))?;
    if !output.status.success() {
        return Err(format!(
            "building {bin} failed ({}); see the compiler output above",
            output.status
        ));
    }
    String::from_utf8_lossy(&output.stdout)
        .lines()
        .filter_map(|line| serde_json::from_str::<serde_json::Value>(line).ok())
        .filter(|m| m["reason"] == "compiler-artifact" && m["target"]["name"] == bin)
        .find_map(|m| m["executable"].as_str().map(PathBuf::from))
        .ok_or_else(|| format!("cargo did not report the {bin} executable"))
}

/// The GEO image's run (shared by the GEO tests), or why there is none.
fn geo_firmware_run() -> &'static Result<Run, String> {
    GEO_RUN.get_or_init(|| {
        check_prerequisites().map_err(|e| format!("SKIP: {e}"))?;
        let built = build_image(GEO_BIN, "geo_tour")?;
        // A folder of its own: run_firmware writes QEMU's output beside the ELF and
        // build_plugin builds relative to it, while the default image's run may be under way.
        let dir = built.parent().ok_or("odd target path")?.join("geo-image");
        std::fs::create_dir_all(&dir).map_err(|e| format!("{}: {e}", dir.display()))?;
        let elf = dir.join(GEO_BIN);
        std::fs::copy(&built, &elf).map_err(|e| format!("{}: {e}", elf.display()))?;
        let plugin = build_plugin(&elf)
            .map_err(|e| notice(&format!("note: no instruction counts: {e}")))
            .ok();
        match run_firmware(&elf, plugin.as_deref()) {
            Err(e) if e.starts_with("PLUGIN: ") => {
                notice(&format!("note: no instruction counts: {}", &e[8..]));
                run_firmware(&elf, None)
            }
            other => other,
        }
    })
}

fn geo_run_or_skip(test: &str) -> Option<&'static Run> {
    match geo_firmware_run() {
        Ok(run) => Some(run),
        Err(e) => match e.strip_prefix("SKIP: ") {
            Some(why) => {
                skip(test, why);
                None
            }
            None => panic!("{test}: {e}"),
        },
    }
}

/// The host's encoded GEO result: the baked `(Problem, Settings)` bytes, a fresh workspace.
fn geo_host_result(bytes: &[u8]) -> Vec<u8> {
    let (problem, settings): (geo_tour::Problem, geo_tour::Settings) =
        postcard::from_bytes(bytes).expect("the baked problem decodes");
    let mut workspace = Box::new(geo_tour::Workspace::new());
    let mut solution = Box::new(geo_tour::Solution::new());
    let result = geo_tour::solve(&problem, &settings, &mut workspace, &mut solution);
    let encoded: Result<&geo_tour::Solution, geo_tour::PlanError> = result.map(|()| &*solution);
    postcard::to_stdvec(&encoded).expect("encode")
}

fn geo_fixtures() -> Vec<fixture_set::EncodedFixture> {
    fixture_set::encode_all(&root().join("fixtures"))
        .expect("fixtures load")
        .into_iter()
        .filter(|f| f.planner == Planner::GeoTour)
        .collect()
}

#[test]
fn geo_results_are_bit_identical_to_the_host() {
    let test = "geo_results_are_bit_identical_to_the_host";
    let Some(run) = geo_run_or_skip(test) else {
        return;
    };
    let fixtures = geo_fixtures();
    assert!(!fixtures.is_empty(), "no GEO fixtures to compare");
    let names: Vec<&str> = fixtures.iter().map(|f| f.name.as_str()).collect();
    let m7_names: Vec<&str> = run.fixtures.iter().map(|f| f.name.as_str()).collect();
    assert_eq!(m7_names, names, "the GEO image ran a different fixture set");
    for (fixture, m7) in fixtures.iter().zip(&run.fixtures) {
        assert_eq!(m7.planner, Planner::GeoTour.key(), "{}", fixture.name);
        let host = hex(&geo_host_result(&fixture.problem));
        assert!(
            host == m7.hex,
            "{}: the host and the emulated Cortex-M7 differ (host {} bytes, M7 {} bytes)",
            fixture.name,
            host.len() / 2,
            m7.hex.len() / 2
        );
    }
}

#[test]
fn geo_figures_are_within_budget() {
    let test = "geo_figures_are_within_budget";
    let Some(run) = geo_run_or_skip(test) else {
        return;
    };
    let Some(instructions) = &run.instructions else {
        skip(
            test,
            "the QEMU instruction-counting plugin could not be built or loaded",
        );
        return;
    };
    let path = root().join(FIGURES_FILE);
    let record_text = std::fs::read_to_string(&path).unwrap_or_default();
    let file: toml::Table =
        toml::from_str(&record_text).unwrap_or_else(|e| panic!("{FIGURES_FILE}: {e}"));
    let recorded_binary = file.get("geo_binary").and_then(|v| v.as_table());
    let recorded_fixtures: BTreeMap<String, &toml::Table> = file
        .get("geo_fixture")
        .and_then(|v| v.as_array())
        .into_iter()
        .flatten()
        .filter_map(|v| v.as_table())
        .filter_map(|t| Some((t.get("name")?.as_str()?.to_owned(), t)))
        .collect();
    let mut figures = Vec::new();
    let mut text =
        format!("{GEO_RECORD_MARKER}\n# Its own QEMU run of the GEO fixtures.\n\n[geo_binary]\n");
    for (key, default_budget) in GEO_BINARY_FIGURES {
        let measured = *run
            .binary
            .get(key)
            .unwrap_or_else(|| panic!("GEO firmware output lacks {key}"));
        let budget = table_u64(recorded_binary, &format!("{key}_budget")).unwrap_or(default_budget);
        let _ = writeln!(text, "{key} = {measured}\n{key}_budget = {budget}");
        figures.push(Figure {
            what: format!("GEO image {key}"),
            measured,
            recorded: table_u64(recorded_binary, key),
            budget,
        });
    }
    // The GEO image's RAM as one image among the others (`[[image]]` of the main part): the
    // same three figures, the same 230 KiB budget.
    let recorded_image = file.get("geo_image").and_then(|v| v.as_table());
    let static_ram = run.binary["static_ram_bytes"];
    let stack = run
        .fixtures
        .iter()
        .map(|f| f.stack_bytes)
        .max()
        .unwrap_or(0);
    text.push_str("\n[geo_image]\nplanner = \"geo-tour\"\ncommand = \"cargo firmware-geo\"\n");
    record_image_ram(
        &mut text,
        &mut figures,
        recorded_image,
        "geo-tour",
        static_ram,
        stack,
    );
    for (fixture, &count) in run.fixtures.iter().zip(instructions) {
        let estimate = fixture.systick_instructions;
        assert!(
            estimate.abs_diff(count) <= 200 + count / 1000,
            "{}: the plugin counted {count} instructions, the firmware's SysTick {estimate}",
            fixture.name
        );
        let recorded = recorded_fixtures.get(&fixture.name).copied();
        let _ = write!(text, "\n[[geo_fixture]]\nname = {:?}\n", fixture.name);
        for (key, measured, default_budget) in [
            ("instructions", count, BUDGET_INSTRUCTIONS_GEO_TOUR),
            ("stack_bytes", fixture.stack_bytes, BUDGET_STACK_BYTES),
            (
                "ram_bytes",
                static_ram + fixture.stack_bytes,
                BUDGET_RAM_BYTES,
            ),
        ] {
            let budget = table_u64(recorded, &format!("{key}_budget")).unwrap_or(default_budget);
            let _ = writeln!(text, "{key} = {measured}\n{key}_budget = {budget}");
            figures.push(Figure {
                what: format!("{} {key}", fixture.name),
                measured,
                recorded: table_u64(recorded, key),
                budget,
            });
        }
    }
    for f in &figures {
        println!(
            "{} | {} | {:?} | {}",
            f.what, f.measured, f.recorded, f.budget
        );
    }
    let updating = std::env::var("RECONFIG_UPDATE_FIGURES").as_deref() == Ok("1");
    if updating {
        let _lock = RECORD_LOCK.lock().unwrap_or_else(|e| e.into_inner());
        let existing = std::fs::read_to_string(&path).unwrap_or_default();
        let main_part = &existing[..existing.len() - geo_record_part(&existing).len()];
        let mut record = main_part.trim_end().to_owned();
        record.push_str("\n\n");
        record.push_str(&text);
        std::fs::write(&path, &record).unwrap_or_else(|e| panic!("{FIGURES_FILE}: {e}"));
        notice(&format!("wrote the GEO image's figures to {FIGURES_FILE}"));
        reconfig_tests::m7_record::update_geo_docs().expect("regenerate the docs");
        reconfig_tests::m7_record::update_images_docs().expect("regenerate the docs");
    }
    let drifted: Vec<String> = figures
        .iter()
        .filter(|_| !updating)
        .filter_map(|f| match f.recorded {
            None => Some(format!(
                "{}: measured {}, not in the record",
                f.what, f.measured
            )),
            Some(r) if (f.measured as f64 - r as f64).abs() > DRIFT_TOLERANCE * r as f64 => {
                Some(format!("{}: measured {}, recorded {r}", f.what, f.measured))
            }
            Some(_) => None,
        })
        .collect();
    assert!(
        drifted.is_empty(),
        "GEO image figures drifted more than {:.0} % from {FIGURES_FILE}:\n{}\nIf intended:\n  {UPDATE_COMMAND}",
        DRIFT_TOLERANCE * 100.0,
        drifted.join("\n")
    );
    let over: Vec<String> = figures
        .iter()
        .filter(|f| f.measured > f.budget)
        .map(|f| format!("{}: {} > {}", f.what, f.measured, f.budget))
        .collect();
    assert!(
        over.is_empty(),
        "GEO image figures over budget:\n{}",
        over.join("\n")
    );
}

#[test]
fn geo_no_fused_multiply_add_in_the_firmware() {
    let test = "geo_no_fused_multiply_add_in_the_firmware";
    let Some(run) = geo_run_or_skip(test) else {
        return;
    };
    let output = match Command::new("arm-none-eabi-objdump")
        .arg("-d")
        .arg(&run.elf)
        .output()
    {
        Ok(o) if o.status.success() => o,
        _ => {
            skip(
                test,
                "arm-none-eabi-objdump is not installed. Install it with \
                 `sudo apt-get install binutils-arm-none-eabi`.",
            );
            return;
        }
    };
    let text = String::from_utf8_lossy(&output.stdout);
    let fused: Vec<&str> = text
        .lines()
        .filter(|line| {
            let mnemonic = line.split('\t').nth(2).unwrap_or("").trim();
            ["vfma", "vfms", "vfnma", "vfnms"]
                .iter()
                .any(|m| mnemonic.starts_with(m))
        })
        .collect();
    assert!(
        fused.is_empty(),
        "fused multiply-add in the GEO image breaks bit-identity with the host:\n{}",
        fused.join("\n")
    );
}
