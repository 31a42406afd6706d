#!/usr/bin/env python3
"""Independent oracle for planner B's corrected plan: the two impulses that make the exact model
reach the target, for two-impulse fixtures (6 unknowns, 6 end conditions: the root is unique,
whatever path a solver takes to it). numpy only; shares no code with the Rust implementation.

Usage: python3 tests/oracle/planner_b_corrected.py fixtures/NAME.toml ... \
           > fixtures/golden/planner-b-corrected.json

Exact model (the planner's nonlinear check, written here from textbook formulas):
* between impulses the mean elements drift with the J2 secular rates (Wang 2018 eq. 4);
* impulse k happens when the deputy's mean argument of latitude u = omega + M reaches u_k after
  dN_k whole turns: dt = (wrap_2pi(u_k - u_now) + 2 pi dN_k) / (d omega/dt + dM/dt);
* at the impulse the mean elements are taken as osculating two-body elements: position and
  velocity from the perifocal frame rotated by R3(-Omega) R1(-i) R3(-omega), dv added along the
  radial, along-track (h x r / |h x r|) and normal (h / |h|) unit vectors, and back to elements;
* the end condition: deputy minus chief (drifted to the last impulse) equals the target relative
  elements, angles compared modulo 2 pi.
Newton's method with a central-difference Jacobian from dv = 0, to a scaled residual below 1e-13
(largest of |da|/a and the other element errors; the rounding floor of M after ~100 rad is ~1e-14).
"""
import json
import math
import sys
import tomllib

import numpy as np

MU = 398600.4418      # km^3/s^2
RE = 6378.137         # km
J2 = 1.08263e-3
D2R = math.pi / 180.0
TWO_PI = 2.0 * math.pi


def rates(s):
    a, e, i = s[0], s[1], s[2]
    n = math.sqrt(MU / a**3)
    eta = math.sqrt(1 - e * e)
    C = 3 * J2 * RE**2 / (2 * (1 - e * e) ** 2) * math.sqrt(MU / a**7)
    c = math.cos(i)
    return np.array([0, 0, 0, -C * c, C / 2 * (5 * c * c - 1), n + C / 2 * eta * (3 * c * c - 1)])


def true_anomaly(M, e):
    M = math.fmod(M, TWO_PI)
    E = M if e < 0.8 else math.pi
    for _ in range(60):
        E -= (E - e * math.sin(E) - M) / (1 - e * math.cos(E))
    return 2.0 * math.atan2(math.sqrt(1 + e) * math.sin(E / 2), math.sqrt(1 - e) * math.cos(E / 2))


def rot3(x):
    c, s = math.cos(x), math.sin(x)
    return np.array([[c, -s, 0], [s, c, 0], [0, 0, 1]])


def rot1(x):
    c, s = math.cos(x), math.sin(x)
    return np.array([[1, 0, 0], [0, c, -s], [0, s, c]])


def to_state(s):
    a, e, i, O, w, M = s
    f = true_anomaly(M, e)
    p = a * (1 - e * e)
    r = p / (1 + e * math.cos(f))
    q = rot3(O) @ rot1(i) @ rot3(w)
    r_pf = np.array([r * math.cos(f), r * math.sin(f), 0.0])
    v_pf = math.sqrt(MU / p) * np.array([-math.sin(f), e + math.cos(f), 0.0])
    return q @ r_pf, q @ v_pf


def near(x, ref):
    """x shifted by whole turns to within pi of ref."""
    return ref + math.remainder(x - ref, TWO_PI)


def to_elements(r, v, ref):
    rn = np.linalg.norm(r)
    h = np.cross(r, v)
    a = 1.0 / (2.0 / rn - v @ v / MU)
    evec = np.cross(v, h) / MU - r / rn
    e = np.linalg.norm(evec)
    i = math.acos(h[2] / np.linalg.norm(h))
    node = np.cross([0.0, 0.0, 1.0], h)
    O = math.atan2(node[1], node[0])
    nhat = node / np.linalg.norm(node)
    w = math.atan2(np.cross(nhat, evec) @ h / np.linalg.norm(h), nhat @ evec)
    f = math.atan2(np.cross(evec, r) @ h / np.linalg.norm(h), evec @ r)
    E = 2.0 * math.atan2(math.sqrt(1 - e) * math.sin(f / 2), math.sqrt(1 + e) * math.cos(f / 2))
    M = E - e * math.sin(E)
    return np.array([a, e, i, near(O, ref[3]), near(w, ref[4]), near(M, ref[5])])


