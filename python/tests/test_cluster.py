"""Campaigns from Python: 1,000 generated cases per planner are the CLI's table byte for byte,
and the same campaign on a Dask cluster of worker processes gives that table too (issue 32)."""

import subprocess

import numpy as np
import pytest

import reconfig
import reconfig.cluster

from test_reconfig import BIN, FIXTURES

# One dispersed campaign per planner: (fixture, --disperse laws, --uniform laws, cases).
CAMPAIGNS = {
    "planner-a": ("huang2012-three-sats-n10",
                  {"spacecraft[0].initial[0]": 0.3, "spacecraft[2].final[1]": 0.3},
                  {"horizon": (9.0, 12.0)}, 1000),
    "planner-b": ("wang2018-gco-to-pco-2imp-roe",
                  {"relative.initial_roe_m[1]": 50.0, "relative.initial_roe_m[2]": 20.0},
                  {"chief.eccentricity": (0.05, 0.08)}, 1000),
    "planner-b-search": ("wang2018-gco-to-pco-search-2imp",
                         {"relative.initial[3]": 2e-3}, {}, 1000),
    "geo-tour": ("geo-servicing-published-60d", {"targets_lon_deg[3]": 0.5},
                 {"mission_time_days": (50.0, 70.0)}, 1000),
    "leo-arc": ("leo-tour-example1-single-arc", {"clients[1][3]": 0.02}, {}, 200),
}


def cli_table(stem, disperse, uniform, cases, seed):
    args = [BIN, "campaign", str(FIXTURES / f"{stem}.toml"), "--cases", str(cases),
            "--seed", str(seed), "--no-times", "--out", "-"]
    for p, s in disperse.items():
        args += ["--disperse", f"{p}={s!r}"]
    for p, (lo, hi) in uniform.items():
        args += ["--uniform", f"{p}={lo!r}:{hi!r}"]
    out = subprocess.run(args, capture_output=True, text=True)
    assert out.returncode == 0, out.stderr
    return out.stdout


def same_columns(a, b):
    assert set(a) == set(b)
    for key in a:
        if key == "solve_time_s":
            continue
        if a[key].dtype == np.float64:  # bit for bit, NaN included
            assert np.array_equal(a[key].view(np.int64), b[key].view(np.int64)), key
        else:
            assert np.array_equal(a[key], b[key]), key


@pytest.mark.parametrize("kind", sorted(CAMPAIGNS))
def test_python_campaign_is_the_cli_table_byte_for_byte(kind, tmp_path):
    stem, disperse, uniform, cases = CAMPAIGNS[kind]
    f = reconfig.load_fixture(FIXTURES / f"{stem}.toml")
    t = reconfig.campaign(f, cases, disperse=disperse, uniform=uniform, seed=11,
                          out=tmp_path / "t.csv", times=False)
    assert (tmp_path / "t.csv").read_text() == cli_table(stem, disperse, uniform, cases, 11)
    assert len(t["case"]) == cases and t["usable"].mean() > 0.5, kind
    # The dispersed numbers moved and the answers differ from case to case.
    assert len(np.unique(t["cost"][t["usable"]])) > 0.9 * t["usable"].sum()


@pytest.fixture(scope="module")
def client():
    # Imported here so the other tests run without Dask; python/test.sh installs it, so in the
    # README's test command this fails rather than skips.
    from dask.distributed import Client, LocalCluster

    cluster = LocalCluster(n_workers=2, threads_per_worker=1, processes=True,
                           dashboard_address=None)
    with Client(cluster) as c:
        yield c
    cluster.close()


def test_dask_campaign_is_the_one_machine_table(client, tmp_path):
    stem, disperse, uniform, _ = CAMPAIGNS["planner-b"]
    f = reconfig.load_fixture(FIXTURES / f"{stem}.toml")
    one = reconfig.campaign(f, 300, disperse=disperse, uniform=uniform, seed=4,
                            out=tmp_path / "one.csv", times=False)
    many = reconfig.cluster.campaign(f, 300, disperse=disperse, uniform=uniform, seed=4,
                                     client=client, partitions=7, out=tmp_path / "dask.csv",
                                     times=False)
    same_columns(one, many)
    assert (tmp_path / "dask.csv").read_bytes() == (tmp_path / "one.csv").read_bytes()
    # Both workers took part (their processes answered partitions).
    assert len(client.scheduler_info()["workers"]) == 2
    # Planner A too, partitioned otherwise.
    stem, disperse, uniform, _ = CAMPAIGNS["planner-a"]
    f = reconfig.load_fixture(FIXTURES / f"{stem}.toml")
    same_columns(reconfig.campaign(f, 50, disperse=disperse, seed=2),
                 reconfig.cluster.campaign(f, 50, disperse=disperse, seed=2, client=client))


def test_dask_campaign_refuses_bad_input_before_sending_work(client):
    f = reconfig.load_fixture(FIXTURES / "wang2018-gco-to-pco-2imp.toml")
    with pytest.raises(ValueError, match="no key `semi_major`"):
        reconfig.cluster.campaign(f, 10, disperse={"chief.semi_major": 1.0}, client=client)
    with pytest.raises(ValueError, match="partitions = 0"):
        reconfig.cluster.campaign(f, 10, client=client, partitions=0)
    empty = reconfig.cluster.campaign(f, 0, client=client)
    assert len(empty["case"]) == 0


def test_partitions_cover_every_case_once():
    for cases in (0, 1, 7, 300):
        for parts in (1, 2, 7, 500):
            ranges = reconfig.cluster.partition(cases, parts)
            covered = [k for first, count in ranges for k in range(first, first + count)]
            assert covered == list(range(cases))
            assert len(ranges) <= parts and all(count > 0 for _, count in ranges)
