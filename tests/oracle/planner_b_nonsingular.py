#!/usr/bin/env python3
"""Independent oracle for planner B's corrected plan on circular and equatorial orbits, in
equinoctial mean elements: the two impulses that make the exact model reach the target, for
two-impulse fixtures (6 unknowns, 6 end conditions: the root is unique). numpy only; shares no
code with the Rust implementation, and takes other routes where it can (Kepler's equation in the
eccentric longitude, the orbit frame from the angular momentum vector).

Usage: python3 tests/oracle/planner_b_nonsingular.py fixtures/NAME.toml ... \
           > fixtures/golden/planner-b-nonsingular.json

Exact model (the planner's nonlinear check in docs/planner-b.md, written here from textbook
formulas):
* elements q = (a, lambda, ex, ey, hx, hy): lambda = M + omega + Omega, (ex, ey) = e (cos, sin)
  (omega + Omega), (hx, hy) = tan(i/2) (cos, sin) Omega;
* between impulses q drifts with the J2 secular rates (Wang 2018 eq. 4): lambda at
  n + dM/dt + domega/dt + dOmega/dt, (ex, ey) turned at domega/dt + dOmega/dt, (hx, hy) turned at
  dOmega/dt;
* impulse k happens when the deputy's phase reaches phi_k after dN_k whole turns:
  dt = (wrap_2pi(phi_k - phi_now) + 2 pi dN_k) / (d phi/dt), phi the mean argument of latitude
  lambda - Omega, or the mean longitude lambda when the chief is equatorial (|sin i| < 1e-3);
* at the impulse the mean elements are osculating two-body elements: position and velocity, dv
  added along the radial, along-track and normal unit vectors, back to elements;
* the end condition: the deputy equals the target orbit at the last impulse, which is the chief
  plus the fixture's relative classical elements at the epoch, drifted with the chief's rates.
Newton's method with a central-difference Jacobian from dv = 0, to a scaled residual below
1e-13 (largest of |da|/a and the other element errors).
"""
import json
import math
import os
import sys
import tomllib

import numpy as np

# The constants, the residual scale and the Newton driver are the classical oracle's; the exact
# model (elements, drift, impulse) is written here in equinoctial elements.
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from planner_b_corrected import D2R, J2, MU, RE, TWO_PI, scaled  # noqa: E402
from planner_b_corrected import solve as newton  # noqa: E402

EQUATORIAL_SIN_I = 1e-3


def from_classical(c):
    a, e, i, O, w, M = c
    t = math.tan(i / 2)
    return np.array([a, M + w + O, e * math.cos(w + O), e * math.sin(w + O),
                     t * math.cos(O), t * math.sin(O)])


def classical_rates(q):
    """(n + dM/dt, domega/dt, dOmega/dt) of q."""
    a = q[0]
    e2 = q[2] ** 2 + q[3] ** 2
    i = 2 * math.atan(math.hypot(q[4], q[5]))
    n = math.sqrt(MU / a**3)
    C = 3 * J2 * RE**2 / (2 * (1 - e2) ** 2) * math.sqrt(MU / a**7)
    c = math.cos(i)
    return (n + C / 2 * math.sqrt(1 - e2) * (3 * c * c - 1), C / 2 * (5 * c * c - 1), -C * c)


def turn(x, y, ang):
    c, s = math.cos(ang), math.sin(ang)
    return c * x - s * y, s * x + c * y


def drift(q, dt, rates_of=None):
    m, w, O = classical_rates(q if rates_of is None else rates_of)
    ex, ey = turn(q[2], q[3], (w + O) * dt)
    hx, hy = turn(q[4], q[5], O * dt)
    return np.array([q[0], q[1] + (m + w + O) * dt, ex, ey, hx, hy])


def phase(q, equatorial):
    return q[1] if equatorial else q[1] - math.atan2(q[5], q[4])


def phase_rate(q, equatorial):
    m, w, O = classical_rates(q)
    return m + w + O if equatorial else m + w


def basis(q):
    """Unit vectors f, g of the equinoctial frame: the node rotation applied to x, y."""
    O = math.atan2(q[5], q[4])
    i = 2 * math.atan(math.hypot(q[4], q[5]))
    cO, sO, ci, si = math.cos(O), math.sin(O), math.cos(i), math.sin(i)
    # R3(O) R1(i) R3(-O): the orbit plane's axes with the longitude origin kept at the node's -O.
    R = (np.array([[cO, -sO, 0], [sO, cO, 0], [0, 0, 1]])
         @ np.array([[1, 0, 0], [0, ci, -si], [0, si, ci]])
         @ np.array([[cO, sO, 0], [-sO, cO, 0], [0, 0, 1]]))
    return R[:, 0], R[:, 1], R[:, 2]


def to_state(q):
    a, lam, ex, ey = q[0], q[1], q[2], q[3]
    K = lam
    for _ in range(60):  # eccentric longitude: lambda = K + ey cos K - ex sin K
        K -= (K + ey * math.cos(K) - ex * math.sin(K) - lam) / (1 - ey * math.sin(K) - ex * math.cos(K))
    e2 = ex * ex + ey * ey
    b = 1 / (1 + math.sqrt(1 - e2))
    n = math.sqrt(MU / a**3)
    r = a * (1 - ex * math.cos(K) - ey * math.sin(K))
    X = a * ((1 - ey * ey * b) * math.cos(K) + ex * ey * b * math.sin(K) - ex)
    Y = a * ((1 - ex * ex * b) * math.sin(K) + ex * ey * b * math.cos(K) - ey)
    Xd = a * a * n / r * (ex * ey * b * math.cos(K) - (1 - ey * ey * b) * math.sin(K))
    Yd = a * a * n / r * ((1 - ex * ex * b) * math.cos(K) - ex * ey * b * math.sin(K))
    f, g, _ = basis(q)
    return X * f + Y * g, Xd * f + Yd * g


