#!/usr/bin/env python3
"""Independent SciPy oracle for the hybrid (chemical + electric) CR3BP transfer planner.

Usage:
python tests/oracle/hybrid_scipy.py [--reconfig target/debug/reconfig] [--out fixtures/golden/hybrid-oracle.json]

(run from the repository root with a Python that has numpy and scipy, e.g. /tmp/hybvenv/bin/python)

For every fixture fixtures/hybrid-*.toml:
  a. take OUR answer (`reconfig solve FILE --json`) and fly its departure costates with
     scipy's DOP853 (rtol 1e-13, atol 1e-15) from this file's own departure state; the throttle
     regime changes (S = 0 for minimum fuel, S = +-eps for the smoothed law) are located by
     solve_ivp's events and the integration restarted there;
  b. run this file's OWN shooting (scipy.optimize.root, MINPACK 'hybr', central-difference
     Jacobian written here) from our answer (every unknown: costates, kappa, l0, t_f) multiplied
     by 1 + d (+1, -1, +1, ...), d = 1e-3 first; where that start is outside the oracle's basin
     (the bang-bang shootings: ours fails from there too, which is recorded by running OUR
     planner from the same start), d = 1e-4, 1e-5, 1e-6 in turn; every attempt is recorded;
  c. run OUR solve 5 times and keep the median of its "solve_time_s".
Writes one JSON object: a "header" (command, versions, date) and "cases" by fixture name.

Model, written from SPEC-hybrid.md (the digest) alone; nothing is shared with core/src/hybrid:
  state y = [r, v, m, lr, lv, lm] (14), rotating frame, Earth at (-mu,0,0), Moon at (1-mu,0,0)
  r' = v,  v' = g(r) + (2vy, -2vx, 0) + u T/m a,  m' = -u T/c,  a = -lv/|lv|
  lr' = -G lv,  lv' = -lr - (-2 lv_y, 2 lv_x, 0),  lm' = -u T |lv|/m^2
  S = 1 - c|lv|/m - lm;  min fuel u = [S < 0];  min energy (eps = 1) u = clamp((eps-S)/(2eps));
  min time u = 1, unknowns p = [l0, lambda] on |p| = 1 and t_f, extra residual H(t_f) + l0 with
  H = lr.v + lv.(g+h) - T|lv|/m - lm T/c.
  kappa free: residual adds dTheta/dkappa + lambda(t0).dx0/dkappa (Theta = 1 - m0(kappa), both
  derivatives by central differences of this file's departure function).
"""
import argparse
import datetime
import json
import math
import platform
import re
import statistics
import subprocess
import sys
import tempfile
import time
import tomllib
from pathlib import Path

import numpy as np
import scipy
from scipy.integrate import solve_ivp
from scipy.optimize import root

# ---------------------------------------------------------------- constants (Table 1) ----------
MU = 1.21506683e-2          # Moon's share of the Earth-Moon mass
LU_KM = 384405.0            # km
TU_S = 375676.967           # s (27.32 d / 2 pi, the paper's)
MU_KG = 3000.0              # kg, before the impulse
G0 = 9.80665                # m/s^2
VU_KMPS = LU_KM / TU_S      # km/s
RTOL, ATOL = 1e-13, 1e-15
DAY_TU = 86400.0 / TU_S     # one day in TU


def force_fu(thrust_n):
    """Newtons -> MU LU / TU^2."""
    return thrust_n / (MU_KG * LU_KM * 1e3 / TU_S ** 2)


def exhaust_vu(isp_s):
    """Specific impulse (s) -> exhaust speed in LU/TU."""
    return isp_s * G0 * 1e-3 / VU_KMPS


