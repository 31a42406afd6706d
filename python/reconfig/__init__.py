"""reconfig from Python: every planner through the one request path, and campaigns.

Every answer comes from the same Rust code as ``reconfig solve`` and ``reconfig campaign``
(the core's ``wire::answer``), so the numbers are the same bits. The GIL is released while
planning. A refused input (a fixture the checks refuse, a setting outside the limits, an
array of the wrong shape, a NaN) raises ``ValueError`` (:class:`Refused` for a request the
checks refused) whose message names the field, the value and the limit.

    import reconfig
    f = reconfig.load_fixture("fixtures/wang2018-gco-to-pco-2imp-roe.toml")
    r = reconfig.solve(f)          # r.status, r.usable, r.cost, r.impulses, r.end_state, ...
    a = reconfig.plan_a(initial, final, horizon=10.0, max_control=1.0, keep_out=2.0, nodes=10)
    a.states                       # NumPy array (spacecraft, nodes, 6)
    t = reconfig.campaign(f, cases=10_000, disperse={"relative.initial_roe_m[1]": 50.0})
    t["cost"]                      # a NumPy array, one entry per case (NaN: no plan)

``reconfig.cluster.campaign`` runs the same campaign on a Dask cluster.
"""

from __future__ import annotations

import functools
import json
import math
import os
from dataclasses import dataclass, field
from typing import Any, Dict, Mapping, Optional, Sequence, Tuple, Union

import numpy as np

from . import _reconfig

__all__ = [
    "Fixture",
    "Result",
    "Refused",
    "load_fixture",
    "solve",
    "fixture_a",
    "plan_a",
    "fixture_b",
    "plan_b",
    "campaign",
    "case_fixture",
]


class Refused(ValueError):
    """A request refused before planning: by the fixture's checks or the planner (``status``
    ``Rejected``) or by the limits (``LimitExceeded``); the message names the field, the value
    and the limit. ``report`` is the JSON object ``reconfig solve --json`` prints for it (for a
    refusal by the limits: ``setting``, ``value``, ``limit``), or None when the fixture's own
    checks refused it before a request was made."""

    def __init__(self, status: str, message: str, report: Optional[Dict[str, Any]] = None):
        super().__init__(f"{status}: {message}")
        self.status = status
        self.message = message
        self.report = report


@dataclass(frozen=True)
class Fixture:
    """A fixture file's text and the name messages give it."""

    name: str
    text: str

    def save(self, path: Union[str, os.PathLike]) -> None:
        """Write the fixture to ``path`` (``reconfig solve`` reads it as it is)."""
        with open(path, "w", encoding="utf-8") as f:
            f.write(self.text)

    def document(self) -> Dict[str, Any]:
        """The fixture's TOML document as a dict (change it and make a fixture of it with
        :meth:`from_document`)."""
        return json.loads(_reconfig.json_from_toml(self.text))

    @classmethod
    def from_document(cls, doc: Mapping[str, Any], name: Optional[str] = None) -> "Fixture":
        """A fixture from its document (the keys of the fixture files: ``planner``,
        ``name``, ...); NumPy arrays and numbers are written as TOML arrays and numbers."""
        plain = _plain(doc)
        bad = _first_not_finite(plain, "")
        if bad is not None:
            raise ValueError(f"{bad[0]} = {bad[1]} is not finite")
        text = _reconfig.toml_from_json(json.dumps(plain, allow_nan=False))
        return cls(name=name or str(doc.get("name", "fixture")), text=text)


def _first_not_finite(v: Any, path: str) -> Optional[Tuple[str, float]]:
    """The first NaN or infinity of a document, with its path (``spacecraft[1].initial[3]``,
    as a campaign's paths name numbers)."""
    if isinstance(v, float) and not math.isfinite(v):
        return path, v
    if isinstance(v, dict):
        items = ((f"{path}.{k}" if path else str(k), x) for k, x in v.items())
    elif isinstance(v, list):
        items = ((f"{path}[{i}]", x) for i, x in enumerate(v))
    else:
        return None
    for p, x in items:
        found = _first_not_finite(x, p)
        if found is not None:
            return found
    return None


def _plain(v: Any) -> Any:
    """A document with NumPy values made plain Python (for JSON)."""
    if isinstance(v, Mapping):
        return {str(k): _plain(x) for k, x in v.items()}
    if isinstance(v, np.ndarray):
        return v.tolist()
    if isinstance(v, (list, tuple)):
        return [_plain(x) for x in v]
    if isinstance(v, np.generic):
        return v.item()
    return v


