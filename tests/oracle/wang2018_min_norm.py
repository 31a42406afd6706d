#!/usr/bin/env python3
"""Independent oracle for planner B (Wang 2018): minimum-norm fixed-point impulses at the paper's
impulse points, written from the paper's equations with numpy (dense SVD pseudo-inverse), sharing
no code with the Rust implementation.

Usage: python3 tests/oracle/wang2018_min_norm.py > fixtures/golden/wang2018-min-norm.json

Model (the issue's errata): chief a = 7178.137 km; relative elements in km, -, deg; impulse times
dt_k = (wrap_2pi(u_k - u_now) + 2 pi dN_k) / n_J2 from the deputy's own mean elements; linear
GVE impulses (eq. 6); F = [P_k B_k], P_k = I_6 + dD (t_N - t_k) with dD by central differences
of the secular rates (not the paper's printed M_3x3); dX = pinv(F) dY (numpy SVD), iterated.
Table 5's fixture uses the mean arguments of latitude of the deputy at the printed times
(impulse_latitudes() below); the printed u column is the true argument of latitude.
"""
import math
import numpy as np

MU = 398600.4418      # km^3/s^2
RE = 6378.137         # km
J2 = 1.08263e-3
D2R = math.pi / 180.0

CHIEF = [7178.137, 0.0678, 63.4349 * D2R, 112.0 * D2R, 0.0, 0.0]
INIT = [4.0940e-4, -1.3888e-4, -1.0831e-3 * D2R, 1.5409e-2 * D2R, -1.6134e-2 * D2R, 9.2428e-3 * D2R]
TARG = [-1.6389e-4, 5.5597e-4, 4.3361e-3 * D2R, 7.1228e-2 * D2R, -6.3572e-2 * D2R, 3.1718e-2 * D2R]


def wrap2pi(x):
    return x % (2.0 * math.pi)


def kepler_true_anomaly(M, e):
    M = math.fmod(M, 2 * math.pi)
    E = M if e < 0.8 else math.pi
    for _ in range(50):
        E -= (E - e * math.sin(E) - M) / (1 - e * math.cos(E))
    return 2.0 * math.atan2(math.sqrt(1 + e) * math.sin(E / 2), math.sqrt(1 - e) * math.cos(E / 2))


def rates(s):
    a, e, i = s[0], s[1], s[2]
    n = math.sqrt(MU / a**3)
    eta = math.sqrt(1 - e * e)
    C = 3 * J2 * RE**2 / (2 * (1 - e * e) ** 2) * math.sqrt(MU / a**7)
    c = math.cos(i)
    return np.array([0, 0, 0, -C * c, C / 2 * (5 * c * c - 1), n + C / 2 * eta * (3 * c * c - 1)])


def rates_jacobian(s, h=None):
    """Exact derivative of rates() w.r.t. (a, e, i), by complex-free central differences at
    relative step 1e-6, which is accurate to ~1e-12 relative here and independent of the paper's
    printed M_3x3."""
    J = np.zeros((6, 6))
    for col, step in ((0, 1e-3), (1, 1e-7), (2, 1e-7)):
        sp = list(s); sm = list(s)
        sp[col] += step; sm[col] -= step
        J[:, col] = (rates(sp) - rates(sm)) / (2 * step)
    return J


def gve(s):
    a, e, i, O, w, M = s
    f = kepler_true_anomaly(M, e)
    p = a * (1 - e * e)
    h = math.sqrt(MU * p)
    r = p / (1 + e * math.cos(f))
    th = w + f
    eta = math.sqrt(1 - e * e)
    sf, cf = math.sin(f), math.cos(f)
    # columns: along-track, radial, normal (the paper's u = [u_theta, u_r, u_h]); km/s -> element
    B = np.array([
        [2 * a * a * p / (h * r), 2 * a * a * e * sf / h, 0],
        [((p + r) * cf + r * e) / h, p * sf / h, 0],
        [0, 0, r * math.cos(th) / h],
        [0, 0, r * math.sin(th) / (h * math.sin(i))],
        [(p + r) * sf / (h * e), -p * cf / (h * e), -r * math.cos(i) * math.sin(th) / (h * math.sin(i))],
        [-eta * (p + r) * sf / (h * e), eta * (p * cf - 2 * r * e) / (h * e), 0],
    ])
    return B


