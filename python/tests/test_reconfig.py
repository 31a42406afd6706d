"""The Python package against the CLI: the same answers, bit for bit (issue 32).

The CLI is the binary `cargo test --workspace` builds (target/debug/reconfig), or
$RECONFIG_BIN; without it the tests fail rather than skip.
"""

import csv
import io
import json
import os
import pathlib
import subprocess

import numpy as np
import pytest

import reconfig

ROOT = pathlib.Path(__file__).resolve().parents[2]
FIXTURES = ROOT / "fixtures"
BIN = os.environ.get("RECONFIG_BIN", str(ROOT / "target" / "debug" / "reconfig"))


def cli(*args):
    out = subprocess.run([BIN, *map(str, args)], capture_output=True, text=True, check=False)
    assert out.returncode in (0, 1), out.stderr
    return out.stdout


@pytest.mark.parametrize(
    "stem,cost_key",
    [
        ("wang2018-gco-to-pco-2imp-roe", "total_dv_mps"),
        ("huang2012-three-sats-n10", "cost"),
        ("geo-servicing-published-60d", "total_dv_mps"),
    ],
)
def test_solve_is_the_cli_answer_to_the_bit(stem, cost_key):
    path = FIXTURES / f"{stem}.toml"
    r = reconfig.solve(reconfig.load_fixture(path))
    j = json.loads(cli("solve", path, "--json"))
    assert r.status == j["status"]
    assert r.usable is True
    assert r.cost == j[cost_key]  # the same double, not approximately
    assert r.work_units > 0


def test_a_hybrid_transfer_is_the_cli_answer_with_its_trajectory():
    path = FIXTURES / "hybrid-min-fuel-k140-4p38d.toml"
    r = reconfig.solve(reconfig.load_fixture(path))
    j = json.loads(cli("solve", path, "--json"))
    assert r.status == j["status"] == "Solved"
    # The campaign's cost of a hybrid transfer is the propellant fraction 1 - m_f.
    assert r.cost == 1.0 - j["final_mass"]
    assert abs(j["final_mass"] - 0.3365) < 1e-4
    assert len(j["trajectory"]) == 401


def test_campaign_is_the_cli_table_whatever_the_threads():
    path = FIXTURES / "wang2018-gco-to-pco-2imp-roe.toml"
    f = reconfig.load_fixture(path)
    law = {"relative.initial_roe_m[1]": 50.0, "relative.initial_roe_m[2]": 20.0}
    one = reconfig.campaign(f, 40, disperse=law, seed=3, threads=1)
    two = reconfig.campaign(f, 40, disperse=law, seed=3, threads=2)
    for key in one:
        if key != "solve_time_s":
            assert np.array_equal(one[key], two[key]), key
    table = cli(
        "campaign", path, "--cases", 40, "--seed", 3, "--threads", 1, "--no-times", "--out", "-",
        "--disperse", "relative.initial_roe_m[1]=50.0", "--disperse", "relative.initial_roe_m[2]=20.0",
    )
    rows = list(csv.DictReader(io.StringIO(table)))
    assert len(rows) == 40
    for k, row in enumerate(rows):
        assert int(row["case"]) == one["case"][k]
        assert float(row["relative.initial_roe_m[1]"]) == one["relative.initial_roe_m[1]"][k]
        assert row["status"] == one["status"][k] == "Solved"
        assert float(row["cost"]) == one["cost"][k]
        assert int(row["work_units"]) == one["work_units"][k]


def test_a_case_saved_from_python_is_the_row_the_cli_solves():
    f = reconfig.load_fixture(FIXTURES / "huang2012-three-sats-n10.toml")
    law = {"spacecraft[1].initial[0]": 0.3}
    table = reconfig.campaign(f, 3, disperse=law, seed=5)
    case = reconfig.case_fixture(f, 2, disperse=law, seed=5)
    assert reconfig.solve(case).cost == table["cost"][2]


def test_refused_inputs_raise_and_name_what_is_wrong(tmp_path):
    f = reconfig.load_fixture(FIXTURES / "wang2018-gco-to-pco-2imp.toml")
    with pytest.raises(ValueError, match=r"path `impulse\[0\].revolutions` cannot be dispersed"):
        reconfig.campaign(f, 3, disperse={"impulse[0].revolutions": 1.0})
    with pytest.raises(ValueError, match="no key `semi_major`"):
        reconfig.campaign(f, 3, disperse={"chief.semi_major": 1.0})
    with pytest.raises(ValueError, match="cases = -1"):
        reconfig.campaign(f, -1)
    with pytest.raises(ValueError, match="seed = -3"):
        reconfig.campaign(f, 3, seed=-3)
    with pytest.raises(ValueError, match="threads = 1.5"):
        reconfig.campaign(f, 3, threads=1.5)
    with pytest.raises(ValueError, match="not finite"):
        reconfig.campaign(f, 3, disperse={"chief.eccentricity": float("nan")})
    with pytest.raises(ValueError, match="sigma = -1"):
        reconfig.campaign(f, 3, disperse={"chief.eccentricity": -1.0})
    bad = reconfig.Fixture(f.name, f.text.replace("eccentricity = 0.0678", "eccentricity = 1.5"))
    with pytest.raises(reconfig.Refused, match="Rejected: .*ccentricity 1.5") as e:
        reconfig.solve(bad)
    assert e.value.status == "Rejected"
    # A dispersed case the checks refuse is a row, named; the others are planned.
    t = reconfig.campaign(f, 200, disperse={"chief.eccentricity": 0.03}, seed=7)
    refused = t["status"] == "Rejected"
    assert 0 < refused.sum() < 100
    assert all("minimum of 100 km" in m for m in t["message"][refused])
    assert np.isnan(t["cost"][refused]).all() and (t["work_units"][refused] == -1).all()
    # A fixture saved from Python reads back as itself.
    f.save(tmp_path / "f.toml")
    assert reconfig.load_fixture(tmp_path / "f.toml").text == f.text


def test_the_type_stubs_name_what_the_extension_exports():
    import ast
    import inspect

    from reconfig import _reconfig

    stub = ast.parse((pathlib.Path(reconfig.__file__).parent / "_reconfig.pyi").read_text())
    stubbed = {
        node.name: [a.arg for a in node.args.args]
        for node in stub.body
        if isinstance(node, ast.FunctionDef)
    }
    exported = {n for n in dir(_reconfig) if not n.startswith("_")}
    assert set(stubbed) == exported
    for name, args in stubbed.items():
        # PyO3 gives each function its Rust signature's names (`text_signature`).
        assert list(inspect.signature(getattr(_reconfig, name)).parameters) == args, name
    assert (pathlib.Path(reconfig.__file__).parent / "py.typed").exists()
