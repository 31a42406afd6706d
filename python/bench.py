"""Figures of the Python package (issue 32), in one run: the call overhead of `solve` against
the answer's own time, and a 100,000-case planner-B Monte Carlo's wall time and peak memory.

    cd python && maturin develop --release && cd .. && python python/bench.py
"""

import resource
import statistics
import time

import reconfig

f = reconfig.load_fixture("fixtures/wang2018-gco-to-pco-2imp-roe.toml")
walls, own = [], []
for _ in range(2000):
    t0 = time.perf_counter()
    r = reconfig.solve(f)
    walls.append(time.perf_counter() - t0)
    own.append(r.solve_time_s)
w, o = statistics.median(walls) * 1e6, statistics.median(own) * 1e6
print(f"solve, planner B fixed points: {w:.1f} us a call, {o:.1f} us of it the answer "
      f"(wire::answer, as the Rust API times it): {w - o:.1f} us of overhead (fixture parse, "
      f"checks, conversion)")
t0 = time.perf_counter()
t = reconfig.campaign(f, 100_000, disperse={"relative.initial_roe_m[1]": 50.0,
                                            "relative.initial_roe_m[2]": 20.0})
wall = time.perf_counter() - t0
peak_mb = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024
print(f"campaign, 100,000 planner-B cases: {wall:.2f} s, {len(t['case']) / wall:.0f} cases/s, "
      f"{int(t['usable'].sum())} usable, peak resident set {peak_mb:.1f} MB")
