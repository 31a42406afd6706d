#!/usr/bin/env python3
"""Independent oracle for planner B's input forms (numpy only; shares no code with the Rust
implementation). Writes the inputs of two fixtures from fixtures in the classical form:

* `roe FIXTURE`: the fixture's relative elements as quasi-nonsingular ROE in metres
  (a da/a, a (du + dOmega cos i), a d(e cos omega), a d(e sin omega), a di, a dOmega sin i), for
  `fixtures/wang2018-gco-to-pco-2imp-roe.toml`.
* `state FIXTURE`: the chief's, the deputy's initial and the deputy's target mean orbits as
  osculating ECI states (km, km/s) by first-order J2 averaging (Kozai's method, short-period
  terms): q_osc = q_mean + (1/n) integral (q'(lambda) - <q'>) d lambda on the mean orbit, with
  q' = dq/dt of the J2-perturbed two-body motion, computed here by central differences of this
  script's own state -> equinoctial conversion along the perturbed velocity field (not from
  Gauss's equations), integrated with numpy's FFT, for
  `fixtures/sso-leo-pair-e0-2imp-state.toml`.

The plans of these fixtures equal the classical fixtures' plans (the conversions are exact
inverses in the planner), so their golden results are the ones of
tests/oracle/planner_b_nonsingular.py for the classical fixtures.
"""
import math
import sys
import tomllib

import numpy as np

sys.path.insert(0, __file__.rsplit("/", 1)[0])
import planner_b_nonsingular as ns  # noqa: E402  (its textbook conversions)

D2R = math.pi / 180.0
SAMPLES = 128


def load_classical(path):
    with open(path, "rb") as fh:
        f = tomllib.load(fh)
    c = f["chief"]
    chief = np.array([c["semi_major_axis_km"], c["eccentricity"], c["inclination_deg"] * D2R,
                      c["raan_deg"] * D2R, c["arg_perigee_deg"] * D2R, c["mean_anomaly_deg"] * D2R])
    unit = np.array([1.0, 1.0, D2R, D2R, D2R, D2R])
    return chief, np.array(f["relative"]["initial"]) * unit, np.array(f["relative"]["target"]) * unit


def roe(chief, rel):
    a, e, i, O, w, M = chief
    d = chief + rel
    return a * 1e3 * np.array([
        rel[0] / a,
        (rel[4] + rel[5]) + rel[3] * math.cos(i),
        d[1] * math.cos(d[4]) - e * math.cos(w),
        d[1] * math.sin(d[4]) - e * math.sin(w),
        rel[2],
        rel[3] * math.sin(i),
    ])


def j2_accel(r):
    x, y, z = r
    rn = np.linalg.norm(r)
    k = -1.5 * ns.J2 * ns.MU * ns.RE**2 / rn**5
    z2 = z * z / (rn * rn)
    return k * np.array([x * (1 - 5 * z2), y * (1 - 5 * z2), z * (3 - 5 * z2)])


def perturbation_rates(q):
    """dq/dt from the J2 acceleration alone: d/dh of q(r, v + h a) at h = 0."""
    r, v = ns.to_state(q)
    a = j2_accel(r)
    h = 10.0  # s: dv = h |a| ~ 1e-4 km/s; central differences leave O((dv/v)^2) ~ 1e-10
    p = ns.to_elements(r, v + h * a, q)
    m = ns.to_elements(r, v - h * a, q)
    return (p - m) / (2 * h)


def short_period(q):
    n = math.sqrt(ns.MU / q[0]**3)
    lam = q[1] + 2 * math.pi * np.arange(SAMPLES) / SAMPLES
    rates = np.array([perturbation_rates(np.concatenate(([q[0], l], q[2:]))) for l in lam])

    def integral(f):
        c = np.fft.rfft(f) / SAMPLES
        k = np.arange(c.size)
        g = np.zeros_like(c)
        g[1:-1] = c[1:-1] / (1j * k[1:-1])
        # the antiderivative's samples (zero mean), over n
        return np.fft.irfft(g * SAMPLES, SAMPLES) / n

    da = integral(rates[:, 0])
    rates[:, 1] += -1.5 * n / q[0] * da
    return np.array([integral(rates[:, j])[0] for j in range(6)])


def osculating_state(classical):
    q = ns.from_classical(classical)
    osc = q + short_period(q)
    return ns.to_state(osc)


if __name__ == "__main__":
    mode, path = sys.argv[1], sys.argv[2]
    chief, init, targ = load_classical(path)
    if mode == "roe":
        print("initial_roe_m = [" + ", ".join(f"{x:.12e}" for x in roe(chief, init)) + "]")
        print("target_roe_m  = [" + ", ".join(f"{x:.12e}" for x in roe(chief, targ)) + "]")
    elif mode == "state":
        for name, el in (("chief", chief), ("deputy.initial", chief + init),
                         ("deputy.target", chief + targ)):
            r, v = osculating_state(el)
            print(f"[{name}]")
            print("position_km = [" + ", ".join(f"{x:.15e}" for x in r) + "]")
            print("velocity_km_s = [" + ", ".join(f"{x:.15e}" for x in v) + "]")
    else:
        raise SystemExit("mode: roe | state")
