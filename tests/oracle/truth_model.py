#!/usr/bin/env python3
"""Independent oracle for the host's truth model (host/src/truth): the same force model written
again in NumPy along other routes, integrated by SciPy's DOP853 at tighter tolerances.

Usage: python3 tests/oracle/truth_model.py > fixtures/golden/truth-model-oracle.json

What is shared with the Rust code is the model's definition, not its implementation:
* the JGM-3 coefficients to degree and order 8, read from the vendored host/data/JGM3-deg8.gfc;
* the Earth-fixed frame: the inertial frame turned by GMST (IAU 1982, UT1 = TT) about z;
* drag: Vallado's exponential atmosphere (4th ed., table 8-4, typed in again here), altitude
  above a sphere of 6378.137 km, atmosphere co-rotating at 7.292115e-5 rad/s, a = -1/2 B rho
  |v_rel| v_rel with B = Cd A / m;
* Sun and Moon: Montenbruck & Gill's low-precision series (Satellite Orbits, eq. 3.43-3.49),
  typed in again here, on the equinox of date; GM_sun 1.32712440018e11, GM_moon 4902.800066.
Other routes: the field's acceleration is the gradient of the potential in spherical
coordinates (fully normalised Legendre functions by the standard column recursion, derivative
in latitude, Vallado eq. 8-27), where the Rust code uses Cunningham's Cartesian V/W recursion
on un-normalised coefficients; the integrator is SciPy's DOP853 (rtol 1e-13, atol 1e-10 km)
where the Rust code uses its own Dormand-Prince 5(4) at 1e-12.
"""
import json
import math
import os

import numpy as np
from scipy.integrate import solve_ivp

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
GFC = os.path.join(ROOT, "host", "data", "JGM3-deg8.gfc")
NMAX = 8
DEG = math.pi / 180.0
ARCSEC = DEG / 3600.0


def read_gfc(path):
    gm = radius = None
    cbar = np.zeros((NMAX + 1, NMAX + 1))
    sbar = np.zeros((NMAX + 1, NMAX + 1))
    body = False
    with open(path) as f:
        for line in f:
            w = line.split()
            if not w or w[0].startswith("#"):
                continue
            if not body:
                if w[0] == "end_of_head":
                    body = True
                elif w[0] == "earth_gravity_constant":
                    gm = float(w[1]) * 1e-9
                elif w[0] == "radius":
                    radius = float(w[1]) * 1e-3
                continue
            n, m = int(w[1]), int(w[2])
            if n <= NMAX:
                cbar[n, m] = float(w[3])
                sbar[n, m] = float(w[4])
    return gm, radius, cbar, sbar


GM, RE, CBAR, SBAR = read_gfc(GFC)


def legendre(nmax, phi):
    """Fully normalised P_nm(sin phi) and their derivatives in phi, n, m <= nmax."""
    s, c = math.sin(phi), math.cos(phi)
    p = np.zeros((nmax + 2, nmax + 2))
    p[0, 0] = 1.0
    p[1, 1] = math.sqrt(3.0) * c
    for m in range(2, nmax + 2):
        p[m, m] = math.sqrt((2 * m + 1) / (2 * m)) * c * p[m - 1, m - 1]
    for m in range(0, nmax + 1):
        for n in range(m + 1, nmax + 2):
            a = math.sqrt((2 * n - 1) * (2 * n + 1) / ((n - m) * (n + m)))
            b = math.sqrt((2 * n + 1) * (n + m - 1) * (n - m - 1) / ((n - m) * (n + m) * (2 * n - 3))) if n >= 2 else 0.0
            p[n, m] = a * s * p[n - 1, m] - (b * p[n - 2, m] if n >= 2 else 0.0)
    dp = np.zeros((nmax + 1, nmax + 1))
    t = s / c
    for n in range(0, nmax + 1):
        for m in range(0, n + 1):
            k = math.sqrt((n - m) * (n + m + 1) / (2.0 if m == 0 else 1.0))
            dp[n, m] = k * p[n, m + 1] - m * t * p[n, m]
    return p, dp


