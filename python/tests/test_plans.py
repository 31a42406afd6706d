"""Every planner's answer from Python is the CLI's `--json` object to the bit, and the
problems given as NumPy arrays are the fixtures' problems (issue 32)."""

import json
import pathlib
import subprocess
import sys
import threading
import time

import numpy as np
import pytest

import reconfig
from reconfig import _reconfig

from test_reconfig import BIN, FIXTURES, ROOT

# Every fixture of one request (LEO tours are answered by their own driver: tests below).
ONE_REQUEST = sorted(
    p for p in list(FIXTURES.glob("*.toml")) + list((FIXTURES / "over-limits").glob("*.toml"))
    if "planner = \"leo-tour\"" not in p.read_text() and "planner =" in p.read_text()
)
TIMES = ("solve_time_s", "check_time_s", "time_s")


def cli_json(path):
    out = subprocess.run([BIN, "solve", str(path), "--json"], capture_output=True, text=True)
    assert out.returncode in (0, 1, 2), out.stderr
    return json.loads(out.stdout)


def untimed(report):
    """The report without its measured times, at any depth."""
    if isinstance(report, dict):
        return {k: untimed(v) for k, v in report.items() if k not in TIMES}
    if isinstance(report, list):
        return [untimed(v) for v in report]
    return report


@pytest.mark.parametrize("path", ONE_REQUEST, ids=lambda p: p.stem)
def test_every_fixture_answers_as_the_cli_to_the_bit(path):
    fixture = reconfig.load_fixture(path)
    _, report = _reconfig.solve_text(fixture.name, fixture.text)
    printed = cli_json(path)
    # json.loads reads the shortest round-trip digits both print: equal floats are equal bits.
    assert untimed(report) == untimed(printed)
    try:
        r = reconfig.solve(fixture)
    except reconfig.Refused as e:
        assert e.status == printed["status"] in ("Rejected", "LimitExceeded")
        assert e.report is not None and e.report["message"] == printed["message"]
        return
    assert r.status == printed["status"] and r.usable is not None
    assert set(r.report) == set(printed)


@pytest.mark.parametrize("stem", ["leo-tour-example1-single-arc", "leo-tour-example1-printed"])
def test_a_leo_tour_answers_as_the_cli_to_the_bit(stem):
    """A tour is answered by its driver: each arc in turn, then the truth model's checks; the
    status is the tour's, as `reconfig solve` prints it."""
    path = FIXTURES / f"{stem}.toml"
    r = reconfig.solve(reconfig.load_fixture(path))
    printed = cli_json(path)
    assert r.status == printed["status"] and r.usable is (printed["status"] in ("Solved", "Usable"))
    assert r.cost == printed["total_dv_mps"] and len(r.arcs) == len(printed["arcs"])
    assert r.work_units >= sum(a["work_units"] for a in printed["arcs"]) > 0
    _, report = _reconfig.solve_text(str(path), path.read_text())
    assert untimed(report) == untimed(printed)


HUANG_INITIAL = [[0, 0, 0, 0, 0, 0], [8, 0, 0, 0, 0, 0], [8, 0, 8, 0, 0, 0]]
HUANG_FINAL = [[12, 12, 12, 0, 0, 0], [0, 12, 12, 0, 0, 0], [0, 12, 0, 0, 0, 0]]


def test_plan_a_from_arrays_is_the_fixture_plan():
    a = reconfig.plan_a(np.array(HUANG_INITIAL, dtype=np.int32), np.array(HUANG_FINAL),
                        horizon=10, max_control=1.0, keep_out=2.0, nodes=10, name="huang")
    f = reconfig.solve(reconfig.load_fixture(FIXTURES / "huang2012-three-sats-n10.toml"))
    assert a.status == f.status == "Solved" and a.cost == f.cost
    assert a.states.shape == (3, 11, 6) and a.controls.shape == (3, 11, 3)
    assert a.states.dtype == np.float64 and a.node_times.shape == (11,)
    assert np.array_equal(a.states, f.states) and np.array_equal(a.controls, f.controls)
    # The plan starts and ends where asked, and its certificate says why it is Solved.
    assert np.abs(a.states[:, 0, :] - np.array(HUANG_INITIAL, float)).max() < 1e-9
    assert np.abs(a.states[:, -1, :] - np.array(HUANG_FINAL, float)).max() < 1e-9
    assert a.min_separation >= 2.0 - 1e-9
    c = a.certificate
    assert c["second_order_evaluated"] and c["min_reduced_eigenvalue"] > 0
    assert c["stationarity"] < 1e-3 and c["max_violation"] == 0.0
    assert all(m["value"] >= 0 for m in c["multipliers"])
    # Settings by the core's names reach the planner: a work budget of 1000 units stops it
    # before any QP solution (it still pays the set-up and the check of its guess, the floor
    # of tests/tests/work_budget.rs).
    cut = reconfig.plan_a(HUANG_INITIAL, HUANG_FINAL, 10.0, 1.0, 2.0, 10,
                          settings={"work_budget": 1000})
    assert cut.status == "BudgetExhausted { verified: false }" and cut.usable is False
    assert cut.cost is None and cut.work_units < a.work_units