def impulse(s, dv_rtn):
    r, v = to_state(s)
    h = np.cross(r, v)
    rh = r / np.linalg.norm(r)
    nh = h / np.linalg.norm(h)
    th = np.cross(nh, rh)
    return to_elements(r, v + dv_rtn[0] * rh + dv_rtn[1] * th + dv_rtn[2] * nh, s)


def fly(case, dv):
    """Deputy through the impulses; the end error, the impulse times."""
    chief, init, targ, points = case
    s = chief + init
    t = 0.0
    times = []
    for k, (u, dN) in enumerate(points):
        d = rates(s)
        dt = ((u - (s[4] + s[5])) % TWO_PI + TWO_PI * dN) / (d[4] + d[5])
        s = s + d * dt
        t += dt
        times.append(t)
        s = impulse(s, dv[3 * k:3 * k + 3])
    err = s - (chief + rates(chief) * t) - targ
    for k in (3, 4, 5):
        err[k] = math.remainder(err[k], TWO_PI)
    return err, times


def scaled(err, a):
    return max(abs(err[0]) / a, *(abs(x) for x in err[1:]))


def solve(case, fly_case=None):
    """Newton on the exact end condition from dv = 0, central-difference Jacobian, to a scaled
    residual below 1e-13. `fly_case(case, dv) -> (err, times)` is the exact model (this file's
    `fly` unless given: planner_b_nonsingular.py passes its equinoctial one); case[0][0] is a
    and case[3] the impulse points."""
    fly_case = fly if fly_case is None else fly_case
    a = case[0][0]
    dv = np.zeros(3 * len(case[3]))
    for it in range(40):
        err, times = fly_case(case, dv)
        if scaled(err, a) < 1e-13:
            return dv, times, it
        J = np.zeros((6, dv.size))
        h = 1e-7
        for j in range(dv.size):
            p = dv.copy(); m = dv.copy()
            p[j] += h; m[j] -= h
            J[:, j] = (fly_case(case, p)[0] - fly_case(case, m)[0]) / (2 * h)
        dv = dv - np.linalg.solve(J, err)
    raise RuntimeError("Newton did not converge")


def load(path):
    with open(path, "rb") as fh:
        f = tomllib.load(fh)
    c = f["chief"]
    chief = np.array([c["semi_major_axis_km"], c["eccentricity"], c["inclination_deg"] * D2R,
                      c["raan_deg"] * D2R, c["arg_perigee_deg"] * D2R, c["mean_anomaly_deg"] * D2R])
    unit = np.array([1.0, 1.0, D2R, D2R, D2R, D2R])
    init = np.array(f["relative"]["initial"]) * unit
    targ = np.array(f["relative"]["target"]) * unit
    points = [(p["arg_latitude_deg"] * D2R, p["revolutions"]) for p in f["impulse"]]
    if len(points) != 2:
        raise SystemExit(f"{path}: the oracle takes two-impulse fixtures (unique root)")
    return f["name"], (chief, init, targ, points)


if __name__ == "__main__":
    out = {"_comment": "Corrected two-impulse plans (exact impulses, J2 secular drift) from the "
                       "independent numpy oracle tests/oracle/planner_b_corrected.py, not from the "
                       "code under test. dv_rtn_mps: [radial, along-track, normal] per impulse, "
                       "m/s; times_s in the exact model."}
    for path in sys.argv[1:]:
        name, case = load(path)
        dv, times, it = solve(case)
        err, _ = fly(case, dv)
        out[name] = {
            "newton_iterations": it,
            "total_dv_mps": round(float(sum(np.linalg.norm(dv[3 * k:3 * k + 3]) for k in range(2)) * 1e3), 10),
            "times_s": [round(t, 6) for t in times],
            "dv_rtn_mps": [[round(float(x) * 1e3, 10) for x in dv[3 * k:3 * k + 3]] for k in range(2)],
            "scaled_residual": float(scaled(err, case[0][0])),
        }
    print(json.dumps(out, indent=1))
