#!/usr/bin/env python3
"""Independent oracle for the LEO tour's per-arc rendezvous (issue 13).

Reads a `reconfig solve FIXTURE --json` output of a leo-tour fixture (the burns: epochs and RTN
components) and the fixture (the clients' Table 1 elements), and flies each arc with its own
code: classical elements -> inertial state, a two-body + J2 force (mu 398600.4418 km^3/s^2,
Re 6378.137 km, J2 1.08263e-3), SciPy's DOP853 at rtol 1e-13 / atol 1e-9 km, the burns applied
in the chaser's radial / along-track / normal frame. It reports each arc's arrival miss (the
chaser against the client flown in the same model) and writes the golden file.

Nothing here calls the code under test: the burns are its inputs, the miss is the oracle's.

Usage:
  reconfig solve fixtures/leo-tour-example1-single-arc.toml --json > plan.json
  python3 tests/oracle/leo_tour_j2.py fixtures/leo-tour-example1-single-arc.toml plan.json \
      > fixtures/golden/leo-tour-example1-single-arc-oracle.toml
"""
import json
import sys
import tomllib

import numpy as np
from scipy.integrate import solve_ivp

MU, RE, J2 = 398600.4418, 6378.137, 1.08263e-3


def state_of(a, e, i, raan, argp, nu):
    i, raan, argp, nu = np.radians([i, raan, argp, nu])
    p = a * (1 - e * e)
    r = p / (1 + e * np.cos(nu))
    rp = np.array([r * np.cos(nu), r * np.sin(nu), 0.0])
    vp = np.sqrt(MU / p) * np.array([-np.sin(nu), e + np.cos(nu), 0.0])

    def rot(axis, ang):
        c, s = np.cos(ang), np.sin(ang)
        if axis == 3:
            return np.array([[c, -s, 0], [s, c, 0], [0, 0, 1]])
        return np.array([[1, 0, 0], [0, c, -s], [0, s, c]])

    q = rot(3, raan) @ rot(1, i) @ rot(3, argp)
    return np.concatenate([q @ rp, q @ vp])


def rhs(_t, y):
    r = y[:3]
    rn = np.linalg.norm(r)
    z2 = (r[2] / rn) ** 2
    k = -1.5 * J2 * MU * RE**2 / rn**5
    a = -MU * r / rn**3 + k * r * np.array([1 - 5 * z2, 1 - 5 * z2, 3 - 5 * z2])
    return np.concatenate([y[3:], a])


def fly(y, t0, t1):
    if t1 <= t0:
        return y
    sol = solve_ivp(rhs, (t0, t1), y, method="DOP853", rtol=1e-13, atol=1e-9)
    return sol.y[:, -1]


def rtn_to_eci(y, dv_rtn_mps):
    r, v = y[:3], y[3:]
    ir = r / np.linalg.norm(r)
    h = np.cross(r, v)
    ih = h / np.linalg.norm(h)
    it = np.cross(ih, ir)
    d = np.array(dv_rtn_mps) / 1e3
    return d[0] * ir + d[1] * it + d[2] * ih


def main():
    fixture = tomllib.load(open(sys.argv[1], "rb"))
    plan = json.load(open(sys.argv[2]))
    clients = [state_of(*c) for c in fixture["clients"]]
    print(f"# Oracle: tests/oracle/leo_tour_j2.py {sys.argv[1]} <plan.json>")
    print("# Burns: the plan under test (inputs); miss: this oracle's own J2 flight (DOP853).")
    print(f'fixture = "{fixture["name"]}"')
    for arc in plan["arcs"]:
        t0, t1 = arc["start_s"], arc["end_s"]
        chaser = fly(clients[arc["from"] - 1], 0.0, t0)
        client = fly(clients[arc["to"] - 1], 0.0, t1)
        t = t0
        for b in arc["burns"]:
            chaser = fly(chaser, t, b["epoch_s"])
            t = b["epoch_s"]
            chaser = chaser.copy()
            chaser[3:] += rtn_to_eci(chaser, b["dv_rtn_mps"])
        chaser = fly(chaser, t, t1)
        miss_m = np.linalg.norm(chaser[:3] - client[:3]) * 1e3
        dv_miss_mps = np.linalg.norm(chaser[3:] - client[3:]) * 1e3
        print()
        print("[[arcs]]")
        print(f'from = {arc["from"]}')
        print(f'to = {arc["to"]}')
        print(f'epochs_s = {[b["epoch_s"] for b in arc["burns"]]!r}')
        print(f'dv_rtn_mps = {[list(b["dv_rtn_mps"]) for b in arc["burns"]]!r}')
        print(f'dv_mps = {arc["dv_mps"]!r}')
        print(f"oracle_miss_m = {miss_m:.6f}")
        print(f"oracle_velocity_miss_mps = {dv_miss_mps:.6f}")


if __name__ == "__main__":
    main()