def _arrays(v: Any) -> Any:
    """A JSON value with its arrays of numbers (nested, rectangular) as NumPy arrays."""
    if isinstance(v, dict):
        return {k: _arrays(x) for k, x in v.items()}
    if isinstance(v, list):
        if v and all(isinstance(x, (int, float, list)) and not isinstance(x, bool) for x in v):
            try:
                a = np.array(v)
            except ValueError:  # ragged
                a = None
            if a is not None and a.dtype.kind in "if":
                return a
        return [_arrays(x) for x in v]
    return v


@dataclass(frozen=True)
class Result:
    """One answer. ``status``, ``usable``, ``cost``, ``work_units``, ``solve_time_s`` and
    ``message`` are the campaign table's columns; ``report`` is the JSON object
    ``reconfig solve --json`` prints (its arrays made NumPy arrays on first use), and its fields
    read as attributes too: ``r.states``,
    ``r.certificate``, ``r.impulses``, ``r.total_dv_mps``, ... ``cost`` is planner A's J or
    the others' total Δv (m/s), given for a usable plan."""

    status: str
    usable: Optional[bool]
    cost: Optional[float]
    work_units: Optional[int]
    solve_time_s: float
    message: str
    plain_report: Dict[str, Any] = field(default_factory=dict, repr=False, compare=False)

    @functools.cached_property
    def report(self) -> Dict[str, Any]:
        """The object ``reconfig solve --json`` prints, numeric arrays as NumPy arrays."""
        return _arrays(self.plain_report)

    def __getattr__(self, name: str) -> Any:
        if name.startswith("_") or name in ("report", "plain_report"):
            raise AttributeError(name)
        report = self.report
        if name in report:
            return report[name]
        raise AttributeError(f"Result has no field {name!r} (the report's are {sorted(report)})")


def load_fixture(path: Union[str, os.PathLike]) -> Fixture:
    """Read a fixture file (TOML) of any planner."""
    with open(path, encoding="utf-8") as f:
        return Fixture(name=os.fspath(path), text=f.read())


def solve(fixture: Fixture) -> Result:
    """Answer a fixture of one request (planner A or B, a GEO tour, a LEO arc). A refused
    request raises :class:`Refused`; any status of a planned request is returned."""
    cols, report = _reconfig.solve_text(fixture.name, fixture.text)
    status = cols["status"][0]
    if status in ("Rejected", "LimitExceeded"):
        raise Refused(status, cols["message"][0], report)
    return Result(
        status=status,
        usable=cols["usable"][0],
        cost=cols["cost"][0],
        work_units=cols["work_units"][0],
        solve_time_s=cols["solve_time_s"][0],
        message=cols["message"][0],
        plain_report=report or {},
    )


def _float_array(name: str, value: Any, shape: Tuple[Optional[int], ...]) -> np.ndarray:
    """``value`` as a float64 array of ``shape`` (None: any length), all finite; else a
    ``ValueError`` naming the field, what it is and what it must be."""
    a = np.asarray(value)
    if a.dtype.kind not in "iuf":
        raise ValueError(f"{name}: dtype {a.dtype} is not a real number type (int or float)")
    want = "(" + ", ".join("any" if n is None else str(n) for n in shape) + ")"
    if a.ndim != len(shape) or any(n is not None and n != m for n, m in zip(shape, a.shape)):
        raise ValueError(f"{name}: shape {a.shape} is not {want}")
    a = a.astype(np.float64)
    bad = np.argwhere(~np.isfinite(a))
    if len(bad):
        at = tuple(int(i) for i in bad[0])
        raise ValueError(f"{name}{list(at)} = {a[at]} is not finite")
    return a


def _number(name: str, value: Any) -> float:
    if isinstance(value, bool) or not isinstance(value, (int, float, np.integer, np.floating)):
        raise ValueError(f"{name} = {value!r} is not a number")
    x = float(value)
    if not np.isfinite(x):
        raise ValueError(f"{name} = {x} is not finite")
    return x


def _whole(name: str, value: Any, low: int, high: int) -> int:
    if isinstance(value, bool) or not isinstance(value, (int, np.integer)) or not low <= value <= high:
        raise ValueError(f"{name} = {value!r} is not a whole number in [{low}, {high}]")
    return int(value)


