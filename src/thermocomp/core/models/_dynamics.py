"""Campaign-aware time-series helpers shared by the dynamic models (ARX, ARX+RF, LSTM).

Rows arrive stacked campaign after campaign; ``groups`` holds the campaign of
each row.  A *segment* is a run of consecutive rows with the same label: lags,
feedback and windows never reach across a segment start.
"""

from __future__ import annotations

import numpy as np

# scipy.signal is imported where lfilter runs: the static families (MLR, PCR) and the compensator's
# one-step law use this module's index helpers only, and its import costs ~0.1 s per process.


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


def last_measured(y: np.ndarray, groups) -> np.ndarray:
    """Index of the last row before ``t`` (in ``t``'s segment) where ``y`` is finite, -1 where
    there is none: ``t - 1`` wherever ``y`` is measured at every sample; the previous probe
    reading of a target measured now and then (``data.sparse_targets``)."""
    y = np.asarray(y, dtype=float)
    n = len(y)
    index = np.where(np.isfinite(y), np.arange(n), -1)
    seen = np.maximum.accumulate(index)
    last = np.empty(n, dtype=int)
    last[1:] = seen[:-1]
    starts = segment_starts(groups, n)
    floor = np.zeros(n, dtype=int)
    floor[starts] = starts
    floor = np.maximum.accumulate(floor)        # each row's segment start
    last[last < floor] = -1
    last[starts] = -1
    return last


def free_run(a: float, u: np.ndarray, groups) -> np.ndarray:
    """``y(t) = a·y(t-1) + u(t)`` per segment, ``y = 0`` before each segment start.

    The simulation (free-run) output of a first-order ARX whose exogenous part
    is ``u``: scipy's ``lfilter`` runs the recursion in C.
    """
    from scipy.signal import lfilter

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


# Sampling counts as uniform when every step equals the first to this relative tolerance (float
# rounding of computed times); then lfilter runs the recursion, else the exact per-step loop.  A
# looser test (np.allclose) would let lfilter use one pole where a stream uses the true steps.
_UNIFORM_RTOL = 1e-12


def first_order_lags(u, time, groups, taus, rest=None, out=None) -> np.ndarray:
    r"""First-order lags of every column of ``u`` for every time constant, per segment.

    .. math:: z_k = a_k\, z_{k-1} + (1 - a_k)\, u_k, \quad a_k = e^{-(t_k - t_{k-1})/\tau},
       \quad z_0 = u_0 \ (\text{a column of } rest\text{: } z_0 = 0)

    the exact discretisation of :math:`\tau \dot z + z = u` for an input held
    over each step, for any (also irregular) sampling, starting in steady
    state at each segment's first sample, or at rest (0) for the columns ``rest`` marks.
    Uniform sampling runs through :func:`scipy.signal.lfilter`; irregular sampling through the recursion
    above, all columns and time constants at once.

    Parameters
    ----------
    u : array (n,) or (n, p)
    time : array (n,)
        Sample time (s).
    groups : array (n,) or None
        Segment labels (see :func:`segment_starts`).
    taus : sequence of float
        Time constants (s).
    rest : array of bool (p,) or None
        Columns whose lags start at 0 (an input that was 0 before the segment: a machine
        state at rest), not at their first value.
    out : array (n, len(taus) * p) or None
        Where to write the lags (a view of a wider array: no second copy of them); None: a new array.

    Returns
    -------
    ndarray (n, len(taus) * p)
        Column ``i * p + j`` is the lag of column ``j`` with ``taus[i]``.
    """
    from scipy.signal import lfilter

    u = np.asarray(u, dtype=float)
    u = u.reshape(len(u), -1)
    taus = np.asarray(taus, dtype=float).ravel()
    time = np.asarray(time, dtype=float)
    p = u.shape[1]
    out = np.empty((len(u), taus.size * p)) if out is None else out
    steady = np.ones(p) if rest is None else 1.0 - np.asarray(rest, dtype=float).reshape(p)
    for start, stop in segment_bounds(groups, len(u)):
        seg, dt = u[start:stop], np.diff(time[start:stop])
        z0 = seg[:1] * steady          # the lag state at the first sample
        if dt.size == 0:
            out[start:stop] = np.tile(z0, taus.size)
        elif np.all(np.abs(dt - dt[0]) <= _UNIFORM_RTOL * abs(dt[0])):
            for i, tau in enumerate(taus):
                a = float(np.exp(-dt[0] / tau))
                # zi: the filter's state before the first sample, so that its first output is z0
                out[start:stop, i * p:(i + 1) * p] = lfilter([1.0 - a], [1.0, -a], seg, axis=0,
                                                             zi=a * z0 + (1.0 - a) * (z0 - seg[:1]))[0]
        else:
            a = np.exp(-dt[:, None] / np.repeat(taus, p)[None, :])
            wide = np.tile(seg, taus.size)
            z = out[start:stop]
            z[0] = np.tile(z0[0], taus.size)
            for k in range(1, len(seg)):
                z[k] = a[k - 1] * z[k - 1] + (1.0 - a[k - 1]) * wide[k]
    return out


def first_order_lag(u, time, groups, tau_s: float) -> np.ndarray:
    """First-order lag of each column of ``u`` per segment of ``groups`` (steady start).

    One time constant of :func:`first_order_lags` (same shape as ``u``).
    """
    u = np.asarray(u, dtype=float)
    out = first_order_lags(u, time, groups, [tau_s])
    return out[:, 0] if u.ndim == 1 else out
