#!/usr/bin/env python3
"""Independent oracle for planner A (Huang 2012 LGL transcription), CasADi + IPOPT.

Reads the problems written by `reconfig sweep --write FILE` (one JSON object per line:
`{"family": ..., "problem": {horizon_tu, max_control_fu, keep_out_lu, degree, test_points,
spacecraft: [{mass_mu, initial_state, final_state}]}}`), builds the same transcription WITHOUT
any code of the planner under test, and solves it with IPOPT from several deterministic starts:

* `line`     - the unconstrained minimum-energy cubic of every axis (a straight line for
               rest-to-rest manoeuvres);
* `analytic` - the Pontryagin guess of docs/planner-a.md / SPEC.md eq. 24-26,
               `u = sat(alpha + beta (2t/T - 1))`, solved here by Newton on a fine quadrature;
* `lift+`, `lift-` - the cubic plus a half-sine bump of size d, out of the plane of motion,
               alternating sign per spacecraft (and its mirror image);
* `swirl`    - the cubic plus a bump of size d whose direction turns with the spacecraft's index
               about the z axis (a roundabout);
* `random`   - the cubic plus a seeded random bump of size d per spacecraft;
* `ours`     - with `--answers FILE` (`reconfig sweep --write-answers`), our node positions.

The transcription (SPEC.md "Planner A"; docs/planner-a.md "Method"): N + 1 LGL nodes (zeros of
(1 - tau^2) L_N'), weights 2 / (N (N + 1) L_N^2), the differentiation matrix of eq. 12, collocation
at every node of the double integrator, so each axis is one degree-N polynomial; unknowns are the
node positions, velocity = (2/T) D x, control force = m (2/T)^2 D D x. Cost T/4 sum w_h |U_h|^2
(exact for these polynomials), |U| <= Umax per component at every node, fixed boundary states,
keep-out |r_i - r_j|^2 >= d^2 at every interior node, at the 7 Gaussian test points per pair
(eq. 27, placed on the analytic trajectories) when the problem asks for them, and - because the
accepted answer must be feasible on the CONTINUOUS trajectory, as ours must - at the continuous
separation minima found on a fine grid, added round by round (at most MAX_ROUNDS) until the
interpolating polynomials keep d (1 - FEAS_TOL) everywhere.

Each answer is checked with the feasibility notion of reconfig: continuous separation (grid of
GRID points plus a bounded local refinement per pair) >= d (1 - FEAS_TOL), every node control
within Umax (1 + 1e-6). The best feasible J over the starts is kept.

Usage:
  python3 tests/oracle/planner_a_ipopt.py PROBLEMS.jsonl --out GOLDEN.jsonl [--answers OURS.jsonl]
      [--only 0,5,7] [--starts line,analytic,...]
Output: one header line `{"header": ...}` then one JSON object per problem, in input order.
"""

import argparse
import json
import math
import platform
import re
import sys
import time

import casadi as ca
import numpy as np
from numpy.polynomial import legendre as leg

FEAS_TOL = 1e-6  # relative keep-out tolerance of an accepted answer
CTRL_TOL = 1e-6  # relative control-bound tolerance of an accepted answer
GRID = 2001  # guard grid per pair (the minima themselves are polynomial roots)
MAX_ROUNDS = 10  # rounds of adding continuous-minimum check points
PIN_DEPTH = 1e-5  # dips deeper than this (relative) get a check point, shallower ones a margin
VERBOSE = False
IPOPT_EXTRA = {}
TEST_POINT_OFFSETS = [-1.07, -0.64, -0.30, 0.0, 0.30, 0.64, 1.07]
ALL_STARTS = ["line", "analytic", "lift+", "lift-", "swirl", "random"]


