//! Tables of timings that `docs/` shows, written by the command that measures them.
//!
//! A timing depends on the machine and its load, so no test may produce one. The command that
//! measures it writes the table to `fixtures/golden/tables/NAME.md` (when asked, e.g.
//! `reconfig demo --record-tables`), with a first line that says the command, the date and the
//! machine's load; a document shows it between `<!-- table NAME:begin … -->` and
//! `<!-- table NAME:end -->`, and `tests/tests/docs_tables.rs` fails when the two differ
//! (`RECONFIG_UPDATE_DOCS=1` copies the records into the documents).

use std::path::PathBuf;

/// Where the table records live, relative to the workspace.
pub const DIR: &str = "fixtures/golden/tables";

/// A markdown table: a header row, which columns are numbers (right-aligned), the rows.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Table {
    /// Column names.
    pub header: Vec<String>,
    /// Whether each column is right-aligned (numbers).
    pub numeric: Vec<bool>,
    /// The cells, row by row.
    pub rows: Vec<Vec<String>>,
}

impl Table {
    /// A table with these columns and no rows yet; `align` has one letter per column, `r` for
    /// a right-aligned (number) column, anything else for a left-aligned one.
    pub fn new(header: &[&str], align: &str) -> Self {
        let mut right = align.chars().map(|c| c == 'r');
        Self {
            header: header.iter().map(|n| (*n).to_string()).collect(),
            numeric: header
                .iter()
                .map(|_| right.next().unwrap_or(false))
                .collect(),
            rows: Vec::new(),
        }
    }

    /// Append a row.
    pub fn push(&mut self, row: Vec<String>) {
        self.rows.push(row);
    }

    /// The table in markdown, one line per row, each ending in a newline.
    pub fn markdown(&self) -> String {
        let line = |cells: &[String]| format!("| {} |\n", cells.join(" | "));
        let rule: Vec<String> = self
            .numeric
            .iter()
            .map(|&r| if r { "---:" } else { "---" }.to_string())
            .collect();
        let mut out = line(&self.header);
        out.push_str(&line(&rule));
        for row in &self.rows {
            out.push_str(&line(row));
        }
        out
    }
}

/// The record file of table `name`, relative to the workspace.
pub fn relative_path(name: &str) -> String {
    format!("{DIR}/{name}.md")
}

/// The record file of table `name`.
pub fn path(name: &str) -> PathBuf {
    crate::figure_record::root().join(relative_path(name))
}

/// The record of table `name`: a line saying `command`, the date and the load, then
/// `caption` (one paragraph, may be empty), then the tables (markdown, blank-line separated).
pub fn record_text(command: &str, caption: &str, tables: &[&Table]) -> String {
    let mut out = format!(
        "Measured by `{command}` on {} ({}).{}{}\n",
        utc_now(),
        machine_load(),
        if caption.is_empty() { "" } else { " " },
        caption
    );
    for t in tables {
        out.push('\n');
        out.push_str(&t.markdown());
    }
    out
}

/// Write the record of table `name` (see [`record_text`]).
///
/// # Errors
/// When the file cannot be written.
pub fn write(name: &str, command: &str, caption: &str, tables: &[&Table]) -> Result<(), String> {
    let path = path(name);
    std::fs::write(&path, record_text(command, caption, tables))
        .map_err(|e| format!("{}: {e}", path.display()))?;
    println!("table record written to {}", relative_path(name));
    Ok(())
}

/// How a record names a `reconfig` command: the command line that builds and runs it.
pub const RECONFIG: &str = "cargo run --release -p reconfig-host --bin reconfig --";

/// [`write()`] for a record taken by `reconfig ARGUMENTS` (e.g. `placement --record`).
///
/// # Errors
/// When the file cannot be written.
pub fn write_reconfig(
    name: &str,
    arguments: &str,
    caption: &str,
    tables: &[&Table],
) -> anyhow::Result<()> {
    write(name, &format!("{RECONFIG} {arguments}"), caption, tables).map_err(anyhow::Error::msg)
}

/// The current time, `YYYY-MM-DD HH:MM UTC`.
fn utc_now() -> String {
    let secs = std::time::SystemTime::now()
        .duration_since(std::time::UNIX_EPOCH)
        .map_or(0, |d| d.as_secs());
    let (y, m, d) = civil_from_days(secs / 86_400);
    let s = secs % 86_400;
    format!(
        "{y:04}-{m:02}-{d:02} {:02}:{:02} UTC",
        s / 3600,
        s / 60 % 60
    )
}

/// Year, month, day of `days` after 1970-01-01 (Howard Hinnant's `civil_from_days`, for the
/// non-negative days a clock gives).
fn civil_from_days(days: u64) -> (u64, u64, u64) {
    let z = days + 719_468;
    let era = z / 146_097;
    let doe = z % 146_097;
    let yoe = (doe - doe / 1460 + doe / 36_524 - doe / 146_096) / 365;
    let doy = doe - (365 * yoe + yoe / 4 - yoe / 100);
    let mp = (5 * doy + 2) / 153;
    let d = doy - (153 * mp + 2) / 5 + 1;
    let m = if mp < 10 { mp + 3 } else { mp - 9 };
    let y = yoe + era * 400 + u64::from(m <= 2);
    (y, m, d)
}

/// The CPUs and the load average (1 minute) of this machine, as the record's context.
fn machine_load() -> String {
    let cpus = std::thread::available_parallelism().map_or(0, std::num::NonZeroUsize::get);
    let load = std::fs::read_to_string("/proc/loadavg")
        .ok()
        .and_then(|t| t.split_whitespace().next().map(str::to_string));
    match load {
        Some(l) => format!("{cpus} CPUs, load average {l}"),
        None => format!("{cpus} CPUs, load average not known"),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn dates_follow_the_civil_calendar() {
        assert_eq!(civil_from_days(0), (1970, 1, 1));
        assert_eq!(civil_from_days(59), (1970, 3, 1));
        // 2000-02-29 (a leap day of a century year divisible by 400) and 2026-11-28.
        assert_eq!(civil_from_days(11_016), (2000, 2, 29));
        assert_eq!(civil_from_days(20_785), (2026, 11, 28));
    }

    #[test]
    fn a_table_is_markdown_with_aligned_numbers() {
        let mut t = Table::new(&["client", "sent"], "lr");
        t.push(vec!["cheap".into(), "3000".into()]);
        assert_eq!(
            t.markdown(),
            "| client | sent |\n| --- | ---: |\n| cheap | 3000 |\n"
        );
    }
}