# ---------------------------------------------------------------- departure (eq. 4) ------------
def departure(kappa, theta, fx):
    """State [r, v, m] just after a tangential impulse kappa (speed ratio) at phase theta.
    Built from the inertial picture: the frames coincide at t0, the Earth moves at omega x r_E;
    the rotating velocity is the inertial one minus omega x r (omega = z)."""
    r0 = fx["parking_radius_km"] / LU_KM
    vc = math.sqrt((1.0 - MU) / r0)
    c1 = exhaust_vu(fx["chemical_specific_impulse_s"])
    ex, ey = math.cos(theta), math.sin(theta)
    x, y = r0 * ex - MU, r0 * ey                      # barycentric position
    vin = (0.0 - kappa * vc * ey, -MU + kappa * vc * ex)  # Earth's velocity (0,-mu) + kappa vc t
    v = (vin[0] + y, vin[1] - x)                      # minus omega x r = (-y, x)
    m0 = math.exp(-(kappa - 1.0) * vc / c1)
    off = fx.get("departure_offset", {})
    dr = [d / LU_KM for d in off.get("position_km", [0, 0, 0])]
    dv = [d * 1e-3 / VU_KMPS for d in off.get("velocity_mps", [0, 0, 0])]
    dm = off.get("mass_kg", 0.0) / MU_KG
    return np.array([x + dr[0], y + dr[1], dr[2], v[0] + dv[0], v[1] + dv[1], dv[2], m0 + dm])


def chem_cost(kappa, fx):
    """Theta(kappa) = 1 - m0(kappa), the chemical propellant (normalised)."""
    r0 = fx["parking_radius_km"] / LU_KM
    vc = math.sqrt((1.0 - MU) / r0)
    return 1.0 - math.exp(-(kappa - 1.0) * vc / exhaust_vu(fx["chemical_specific_impulse_s"]))


# ---------------------------------------------------------------- canonical system -------------
def grav(x, y, z):
    """g(r) and the pieces of G = dg/dr (returned as a function applying G to a vector)."""
    d1 = (x + MU, y, z)
    d2 = (x + MU - 1.0, y, z)
    r1 = math.sqrt(d1[0] ** 2 + y * y + z * z)
    r2 = math.sqrt(d2[0] ** 2 + y * y + z * z)
    k1, k2 = (1.0 - MU) / r1 ** 3, MU / r2 ** 3
    g = (x - k1 * d1[0] - k2 * d2[0], y - k1 * y - k2 * y, -k1 * z - k2 * z)

    def G_times(l):
        out = [l[0], l[1], 0.0]
        for k, d, rr in ((k1, d1, r1), (k2, d2, r2)):
            dl = 3.0 * (d[0] * l[0] + d[1] * l[1] + d[2] * l[2]) / (rr * rr)
            for i in range(3):
                out[i] -= k * (l[i] - d[i] * dl)
        return out
    return g, G_times


def switching(y, c):
    lv = math.sqrt(y[10] ** 2 + y[11] ** 2 + y[12] ** 2)
    return 1.0 - c * lv / y[6] - y[13]


def throttle(regime, s, eps):
    if regime != "mid":
        return 1.0 if regime == "full" else 0.0
    return min(1.0, max(0.0, (eps - s) / (2.0 * eps)))      # "mid": smoothed, |S| <= eps


def make_rhs(T, c, regime, eps):
    def rhs(t, y):
        g, G_times = grav(y[0], y[1], y[2])
        m, lr, lv = y[6], y[7:10], y[10:13]
        nl = math.sqrt(lv[0] ** 2 + lv[1] ** 2 + lv[2] ** 2)
        u = throttle(regime, 1.0 - c * nl / m - y[13], eps)
        a = u * T / (m * nl) if nl > 0 else 0.0        # thrust acc along -lv/|lv|
        Gl = G_times(lv)
        return [y[3], y[4], y[5],
                g[0] + 2.0 * y[4] - a * lv[0], g[1] - 2.0 * y[3] - a * lv[1], g[2] - a * lv[2],
                -u * T / c,
                -Gl[0], -Gl[1], -Gl[2],
                -lr[0] + 2.0 * lv[1], -lr[1] - 2.0 * lv[0], -lr[2],
                -u * T * nl / (m * m)]
    return rhs


