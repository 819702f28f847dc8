"""An ATI model's units as blocks of a stated length of a campaign (``ATIRegressor.unit_h``).

A record logged a day per file for weeks, its files chained by ``continues``, is fitted and
predicted as ONE campaign (:mod:`thermocomp.core.continuation`): its state carried across the
days.  ATI keys a campaign by its initial ambient, so on such a record it had one unit and kept
one model (audit105, edm65's six train days).  With ``unit_h`` the units are the blocks of
``unit_h`` hours of each campaign's own time, from its first row (day files of 24 h are a
chain's 24 h blocks), each keyed by its own initial ambient: the first block by the campaign's
``ambient_c0``, a later one by the mean of the ambient sensors at its first row (the block
before's where that row has none: causal, as the stream reads it).  The batch and the stream
share these two functions, so replay of a continuing campaign gives what run scored.
"""

from __future__ import annotations

import numpy as np

from ..context import AMBIENT_C0, TIME, groups_of

# a row this close to a block's edge (share of a block) is on it: a joined chain's times and a
# stream's lead-in shifted onto the test campaign's clock differ by rounding at the day's edge
EDGE = 1e-9


def block_of(time, first: float, unit_h: float) -> np.ndarray:
    """Block index of each ``time`` (s) of a campaign whose first row is at ``first``."""
    return np.floor((np.asarray(time, float) - first) / (3600.0 * unit_h) + EDGE).astype(int)


def block_ambient(previous: float, readings) -> float:
    """A new block's initial ambient: the mean of its first row's ambient ``readings``, the
    ``previous`` block's where one of them is not finite."""
    a = np.asarray(readings, float)
    return float(a.mean()) if a.size and np.all(np.isfinite(a)) else previous


def units(context, unit_h: float, ambient: list[str]) -> tuple[np.ndarray, np.ndarray]:
    """``(unit of each row, its unit's initial ambient)`` of a batch ``context`` (a DataFrame:
    ``campaign``, ``time``, ``ambient_c0`` and the raw ``ambient`` columns)."""
    n = len(context)
    groups = groups_of(context)
    groups = np.zeros(n, dtype=object) if groups is None else groups
    time = np.asarray(context[TIME], float)
    a0 = np.asarray(context[AMBIENT_C0], float).copy()
    readings = np.column_stack([np.asarray(context[c], float) for c in ambient]) if ambient \
        else np.empty((n, 0))
    label = np.empty(n, dtype=object)
    starts = np.flatnonzero(np.r_[True, groups[1:] != groups[:-1]]) if n else np.empty(0, int)
    for lo, hi in zip(starts, [*starts[1:], n]):
        block = block_of(time[lo:hi], time[lo], unit_h)
        edges = np.flatnonzero(np.r_[True, block[1:] != block[:-1]])
        level = a0[lo]
        for k, (b0, b1) in enumerate(zip(edges, [*edges[1:], hi - lo])):
            if k:
                level = block_ambient(level, readings[lo + b0])
            a0[lo + b0:lo + b1] = level
            label[lo + b0:lo + b1] = f"{groups[lo]}#{block[b0]}"
    return label, a0
