"""A campaign on a Dask cluster (``distributed``): the cases partitioned into contiguous
ranges, each range answered by a worker with the same Rust code as ``reconfig.campaign``, the
parts gathered in case order. Case ``k`` draws its numbers from its own random stream, so the
table is the one-machine table, bit for bit apart from the time column, whatever the
partitions, the workers and their threads.

    from dask.distributed import Client
    t = reconfig.cluster.campaign(f, 1_000_000, disperse=law, client=Client("tcp://host:8786"))

Dask is imported only here: ``pip install "dask[distributed]"`` to use it.
"""

from __future__ import annotations

import os
from typing import Any, Dict, List, Mapping, Optional, Sequence, Tuple, Union

import numpy as np

from . import Fixture, _check_campaign, _laws, _reconfig, _table

__all__ = ["campaign", "partition"]


def partition(cases: int, parts: int) -> List[Tuple[int, int]]:
    """``cases`` split into at most ``parts`` contiguous ranges ``(first, count)`` whose
    sizes differ by at most one, none empty (none at all for no cases)."""
    parts = max(1, min(parts, cases))
    base, extra = divmod(cases, parts)
    ranges, first = [], 0
    for k in range(parts):
        count = base + (1 if k < extra else 0)
        if count:
            ranges.append((first, count))
        first += count
    return ranges


def _answer_part(args: Sequence[Any]) -> Tuple[Dict[str, List[Any]], Optional[str]]:
    """One partition, on a worker: the extension's columns and CSV rows."""
    return _reconfig.campaign(*args)


def campaign(
    fixture: Fixture,
    cases: int,
    disperse: Optional[Mapping[str, float]] = None,
    uniform: Optional[Mapping[str, Tuple[float, float]]] = None,
    seed: int = 1,
    client: Any = None,
    partitions: Optional[int] = None,
    threads: int = 1,
    out: Union[str, os.PathLike, None] = None,
    times: bool = True,
) -> Dict[str, np.ndarray]:
    """:func:`reconfig.campaign` on a Dask cluster: ``client`` a ``distributed.Client`` (the
    current one when None); ``partitions`` the number of case ranges (default: four per
    worker thread, so a slow range does not hold the others up); ``threads`` the rayon threads
    each partition uses on its worker (1: the worker's Dask threads are the parallelism).
    Returns the same columns as :func:`reconfig.campaign`; ``out`` writes the same CSV."""
    from dask.distributed import get_client

    _check_campaign(cases, threads, seed)
    if partitions is not None and (isinstance(partitions, bool) or not isinstance(partitions, int)
                                   or partitions < 1):
        raise ValueError(f"partitions = {partitions!r} is not a whole number >= 1")
    gauss, flat = _laws(disperse, uniform)
    # The campaign's input checked here, before any task is sent (a bad path named once).
    _reconfig.campaign(fixture.name, fixture.text, cases, gauss, flat, seed, 1, 0, 0, False,
                       False, False)
    client = client if client is not None else get_client()
    if partitions is None:
        partitions = 4 * max(1, sum(client.nthreads().values()))
    table = out is not None
    tasks = [
        (fixture.name, fixture.text, cases, gauss, flat, seed, threads, first, count, table,
         bool(times), False)
        for first, count in partition(cases, partitions)
    ]
    parts = client.gather(client.map(_answer_part, tasks, pure=False))
    if not parts:  # no cases: the one-machine call gives the empty columns and the header
        parts = [_reconfig.campaign(fixture.name, fixture.text, cases, gauss, flat, seed, 1, 0,
                                    0, table, bool(times), False)]
    cols: Dict[str, List[Any]] = {}
    for part_cols, _ in parts:
        for key, values in part_cols.items():
            cols.setdefault(key, []).extend(values)
    if out is not None:
        with open(out, "w", encoding="utf-8", newline="") as f:
            f.write("".join(csv for _, csv in parts))
    return _table(cols)
