//! `reconfig._reconfig`: the Python extension of reconfig (issue 32). Every answer goes
//! through the host's campaign runner (`reconfig_host::campaign`), so through the core's one
//! request path (`wire::answer`), the same call as `reconfig solve` and `reconfig campaign`:
//! the same bits. The GIL is released while planning.

use anyhow::Context;
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use pyo3::types::PyDict;
use reconfig_host::campaign::dispersion::Dispersion;
use reconfig_host::campaign::table::write_csv;
use reconfig_host::campaign::{answer_fixture, progress_bar, Campaign, Row};
use reconfig_host::drivers::answer::error_json;
use reconfig_host::drivers::leo_report;
use reconfig_host::fixture::leo_tour::LeoTourFixture;
use reconfig_host::fixture::{self, Fixture};

thread_local! {
    /// Each Python thread's buffers for `solve_text`, made on its first solve.
    static BUFFERS: std::cell::RefCell<Option<Box<reconfig_core::wire::AllPlanners>>> =
        const { std::cell::RefCell::new(None) };
}

/// A report (the JSON object `reconfig solve --json` prints) as Python objects: dicts, lists,
/// floats (the same doubles), ints, strings, None.
fn python_value<'py>(py: Python<'py>, v: &serde_json::Value) -> PyResult<Bound<'py, PyAny>> {
    pythonize::pythonize(py, v).map_err(|e| PyValueError::new_err(format!("report: {e}")))
}

/// A refused input as Python's `ValueError`, its message naming the field, value and limit.
fn refused(e: &anyhow::Error) -> PyErr {
    PyValueError::new_err(format!("{e:#}"))
}

/// The rows as columns: a dict of lists, one entry per case.
fn columns<'py>(
    py: Python<'py>,
    dispersions: &[Dispersion],
    rows: &[Row],
) -> PyResult<Bound<'py, PyDict>> {
    let d = PyDict::new(py);
    d.set_item("case", rows.iter().map(|r| r.case).collect::<Vec<_>>())?;
    let paths: Vec<String> = dispersions.iter().map(|x| x.path.to_string()).collect();
    for (k, path) in paths.iter().enumerate() {
        let values: Vec<Option<f64>> = rows.iter().map(|r| r.inputs.get(k).copied()).collect();
        d.set_item(path, values)?;
    }
    d.set_item(
        "status",
        rows.iter().map(|r| r.status.clone()).collect::<Vec<_>>(),
    )?;
    d.set_item("usable", rows.iter().map(|r| r.usable).collect::<Vec<_>>())?;
    d.set_item("cost", rows.iter().map(|r| r.cost).collect::<Vec<_>>())?;
    d.set_item(
        "work_units",
        rows.iter().map(|r| r.work_units).collect::<Vec<_>>(),
    )?;
    d.set_item(
        "solve_time_s",
        rows.iter().map(|r| r.solve_time_s).collect::<Vec<_>>(),
    )?;
    d.set_item(
        "message",
        rows.iter().map(|r| r.message.clone()).collect::<Vec<_>>(),
    )?;
    Ok(d)
}

/// Build a campaign of `fixture_text`.
fn build(
    name: &str,
    fixture_text: &str,
    disperse: Vec<String>,
    uniform: Vec<String>,
    seed: u64,
    cases: u64,
) -> Result<Campaign, anyhow::Error> {
    let mut dispersions = disperse
        .iter()
        .map(|a| Dispersion::gaussian(a))
        .collect::<anyhow::Result<Vec<_>>>()?;
    for a in &uniform {
        dispersions.push(Dispersion::uniform(a)?);
    }
    let limits = reconfig_core::limits::Limits::default();
    Campaign::new(name, fixture_text, dispersions, seed, cases, limits)
}

/// Answer one fixture's text as `reconfig solve` does: its row as columns (`status`,
/// `usable`, `cost`, `work_units`, `solve_time_s`, `message`) and the JSON object
/// `reconfig solve --json` prints for it, as Python objects (`None` when the fixture's own checks refused it:
/// the row's message says why). A fixture of one request is answered as a campaign row of no
/// dispersion; a LEO tour by its driver (each arc answered in turn, then checked in the truth
/// model), its status the tour's.
#[pyfunction]
fn solve_text<'py>(
    py: Python<'py>,
    name: &str,
    fixture_text: &str,
) -> PyResult<(Bound<'py, PyDict>, Option<Bound<'py, PyAny>>)> {
    let fixture = fixture::parse(fixture_text)
        .with_context(|| format!("in fixture {name}"))
        .map_err(|e| refused(&e))?;
    if let Fixture::LeoTour(tour) = &fixture {
        return solve_tour(py, tour);
    }
    let limits = reconfig_core::limits::Limits::default();
    // On the calling thread with its own buffers, kept between calls: no thread pool to start
    // and no 240 KB to allocate per solve; the fixture parsed once.
    let (row, report) = py.detach(|| {
        BUFFERS.with(|cell| {
            let mut slot = cell.borrow_mut();
            let buffers = slot.get_or_insert_with(reconfig_host::drivers::answer::buffers);
            answer_fixture(&fixture, &limits, buffers, true)
        })
    });
    let report = match report.transpose().map_err(|e| refused(&e))? {
        Some(v) => Some(python_value(py, &v)?),
        None => None,
    };
    Ok((columns(py, &[], &[row])?, report))
}

