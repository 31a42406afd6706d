//! `reconfig fairness`'s tables: printed, and written as records for the harness document.

use super::{Args, Checks, ClientFigures};
use crate::harness::flood::FloodMode;
use crate::table_record::Table;
use anyhow::Result;

/// A phase's clients as a table (round trips in µs).
pub(super) fn phase_table(rows: &[ClientFigures]) -> Table {
    let mut t = Table::new(
        &[
            "client",
            "sent",
            "correct",
            "wrong",
            "lost",
            "req/s",
            "rtt p50 us",
            "p99 us",
            "max us",
            "starved",
            "waited",
            "other turns",
        ],
        "lrrrrrrrrrrr",
    );
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

/// `--record`: the tables of this run as `fixtures/golden/tables/NAME.md`, the caption
/// `what` followed by each check's outcome.
pub(super) fn record(
    args: &Args,
    name: &str,
    what: &str,
    checks: &Checks,
    tables: &[&Table],
) -> Result<()> {
    let mut command = format!("fairness --seconds {} --record", args.seconds);
    if let Some(mode) = args.flood {
        command.push_str(&format!(" --flood {}", mode_name(mode)));
    }
    let held = |ok: bool| if ok { "held" } else { "FAILED" };
    let caption = format!(
        "{what} Every answer correct and nothing lost: {}; served in turn: {}; cheap p99 within \
         {} ms: {}; throughput ratio at least 0.5 (two phases only): {}; service stopped \
         cleanly: {} ({COLUMNS}.)",
        held(checks.all_correct),
        held(checks.served_in_turn),
        args.budget_ms,
        held(checks.cheap_within_budget),
        held(checks.throughput_ratio_ok),
        held(checks.stopped_cleanly),
    );
    crate::table_record::write_reconfig(name, &command, &caption, tables)
}

/// The closing line of a run: how the service stopped and whether every check held.
pub(super) fn print_stopped(stopped: bool, what: &str, passed: bool) {
    println!(
        "flight service stopped {}; {what} {}",
        if stopped { "cleanly" } else { "UNCLEANLY" },
        if passed { "passed" } else { "FAILED" }
    );
}

/// The flood mode's name on the command line.
pub(super) fn mode_name(mode: FloodMode) -> String {
    format!("{mode:?}").to_lowercase()
}
