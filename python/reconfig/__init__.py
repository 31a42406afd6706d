"""reconfig from Python: fixtures answered through the one request path, and campaigns.

Every answer comes from the same Rust code as ``reconfig solve`` and ``reconfig campaign``
(the core's ``wire::answer``), so the numbers are the same bits. The GIL is released while
planning. A refused input (a fixture the checks refuse, a dispersion that names no number)
raises ``ValueError`` whose message names the field, the value and the limit.

    import reconfig
    f = reconfig.load_fixture("fixtures/wang2018-gco-to-pco-2imp-roe.toml")
    r = reconfig.solve(f)                   # r.status, r.usable, r.cost, r.work_units
    t = reconfig.campaign(f, cases=10_000, disperse={"relative.initial_roe_m[1]": 50.0})
    t["cost"]                               # a NumPy array, one entry per case (NaN: no plan)
"""

from __future__ import annotations

import os
from dataclasses import dataclass
from typing import Dict, Mapping, Optional, Tuple

import numpy as np

from . import _reconfig

__all__ = ["Fixture", "Result", "Refused", "load_fixture", "solve", "campaign", "case_fixture"]


class Refused(ValueError):
    """A request refused before planning: by the fixture's checks or the planner (``status``
    ``Rejected``) or by the limits (``LimitExceeded``); the message names the field, the value
    and the limit."""

    def __init__(self, status: str, message: str):
        super().__init__(f"{status}: {message}")
        self.status = status
        self.message = message


@dataclass(frozen=True)
class Fixture:
    """A fixture file's text and the name messages give it."""

    name: str
    text: str

    def save(self, path: str | os.PathLike) -> None:
        """Write the fixture to ``path`` (``reconfig solve`` reads it as it is)."""
        with open(path, "w", encoding="utf-8") as f:
            f.write(self.text)


@dataclass(frozen=True)
class Result:
    """One answer, its fields named as the CLI's ``--json`` and ``campaign`` table name them."""

    status: str
    usable: Optional[bool]
    cost: Optional[float]
    work_units: Optional[int]
    solve_time_s: float
    message: str


def load_fixture(path: str | os.PathLike) -> Fixture:
    """Read a fixture file (TOML) of any planner."""
    with open(path, encoding="utf-8") as f:
        return Fixture(name=os.fspath(path), text=f.read())


def solve(fixture: Fixture) -> Result:
    """Answer a fixture of one request (planner A or B, a GEO tour, a LEO arc). A refused
    request raises :class:`Refused`; any status of a planned request is returned."""
    cols = _reconfig.solve_text(fixture.name, fixture.text)
    if cols["status"][0] in ("Rejected", "LimitExceeded"):
        raise Refused(cols["status"][0], cols["message"][0])
    return Result(
        status=cols["status"][0],
        usable=cols["usable"][0],
        cost=cols["cost"][0],
        work_units=cols["work_units"][0],
        solve_time_s=cols["solve_time_s"][0],
        message=cols["message"][0],
    )


def _check_seed(seed) -> None:
    if not isinstance(seed, int) or not 0 <= seed < 2**64:
        raise ValueError(f"seed = {seed!r} is not a whole number in [0, 2^64)")


def _laws(
    disperse: Optional[Mapping[str, float]], uniform: Optional[Mapping[str, Tuple[float, float]]]
):
    gauss = [f"{p}={float(s)!r}" for p, s in (disperse or {}).items()]
    flat = [f"{p}={float(lo)!r}:{float(hi)!r}" for p, (lo, hi) in (uniform or {}).items()]
    return gauss, flat


def campaign(
    fixture: Fixture,
    cases: int,
    disperse: Optional[Mapping[str, float]] = None,
    uniform: Optional[Mapping[str, Tuple[float, float]]] = None,
    seed: int = 1,
    threads: int = 0,
) -> Dict[str, np.ndarray]:
    """A Monte Carlo campaign (``reconfig campaign``): ``disperse`` maps a path to a standard
    deviation, ``uniform`` a path to ``(low, high)``; ``threads`` 0 uses every core. Returns
    columns as NumPy arrays, one entry per case: ``case``, one column per path, ``status``,
    ``usable``, ``cost`` (NaN without a usable plan), ``work_units`` (-1 when nothing was
    planned), ``solve_time_s``, ``message``. The same rows as the CLI, whatever ``threads``."""
    if not isinstance(cases, int) or cases < 0:
        raise ValueError(f"cases = {cases!r} is not a whole number >= 0")
    if not isinstance(threads, int) or threads < 0:
        raise ValueError(f"threads = {threads!r} is not a whole number >= 0")
    _check_seed(seed)
    gauss, flat = _laws(disperse, uniform)
    cols = _reconfig.campaign(fixture.name, fixture.text, cases, gauss, flat, seed, threads)
    out: Dict[str, np.ndarray] = {}
    for key, values in cols.items():
        if key in ("status", "message"):
            out[key] = np.array(values, dtype=object)
        elif key == "usable":
            out[key] = np.array([v is True for v in values], dtype=bool)
        elif key in ("case", "work_units"):
            out[key] = np.array([-1 if v is None else v for v in values], dtype=np.int64)
        else:
            out[key] = np.array([np.nan if v is None else v for v in values], dtype=np.float64)
    return out


def case_fixture(
    fixture: Fixture,
    case: int,
    disperse: Optional[Mapping[str, float]] = None,
    uniform: Optional[Mapping[str, Tuple[float, float]]] = None,
    seed: int = 1,
) -> Fixture:
    """Case ``case`` of a campaign as a fixture (``reconfig campaign --show-case``)."""
    _check_seed(seed)
    if not isinstance(case, int) or not 0 <= case < 2**64 - 1:
        raise ValueError(f"case = {case!r} is not a whole number in [0, 2^64 - 1)")
    gauss, flat = _laws(disperse, uniform)
    text = _reconfig.case_text(fixture.name, fixture.text, gauss, flat, seed, case)
    return Fixture(name=f"{fixture.name} case {case}", text=text)