# ---------------------------------------------------------------- LGL grid
def lgl(n):
    """Nodes, weights and differentiation matrix of degree n (SPEC eq. 12)."""
    cn = np.zeros(n + 1)
    cn[n] = 1.0
    inner = np.sort(leg.legroots(leg.legder(cn)).real)
    tau = np.concatenate(([-1.0], inner, [1.0]))
    # Polish the interior roots with Newton on L_N'.
    d1, d2 = leg.legder(cn), leg.legder(cn, 2)
    for _ in range(5):
        tau[1:-1] -= leg.legval(tau[1:-1], d1) / leg.legval(tau[1:-1], d2)
    ln = leg.legval(tau, cn)
    w = 2.0 / (n * (n + 1) * ln**2)
    dm = np.zeros((n + 1, n + 1))
    for h in range(n + 1):
        for k in range(n + 1):
            if h != k:
                dm[h, k] = ln[h] / (ln[k] * (tau[h] - tau[k]))
    dm[0, 0] = -n * (n + 1) / 4.0
    dm[n, n] = n * (n + 1) / 4.0
    return tau, w, dm


def bary_weights(tau):
    n = len(tau)
    bw = np.ones(n)
    for k in range(n):
        for j in range(n):
            if j != k:
                bw[k] /= tau[k] - tau[j]
    return bw


def interp_matrix(tau, bw, s):
    """Rows of Lagrange interpolation at points s (in tau), barycentric form."""
    s = np.atleast_1d(s)
    out = np.zeros((len(s), len(tau)))
    for r, x in enumerate(s):
        diff = x - tau
        hit = np.where(np.abs(diff) < 1e-14)[0]
        if len(hit):
            out[r, hit[0]] = 1.0
            continue
        q = bw / diff
        out[r] = q / q.sum()
    return out


# ---------------------------------------------------------------- analytic guess (eq. 24-26)
def cubic_axis(p0, v0, p1, v1, T, t):
    """The minimum-energy cubic through the four boundary values (Hermite)."""
    s = t / T
    h00 = 2 * s**3 - 3 * s**2 + 1
    h10 = s**3 - 2 * s**2 + s
    h01 = -2 * s**3 + 3 * s**2
    h11 = s**3 - s**2
    return h00 * p0 + h10 * T * v0 + h01 * p1 + h11 * T * v1


QUAD = 4001


def _reach(alpha, beta, p0, v0, T, mass, umax):
    t = np.linspace(0.0, T, QUAD)
    u = np.clip(alpha + beta * (2 * t / T - 1), -umax, umax) / mass
    dt = t[1] - t[0]
    wq = np.full(QUAD, dt)
    wq[0] = wq[-1] = dt / 2
    v1 = v0 + np.sum(wq * u)
    p1 = p0 + v0 * T + np.sum(wq * (T - t) * u)
    return v1, p1


def analytic_axis(p0, v0, p1, v1, T, mass, umax):
    """(alpha, beta) of u = sat(alpha + beta (2t/T - 1)); Newton with finite differences."""
    # Unsaturated law: the cubic's acceleration, u = m a(t), a linear in t.
    a0 = (6 * (p1 - p0) - 2 * T * (2 * v0 + v1)) / T**2
    a1 = (-12 * (p1 - p0) + 6 * T * (v0 + v1)) / T**3  # a(t) = a0 + a1 t
    alpha = mass * (a0 + a1 * T / 2)
    beta = mass * a1 * T / 2
    if abs(alpha) + abs(beta) <= umax:
        return alpha, beta, False

    def resid(a, b):
        rv, rp = _reach(a, b, p0, v0, T, mass, umax)
        return np.array([rv - v1, (rp - p1) / T])

    x = np.array([alpha, beta])
    r = resid(*x)
    for _ in range(60):
        if np.linalg.norm(r) < 1e-11 * (1 + abs(p1) + abs(v1)):
            break
        eps = 1e-7 * (1 + np.abs(x))
        jac = np.zeros((2, 2))
        for k in range(2):
            xe = x.copy()
            xe[k] += eps[k]
            jac[:, k] = (resid(*xe) - r) / eps[k]
        try:
            step = np.linalg.lstsq(jac, -r, rcond=None)[0]
        except np.linalg.LinAlgError:
            break
        lam = 1.0
        for _ in range(40):
            xn = x + lam * step
            rn = resid(*xn)
            if np.linalg.norm(rn) < np.linalg.norm(r):
                break
            lam *= 0.5
        x, r = xn, rn
    return x[0], x[1], True


