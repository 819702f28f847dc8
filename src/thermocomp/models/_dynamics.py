"""Campaign-aware time-series helpers shared by the dynamic models (ARX, ARX+RF, LSTM).

Rows arrive stacked campaign after campaign; ``groups`` holds the campaign of
each row.  A *segment* is a run of consecutive rows with the same label: lags,
feedback and windows never reach across a segment start.
"""

from __future__ import annotations

import numpy as np
from scipy.signal import lfilter


def segment_starts(groups, n: int) -> np.ndarray:
    """Index of the first row of each segment (``[0]`` when ``groups`` is None)."""
    if n == 0:
        return np.zeros(0, dtype=int)
    if groups is None:
        return np.array([0])
    g = np.asarray(groups)
    if len(g) != n:
        raise ValueError(f"groups has {len(g)} rows, X has {n}")
    return np.flatnonzero(np.r_[True, g[1:] != g[:-1]])


def segment_bounds(groups, n: int) -> list[tuple[int, int]]:
    """``(start, stop)`` of each segment."""
    starts = segment_starts(groups, n)
    return list(zip(starts.tolist(), np.r_[starts[1:], n].tolist()))


def lag_index(groups, n: int, lag: int) -> np.ndarray:
    """Row index of ``t - lag`` inside each segment, held at the segment's first row."""
    idx = np.arange(n)
    if lag == 0 or n == 0:
        return idx
    starts = segment_starts(groups, n)
    first = np.repeat(starts, np.diff(np.r_[starts, n]))
    return np.maximum(idx - lag, first)


def previous(y: np.ndarray, groups, fill: float = 0.0) -> np.ndarray:
    """``y(t-1)`` inside each segment, ``fill`` at segment starts."""
    y = np.asarray(y, dtype=float)
    prev = np.empty_like(y)
    prev[1:] = y[:-1]
    prev[segment_starts(groups, len(y))] = fill
    return prev


def free_run(a: float, u: np.ndarray, groups) -> np.ndarray:
    """``y(t) = a·y(t-1) + u(t)`` per segment, ``y = 0`` before each segment start.

    The simulation (free-run) output of a first-order ARX whose exogenous part
    is ``u``: scipy's ``lfilter`` runs the recursion in C.
    """
    u = np.asarray(u, dtype=float)
    if a == 0.0:
        return u.copy()
    y = np.empty_like(u)
    for start, stop in segment_bounds(groups, len(u)):
        y[start:stop] = lfilter([1.0], [1.0, -a], u[start:stop])
    return y


def window_index(groups, n: int, window: int) -> np.ndarray:
    """``(n, window)`` row indices of the last ``window`` samples up to each row.

    Windows are padded with the segment's first row (the machine is taken as
    steady before a campaign starts, as in the reference frame).
    """
    return np.stack([lag_index(groups, n, lag) for lag in range(window - 1, -1, -1)], axis=1)