def hamiltonian_full(y, T, c):
    """Minimum-time H without l0: lr.v + lv.(g+h) - T|lv|/m - lm T/c."""
    g, _ = grav(y[0], y[1], y[2])
    lv = y[10:13]
    h = (2.0 * y[4], -2.0 * y[3], 0.0)
    drift = np.dot(y[7:10], y[3:6]) + sum(lv[i] * (g[i] + h[i]) for i in range(3))
    return drift - T * np.linalg.norm(lv) / y[6] - y[13] * T / c


def regime_of(s, eps, law):
    if law == "min-time":
        return "full"
    if eps == 0.0:
        return "full" if s < 0 else "off"
    return "full" if s < -eps else ("off" if s > eps else "mid")


def events_for(regime, eps, c, law):
    """Terminal events leaving `regime`, each with the regime entered (S crosses a boundary in
    the only direction that leaves: a wrong-sided round-off value at a restart cannot fire)."""
    if law == "min-time":
        return [], []
    out = []

    def ev(level, direction, target):
        f = lambda t, y: switching(y, c) - level   # noqa: E731
        f.terminal, f.direction = True, direction
        out.append((f, target))
    if regime == "full":
        ev(-eps, +1, "off" if eps == 0.0 else "mid")
    elif regime == "off":
        ev(eps, -1, "full" if eps == 0.0 else "mid")
    else:
        ev(eps, +1, "off")
        ev(-eps, -1, "full")
    return [f for f, _ in out], [t for _, t in out]


def fly(y0, tf, T, c, law, eps, max_arcs=400):
    """Integrate the canonical system over [0, tf], restarting at each regime change.
    Returns (y(tf), switch times in TU, number of rhs evaluations)."""
    t, y = 0.0, np.asarray(y0, float)
    regime = regime_of(switching(y, c), eps, law)
    switches, nfev = [], 0
    for _ in range(max_arcs):
        evs, targets = events_for(regime, eps, c, law)
        sol = solve_ivp(make_rhs(T, c, regime, eps), (t, tf), y, method="DOP853",
                        rtol=RTOL, atol=ATOL, events=evs or None)
        nfev += sol.nfev
        if sol.status == 1:                               # an event ended the arc
            k = next(i for i, te in enumerate(sol.t_events) if len(te))
            t, y = sol.t_events[k][0], sol.y_events[k][0]
            regime = targets[k]
            switches.append(t)
            continue
        if sol.status != 0:
            raise RuntimeError(sol.message)
        return sol.y[:, -1], switches, nfev
    raise RuntimeError("too many arcs")