def analytic_positions(sc, T, umax, times):
    """Positions (len(times) x 3) of the analytic guess of one spacecraft."""
    m = sc["mass_mu"]
    a, b = sc["initial_state"], sc["final_state"]
    out = np.zeros((len(times), 3))
    tq = np.linspace(0.0, T, QUAD)
    for k in range(3):
        alpha, beta, sat = analytic_axis(a[k], a[k + 3], b[k], b[k + 3], T, m, umax)
        if not sat:
            out[:, k] = cubic_axis(a[k], a[k + 3], b[k], b[k + 3], T, times)
            continue
        acc = np.clip(alpha + beta * (2 * tq / T - 1), -umax, umax) / m
        vel = a[k + 3] + np.concatenate(([0.0], np.cumsum(0.5 * (acc[1:] + acc[:-1]) * np.diff(tq))))
        pos = a[k] + np.concatenate(([0.0], np.cumsum(0.5 * (vel[1:] + vel[:-1]) * np.diff(tq))))
        out[:, k] = np.interp(times, tq, pos)
    return out


# ---------------------------------------------------------------- transcription
class Transcription:
    def __init__(self, prob):
        self.p = prob
        self.T = prob["horizon_tu"]
        self.n = prob["degree"]
        self.umax = prob["max_control_fu"]
        self.d = prob["keep_out_lu"]
        self.sc = prob["spacecraft"]
        self.m = len(self.sc)
        self.tau, self.w, self.D = lgl(self.n)
        self.bw = bary_weights(self.tau)
        self.times = self.T / 2 * (self.tau + 1)
        self.pairs = [(i, j) for i in range(self.m) for j in range(i + 1, self.m)]
        self.grid_s = np.linspace(-1, 1, GRID)
        self.test_times = {pr: [] for pr in self.pairs}
        if prob.get("test_points", False):
            self._place_test_points()

    def to_tau(self, t):
        return 2 * np.asarray(t) / self.T - 1

    def _place_test_points(self):
        """Eq. 27 on the analytic trajectories (SPEC.md steps 1-4)."""
        fine = np.linspace(0.0, self.T, QUAD)
        pos = [analytic_positions(s, self.T, self.umax, fine) for s in self.sc]
        for i, j in self.pairs:
            rel = pos[i] - pos[j]
            dn = np.linalg.norm(
                np.array([np.interp(self.times, fine, rel[:, k]) for k in range(3)]).T, axis=1
            )
            kk = int(np.argmin(dn))
            lo = self.times[max(kk - 1, 0)]
            hi = self.times[min(kk + 1, self.n)]
            sel = (fine >= lo) & (fine <= hi)
            sep = np.linalg.norm(rel[sel], axis=1)
            mu = fine[sel][int(np.argmin(sep))]
            sigma = 0.5 * (hi - lo)
            self.test_times[(i, j)] = [
                mu + o * sigma for o in TEST_POINT_OFFSETS if 0.0 < mu + o * sigma < self.T
            ]

    def pair_minima(self, X, i, j):
        """Every local minimum (separation, time) of pair (i, j) on the continuous interpolant.

        Each axis of r_i - r_j is one degree-N polynomial (Legendre coefficients through the N + 1
        nodes, exact); |r|^2 is of degree 2N and its critical points are the real roots of the
        derivative in [-1, 1], found as eigenvalues (no grid a fast pass could slip through), then
        confirmed against a fine grid as a guard against lost roots.
        """
        rel = X[i] - X[j]
        coeffs = [leg.legfit(self.tau, rel[:, k], self.n) for k in range(3)]
        sq = np.zeros(1)
        for c in coeffs:
            sq = leg.legadd(sq, leg.legmul(c, c))
        cand = [-1.0, 1.0]
        roots = leg.legroots(leg.legder(sq))
        cand += [r.real for r in roots if abs(r.imag) < 1e-7 and -1.0 <= r.real <= 1.0]
        # Guard: the least grid point, polished by Newton on the derivative.
        grid = np.sqrt(np.maximum(leg.legval(self.grid_s, sq), 0.0))
        s = self.grid_s[int(np.argmin(grid))]
        d1, d2 = leg.legder(sq), leg.legder(sq, 2)
        for _ in range(20):
            h2 = leg.legval(s, d2)
            if h2 <= 0:
                break
            s = min(1.0, max(-1.0, s - leg.legval(s, d1) / h2))
        cand.append(s)
        cand = np.array(cand)
        vals = np.sqrt(np.maximum(leg.legval(cand, sq), 0.0))
        order = np.argsort(cand)
        cand, vals = cand[order], vals[order]
        out = []
        for k, (c, v) in enumerate(zip(cand, vals)):
            # keep minima (a candidate not above its neighbours among the candidates)
            left = vals[k - 1] if k > 0 else math.inf
            right = vals[k + 1] if k + 1 < len(vals) else math.inf
            if v <= left + 1e-15 and v <= right + 1e-15:
                out.append((float(v), float(self.T / 2 * (c + 1))))
        return out

    def continuous_min(self, X):
        """Per pair: (least separation, time) on the continuous interpolant."""
        return {pr: min(self.pair_minima(X, *pr)) for pr in self.pairs}

    def local_minima_below(self, X, level):
        """Times of every interior local minimum of each pair's separation below `level`."""
        found = {}
        for pr in self.pairs:
            ts = [t for v, t in self.pair_minima(X, *pr) if v < level and 0.0 < t < self.T]
            if ts:
                found[pr] = ts
        return found

    def controls(self, X):
        s = (2.0 / self.T) ** 2
        return np.array([self.sc[i]["mass_mu"] * s * (self.D @ (self.D @ X[i])) for i in range(self.m)])

    def cost(self, X):
        U = self.controls(X)
        return float(self.T / 4 * np.sum(self.w[None, :, None] * U**2))

    def check(self, X):
        cm = self.continuous_min(X)
        sep_min = min(v[0] for v in cm.values()) if cm else math.inf
        worst = min(cm, key=lambda k: cm[k][0]) if cm else None
        umax_seen = float(np.max(np.abs(self.controls(X))))
        # boundary conditions of the polynomial (the dynamics hold by construction)
        V = np.array([(2.0 / self.T) * (self.D @ X[i]) for i in range(self.m)])
        bc = 0.0
        for i, s in enumerate(self.sc):
            a, b = np.array(s["initial_state"]), np.array(s["final_state"])
            bc = max(bc, np.max(np.abs(X[i, 0] - a[:3])), np.max(np.abs(X[i, -1] - b[:3])))
            bc = max(bc, np.max(np.abs(V[i, 0] - a[3:])), np.max(np.abs(V[i, -1] - b[3:])))
        feasible = (
            sep_min >= self.d * (1 - FEAS_TOL)
            and umax_seen <= self.umax * (1 + CTRL_TOL)
            and bc <= 1e-6 * (1 + max(abs(v) for s in self.sc for v in s["initial_state"] + s["final_state"]))
        )
        return {
            "feasible": bool(feasible),
            "min_separation_lu": sep_min,
            "min_separation_pair": list(worst) if worst else None,
            "min_separation_time_tu": cm[worst][1] if worst else None,
            "separation_margin": (sep_min / self.d - 1.0) if cm else None,
            "max_control_fu": umax_seen,
            "control_margin": 1.0 - umax_seen / self.umax,
            "boundary_error": bc,
        }

    def build(self):
        """The parts of the NLP that do not change between keep-out rounds."""
        m, n, T = self.m, self.n, self.T
        x = ca.SX.sym("x", m * (n + 1) * 3)
        X = [ca.reshape(x[i * (n + 1) * 3 : (i + 1) * (n + 1) * 3], n + 1, 3) for i in range(m)]
        D = ca.DM(self.D)
        s2 = (2.0 / T) ** 2
        U = [self.sc[i]["mass_mu"] * s2 * ca.mtimes(D, ca.mtimes(D, X[i])) for i in range(m)]
        Vel = [(2.0 / T) * ca.mtimes(D, X[i]) for i in range(m)]
        W = ca.DM(self.w)
        J = 0
        for i in range(m):
            J += T / 4 * ca.sum1(W * ca.sum2(U[i] ** 2))
        g, lbg, ubg = [], [], []
        for i, s in enumerate(self.sc):
            a, b = s["initial_state"], s["final_state"]
            g += [X[i][0, :].T - ca.DM(a[:3]), X[i][n, :].T - ca.DM(b[:3])]
            g += [Vel[i][0, :].T - ca.DM(a[3:]), Vel[i][n, :].T - ca.DM(b[3:])]
            lbg += [0.0] * 12
            ubg += [0.0] * 12
            g.append(ca.reshape(U[i], -1, 1))
            lbg += [-self.umax] * (3 * (n + 1))
            ubg += [self.umax] * (3 * (n + 1))
        self.x, self.X, self.J, self.g0, self.lbg0, self.ubg0 = x, X, J, g, lbg, ubg
        self.extra, self.margin = {}, {}

    def solve(self, X0, extra, margin):
        """One IPOPT solve with keep-out (d + margin per pair) at every interior node, the test
        points and the `extra` {pair: [t]} points (interpolation rows are numbers, so the NLP is
        rebuilt per round: a symbolic row would make every Hessian entry an expression)."""
        m, n, X = self.m, self.n, self.X
        g, lbg, ubg = list(self.g0), list(self.lbg0), list(self.ubg0)
        for i, j in self.pairs:
            d2 = (self.d + margin.get((i, j), 0.0)) ** 2
            rel = X[i] - X[j]
            g.append(ca.sum2(rel[1:n, :] ** 2))
            lbg += [d2] * (n - 1)
            ubg += [ca.inf] * (n - 1)
            ts = list(self.test_times[(i, j)]) + list(extra.get((i, j), []))
            if ts:
                E = ca.DM(interp_matrix(self.tau, self.bw, self.to_tau(ts)))
                g.append(ca.sum2(ca.mtimes(E, rel) ** 2))
                lbg += [d2] * len(ts)
                ubg += [ca.inf] * len(ts)
        opts = {
            "ipopt.print_level": 0,
            "print_time": False,
            "ipopt.tol": 1e-10,
            "ipopt.constr_viol_tol": 1e-10,
            "ipopt.max_iter": 500,
            "ipopt.sb": "yes",
            **IPOPT_EXTRA,
        }
        solver = ca.nlpsol("s", "ipopt", {"x": self.x, "f": self.J, "g": ca.vertcat(*g)}, opts)
        x0 = np.concatenate([np.asarray(X0[i]).reshape(-1, order="F") for i in range(m)])
        t0 = time.perf_counter()
        res = solver(x0=x0, lbg=lbg, ubg=ubg)
        self.ipopt_wall_s += time.perf_counter() - t0
        stats = solver.stats()
        xs = np.array(res["x"]).ravel()
        Xs = np.array(
            [xs[i * (n + 1) * 3 : (i + 1) * (n + 1) * 3].reshape(n + 1, 3, order="F") for i in range(m)]
        )
        return Xs, stats["return_status"], stats.get("iter_count", -1)

    def solve_continuous(self, X0):
        """Solve; then, while the interpolant dips below d, pin each dip deeper than PIN_DEPTH d
        with a check point (a pinned dip moves aside and shrinks about fourfold per round) and
        raise a pair whose dips are shallower by 1.2 times their depth (parts per 1e5 of d, so
        the cost moves by less than that), and solve again from the last answer."""
        # Check points and margins found by earlier starts of this problem are kept: they are
        # valid keep-out checks for any trajectory, and save the later starts most rounds.
        extra, margin = self.extra, self.margin
        self.ipopt_wall_s = 0.0
        X = X0
        statuses = []
        iters = 0
        rounds = 0
        h = self.T / self.n
        for rounds in range(MAX_ROUNDS + 1):
            out = self.solve(X, extra, margin)
            if out is None:
                statuses.append("oracle_slots_full")
                break
            X, status, it = out
            statuses.append(status)
            iters += it
            if VERBOSE:
                cm = self.continuous_min(X)
                print(rounds, status, self.cost(X), min(v[0] for v in cm.values()), file=sys.stderr)
            if status not in ("Solve_Succeeded", "Solved_To_Acceptable_Level"):
                break
            dips = self.local_minima_below(X, self.d * (1 - 0.1 * FEAS_TOL))
            if not dips:
                break
            for pr, ts in dips.items():
                depth = self.d - min(v for v, t in self.pair_minima(X, *pr))
                if depth > PIN_DEPTH * self.d:
                    extra.setdefault(pr, []).extend(ts)
                else:
                    margin[pr] = margin.get(pr, 0.0) + 1.2 * depth
        return X, statuses, rounds, iters


