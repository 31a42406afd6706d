//! `reconfig fairness`'s tables: printed, and written as records for the harness document.

use super::{Args, ClientFigures};
use crate::harness::flood::FloodMode;
use crate::table_record::Table;
use anyhow::{anyhow, Result};

/// A phase's clients as a table (round trips in µs).
pub(super) fn phase_table(rows: &[ClientFigures]) -> Table {
    let mut t = Table::new(&[
        ("client", false),
        ("sent", true),
        ("correct", true),
        ("wrong", true),
        ("lost", true),
        ("req/s", true),
        ("rtt p50 us", true),
        ("p99 us", true),
        ("max us", true),
        ("starved", true),
        ("waited", true),
        ("other turns", true),
    ]);
    for r in rows {
        t.push(vec![
            r.client.clone(),
            r.sent.to_string(),
            r.correct.to_string(),
            r.wrong.to_string(),
            r.lost.to_string(),
            format!("{:.1}", r.throughput_per_s),
            format!("{:.1}", r.rtt_p50_us),
            format!("{:.1}", r.rtt_p99_us),
            format!("{:.1}", r.rtt_max_us),
            r.starved.to_string(),
            r.most_other_turns_waited.to_string(),
            r.other_turns.to_string(),
        ]);
    }
    t
}

/// What the columns of [`phase_table`] mean.
const COLUMNS: &str = "starved: lost or served out of turn; waited: most turns of other \
                       clients one request waited for; other turns: turns given to other \
                       clients between the client's first request and its last answer";

pub(super) fn print_phase(title: &str, rows: &[ClientFigures]) {
    println!("\n== {title}\n{}({COLUMNS})", phase_table(rows).markdown());
}

/// `--record`: the tables of this run as `fixtures/golden/tables/NAME.md`.
pub(super) fn record(args: &Args, name: &str, caption: &str, tables: &[&Table]) -> Result<()> {
    let mut command = format!(
        "cargo run --release -p reconfig-host --bin reconfig -- fairness --seconds {} --record",
        args.seconds
    );
    if let Some(mode) = args.flood {
        command.push_str(&format!(" --flood {}", mode_name(mode)));
    }
    crate::table_record::write(name, &command, &format!("{caption} ({COLUMNS}.)"), tables)
        .map_err(|e| anyhow!(e))
}

/// The flood mode's name on the command line.
pub(super) fn mode_name(mode: FloodMode) -> String {
    format!("{mode:?}").to_lowercase()
}

/// Whether a check held, in a record's words.
pub(super) fn held(ok: bool) -> &'static str {
    if ok {
        "held"
    } else {
        "FAILED"
    }
}
