//! `reconfig campaign FIXTURE --cases N --disperse PATH=SIGMA ...`: a Monte Carlo campaign of
//! one fixture of any planner (one request), its cases answered in parallel on every core, a
//! CSV row per case (`crate::campaign`).

use crate::campaign::dispersion::Dispersion;
use crate::campaign::table::{same_answers, summary, write_csv};
use crate::campaign::{progress_bar, Campaign, Row};
use crate::limits::LimitsArg;
use anyhow::{bail, Context, Result};
use std::io::Write;
use std::path::PathBuf;
use std::process::ExitCode;
use std::time::Instant;

/// Arguments of `reconfig campaign`.
#[derive(clap::Args, Debug)]
#[command(
    after_help = "Example: 10,000 dispersed planner-B cases on every core\n  \
reconfig campaign fixtures/wang2018-gco-to-pco-2imp-roe.toml --cases 10000 \\\n    \
--disperse 'relative.initial_roe_m[1]=50' --disperse 'relative.initial_roe_m[2]=20' \\\n    \
--out cases.csv\nA path names a float of the fixture's TOML: keys joined by `.`, array \
elements by `[i]`. Case K is the fixture with its numbers drawn from random stream K of the \
seed, whatever the thread count; `--show-case K` prints it as a fixture for `reconfig solve`."
)]
pub struct Args {
    /// Fixture file (TOML) of one request.
    pub fixture: PathBuf,
    /// Number of cases.
    #[arg(long, default_value_t = 1000)]
    pub cases: u64,
    /// Random seed.
    #[arg(long, default_value_t = 1)]
    pub seed: u64,
    /// `PATH=SIGMA`: add a normal deviate of standard deviation SIGMA (the file's units).
    #[arg(long, value_parser = Dispersion::gaussian)]
    pub disperse: Vec<Dispersion>,
    /// `PATH=LOW:HIGH`: draw the number uniformly in [LOW, HIGH).
    #[arg(long, value_parser = Dispersion::uniform)]
    pub uniform: Vec<Dispersion>,
    /// Threads (0: one per core).
    #[arg(long, default_value_t = 0)]
    pub threads: usize,
    /// Write the table (CSV, one row per case) here; `-` for standard output.
    #[arg(long)]
    pub out: Option<PathBuf>,
    /// Leave the time column empty, so that two runs' tables compare byte for byte.
    #[arg(long)]
    pub no_times: bool,
    /// Run on one thread, then on every core: check the answers are the same, bit for bit,
    /// and print both throughputs (the campaign figure of issue 32).
    #[arg(long)]
    pub scaling: bool,
    /// Print case K as a fixture file and stop.
    #[arg(long)]
    pub show_case: Option<u64>,
    /// Write the run's figures (throughput, wall time, peak memory) as the timing record
    /// `fixtures/golden/tables/campaign-NAME.md` (docs/campaigns.md shows it).
    #[arg(long, value_name = "NAME")]
    pub record: Option<String>,
    #[command(flatten)]
    pub limits: LimitsArg,
}

/// Run `reconfig campaign`: exit 0 when the campaign ran (whatever its cases' statuses, which
/// are its result), 2 when its input is refused.
pub fn run(args: &Args) -> Result<ExitCode> {
    let text = std::fs::read_to_string(&args.fixture)
        .with_context(|| format!("cannot read fixture {}", args.fixture.display()))?;
    let dispersions = args.disperse.iter().chain(&args.uniform).cloned().collect();
    let campaign = Campaign::new(
        &args.fixture.display().to_string(),
        &text,
        dispersions,
        args.seed,
        args.cases,
        args.limits.load()?,
    )?;
    if let Some(case) = args.show_case {
        print!("{}", campaign.case_text(case)?);
        return Ok(ExitCode::SUCCESS);
    }
    let cores = std::thread::available_parallelism().map_or(1, usize::from);
    let threads = if args.threads == 0 {
        cores
    } else {
        args.threads
    };
    let to_stdout = args.out.as_deref() == Some(std::path::Path::new("-"));
    let started = Instant::now();
    let mut one_thread_rate = None;
    let (rows, rate) = if args.scaling {
        let (one, one_rate) = timed(&campaign, 1, !to_stdout)?;
        one_thread_rate = Some(one_rate);
        let (all, all_rate) = timed(&campaign, cores, !to_stdout)?;
        if !same_answers(&one, &all) {
            bail!("the answers on 1 and {cores} threads differ: the campaign is not deterministic");
        }
        eprintln!(
            "scaling: 1 thread {one_rate:.1} cases/s, {cores} threads {all_rate:.1} cases/s \
             (x{:.2}); the answers are the same, bit for bit",
            all_rate / one_rate
        );
        (all, all_rate)
    } else {
        timed(&campaign, threads, !to_stdout)?
    };
    match &args.out {
        Some(_) if to_stdout => {
            write_csv(
                &campaign,
                &rows,
                !args.no_times,
                true,
                std::io::stdout().lock(),
            )?;
        }
        Some(p) => {
            let file = std::fs::File::create(p)
                .with_context(|| format!("cannot write {}", p.display()))?;
            write_csv(
                &campaign,
                &rows,
                !args.no_times,
                true,
                std::io::BufWriter::new(file),
            )?;
        }
        None => {}
    }
    let s = summary(&rows);
    let mut err = std::io::stderr().lock();
    writeln!(
        err,
        "{} cases, {} usable; {:.1} cases/s on {} threads; most work units {}",
        s.cases,
        s.usable,
        rate,
        if args.scaling { cores } else { threads },
        s.work_units_max
    )?;
    for (status, n) in &s.by_status {
        writeln!(err, "  {n:>8}  {status}")?;
    }
    if let Some(name) = &args.record {
        let figures = Figures {
            threads: if args.scaling { cores } else { threads },
            rate,
            one_thread_rate,
            wall_s: started.elapsed().as_secs_f64(),
            peak_mb: peak_resident_mb(),
        };
        record(args, name, &campaign, &rows, &figures)?;
    }
    Ok(ExitCode::SUCCESS)
}