def test_plan_b_from_arrays_is_the_fixture_plan():
    doc = reconfig.load_fixture(FIXTURES / "wang2018-gco-to-pco-2imp-roe.toml").document()
    chief = [doc["chief"][k] for k in ("semi_major_axis_km", "eccentricity", "inclination_deg",
                                       "raan_deg", "arg_perigee_deg", "mean_anomaly_deg")]
    points = np.array([[i["arg_latitude_deg"], i["revolutions"]] for i in doc["impulse"]])
    b = reconfig.plan_b(np.array(chief), np.array(doc["relative"]["initial_roe_m"]),
                        doc["relative"]["target_roe_m"], impulses=points, form="roe_m")
    f = reconfig.solve(reconfig.load_fixture(FIXTURES / "wang2018-gco-to-pco-2imp-roe.toml"))
    assert b.status == "Solved" and b.total_dv_mps == f.total_dv_mps == f.cost
    assert len(b.impulses) == 2 and b.impulses[0]["dv_rtn_mps"].shape == (3,)
    assert np.array_equal(b.end_state["roe_m"], f.end_state["roe_m"])
    assert abs(b.terminal_error_m) < 1e-3
    # The search form, from a mapping chief.
    s = reconfig.plan_b(doc["chief"], doc["relative"]["initial_roe_m"],
                        doc["relative"]["target_roe_m"], search=(2, 14), form="roe_m")
    assert s.status == "Solved" and s.total_dv_mps <= b.total_dv_mps + 1e-9


def test_bad_arrays_are_refused_naming_the_field_before_planning():
    x0, x1 = np.array(HUANG_INITIAL, float), np.array(HUANG_FINAL, float)
    args = dict(horizon=10.0, max_control=1.0, keep_out=2.0, nodes=10)
    with pytest.raises(ValueError, match=r"final: shape \(2, 6\) is not \(3, 6\)"):
        reconfig.plan_a(x0, x1[:2], **args)
    with pytest.raises(ValueError, match=r"initial: shape \(3, 5\) is not \(any, 6\)"):
        reconfig.plan_a(x0[:, :5], x1, **args)
    with pytest.raises(ValueError, match=r"initial: dtype complex128 is not a real number"):
        reconfig.plan_a(x0 + 0j, x1, **args)
    with pytest.raises(ValueError, match=r"initial: dtype <U"):
        reconfig.plan_a([["a"] * 6] * 3, x1, **args)
    bad = x1.copy()
    bad[2, 4] = np.nan
    with pytest.raises(ValueError, match=r"final\[2, 4\] = nan is not finite"):
        reconfig.plan_a(x0, bad, **args)
    with pytest.raises(ValueError, match=r"mass: shape \(2,\) is not \(3\)"):
        reconfig.plan_a(x0, x1, mass=[1.0, 2.0], **args)
    with pytest.raises(ValueError, match=r"horizon = inf is not finite"):
        reconfig.plan_a(x0, x1, **{**args, "horizon": float("inf")})
    with pytest.raises(ValueError, match=r"nodes = 10.5 is not a whole number"):
        reconfig.plan_a(x0, x1, **{**args, "nodes": 10.5})
    # Out of range: refused by the core's checks, named with the value and the limit.
    with pytest.raises(reconfig.Refused, match="MaxControl = -1 must be positive"):
        reconfig.plan_a(x0, x1, **{**args, "max_control": -1.0})
    with pytest.raises(reconfig.Refused, match="Degree 400 exceeds capacity 24"):
        reconfig.plan_a(x0, x1, **{**args, "nodes": 400})
    with pytest.raises(reconfig.Refused, match="work_budget"):
        reconfig.plan_a(x0, x1, **args, settings={"work_budget": 10**15})
    with pytest.raises(ValueError, match="no_such_setting"):
        reconfig.plan_a(x0, x1, **args, settings={"no_such_setting": 1})
    chief = [7178.137, 0.0678, 63.4349, 112.0, 0.0, 0.0]
    with pytest.raises(ValueError, match=r"impulses\[1, 1\] = 0.5 is not a whole number"):
        reconfig.plan_b(chief, np.zeros(6), np.zeros(6), impulses=[[10.0, 1], [20.0, 0.5]])
    with pytest.raises(ValueError, match="either impulses"):
        reconfig.plan_b(chief, np.zeros(6), np.zeros(6))
    with pytest.raises(ValueError, match=r"chief: shape \(5,\) is not \(6\)"):
        reconfig.plan_b(chief[:5], np.zeros(6), np.zeros(6), search=(2, 3))
    with pytest.raises(reconfig.Refused, match=r"ccentricity 1.5"):
        reconfig.plan_b([7178.137, 1.5, 63.4, 112.0, 0, 0], np.zeros(6), np.ones(6) * 1e-4,
                        search=(2, 3))