def fixture_a(
    initial: Any,
    final: Any,
    horizon: float,
    max_control: float,
    keep_out: float,
    nodes: int,
    mass: Any = None,
    test_points: bool = True,
    settings: Optional[Mapping[str, Any]] = None,
    name: str = "plan_a",
) -> Fixture:
    """Planner A's problem as a fixture: ``initial`` and ``final`` states, arrays (M, 6) of
    ``[x, y, z, vx, vy, vz]`` in the normalised units (LU, LU/TU); the horizon T (TU), the
    control bound Umax, the keep-out distance d (LU), the polynomial degree N (``nodes``),
    masses (M,) (default 1), and ``settings`` by the core's names (``Settings`` of
    ``reconfig_core::pseudospectral``; a name it does not have is refused)."""
    x0 = _float_array("initial", initial, (None, 6))
    x1 = _float_array("final", final, (x0.shape[0], 6))
    m = np.ones(x0.shape[0]) if mass is None else _float_array("mass", mass, (x0.shape[0],))
    doc: Dict[str, Any] = {
        "name": name,
        "planner": "pseudospectral",
        "horizon": _number("horizon", horizon),
        "max_control": _number("max_control", max_control),
        "keep_out": _number("keep_out", keep_out),
        "nodes": _whole("nodes", nodes, 0, 65535),
        "test_points": bool(test_points),
        "spacecraft": [
            {"mass": float(mk), "initial": a.tolist(), "final": b.tolist()}
            for mk, a, b in zip(m, x0, x1)
        ],
    }
    if settings:
        doc["settings"] = dict(settings)
    return Fixture.from_document(doc, name=name)


def plan_a(initial: Any, final: Any, horizon: float, max_control: float, keep_out: float,
           nodes: int, **options: Any) -> Result:
    """Plan planner A's problem (see :func:`fixture_a` for the arguments): ``solve`` of its
    fixture. ``r.states`` (M, N+1, 6), ``r.controls`` (M, N+1, 3), ``r.node_times`` (N+1,),
    ``r.certificate``, ``r.min_separation``, ... as ``reconfig solve --json`` names them."""
    return solve(fixture_a(initial, final, horizon, max_control, keep_out, nodes, **options))


_CLASSICAL = (
    "semi_major_axis_km",
    "eccentricity",
    "inclination_deg",
    "raan_deg",
    "arg_perigee_deg",
    "mean_anomaly_deg",
)


def fixture_b(
    chief: Any,
    initial: Any,
    target: Any,
    impulses: Any = None,
    search: Optional[Tuple[int, int]] = None,
    form: str = "elements",
    settings: Optional[Mapping[str, Any]] = None,
    name: str = "plan_b",
) -> Fixture:
    """Planner B's problem as a fixture. ``chief``: mean classical elements, an array (6,)
    ``[a_km, e, i_deg, raan_deg, argp_deg, M_deg]``, or a mapping of any chief form of the
    fixture files. ``initial``, ``target``: the relative state, arrays (6,): with
    ``form="elements"`` ``[da_km, de, di_deg, dRAAN_deg, dargp_deg, dM_deg]``, with
    ``form="roe_m"`` the quasi-nonsingular ROE in metres. The impulse points: ``impulses``, an
    array (K, 2) of ``[mean argument of latitude in degrees, whole revolutions]``, or
    ``search=(K, max_revolutions)`` for the bounded search."""
    if isinstance(chief, Mapping):
        chief_doc = _plain(chief)
    else:
        c = _float_array("chief", chief, (6,))
        chief_doc = dict(zip(_CLASSICAL, c.tolist()))
    x0 = _float_array("initial", initial, (6,))
    x1 = _float_array("target", target, (6,))
    if form == "elements":
        relative = {"initial": x0.tolist(), "target": x1.tolist()}
    elif form == "roe_m":
        relative = {"initial_roe_m": x0.tolist(), "target_roe_m": x1.tolist()}
    else:
        raise ValueError(f"form = {form!r} is not 'elements' or 'roe_m'")
    doc: Dict[str, Any] = {"name": name, "planner": "impulsive", "chief": chief_doc,
                           "relative": relative}
    if (impulses is None) == (search is None):
        raise ValueError("give either impulses (an array (K, 2)) or search=(K, max_revolutions)")
    if impulses is not None:
        points = _float_array("impulses", impulses, (None, 2))
        entries = []
        for k, (angle_deg, revs) in enumerate(points):
            if revs != np.round(revs) or not -(2**31) <= revs < 2**31:
                raise ValueError(f"impulses[{k}, 1] = {revs} is not a whole number of revolutions")
            entries.append({"arg_latitude_deg": float(angle_deg), "revolutions": int(revs)})
        doc["impulse"] = entries
    else:
        k, revs = search
        doc["search"] = {
            "impulses": _whole("search[0] (impulses)", k, 0, 255),
            "max_revolutions": _whole("search[1] (max_revolutions)", revs, -(2**31), 2**31 - 1),
        }
    if settings:
        doc["settings"] = dict(settings)
    return Fixture.from_document(doc, name=name)


