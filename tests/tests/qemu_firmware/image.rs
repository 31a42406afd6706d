//! One firmware image: build it as its cargo alias does, run it in QEMU (with the
//! instruction-counting plugin when it loads), and parse what it printed
//! (`firmware/src/m7/` documents the output protocol).

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};

use crate::prerequisites::{cargo, check_prerequisites, notice, root, skip, TARGET};

/// One fixture's line pair in the firmware output.
#[derive(Debug, Clone)]
pub struct FixtureReport {
    pub name: String,
    pub planner: String,
    pub stack_bytes: u64,
    /// The firmware's own SysTick estimate (to within 40 instructions).
    pub systick_instructions: u64,
    /// Work units the solve reported (`SolveInfo::work_units`), when the planner meters its
    /// work.
    pub work_units: Option<u64>,
    /// Kepler solves and their Newton steps in the case (planner B's kernel image only).
    pub kepler: Option<(u64, u64)>,
    pub hex: String,
}

/// One kernel case of the GEO image (`kernel` line, after the fixtures).
#[derive(Debug, Clone)]
pub struct KernelReport {
    pub name: String,
    /// The units the solve charges for what the case ran.
    pub units: u64,
    pub stack_bytes: u64,
    /// The firmware's own SysTick estimate (to within 40 instructions).
    pub systick_instructions: u64,
}

/// Everything one firmware run produced.
#[derive(Debug)]
pub struct Run {
    pub elf: PathBuf,
    pub binary: BTreeMap<String, u64>,
    pub fixtures: Vec<FixtureReport>,
    /// Instructions per solve, by fixture index; `None` without the plugin.
    pub instructions: Option<Vec<u64>>,
    /// The GEO image's kernel cases (none in the other images).
    pub kernels: Vec<KernelReport>,
    /// Instructions per kernel case, by kernel index; `None` without the plugin.
    pub kernel_instructions: Option<Vec<u64>>,
}

impl Run {
    /// The largest stack high-water over the image's fixtures.
    pub fn largest_stack_bytes(&self) -> u64 {
        self.fixtures
            .iter()
            .map(|f| f.stack_bytes)
            .max()
            .unwrap_or(0)
    }
}

/// A shared run, or `None` after reporting a skip (an `Err` starting with "SKIP: " is a
/// missing prerequisite; any other error fails the test).
pub fn or_skip<T>(test: &str, run: &'static Result<T, String>) -> Option<&'static T> {
    match run {
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

/// The run's instruction counts per solve, or `None` after reporting a skip (the QEMU
/// instruction-counting plugin did not load).
pub fn instructions_or_skip<'a>(test: &str, run: &'a Run) -> Option<&'a [u64]> {
    let counts = run.instructions.as_deref();
    if counts.is_none() {
        skip(
            test,
            "the QEMU instruction-counting plugin could not be built or loaded; the note above \
             says why and what to install",
        );
    }
    counts
}

/// Build one image (`bin`; with exactly `features`, or the default features for `None`) as its
/// cargo alias does; the ELF's path.
pub fn build_image(bin: &str, features: Option<&str>) -> Result<PathBuf, String> {
    let mut command = Command::new(cargo());
    command.current_dir(root()).args([
        "build",
        "--release",
        "--target",
        TARGET,
        "-p",
        "reconfig-firmware",
        "--bin",
        bin,
    ]);
    if let Some(features) = features {
        command.args(["--no-default-features", "--features", features]);
    }
    let output = command
        .arg("--message-format=json-render-diagnostics")
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

/// Build an image and copy its ELF into a folder of its own (`folder`, beside the build
/// output): `run_firmware` writes QEMU's output beside the ELF and `build_plugin` builds
/// relative to it, while another image's run may be under way; and images that share the
/// build output path (the one-planner images) would overwrite each other.
pub fn build_image_in(bin: &str, features: Option<&str>, folder: &str) -> Result<PathBuf, String> {
    let built = build_image(bin, features)?;
    let dir = built.parent().ok_or("odd target path")?.join(folder);
    std::fs::create_dir_all(&dir).map_err(|e| format!("{}: {e}", dir.display()))?;
    let elf = dir.join(bin);
    std::fs::copy(&built, &elf).map_err(|e| format!("{}: {e}", elf.display()))?;
    Ok(elf)
}

/// Check the prerequisites, build the image in its folder and run it with the instruction
/// counts (see [`run_counted`]).
pub fn build_and_run(bin: &str, features: Option<&str>, folder: &str) -> Result<Run, String> {
    check_prerequisites().map_err(|e| format!("SKIP: {e}"))?;
    let elf = build_image_in(bin, features, folder)?;
    run_counted(&elf)
}

/// Run an image with the instruction-counting plugin; without counts (and a note saying why)
/// when the plugin cannot be built or this QEMU has no TCG plugin support.
pub fn run_counted(elf: &Path) -> Result<Run, String> {
    let plugin = build_plugin(elf)
        .map_err(|e| notice(&format!("note: no instruction counts: {e}")))
        .ok();
    match run_firmware(elf, plugin.as_deref()) {
        Err(e) if e.starts_with("PLUGIN: ") => {
            notice(&format!("note: no instruction counts: {}", &e[8..]));
            run_firmware(elf, None)
        }
        other => other,
    }
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

/// Run an image in QEMU (the runner of .cargo/config.toml, plus the plugin when given).
pub fn run_firmware(elf: &Path, plugin: Option<&Path>) -> Result<Run, String> {
    // The plugin counts the instructions between the marker functions.
    let mut extra = Vec::new();
    if let Some(plugin) = plugin {
        let markers = elf32_symbols(elf, &["reconfig_measure_start", "reconfig_measure_stop"])?;
        extra.push("-plugin".to_owned());
        extra.push(format!(
            "{},start={:#x},stop={:#x}",
            plugin.display(),
            markers[0],
            markers[1]
        ));
        extra.extend(["-d".to_owned(), "plugin".to_owned()]);
    }
    let reconfig_tests::qemu::Output {
        status,
        stdout,
        stderr,
    } = reconfig_tests::qemu::run_m7(Path::new("qemu-system-arm"), elf, &extra)?;
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
        let mut counts: Vec<u64> = counts.into_values().collect();
        if counts.len() != run.fixtures.len() + run.kernels.len() {
            return Err(format!(
                "the plugin reported {} measurements for {} fixtures and {} kernels; stderr:\n{}",
                counts.len(),
                run.fixtures.len(),
                run.kernels.len(),
                tail(&stderr)
            ));
        }
        // The fixtures' measurements come first, then the kernels'.
        run.kernel_instructions = Some(counts.split_off(run.fixtures.len()));
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
    let mut kernels: Vec<KernelReport> = Vec::new();
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
                    kepler: match f.get("kepler_solves") {
                        Some(_) => {
                            Some((number(&f, "kepler_solves")?, number(&f, "kepler_steps")?))
                        }
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
            "kernel" => {
                if number(&f, "index")? != kernels.len() as u64 {
                    return Err(format!("kernel lines out of order at {line}"));
                }
                kernels.push(KernelReport {
                    name: f.get("name").ok_or("kernel without name")?.to_string(),
                    units: number(&f, "units")?,
                    stack_bytes: number(&f, "stack_bytes")?,
                    systick_instructions: number(&f, "systick_instructions")?,
                });
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
        kernels,
        kernel_instructions: None,
    })
}