# ---------------------------------------------------------------- the shooting problem ---------
class Case:
    def __init__(self, fx):
        self.fx = fx
        self.law = fx["objective"]
        self.eps = {"min-fuel": 0.0, "min-energy": 1.0, "min-time": 0.0}[self.law]
        self.T = force_fu(fx["thrust_n"])
        self.c = exhaust_vu(fx["specific_impulse_s"])
        self.theta = fx["theta_rad"]
        self.free_kappa = "kappa" in fx.get("free", [])
        self.rf = np.array(fx["arrival"]["r_lu"])
        self.vf = np.array(fx["arrival"]["v_vu"])
        self.tf_fixed = fx["duration_days"] * DAY_TU

    def unpack(self, z):
        """z -> (kappa, tf, lambda(7), l0 or None)."""
        kappa, tf, l0 = self.fx["kappa"], self.tf_fixed, None
        if self.law == "min-time":
            l0, lam, tf = z[0], z[1:8], z[8]
        elif self.free_kappa:
            lam, kappa = z[:7], z[7]
        else:
            lam = z[:7]
        return kappa, tf, np.asarray(lam), l0

    def residual(self, z, detail=False):
        kappa, tf, lam, l0 = self.unpack(z)
        x0 = departure(kappa, self.theta, self.fx)
        try:
            yf, sw, _ = fly(np.concatenate([x0, lam]), tf, self.T, self.c, self.law, self.eps)
        except RuntimeError:          # e.g. a trial flight into a primary: a big residual
            if detail:
                raise
            return np.full(len(z), 1e3)
        F = list(yf[0:3] - self.rf) + list(yf[3:6] - self.vf) + [yf[13]]
        if self.law == "min-time":
            F += [hamiltonian_full(yf, self.T, self.c) + l0, float(np.dot(z[:8], z[:8])) - 1.0]
        elif self.free_kappa:
            h = 1e-6
            dx0 = (departure(kappa + h, self.theta, self.fx)
                   - departure(kappa - h, self.theta, self.fx)) / (2 * h)
            dth = (chem_cost(kappa + h, self.fx) - chem_cost(kappa - h, self.fx)) / (2 * h)
            F += [dth + float(np.dot(lam, dx0))]
        F = np.array(F)
        if detail:
            return F, yf, sw, tf, kappa, x0
        return F

    def fd_jacobian(self, z):
        """Central differences, step 1e-6 of max(|z_j|, 1e-2 |z|_inf) (forward differences are
        not accurate enough here: the Newton step from 1e-3 off is ill-conditioned)."""
        J = np.empty((len(z), len(z)))                        # square systems only
        scale = 1e-2 * np.max(np.abs(z))
        for j in range(len(z)):
            h = 1e-6 * max(abs(z[j]), scale)
            zp, zm = z.copy(), z.copy()
            zp[j] += h
            zm[j] -= h
            J[:, j] = (self.residual(zp) - self.residual(zm)) / (2 * h)
        return J


def solve_oracle(case, z0):
    """MINPACK hybrd (Powell hybrid) with this file's Jacobian, then Newton polishing on the
    same Jacobian if needed. Returns the root result and counts."""
    counts = {"nfev": 0, "njev": 0}

    def fun(z):
        counts["nfev"] += 1
        return case.residual(z)

    def jac(z):                                          # 2 len(z) propagations each
        counts["njev"] += 1
        return case.fd_jacobian(z)
    sol = root(fun, z0, jac=jac, method="hybr", options={"xtol": 1e-13, "maxfev": 200})
    z, F = sol.x, fun(sol.x)
    polish = 0
    while np.max(np.abs(F)) > 1e-11 and polish < 4:      # hybr stalls on noise: plain Newton
        step = np.linalg.solve(jac(z), -F)
        z_new = z + step
        F_new = fun(z_new)
        if np.max(np.abs(F_new)) >= np.max(np.abs(F)):
            break
        z, F, polish = z_new, F_new, polish + 1
    return z, F, sol, counts, polish


def final_mass_fixed_kappa(case, kappa, lam0):
    """Envelope check for kappa free: a fixed-kappa shooting at kappa, its final mass."""
    fx = dict(case.fx, kappa=kappa, free=[])
    sub = Case(fx)
    z, F, _, _, _ = solve_oracle(sub, np.array(lam0, float))
    _, yf, _, _, _, _ = sub.residual(z, detail=True)
    return yf[6], float(np.max(np.abs(F)))


# ---------------------------------------------------------------- driver -----------------------
def our_solve(reconfig, path, check=True):
    """OUR answer (the CLI exits 1 on an unsolved request but still prints its JSON)."""
    out = subprocess.run([reconfig, "solve", str(path), "--json"], check=check,
                         capture_output=True, text=True).stdout
    d = json.loads(out)
    d.pop("trajectory", None)
    return d


def perturbed(z, d):
    pattern = np.array([1.0 if i % 2 == 0 else -1.0 for i in range(len(z))])
    return np.asarray(z, float) * (1.0 + d * pattern)