def plan_b(chief: Any, initial: Any, target: Any, **options: Any) -> Result:
    """Plan planner B's problem (see :func:`fixture_b` for the arguments): ``solve`` of its
    fixture. ``r.impulses`` (each with ``dv_rtn_mps``, ``time_s``, ...), ``r.total_dv_mps``,
    ``r.end_state``, ``r.terminal_error_m``, ... as ``reconfig solve --json`` names them."""
    return solve(fixture_b(chief, initial, target, **options))


def _check_seed(seed: Any) -> None:
    if isinstance(seed, bool) or not isinstance(seed, int) or not 0 <= seed < 2**64:
        raise ValueError(f"seed = {seed!r} is not a whole number in [0, 2^64)")


def _laws(
    disperse: Optional[Mapping[str, float]], uniform: Optional[Mapping[str, Tuple[float, float]]]
):
    gauss = [f"{p}={float(s)!r}" for p, s in (disperse or {}).items()]
    flat = [f"{p}={float(lo)!r}:{float(hi)!r}" for p, (lo, hi) in (uniform or {}).items()]
    return gauss, flat


def _check_campaign(cases: Any, threads: Any, seed: Any) -> None:
    if isinstance(cases, bool) or not isinstance(cases, int) or cases < 0:
        raise ValueError(f"cases = {cases!r} is not a whole number >= 0")
    if isinstance(threads, bool) or not isinstance(threads, int) or threads < 0:
        raise ValueError(f"threads = {threads!r} is not a whole number >= 0")
    _check_seed(seed)


def _table(cols: Mapping[str, Sequence[Any]]) -> Dict[str, np.ndarray]:
    """The extension's columns as NumPy arrays."""
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


def campaign(
    fixture: Fixture,
    cases: int,
    disperse: Optional[Mapping[str, float]] = None,
    uniform: Optional[Mapping[str, Tuple[float, float]]] = None,
    seed: int = 1,
    threads: int = 0,
    out: Union[str, os.PathLike, None] = None,
    times: bool = True,
    progress: bool = False,
) -> Dict[str, np.ndarray]:
    """A Monte Carlo campaign (``reconfig campaign``): ``disperse`` maps a path to a standard
    deviation, ``uniform`` a path to ``(low, high)``; ``threads`` 0 uses every core. Returns
    columns as NumPy arrays, one entry per case: ``case``, one column per path, ``status``,
    ``usable``, ``cost`` (NaN without a usable plan), ``work_units`` (-1 when nothing was
    planned), ``solve_time_s``, ``message``. The same rows as the CLI, whatever ``threads``.
    ``out``: also write the table as CSV, the bytes ``reconfig campaign --out`` writes (the
    time column empty when ``times`` is False); ``progress``: a progress bar on stderr."""
    _check_campaign(cases, threads, seed)
    gauss, flat = _laws(disperse, uniform)
    cols, csv = _reconfig.campaign(
        fixture.name, fixture.text, cases, gauss, flat, seed, threads, 0, cases,
        out is not None, bool(times), bool(progress),
    )
    if out is not None:
        with open(out, "w", encoding="utf-8", newline="") as f:
            f.write(csv)
    return _table(cols)


def case_fixture(
    fixture: Fixture,
    case: int,
    disperse: Optional[Mapping[str, float]] = None,
    uniform: Optional[Mapping[str, Tuple[float, float]]] = None,
    seed: int = 1,
) -> Fixture:
    """Case ``case`` of a campaign as a fixture (``reconfig campaign --show-case``)."""
    _check_seed(seed)
    if isinstance(case, bool) or not isinstance(case, int) or not 0 <= case < 2**64 - 1:
        raise ValueError(f"case = {case!r} is not a whole number in [0, 2^64 - 1)")
    gauss, flat = _laws(disperse, uniform)
    text = _reconfig.case_text(fixture.name, fixture.text, gauss, flat, seed, case)
    return Fixture(name=f"{fixture.name} case {case}", text=text)