def n_j2(s):
    d = rates(s)
    return d[4] + d[5]


def solve(points, times=None, iters=30):
    chief = np.array(CHIEF)
    dep0 = chief + np.array(INIT)
    N = len(points)
    dv = np.zeros((N, 3))  # along, radial, normal in km/s
    for it in range(iters):
        s = dep0.copy()
        t = 0.0
        u_prev = s[4] + s[5]
        tk, sk0, sprev = [], [], []
        for k, (u, dN) in enumerate(points):
            if times is None:
                dt = (wrap2pi(u - u_prev) + 2 * math.pi * dN) / n_j2(s)
            else:
                dt = times[k] - t
            sprev.append(s.copy())
            s = s + rates(s) * dt
            t += dt
            tk.append(t)
            sk0.append(s.copy())
            s = s + gve(s) @ dv[k]
            u_prev = s[4] + s[5]
        tN = tk[-1]
        F = np.zeros((6, 3 * N))
        for k in range(N):
            P = np.eye(6) + rates_jacobian(sprev[k]) * (tN - tk[k])
            F[:, 3 * k:3 * k + 3] = P @ gve(sk0[k])
        dY = np.array(TARG) - np.array(INIT) - (rates(dep0) - rates(chief)) * tN
        new = (np.linalg.pinv(F) @ dY).reshape(N, 3)
        change = np.max(np.abs(new - dv))
        dv = new
        if change < 1e-15:
            break
    total = sum(np.linalg.norm(v) for v in dv) * 1000.0
    return total, dv * 1000.0, tk, it + 1


CASES = {
    "wang2018-gco-to-pco-3imp": ([(274.155, 2), (238.864, 10), (285.649, 2)], None),
    "wang2018-gco-to-pco-2imp": ([(274.787, 14), (223.964, 0)], None),
    "wang2018-gco-to-pco-4imp": ([(266.683882912, 2), (281.328967107, 4), (236.538571157, 5),
                                  (287.665882973, 2)], None),
}

TABLE5_TRUE_U = [(259.004, 2), (273.606, 4), (230.339, 5), (280.045, 2)]
TABLE5_TIMES = [16592.786, 41054.099, 76629.552, 89593.915]

def impulse_latitudes(points, times):
    """Mean (omega + M) and true (omega + f) arguments of latitude of the deputy just before each
    impulse of the converged solution, in degrees."""
    _, dv, _, _ = solve(points, times)
    dv = dv / 1000.0
    chief = np.array(CHIEF)
    s = chief + np.array(INIT)
    t = 0.0
    out = []
    for k in range(len(points)):
        s = s + rates(s) * (times[k] - t)
        t = times[k]
        mean_u = wrap2pi(s[4] + s[5]) / D2R
        true_u = wrap2pi(s[4] + kepler_true_anomaly(s[5], s[1])) / D2R
        out.append((mean_u, true_u))
        s = s + gve(s) @ dv[k]
    return out


if __name__ == "__main__":
    import json
    out = {
        "_comment": "Golden minimum-norm fixed points at the paper's impulse points, from the "
                    "independent numpy oracle tests/oracle/wang2018_min_norm.py (not from the code "
                    "under test). dv_rtn_mps: [radial, along-track, normal] per impulse, m/s.",
    }
    for name, (pts, times) in CASES.items():
        pts_rad = [(u * D2R, n) for u, n in pts]
        total, dv, tk, it = solve(pts_rad, times)
        out[name] = {
            "oracle_iterations": it,
            "min_norm_total_dv_mps": round(float(total), 10),
            "times_s": [round(float(t), 6) for t in tk],
            "dv_rtn_mps": [[round(float(v[1]), 9), round(float(v[0]), 9), round(float(v[2]), 9)] for v in dv],
        }
    pts = [(u * D2R, n) for u, n in TABLE5_TRUE_U]
    lat = impulse_latitudes(pts, TABLE5_TIMES)
    out["table5"] = {
        "_comment": "deputy's mean / true argument of latitude (deg) at Table 5's printed times",
        "mean_u_deg": [round(m, 9) for m, _ in lat],
        "true_u_deg": [round(t, 9) for _, t in lat],
    }
    print(json.dumps(out, indent=1))