# ---------------------------------------------------------------- starts
def start_positions(tr, name, index, ours=None):
    T, times, d = tr.T, tr.times, tr.d
    if name == "ours":
        return np.array(ours)
    if name == "analytic":
        return np.array([analytic_positions(s, T, tr.umax, times) for s in tr.sc])
    base = np.zeros((tr.m, tr.n + 1, 3))
    for i, s in enumerate(tr.sc):
        a, b = s["initial_state"], s["final_state"]
        for k in range(3):
            base[i, :, k] = cubic_axis(a[k], a[k + 3], b[k], b[k + 3], T, times)
    if name == "line":
        return base
    bump = np.sin(math.pi * times / T) ** 2  # zero value and slope at both ends
    rng = np.random.default_rng(1000 + index)
    for i in range(tr.m):
        if name in ("lift+", "lift-"):
            sign = (1 if i % 2 == 0 else -1) * (1 if name == "lift+" else -1)
            direction = np.array([0.0, 0.0, sign])
        elif name == "swirl":
            ang = 2 * math.pi * i / tr.m
            direction = np.array([math.cos(ang), math.sin(ang), 0.0])
        else:
            direction = rng.normal(size=3)
            direction /= np.linalg.norm(direction)
        base[i] += d * bump[:, None] * direction[None, :]
    return base