def field_accel_fixed(r, nmax, mmax):
    x, y, z = r
    rn = math.sqrt(x * x + y * y + z * z)
    rxy = math.sqrt(x * x + y * y)
    phi = math.asin(z / rn)
    lam = math.atan2(y, x)
    p, dp = legendre(nmax, phi)
    dudr = dudphi = dudlam = 0.0
    for n in range(0, nmax + 1):
        q = (RE / rn) ** n
        for m in range(0, min(n, mmax) + 1):
            cm, sm = math.cos(m * lam), math.sin(m * lam)
            cs = CBAR[n, m] * cm + SBAR[n, m] * sm
            dudr += (n + 1) * q * p[n, m] * cs
            dudphi += q * dp[n, m] * cs
            dudlam += q * m * p[n, m] * (SBAR[n, m] * cm - CBAR[n, m] * sm)
    dudr *= -GM / rn**2
    dudphi *= GM / rn
    dudlam *= GM / rn
    k = dudr / rn - z / (rn * rn * rxy) * dudphi
    return np.array([
        k * x - dudlam / (rxy * rxy) * y,
        k * y + dudlam / (rxy * rxy) * x,
        dudr / rn * z + rxy / (rn * rn) * dudphi,
    ])


def julian_date(y, mo, d, h=0, mi=0, s=0.0):
    if mo <= 2:
        y, mo = y - 1, mo + 12
    a = y // 100
    b = 2 - a + a // 4
    return math.floor(365.25 * (y + 4716)) + math.floor(30.6001 * (mo + 1)) + d + b - 1524.5 + (h + mi / 60 + s / 3600) / 24


def gmst(jd):
    d = jd - 2451545.0
    t = d / 36525.0
    return math.fmod((280.46061837 + 360.98564736629 * d + 0.000387933 * t * t - t**3 / 38710000.0) * DEG, 2 * math.pi)


EPS = 23.43929111 * DEG


def ecl_to_eq(r, lon, lat):
    v = np.array([r * math.cos(lon) * math.cos(lat), r * math.sin(lon) * math.cos(lat), r * math.sin(lat)])
    ce, se = math.cos(EPS), math.sin(EPS)
    return np.array([v[0], ce * v[1] - se * v[2], se * v[1] + ce * v[2]])


def sun(jd):
    t = (jd - 2451545.0) / 36525.0
    m = (357.5256 + 35999.049 * t) * DEG
    lon = 282.94 * DEG + m + (6892 * math.sin(m) + 72 * math.sin(2 * m)) * ARCSEC + 1.3972 * DEG * t
    r = (149.619 - 2.499 * math.cos(m) - 0.021 * math.cos(2 * m)) * 1e6
    return ecl_to_eq(r, lon, 0.0)


def moon(jd):
    t = (jd - 2451545.0) / 36525.0
    l0 = (218.31617 + 481267.88088 * t) * DEG
    l = (134.96292 + 477198.86753 * t) * DEG
    lp = (357.52543 + 35999.04944 * t) * DEG
    f = (93.27283 + 483202.01873 * t) * DEG
    d = (297.85027 + 445267.11135 * t) * DEG
    terms = [(22640, l), (769, 2 * l), (-4586, l - 2 * d), (2370, 2 * d), (-668, lp), (-412, 2 * f),
             (-212, 2 * l - 2 * d), (-206, l + lp - 2 * d), (192, l + 2 * d), (-165, lp - 2 * d),
             (148, l - lp), (-125, d), (-110, l + lp), (-55, 2 * f - 2 * d)]
    lon = l0 + sum(k * math.sin(x) for k, x in terms) * ARCSEC
    lat_terms = [(-526, f - 2 * d), (44, l + f - 2 * d), (-31, -l + f - 2 * d), (-25, -2 * l + f),
                 (-23, lp + f - 2 * d), (21, -l + f), (11, -lp + f - 2 * d)]
    lat = (18520 * math.sin(f + lon - l0 + (412 * math.sin(2 * f) + 541 * math.sin(lp)) * ARCSEC)
           + sum(k * math.sin(x) for k, x in lat_terms)) * ARCSEC
    rterms = [(-20905, l), (-3699, 2 * d - l), (-2956, 2 * d), (-570, 2 * l), (246, 2 * l - 2 * d),
              (-205, lp - 2 * d), (-171, l + 2 * d), (-152, l + lp - 2 * d)]
    r = 385000 + sum(k * math.cos(x) for k, x in rterms)
    return ecl_to_eq(r, lon, lat)