def ours_from(reconfig, path, case, z0):
    """OUR planner from the oracle's start z0: the fixture with its start replaced."""
    kappa, tf, lam, l0 = case.unpack(z0)
    txt = path.read_text()
    sub = [(r"^costates = \[.*\]$", "costates = [" + ", ".join(map(repr, map(float, lam))) + "]"),
           (r"^kappa = .*$", f"kappa = {float(kappa)!r}")]       # the first: top level
    if l0 is not None:   # (a fixed t_f is left as written: a changed one would walk from it)
        sub += [(r"^cost_multiplier = .*$", f"cost_multiplier = {float(l0)!r}"),
                (r"^duration_days = .*$", f"duration_days = {float(tf / DAY_TU)!r}")]
    for pat, rep in sub:
        txt = re.sub(pat, rep, txt, count=1, flags=re.M)
    with tempfile.TemporaryDirectory() as tmp:
        q = Path(tmp) / path.name
        q.write_text(txt)
        d = our_solve(reconfig, q, check=False)
    return {"status": str(d["status"]), "final_mass": d["final_mass"],
            "residual": d["residual"], "iterations": d["iterations"],
            "solve_time_s": d["solve_time_s"]}


def run_case(path, reconfig):
    fx = tomllib.loads(path.read_text())
    case = Case(fx)
    runs = [our_solve(reconfig, path) for _ in range(5)]
    ours = runs[0]
    our_time = statistics.median(r["solve_time_s"] for r in runs)
    # a. fly our answer
    lam = list(ours["costates"])
    if case.law == "min-time":
        z_ours = np.array([ours["cost_multiplier"]] + lam + [ours["tf_days"] * DAY_TU])
    elif case.free_kappa:
        z_ours = np.array(lam + [ours["kappa"]])
    else:
        z_ours = np.array(lam)
    F, yf, sw, tf, kappa, x0 = case.residual(z_ours, detail=True)
    flight = {"miss_position_lu": float(np.linalg.norm(yf[0:3] - case.rf)),
              "miss_velocity_vu": float(np.linalg.norm(yf[3:6] - case.vf)),
              "lambda_m_tf": float(yf[13]), "residual_max": float(np.max(np.abs(F))),
              "residual": F.tolist(), "final_mass": float(yf[6]),
              "mass_after_impulse": float(x0[6]),
              "regime_changes_days": [t / DAY_TU for t in sw]}   # S = 0 (or +-eps) crossings
    # b. the oracle's own shooting from perturbed starts, 1e-3 first (each timed alone)
    attempts = []
    for d in (1e-3, 1e-4, 1e-5, 1e-6):
        z0 = perturbed(z_ours, d)
        t0 = time.perf_counter()
        z, F, sol, counts, polish = solve_oracle(case, z0)
        wall = time.perf_counter() - t0
        res = float(np.max(np.abs(F)))
        attempts.append({"perturbation": d, "converged": bool(res < 1e-9), "residual_max": res,
                         "nfev": counts["nfev"], "njev": counts["njev"], "time_s": wall,
                         "propagations": counts["nfev"] + 2 * len(z) * counts["njev"],
                         "hybr_message": sol.message, "newton_polish_steps": polish,
                         "ours_from_same_start": ours_from(reconfig, path, case, z0)})
        if res < 1e-9:
            break
    F, yf, sw, tf, kappa, x0 = case.residual(z, detail=True)
    oracle = dict(attempts[-1])
    oracle.pop("ours_from_same_start")
    oracle.update({"residual": F.tolist(), "final_mass": float(yf[6]), "tf_days": tf / DAY_TU,
                   "kappa": kappa, "costates": list(z[1:8] if case.law == "min-time" else z[:7]),
                   "cost_multiplier": float(z[0]) if case.law == "min-time" else 1.0,
                   "regime_changes_days": [t / DAY_TU for t in sw], "attempts": attempts})
    if case.free_kappa:   # the transversality sign: m_f(kappa) must be stationary at kappa*
        dk = 1e-4
        mp, rp = final_mass_fixed_kappa(case, kappa + dk, z[:7])
        mm, rm = final_mass_fixed_kappa(case, kappa - dk, z[:7])
        curv = (mp + mm - 2 * yf[6]) / dk ** 2          # m_f'' (negative at a maximum)
        oracle["envelope"] = {"dkappa": dk, "final_mass_plus": float(mp),
                              "final_mass_minus": float(mm), "residuals": [rp, rm],
                              "dmf_dkappa": float((mp - mm) / (2 * dk)), "d2mf_dkappa2": curv,
                              "parabola_vertex_minus_kappa": float(-(mp - mm) / (2 * dk) / curv)}
    keep = ("status", "objective", "final_mass", "tf_days", "kappa", "theta_rad", "costates",
            "cost_multiplier", "mass_after_impulse", "residual", "iterations",
            "switch_times_days", "end_miss")
    same = attempts[-1]["ours_from_same_start"]
    agreement = {"final_mass_diff": oracle["final_mass"] - ours["final_mass"],
                 "tf_days_diff": oracle["tf_days"] - ours["tf_days"],
                 "kappa_diff": oracle["kappa"] - ours["kappa"],
                 "time_ratio_oracle_over_ours": oracle["time_s"] / our_time,
                 "time_ratio_vs_ours_from_same_start": oracle["time_s"] / same["solve_time_s"]}
    return {"ours": {k: ours.get(k) for k in keep}, "our_solve_time_s_median5": our_time,
            "our_solve_times_s": [r["solve_time_s"] for r in runs], "flight_of_ours": flight,
            "oracle": oracle, "agreement": agreement}


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--reconfig", default="target/debug/reconfig")
    ap.add_argument("--out", default="fixtures/golden/hybrid-oracle.json")
    ap.add_argument("--fixtures", default="fixtures")
    args = ap.parse_args()
    cases = {}
    for path in sorted(Path(args.fixtures).glob("hybrid-*.toml")):
        t0 = time.perf_counter()
        c = run_case(path, args.reconfig)
        cases[path.stem] = c
        a = c["agreement"]
        print(f"{path.stem}: ours m_f {c['ours']['final_mass']:.10f} oracle "
              f"{c['oracle']['final_mass']:.10f} dm {a['final_mass_diff']:.2e} "
              f"dtf {a['tf_days_diff']:.2e} d; flight miss "
              f"{c['flight_of_ours']['residual_max']:.2e}; oracle res "
              f"{c['oracle']['residual_max']:.2e} from d={c['oracle']['perturbation']:.0e} "
              f"({time.perf_counter() - t0:.1f} s)",
              file=sys.stderr)
    header = {
        "produced_by": "tests/oracle/hybrid_scipy.py",
        "command": " ".join([Path(sys.executable).as_posix(), *sys.argv]),
        "python": platform.python_version(), "numpy": np.__version__,
        "scipy": scipy.__version__, "platform": platform.platform(),
        "date": datetime.datetime.now(datetime.timezone.utc).isoformat(timespec="seconds"),
        "reconfig": args.reconfig,
        "integrator": f"solve_ivp DOP853 rtol {RTOL} atol {ATOL}, restarted at throttle switches",
        "shooting": "scipy.optimize.root hybr (xtol 1e-13), central-difference Jacobian (step "
                    "1e-6 rel.), Newton polish to 1e-11; start = ours * (1 + d (+1,-1,...)), "
                    "d = 1e-3, then 1e-4, 1e-5, 1e-6 until max|F| < 1e-9 (converged)",
        "our_time": "median of 5 runs of the CLI's solve_time_s",
    }
    Path(args.out).write_text(json.dumps({"header": header, "cases": cases}, indent=1) + "\n")


if __name__ == "__main__":
    main()
