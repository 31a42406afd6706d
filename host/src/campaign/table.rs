//! A campaign's rows as a CSV table (one row per case: the case, its dispersed numbers, the
//! status, the verdict, the cost, the work units, the time, the refusal) and its summary.

use super::{Campaign, Row};
use anyhow::Result;
use std::collections::BTreeMap;
use std::io::Write;

/// Write `rows` as CSV to `out`. Numbers print as Rust's shortest round-trip form, so two
/// runs' tables are equal byte for byte when their answers are equal bit for bit, apart from
/// the `solve_time_s` column (left empty with `times = false`). The header line comes first
/// when `header`: the parts of a campaign (`Campaign::run_range`) written in turn, the first
/// with its header, are the whole campaign's table.
///
/// # Errors
/// Writing to `out` fails.
pub fn write_csv<W: Write>(
    campaign: &Campaign,
    rows: &[Row],
    times: bool,
    header: bool,
    out: W,
) -> Result<()> {
    let mut w = csv::Writer::from_writer(out);
    let mut names = vec!["case".to_owned()];
    names.extend(campaign.dispersions().iter().map(|d| d.path.to_string()));
    names.extend(
        [
            "status",
            "usable",
            "cost",
            "work_units",
            "solve_time_s",
            "message",
        ]
        .map(String::from),
    );
    if header {
        w.write_record(&names)?;
    }
    let opt = |x: Option<String>| x.unwrap_or_default();
    for r in rows {
        let mut rec = vec![r.case.to_string()];
        rec.extend(r.inputs.iter().map(f64::to_string));
        rec.push(r.status.clone());
        rec.push(opt(r.usable.map(|u| u.to_string())));
        rec.push(opt(r.cost.map(|c| c.to_string())));
        rec.push(opt(r.work_units.map(|u| u.to_string())));
        rec.push(if times {
            r.solve_time_s.to_string()
        } else {
            String::new()
        });
        rec.push(r.message.clone());
        w.write_record(&rec)?;
    }
    w.flush()?;
    Ok(())
}

/// Whether two runs' rows are the same answers: every column but the time, bit for bit.
pub fn same_answers(a: &[Row], b: &[Row]) -> bool {
    let key = |r: &Row| {
        (
            r.case,
            r.inputs.iter().map(|x| x.to_bits()).collect::<Vec<_>>(),
            r.status.clone(),
            r.usable,
            r.cost.map(f64::to_bits),
            r.work_units,
            r.message.clone(),
        )
    };
    a.len() == b.len() && a.iter().zip(b).all(|(x, y)| key(x) == key(y))
}

/// Counts of a run: rows by status, usable plans, the largest work units.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Summary {
    /// Rows per status.
    pub by_status: BTreeMap<String, u64>,
    /// Rows whose plan is usable.
    pub usable: u64,
    /// Rows.
    pub cases: u64,
    /// The most work units any case used.
    pub work_units_max: u64,
}

/// Summarise `rows`.
pub fn summary(rows: &[Row]) -> Summary {
    let mut by_status = BTreeMap::new();
    for r in rows {
        *by_status.entry(r.status.clone()).or_insert(0) += 1;
    }
    Summary {
        by_status,
        usable: rows.iter().filter(|r| r.usable == Some(true)).count() as u64,
        cases: rows.len() as u64,
        work_units_max: rows.iter().filter_map(|r| r.work_units).max().unwrap_or(0),
    }
}