def ipopt_banner_version():
    """The IPOPT version casadi loads, read from IPOPT's own banner (printed on stdout)."""
    import os
    import tempfile

    with tempfile.TemporaryFile() as tmp:
        sys.stdout.flush()
        saved = os.dup(1)
        os.dup2(tmp.fileno(), 1)
        try:
            x = ca.SX.sym("a")
            ca.nlpsol("v", "ipopt", {"x": x, "f": x**2}, {"ipopt.print_level": 5})(x0=1)
        finally:
            sys.stdout.flush()
            os.dup2(saved, 1)
            os.close(saved)
        tmp.seek(0)
        text = tmp.read().decode(errors="replace")
    found = re.search(r"Ipopt version ([0-9.]+)", text)
    return found.group(1) if found else "unknown"


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("problems")
    ap.add_argument("--out", required=True)
    ap.add_argument("--answers", help="reconfig sweep --write-answers FILE: restart from ours too")
    ap.add_argument("--only", help="comma-separated problem indices")
    ap.add_argument("--starts", default=",".join(ALL_STARTS))
    args = ap.parse_args()

    problems = [json.loads(line) for line in open(args.problems) if line.strip()]
    ours = {}
    if args.answers:
        for line in open(args.answers):
            if line.strip():
                a = json.loads(line)
                ours[a["index"]] = a
    # --only also sets the order (so an interrupted run has done a balanced subset).
    order = [int(v) for v in args.only.split(",")] if args.only else list(range(len(problems)))
    # `--starts ""` with `--answers`: the restart from ours alone (issue 28 item 4).
    starts = [s for s in args.starts.split(",") if s]
    ipopt_version = ipopt_banner_version()
    header = {
        "header": {
            "command": " ".join(["python3", "tests/oracle/planner_a_ipopt.py"] + sys.argv[1:]),
            "casadi": ca.__version__,
            "ipopt": ipopt_version,
            "numpy": np.__version__,
            "python": platform.python_version(),
            "feas_tol_relative": FEAS_TOL,
            "control_tol_relative": CTRL_TOL,
            "grid_points": GRID,
            "max_rounds": MAX_ROUNDS,
            "starts": starts,
            "note": "J is the best feasible cost over the starts; solved=false means no start "
            "ended feasible (excluded from the 'of the problems the oracle solves' rates)",
        }
    }
    with open(args.out, "w") as out:
        out.write(json.dumps(header) + "\n")
        for index in order:
            item = problems[index]
            prob = item["problem"]
            tr = Transcription(prob)
            tr.build()
            tried = []
            best = None
            names = list(starts)
            if index in ours and ours[index].get("nodes"):
                names.append("ours")
            seen = []
            for name in names:
                X0 = start_positions(tr, name, index, ours.get(index, {}).get("nodes"))
                # The analytic guess equals the line when no bound is active: solve it once.
                if any(np.array_equal(X0, s) or np.max(np.abs(X0 - s)) < 1e-9 for s in seen):
                    tried.append({"start": name, "error": "same start as an earlier one"})
                    continue
                seen.append(X0)
                t0 = time.perf_counter()
                try:
                    X, statuses, rounds, iters = tr.solve_continuous(X0)
                    chk = tr.check(X)
                    J = tr.cost(X)
                except Exception as e:  # noqa: BLE001 - a failed start is recorded, not fatal
                    tried.append({"start": name, "error": str(e)})
                    continue
                dt = time.perf_counter() - t0
                rec = {
                    "start": name,
                    "cost": J,
                    "ipopt_status": statuses[-1],
                    "rounds": rounds,
                    "ipopt_iterations": iters,
                    "time_ms": dt * 1e3,
                    "ipopt_time_ms": tr.ipopt_wall_s * 1e3,
                    **chk,
                }
                tried.append(rec)
                if chk["feasible"] and (best is None or J < best["cost"]):
                    best = rec
            summary = {
                "index": index,
                "family": item["family"],
                "solved": best is not None,
                "cost": best["cost"] if best else None,
                "start": best["start"] if best else None,
                "ipopt_status": best["ipopt_status"] if best else None,
                "separation_margin": best["separation_margin"] if best else None,
                "control_margin": best["control_margin"] if best else None,
                "min_separation_lu": best["min_separation_lu"] if best else None,
                "best_without_ours": min(
                    (r["cost"] for r in tried if r.get("feasible") and r["start"] != "ours"), default=None
                ),
                "ours_restart": next(
                    (
                        {"cost": r.get("cost"), "feasible": r.get("feasible", False), "error": r.get("error")}
                        for r in tried
                        if r["start"] == "ours"
                    ),
                    None,
                ),
                # IPOPT's wall time (all keep-out rounds) from the first start, the line: one
                # complete solve, comparable with one of ours (later starts inherit its check
                # points and need fewer rounds).
                "ipopt_time_ms": next((r["ipopt_time_ms"] for r in tried if "ipopt_time_ms" in r), None),
                "starts": [
                    {k: r[k] for k in ("start", "cost", "feasible", "ipopt_status", "rounds", "ipopt_time_ms", "error") if k in r}
                    for r in tried
                ],
            }
            out.write(json.dumps(summary) + "\n")
            out.flush()
            print(
                f"{index:3d} {item['family']:11s} solved={summary['solved']} J={summary['cost']} start={summary['start']}",
                file=sys.stderr,
                flush=True,
            )


if __name__ == "__main__":
    main()