# Vallado table 8-4: base altitude km, density kg/m^3, scale height km.
ATMOSPHERE = [
    (0, 1.225, 7.249), (25, 3.899e-2, 6.349), (30, 1.774e-2, 6.682), (40, 3.972e-3, 7.554),
    (50, 1.057e-3, 8.382), (60, 3.206e-4, 7.714), (70, 8.770e-5, 6.549), (80, 1.905e-5, 5.799),
    (90, 3.396e-6, 5.382), (100, 5.297e-7, 5.877), (110, 9.661e-8, 7.263), (120, 2.438e-8, 9.473),
    (130, 8.484e-9, 12.636), (140, 3.845e-9, 16.149), (150, 2.070e-9, 22.523),
    (180, 5.464e-10, 29.740), (200, 2.789e-10, 37.105), (250, 7.248e-11, 45.546),
    (300, 2.418e-11, 53.628), (350, 9.518e-12, 53.298), (400, 3.725e-12, 58.515),
    (450, 1.585e-12, 60.828), (500, 6.967e-13, 63.822), (600, 1.454e-13, 71.835),
    (700, 3.614e-14, 88.667), (800, 1.170e-14, 124.64), (900, 5.245e-15, 181.05),
    (1000, 3.019e-15, 268.00),
]
OMEGA_EARTH = 7.292115e-5


def density(h):
    base, rho0, scale = ATMOSPHERE[0]
    for row in ATMOSPHERE:
        if h >= row[0]:
            base, rho0, scale = row
    return rho0 * math.exp(-(h - base) / scale)


def third(gm, s, r):
    d = s - r
    return gm * (d / np.linalg.norm(d) ** 3 - s / np.linalg.norm(s) ** 3)


def rhs(t, y, case):
    r, v = y[:3], y[3:]
    jd = case["epoch_jd"] + t / 86400.0
    th = gmst(jd)
    c, s = math.cos(th), math.sin(th)
    rf = np.array([c * r[0] + s * r[1], -s * r[0] + c * r[1], r[2]])
    gf = field_accel_fixed(rf, case["degree"], case["order"])
    a = np.array([c * gf[0] - s * gf[1], s * gf[0] + c * gf[1], gf[2]])
    if case["ballistic_m2_kg"] is not None:
        vrel = v - np.cross([0.0, 0.0, OMEGA_EARTH], r)
        h = np.linalg.norm(r) - 6378.137
        a = a - 0.5 * case["ballistic_m2_kg"] * density(h) * np.linalg.norm(vrel) * vrel * 1e3
    if case["sun"]:
        a = a + third(1.32712440018e11, sun(jd), r)
    if case["moon"]:
        a = a + third(4902.800066, moon(jd), r)
    return np.concatenate([v, a])


def kepler_state(a, e, i, raan, argp, ma, mu=GM):
    ecc_anom = ma
    for _ in range(50):
        ecc_anom -= (ecc_anom - e * math.sin(ecc_anom) - ma) / (1 - e * math.cos(ecc_anom))
    nu = 2 * math.atan2(math.sqrt(1 + e) * math.sin(ecc_anom / 2), math.sqrt(1 - e) * math.cos(ecc_anom / 2))
    p = a * (1 - e * e)
    r = p / (1 + e * math.cos(nu))
    rp = np.array([r * math.cos(nu), r * math.sin(nu), 0.0])
    vp = np.array([-math.sqrt(mu / p) * math.sin(nu), math.sqrt(mu / p) * (e + math.cos(nu)), 0.0])
    co, so, ci, si, cw, sw = math.cos(raan), math.sin(raan), math.cos(i), math.sin(i), math.cos(argp), math.sin(argp)
    rot = np.array([
        [co * cw - so * sw * ci, -co * sw - so * cw * ci, so * si],
        [so * cw + co * sw * ci, -so * sw + co * cw * ci, -co * si],
        [sw * si, cw * si, ci],
    ])
    return rot @ rp, rot @ vp