/// A LEO tour answered as `reconfig solve` answers it (`leo_report`), as one row and its JSON.
fn solve_tour<'py>(
    py: Python<'py>,
    tour: &LeoTourFixture,
) -> PyResult<(Bound<'py, PyDict>, Option<Bound<'py, PyAny>>)> {
    let limits = reconfig_core::limits::Limits::default();
    let started = std::time::Instant::now();
    let evaluated = py.detach(|| leo_report::evaluate(tour, &limits));
    let solve_time_s = started.elapsed().as_secs_f64();
    let (report, status, usable, cost, work_units, message) = match &evaluated {
        Ok(r) => {
            let usable = r.usable();
            let cost = usable.then(|| r.total_dv_mps());
            let status = r.status().to_owned();
            (
                r.to_json(),
                status,
                Some(usable),
                cost,
                Some(r.work_units()),
                String::new(),
            )
        }
        Err(e) => {
            let (report, status, message) = error_json(&tour.name, e);
            (report, status.to_owned(), None, None, None, message)
        }
    };
    let d = PyDict::new(py);
    d.set_item("case", vec![0_u64])?;
    d.set_item("status", vec![status])?;
    d.set_item("usable", vec![usable])?;
    d.set_item("cost", vec![cost])?;
    d.set_item("work_units", vec![work_units])?;
    d.set_item("solve_time_s", vec![solve_time_s])?;
    d.set_item("message", vec![message])?;
    Ok((d, Some(python_value(py, &report)?)))
}

/// Run cases `first .. first + count` of a campaign (see `reconfig campaign`): `disperse`
/// entries `PATH=SIGMA`, `uniform` entries `PATH=LOW:HIGH`; `threads` 0 for one per core.
/// Columns, one entry per case, and with `table` the rows as `reconfig campaign --out`
/// writes them (the header when `first` is 0; the time column empty unless `times`).
// The Python function's arguments, one each (the Python wrapper names them).
#[allow(clippy::too_many_arguments)]
#[pyfunction]
#[pyo3(signature = (name, fixture_text, cases, disperse, uniform, seed, threads, first, count, table, times, progress))]
fn campaign<'py>(
    py: Python<'py>,
    name: &str,
    fixture_text: &str,
    cases: u64,
    disperse: Vec<String>,
    uniform: Vec<String>,
    seed: u64,
    threads: usize,
    first: u64,
    count: u64,
    table: bool,
    times: bool,
    progress: bool,
) -> PyResult<(Bound<'py, PyDict>, Option<String>)> {
    let c = build(name, fixture_text, disperse, uniform, seed, cases).map_err(|e| refused(&e))?;
    let rows = py
        .detach(|| {
            let bar = progress_bar(count, progress);
            let rows = c.run_range(first, count, threads, &bar);
            bar.finish_and_clear();
            rows
        })
        .map_err(|e| refused(&e))?;
    let csv = if table {
        let mut out = Vec::new();
        write_csv(&c, &rows, times, first == 0, &mut out).map_err(|e| refused(&e))?;
        Some(String::from_utf8(out).map_err(|e| refused(&e.into()))?)
    } else {
        None
    };
    Ok((columns(py, c.dispersions(), &rows)?, csv))
}

/// A fixture document given as JSON text (a Python dict's `json.dumps`), as TOML text: what
/// `reconfig solve` reads.
#[pyfunction]
fn toml_from_json(json_text: &str) -> PyResult<String> {
    let doc: toml::Value = serde_json::from_str(json_text)
        .map_err(|e| PyValueError::new_err(format!("not a fixture document: {e}")))?;
    toml::to_string(&doc).map_err(|e| PyValueError::new_err(format!("not a fixture document: {e}")))
}

/// A fixture's TOML text as JSON text (its document, for Python to read).
#[pyfunction]
fn json_from_toml(text: &str) -> PyResult<String> {
    let doc: toml::Value =
        toml::from_str(text).map_err(|e| PyValueError::new_err(format!("not TOML: {e}")))?;
    serde_json::to_string(&doc).map_err(|e| PyValueError::new_err(format!("not JSON: {e}")))
}

/// Case `case` of a campaign as fixture text (`reconfig campaign --show-case`).
#[pyfunction]
#[pyo3(signature = (name, fixture_text, disperse, uniform, seed, case))]
fn case_text(
    name: &str,
    fixture_text: &str,
    disperse: Vec<String>,
    uniform: Vec<String>,
    seed: u64,
    case: u64,
) -> PyResult<String> {
    let c = build(
        name,
        fixture_text,
        disperse,
        uniform,
        seed,
        case.saturating_add(1),
    )
    .map_err(|e| refused(&e))?;
    c.case_text(case).map_err(|e| refused(&e))
}

#[pymodule]
fn _reconfig(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_function(wrap_pyfunction!(solve_text, m)?)?;
    m.add_function(wrap_pyfunction!(campaign, m)?)?;
    m.add_function(wrap_pyfunction!(case_text, m)?)?;
    m.add_function(wrap_pyfunction!(toml_from_json, m)?)?;
    m.add_function(wrap_pyfunction!(json_from_toml, m)?)?;
    Ok(())
}