/// A run's figures for its record.
struct Figures {
    threads: usize,
    rate: f64,
    one_thread_rate: Option<f64>,
    wall_s: f64,
    peak_mb: Option<f64>,
}

/// Write the timing record `campaign-NAME`: the command, the campaign and its figures.
fn record(args: &Args, name: &str, c: &Campaign, rows: &[Row], f: &Figures) -> Result<()> {
    let s = summary(rows);
    let mut t = crate::table_record::Table::new(
        &[
            "fixture",
            "dispersed",
            "cases",
            "1 thread (cases/s)",
            "threads",
            "cases/s",
            "ratio",
            "wall (s)",
            "peak memory (MB)",
            "statuses",
        ],
        "llrrrrrrrl",
    );
    let dash = || "—".to_owned();
    t.push(vec![
        args.fixture.display().to_string(),
        c.dispersions()
            .iter()
            .map(|d| format!("`{}`", d.path))
            .collect::<Vec<_>>()
            .join(", "),
        s.cases.to_string(),
        f.one_thread_rate.map_or_else(dash, |r| format!("{r:.1}")),
        f.threads.to_string(),
        format!("{:.1}", f.rate),
        f.one_thread_rate
            .map_or_else(dash, |r| format!("{:.2}", f.rate / r)),
        format!("{:.2}", f.wall_s),
        f.peak_mb.map_or_else(dash, |m| format!("{m:.1}")),
        s.by_status
            .iter()
            .map(|(k, n)| format!("{n} {k}"))
            .collect::<Vec<_>>()
            .join(", "),
    ]);
    // Arguments with brackets or spaces quoted, so that the record's command runs as shown.
    let argv: Vec<String> = std::env::args()
        .skip(1)
        .map(|a| {
            if a.contains(['[', ' ', '{', '*']) {
                format!("'{a}'")
            } else {
                a
            }
        })
        .collect();
    crate::table_record::write_reconfig(
        &format!("campaign-{name}"),
        &argv.join(" "),
        "One campaign: its cases answered through the one request path; with `--scaling` on \
         one thread and then on every core, the answers checked the same bit for bit, the \
         ratio the two throughputs' (wall includes both runs); peak memory is the process's \
         largest resident set.",
        &[&t],
    )
}

/// The process's largest resident set so far, MB (Linux `getrusage`, kB).
fn peak_resident_mb() -> Option<f64> {
    // SAFETY: `getrusage` fills the struct it is given; a zeroed `rusage` is a valid value.
    let mut usage: libc::rusage = unsafe { std::mem::zeroed() };
    // SAFETY: RUSAGE_SELF and a valid pointer to an `rusage`.
    let ok = unsafe { libc::getrusage(libc::RUSAGE_SELF, &mut usage) } == 0;
    ok.then(|| usage.ru_maxrss as f64 / 1024.0)
}

/// Run `campaign` on `threads` threads: the rows and the throughput, cases/s.
fn timed(campaign: &Campaign, threads: usize, progress: bool) -> Result<(Vec<Row>, f64)> {
    let bar = progress_bar(campaign.cases(), progress);
    let started = Instant::now();
    let rows = campaign.run(threads, &bar)?;
    let elapsed = started.elapsed().as_secs_f64();
    bar.finish_and_clear();
    Ok((rows, campaign.cases() as f64 / elapsed.max(1e-9)))
}
