"""An analyst's session with reconfig (docs/python.md shows it; python/tests run it): planner A
and planner B from arrays, a LEO tour from its fixture, a dispersed campaign, its plots.

    python python/examples/session.py OUT_DIR      # from the repository's root
"""

import sys
from pathlib import Path

import matplotlib

matplotlib.use("Agg")  # files, no display
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

import reconfig  # noqa: E402

out = Path(sys.argv[1] if len(sys.argv) > 1 else ".")

# Planner A from arrays: three spacecraft swap places (Huang 2012), states [x y z vx vy vz].
x0 = np.array([[0, 0, 0, 0, 0, 0], [8, 0, 0, 0, 0, 0], [8, 0, 8, 0, 0, 0]], float)
x1 = np.array([[12, 12, 12, 0, 0, 0], [0, 12, 12, 0, 0, 0], [0, 12, 0, 0, 0, 0]], float)
a = reconfig.plan_a(x0, x1, horizon=10.0, max_control=1.0, keep_out=2.0, nodes=10)
print(f"planner A: {a.status}, J = {a.cost:.6f}, states {a.states.shape}, "
      f"min separation {a.min_separation:.6f}, "
      f"reduced-Hessian eigenvalue {a.certificate['min_reduced_eigenvalue']:.4f}")
fig, ax = plt.subplots()
for k in range(a.states.shape[0]):
    ax.plot(a.states[k, :, 0], a.states[k, :, 1], "o-", label=f"spacecraft {k + 1}")
ax.set_xlabel("x, LU"); ax.set_ylabel("y, LU"); ax.legend(); ax.set_aspect("equal")
fig.savefig(out / "planner-a-xy.png")

# Planner B from arrays: mean chief elements (a km, e, i, RAAN, argp, M in degrees), the
# relative state as ROE in metres, two fixed impulse points [u deg, whole revolutions].
chief = [7178.137, 0.0678, 63.4349, 112.0, 0.0, 0.0]
roe0_m = [0.4094, -0.00926622, -996.918922, -136.763542, -135.693069, 1726.666146]
roe1_m = [-0.16389, 0.02308541, 3990.526802, -544.416585, 543.235821, 7981.502775]
b = reconfig.plan_b(chief, roe0_m, roe1_m, form="roe_m", impulses=[[274.787, 14], [223.964, 0]])
print(f"planner B: {b.status}, total dv {b.total_dv_mps:.5f} m/s, first burn RTN "
      f"{np.round(b.impulses[0]['dv_rtn_mps'], 5)} m/s, terminal error {b.terminal_error_m:.2e} m")

# Any fixture, a LEO tour too: the result's fields are `reconfig solve --json`'s.
r = reconfig.solve(reconfig.load_fixture("fixtures/leo-tour-example1-single-arc.toml"))
print(f"LEO tour: {r.status}, {r.cost:.3f} m/s, arcs {[round(x['dv_mps'], 3) for x in r.arcs]}")

# 2,000 dispersed planner-B cases on every core: columns as NumPy arrays, one entry per case.
f = reconfig.load_fixture("fixtures/wang2018-gco-to-pco-2imp-roe.toml")
law = {"relative.initial_roe_m[1]": 50.0, "relative.initial_roe_m[2]": 20.0}  # the file's units
t = reconfig.campaign(f, cases=2_000, seed=1, disperse=law, out=out / "cases.csv")
print(f"campaign: {t['usable'].sum()} of {len(t['case'])} usable, total dv "
      f"{np.nanmin(t['cost']):.4f} .. {np.nanmax(t['cost']):.4f} m/s")
fig, ax = plt.subplots()
ax.scatter(t["relative.initial_roe_m[2]"], t["cost"], s=2)
ax.set_xlabel("a d(e cos omega) at the start, m"); ax.set_ylabel("total dv, m/s")
fig.savefig(out / "campaign-dv.png")

# Case 17 as a fixture: `reconfig solve case17.toml` gives row 17 again.
reconfig.case_fixture(f, 17, disperse=law).save(out / "case17.toml")