def to_elements(r, v, ref):
    rn = np.linalg.norm(r)
    h = np.cross(r, v)
    w = h / np.linalg.norm(h)
    a = 1.0 / (2.0 / rn - v @ v / MU)
    hx = -w[1] / (1 + w[2])
    hy = w[0] / (1 + w[2])
    q = np.array([a, 0.0, 0.0, 0.0, hx, hy])
    f, g, _ = basis(q)
    evec = np.cross(v, h) / MU - r / rn
    ex, ey = evec @ f, evec @ g
    X, Y = r @ f, r @ g
    e2 = ex * ex + ey * ey
    b = 1 / (1 + math.sqrt(1 - e2))
    s = math.sqrt(1 - e2)
    sK = ey + ((1 - ey * ey * b) * Y - ex * ey * b * X) / (a * s)
    cK = ex + ((1 - ex * ex * b) * X - ex * ey * b * Y) / (a * s)
    K = math.atan2(sK, cK)
    lam = K + ey * math.cos(K) - ex * math.sin(K)
    q[1] = ref[1] + math.remainder(lam - ref[1], TWO_PI)
    q[2], q[3] = ex, ey
    return q


def impulse(q, dv_rtn):
    r, v = to_state(q)
    h = np.cross(r, v)
    rh = r / np.linalg.norm(r)
    nh = h / np.linalg.norm(h)
    th = np.cross(nh, rh)
    return to_elements(r, v + dv_rtn[0] * rh + dv_rtn[1] * th + dv_rtn[2] * nh, q)


def fly(case, dv):
    """Deputy through the impulses; the end error, the impulse times."""
    chief, deputy0, target0, points, equatorial = case
    s = deputy0.copy()
    t = 0.0
    times = []
    for k, (u, dN) in enumerate(points):
        dt = ((u - phase(s, equatorial)) % TWO_PI + TWO_PI * dN) / phase_rate(s, equatorial)
        s = drift(s, dt)
        t += dt
        times.append(t)
        s = impulse(s, dv[3 * k:3 * k + 3])
    err = s - drift(target0, t, rates_of=chief)
    err[1] = math.remainder(err[1], TWO_PI)
    return err, times


def solve(case):
    return newton(case, fly_case=fly)


def load(path):
    with open(path, "rb") as fh:
        f = tomllib.load(fh)
    c = f["chief"]
    chief_c = np.array([c["semi_major_axis_km"], c["eccentricity"], c["inclination_deg"] * D2R,
                        c["raan_deg"] * D2R, c["arg_perigee_deg"] * D2R,
                        c["mean_anomaly_deg"] * D2R])
    unit = np.array([1.0, 1.0, D2R, D2R, D2R, D2R])
    init = np.array(f["relative"]["initial"]) * unit
    targ = np.array(f["relative"]["target"]) * unit
    equatorial = abs(math.sin(chief_c[2])) < EQUATORIAL_SIN_I and math.cos(chief_c[2]) > 0
    key = "mean_longitude_deg" if equatorial else "arg_latitude_deg"
    points = [(p[key] * D2R, p["revolutions"]) for p in f["impulse"]]
    if len(points) != 2:
        raise SystemExit(f"{path}: the oracle takes two-impulse fixtures (unique root)")
    case = (from_classical(chief_c), from_classical(chief_c + init), from_classical(chief_c + targ),
            points, equatorial)
    return f["name"], case


if __name__ == "__main__":
    out = {"_comment": "Corrected two-impulse plans (exact impulses, J2 secular drift, equinoctial "
                       "elements) from the independent numpy oracle "
                       "tests/oracle/planner_b_nonsingular.py, not from the code under test. "
                       "dv_rtn_mps: [radial, along-track, normal] per impulse, m/s; times_s in "
                       "the exact model; end_position_error_m: the flown plan's distance from "
                       "the target orbit's position at the last impulse."}
    for path in sys.argv[1:]:
        name, case = load(path)
        dv, times, it = solve(case)
        err, _ = fly(case, dv)
        # Independent end check: fly the rounded plan and compare positions.
        dv_r = np.array([round(float(x) * 1e3, 10) / 1e3 for x in dv])
        err_r, times_r = fly(case, dv_r)
        tgt = drift(case[2], times_r[-1], rates_of=case[0])
        end = tgt + err_r
        end_err_m = float(np.linalg.norm(to_state(end)[0] - to_state(tgt)[0]) * 1e3)
        out[name] = {
            "newton_iterations": it,
            "total_dv_mps": round(float(sum(np.linalg.norm(dv[3 * k:3 * k + 3]) for k in range(2)) * 1e3), 10),
            "times_s": [round(t, 6) for t in times],
            "dv_rtn_mps": [[round(float(x) * 1e3, 10) for x in dv[3 * k:3 * k + 3]] for k in range(2)],
            "scaled_residual": float(scaled(err, case[0][0])),
            "end_position_error_m": end_err_m,
        }
    print(json.dumps(out, indent=1))