def self_check():
    """The Legendre derivative against a difference quotient (guards the oracle itself)."""
    phi, h = 0.7, 1e-6
    _, dp = legendre(NMAX, phi)
    pp, _ = legendre(NMAX, phi + h)
    pm, _ = legendre(NMAX, phi - h)
    for n in range(NMAX + 1):
        for m in range(n + 1):
            fd = (pp[n, m] - pm[n, m]) / (2 * h)
            assert abs(fd - dp[n, m]) < 1e-7 * max(1.0, abs(dp[n, m])), (n, m, fd, dp[n, m])


def main():
    self_check()
    epoch = julian_date(2025, 1, 1)
    cases = [
        # The SSO chief of fixtures/sso-leo-pair-e0-2imp.toml, everything on, one day.
        dict(name="sso-700km-full-1d", elements=[7078.137, 0.001, 98.2, 30.0, 90.0, 10.0],
             degree=8, order=8, ballistic_m2_kg=0.022, sun=True, moon=True, duration_s=86400.0),
        # Wang 2018's chief (perigee 313 km): drag large, everything on, one day.
        dict(name="wang2018-chief-full-1d", elements=[7178.137, 0.0678, 63.4349, 112.0, 0.0, 0.0],
             degree=8, order=8, ballistic_m2_kg=0.022, sun=True, moon=True, duration_s=86400.0),
        # GEO, where the Sun and the Moon dominate the perturbations, two days.
        dict(name="geo-field-sun-moon-2d", elements=[42164.17, 0.0002, 0.05, 0.0, 0.0, 75.0],
             degree=8, order=8, ballistic_m2_kg=None, sun=True, moon=True, duration_s=172800.0),
    ]
    out = {
        "_comment": "End states of the truth model's force model from the independent NumPy/SciPy oracle "
                    "tests/oracle/truth_model.py (spherical-coordinate gradient of the JGM-3 potential, "
                    "DOP853 rtol 1e-13), not from the code under test. Epoch 2025-01-01T00:00:00 TT "
                    "(JD 2460676.5). Elements: osculating two-body a km, e, i, RAAN, argp, M deg in the "
                    "inertial frame of date, with GM of JGM-3.",
        "epoch_jd": epoch,
        "cases": [],
    }
    for case in cases:
        case = dict(case, epoch_jd=epoch)
        a, e, i, raan, argp, ma = case["elements"]
        r0, v0 = kepler_state(a, e, i * DEG, raan * DEG, argp * DEG, ma * DEG)
        sol = solve_ivp(rhs, (0.0, case["duration_s"]), np.concatenate([r0, v0]), method="DOP853",
                        rtol=1e-13, atol=1e-10, args=(case,))
        assert sol.success, sol.message
        y = sol.y[:, -1]
        out["cases"].append({
            "name": case["name"],
            "degree": case["degree"],
            "order": case["order"],
            "ballistic_m2_kg": case["ballistic_m2_kg"],
            "sun": case["sun"],
            "moon": case["moon"],
            "duration_s": case["duration_s"],
            "start_pos_km": [float(x) for x in r0],
            "start_vel_km_s": [float(x) for x in v0],
            "end_pos_km": [float(x) for x in y[:3]],
            "end_vel_km_s": [float(x) for x in y[3:]],
            "oracle_steps": int(sol.t.size - 1),
        })
    print(json.dumps(out, indent=1))


if __name__ == "__main__":
    main()
