//! `reconfig._reconfig`: the Python extension of reconfig (issue 32). Every answer goes
//! through the host's campaign runner (`reconfig_host::campaign`), so through the core's one
//! request path (`wire::answer`), the same call as `reconfig solve` and `reconfig campaign`:
//! the same bits. The GIL is released while planning.

use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use pyo3::types::PyDict;
use reconfig_host::campaign::dispersion::Dispersion;
use reconfig_host::campaign::{Campaign, Row};

thread_local! {
    /// Each Python thread's buffers for `solve_text`, made on its first solve.
    static BUFFERS: std::cell::RefCell<Option<Box<reconfig_core::wire::AllPlanners>>> =
        const { std::cell::RefCell::new(None) };
}

/// A refused input as Python's `ValueError`, its message naming the field, value and limit.
fn refused(e: &anyhow::Error) -> PyErr {
    PyValueError::new_err(format!("{e:#}"))
}

/// The rows as columns: a dict of lists, one entry per case.
fn columns<'py>(py: Python<'py>, c: &Campaign, rows: &[Row]) -> PyResult<Bound<'py, PyDict>> {
    let d = PyDict::new(py);
    d.set_item("case", rows.iter().map(|r| r.case).collect::<Vec<_>>())?;
    let paths: Vec<String> = c.dispersions().iter().map(|x| x.path.to_string()).collect();
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

/// Answer one fixture's text (one request): a dict with `status`, `usable`, `cost`,
/// `work_units`, `solve_time_s`, `message`, as a campaign row of no dispersion.
#[pyfunction]
fn solve_text<'py>(
    py: Python<'py>,
    name: &str,
    fixture_text: &str,
) -> PyResult<Bound<'py, PyDict>> {
    let c = build(name, fixture_text, Vec::new(), Vec::new(), 0, 1).map_err(|e| refused(&e))?;
    // On the calling thread with its own buffers, kept between calls: no thread pool to start
    // and no 240 KB to allocate per solve.
    let row = py.detach(|| {
        BUFFERS.with(|cell| {
            let mut slot = cell.borrow_mut();
            let buffers = slot.get_or_insert_with(reconfig_host::drivers::answer::buffers);
            c.answer_case(0, buffers)
        })
    });
    columns(py, &c, &[row])
}

/// Run a campaign (see `reconfig campaign`): `disperse` entries `PATH=SIGMA`, `uniform`
/// entries `PATH=LOW:HIGH`; `threads` 0 for one per core. Columns, one entry per case.
// The Python function's arguments, one each (the Python wrapper names them).
#[allow(clippy::too_many_arguments)]
#[pyfunction]
#[pyo3(signature = (name, fixture_text, cases, disperse, uniform, seed, threads))]
fn campaign<'py>(
    py: Python<'py>,
    name: &str,
    fixture_text: &str,
    cases: u64,
    disperse: Vec<String>,
    uniform: Vec<String>,
    seed: u64,
    threads: usize,
) -> PyResult<Bound<'py, PyDict>> {
    let c = build(name, fixture_text, disperse, uniform, seed, cases).map_err(|e| refused(&e))?;
    let rows = py
        .detach(|| c.run(threads, &indicatif::ProgressBar::hidden()))
        .map_err(|e| refused(&e))?;
    columns(py, &c, &rows)
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
    Ok(())
}
