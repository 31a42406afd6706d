"""Figures of the Python package (issue 32), in one run, written as the timing record
`fixtures/golden/tables/python-bench.md` with `--record` (docs/python.md shows it; the test
`docs_tables` fails when the two differ):

* the call overhead of `solve` and of `plan_a` (NumPy arrays in) against the answer's own time
  (`wire::answer`, as the Rust API times it, in the same call);
* a 100,000-case planner-B Monte Carlo's wall time and peak memory;
* campaign throughput on 1 thread and on every core, and on a Dask cluster of local worker
  processes (one per core), the answers checked the same each time.

    pip install ./python "dask[distributed]" && python python/examples/bench.py [--record]
"""

import datetime
import logging
import os
import pathlib
import resource
import statistics
import sys
import time

import numpy as np

import reconfig
import reconfig.cluster

ROOT = pathlib.Path(__file__).resolve().parents[2]


def overhead(call, n=2000):
    """Median wall time of a call and of the answer inside it (µs)."""
    walls, own = [], []
    for _ in range(n):
        t0 = time.perf_counter()
        r = call()
        walls.append(time.perf_counter() - t0)
        own.append(r.solve_time_s)
    return statistics.median(walls) * 1e6, statistics.median(own) * 1e6


def read(r):
    """The answer with its report read (every field converted, arrays made)."""
    assert r.report
    return r


def same(a, b):
    """Two campaign tables hold the same answers, bit for bit, times aside."""
    return all(
        np.array_equal(a[k].view(np.int64), b[k].view(np.int64)) if a[k].dtype == np.float64
        else np.array_equal(a[k], b[k])
        for k in a if k != "solve_time_s")


def main():
    os.chdir(ROOT)
    calls, campaigns = [], []
    f = reconfig.load_fixture("fixtures/wang2018-gco-to-pco-2imp-roe.toml")
    calls.append(("`solve(fixture)`, planner B at fixed points (the report left unread)",
                  *overhead(lambda: reconfig.solve(f))))
    calls.append(("`solve(fixture)` and its report read (`r.impulses`, ...)",
                  *overhead(lambda: read(reconfig.solve(f)))))
    x0 = np.array([[0, 0, 0, 0, 0, 0], [8, 0, 0, 0, 0, 0], [8, 0, 8, 0, 0, 0]], float)
    x1 = np.array([[12, 12, 12, 0, 0, 0], [0, 12, 12, 0, 0, 0], [0, 12, 0, 0, 0, 0]], float)
    calls.append(("`plan_a(arrays)`, Huang 2012 N = 10, trajectories read (`r.states`, ...)",
                  *overhead(lambda: read(reconfig.plan_a(x0, x1, 10.0, 1.0, 2.0, 10)), n=1000)))

    law = {"relative.initial_roe_m[1]": 50.0, "relative.initial_roe_m[2]": 20.0}
    t0 = time.perf_counter()
    t = reconfig.campaign(f, 100_000, disperse=law)
    wall = time.perf_counter() - t0
    peak_mb = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024
    cores = os.cpu_count() or 1
    campaigns.append(("`campaign`, planner B, fixed points", 100_000, f"{cores} threads",
                      100_000 / wall, "—", wall, peak_mb,
                      f"{int(t['usable'].sum())} usable"))

    a = reconfig.load_fixture("fixtures/huang2012-three-sats-n10.toml")
    law_a = {"spacecraft[0].initial[0]": 0.3, "spacecraft[2].final[1]": 0.3}
    n = 20_000
    tables, rates = {}, {}
    for threads in (1, cores):
        t0 = time.perf_counter()
        tables[threads] = reconfig.campaign(a, n, disperse=law_a, threads=threads)
        rates[threads] = n / (time.perf_counter() - t0)
    usable = f"{int(tables[1]['usable'].sum())} usable"
    campaigns.append(("`campaign`, planner A", n, "1 thread", rates[1], "1.00", n / rates[1],
                      None, usable))
    campaigns.append(("`campaign`, planner A", n, f"{cores} threads", rates[cores],
                      f"{rates[cores] / rates[1]:.2f}", n / rates[cores], None,
                      usable + ("; same answers" if same(tables[1], tables[cores]) else
                                "; ANSWERS DIFFER")))

    # Imported only now, so the peak memory above is the package's and NumPy's alone.
    from dask.distributed import Client, LocalCluster

    # silence_logs: a worker's heartbeat that meets the closing scheduler logs an error.
    with LocalCluster(n_workers=cores, threads_per_worker=1, processes=True,
                      dashboard_address=None, silence_logs=logging.CRITICAL) as cluster, \
            Client(cluster) as client:
        reconfig.cluster.campaign(a, 100, disperse=law_a, client=client)  # workers import it
        t0 = time.perf_counter()
        d = reconfig.cluster.campaign(a, n, disperse=law_a, client=client)
        rate = n / (time.perf_counter() - t0)
    campaigns.append((f"`cluster.campaign`, planner A, Dask `LocalCluster` of {cores} worker "
                      "processes", n, f"{cores} processes", rate, f"{rate / rates[1]:.2f}",
                      n / rate, None, usable + ("; same answers" if same(tables[1], d) else
                                                "; ANSWERS DIFFER")))

    load = os.getloadavg()[0]
    now = datetime.datetime.now(datetime.timezone.utc).strftime("%Y-%m-%d %H:%M UTC")
    lines = [
        f"Measured by `python python/examples/bench.py --record` on {now} ({cores} CPUs, load "
        f"average {load:.2f}), the package installed with `pip install ./python` (release). "
        "A call's time is the median over 2000 calls (1000 for `plan_a`); its answer is "
        "`wire::answer`'s time as the Rust API measures it inside the same call, the overhead "
        "the rest: the fixture's text parsed and checked, the report built and handed to "
        "Python (and read, where said). The throughput ratio is against one thread in the same "
        "run; peak memory is the process's largest resident set (the interpreter and NumPy "
        "included).",
        "",
        "| call | per call (µs) | the answer (µs) | overhead (µs) |",
        "| --- | ---: | ---: | ---: |",
    ]
    lines += [f"| {c} | {w:.1f} | {o:.1f} | {w - o:.1f} |" for c, w, o in calls]
    lines += [
        "",
        "| campaign | cases | on | cases/s | ratio | wall (s) | peak memory (MB) | answers |",
        "| --- | ---: | --- | ---: | ---: | ---: | ---: | --- |",
    ]
    lines += [
        f"| {c} | {k} | {on} | {r:.0f} | {ratio} | {w:.2f} | "
        f"{'—' if m is None else f'{m:.1f}'} | {ans} |"
        for c, k, on, r, ratio, w, m, ans in campaigns
    ]
    text = "\n".join(lines) + "\n"
    print(text)
    if "--record" in sys.argv[1:]:
        path = ROOT / "fixtures" / "golden" / "tables" / "python-bench.md"
        path.write_text(text)
        print(f"wrote {path.relative_to(ROOT)}")


# The Dask workers are processes that import this file: only the main one runs the figures.
if __name__ == "__main__":
    main()