def test_a_document_round_trips_and_refuses_what_toml_cannot_plan():
    f = reconfig.load_fixture(FIXTURES / "huang2012-three-sats-n10.toml")
    doc = f.document()
    assert doc["nodes"] == 10 and doc["spacecraft"][1]["initial"][0] == 8
    again = reconfig.Fixture.from_document(doc)
    assert reconfig.solve(again).cost == reconfig.solve(f).cost
    doc["spacecraft"][1]["initial"][3] = float("nan")
    with pytest.raises(ValueError, match=r"spacecraft\[1\]\.initial\[3\] = nan is not finite"):
        reconfig.Fixture.from_document(doc)
    doc["spacecraft"][1]["initial"][3] = np.float64(0.5)  # NumPy scalars and arrays are numbers
    doc["spacecraft"][2]["final"] = np.zeros(6)
    assert "final = [0.0, 0.0, 0.0, 0.0, 0.0, 0.0]" in reconfig.Fixture.from_document(doc).text


def test_planning_releases_the_gil():
    """While a campaign plans, another Python thread runs. Not a timing test: with a switch
    interval of 1000 s the interpreter never takes the GIL from the planning thread, so the
    counter can move during the call only if the call released it."""
    f = reconfig.load_fixture(FIXTURES / "huang2012-three-sats-n20.toml")
    old = sys.getswitchinterval()
    sys.setswitchinterval(1000.0)
    count, stop = [0], threading.Event()

    def spin():
        while not stop.is_set():
            count[0] += 1
            time.sleep(0)  # gives the GIL back: the main thread is never waiting on this one

    spinner = threading.Thread(target=spin)
    try:
        spinner.start()
        while count[0] == 0:
            time.sleep(0)
        before = count[0]
        reconfig.campaign(f, 400, disperse={"spacecraft[0].initial[0]": 0.1}, threads=1)
        during_campaign = count[0] - before
        before = count[0]
        for _ in range(300):
            reconfig.solve(f)
        during_solves = count[0] - before
    finally:
        stop.set()
        spinner.join()
        sys.setswitchinterval(old)
    assert during_campaign > 0 and during_solves > 0


def test_the_session_example_runs(tmp_path):
    """docs/python.md's session is python/examples/session.py, and it runs: its plots and its
    table are written, and what it prints is what the planners answer."""
    session = ROOT / "python" / "examples" / "session.py"
    doc = (ROOT / "docs" / "python.md").read_text()
    block = doc.split("<!-- session:begin -->\n```python\n")[1].split("```\n<!-- session:end -->")[0]
    assert block == session.read_text()
    out = subprocess.run([sys.executable, str(session), str(tmp_path)], cwd=ROOT,
                         capture_output=True, text=True)
    assert out.returncode == 0, out.stderr
    assert "planner A: Solved, J = 6.743183" in out.stdout
    assert "planner B: Solved" in out.stdout and "2000 of 2000 usable" in out.stdout
    for name in ("planner-a-xy.png", "campaign-dv.png", "cases.csv", "case17.toml"):
        assert (tmp_path / name).stat().st_size > 0, name
