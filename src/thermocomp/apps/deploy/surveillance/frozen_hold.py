"""(mon105c/d) How long a sensor just out for a freeze by its run alone is read at its held value
instead of its stand-in: one arithmetic for the served monitor (:mod:`.monitor`) and the code's
mirror (:class:`~thermocomp.apps.deploy.export.watch.CodeMonitor`), which the C repeats.

(dep106) The ring of ``TREND_ROWS`` keeps one row per ``tau / (TREND_ROWS // 2)`` seconds (a row
that starts a new step of time; one with no time always), so at any logger half the ring spans
``tau`` and the other half the run: at 128 rows one per sample a 10 s logger's fit saw 1170 s, a
1 s logger's 117 s.  A logger at least that slow (28.1 s at tau 1800: every record's 30-300 s)
keeps every row, as before.  Each row carries its sample's number, so the run's first reading is
found in the ring whether or not it was kept."""

from __future__ import annotations

import numpy as np

from .states import TREND_ROWS


def trend_step(tau: float) -> float:
    """Seconds of time one kept row stands for (half the ring spans ``tau``)."""
    return float(tau) / (TREND_ROWS // 2)


def keeps(time: float, newest: float, tau: float) -> bool:
    """Whether the ring keeps a row at ``time`` after its newest row at ``newest`` (:func:`kept`)."""
    step = trend_step(tau)
    return not np.floor(time / step) == np.floor(newest / step)


def push_row(past: np.ndarray, past_t: np.ndarray, past_n: np.ndarray, pos: int, rows: int,
             row: np.ndarray, time: float, tau: float) -> tuple[int, int]:
    """One sample's ``row`` at ``time`` into the ring (in place) where :func:`keeps` keeps it,
    with its number ``rows``; ``(pos, rows)`` after it.  The served monitor's row path and the
    code's mirror step it alike (the C repeats it in ``monitor_step``)."""
    if keeps(time, past_t[pos - 1], tau):
        past[pos], past_t[pos], past_n[pos] = row, time, rows
        pos = (pos + 1) % TREND_ROWS
    return pos, rows + 1


def kept(times: np.ndarray, newest: float, tau: float) -> np.ndarray:
    """Which of the rows at ``times`` (in order) the ring keeps after its newest row at ``newest``:
    each that starts a new step of :func:`trend_step` (one with no time, or after one, always)."""
    step = trend_step(tau)
    t = np.asarray(times, float)
    bins = np.floor(t / step)
    before = np.floor(np.concatenate([[newest], t[:-1]]) / step)
    with np.errstate(invalid="ignore"):
        return ~(bins == before)


def fitted(past_t: np.ndarray, past: np.ndarray, past_n: np.ndarray, pos: int, first_n: float,
           tau: float) -> tuple[np.ndarray, np.ndarray, float]:
    """``(times, readings, t0)`` the rate is fitted to: the ring's rows (``TREND_ROWS`` at ``pos``,
    times ``past_t``, sample numbers ``past_n``) within ``tau`` s before and at the newest row kept
    up to the run's first reading (sample number ``first_n``), whose time ``t0`` is their 0; none
    where fewer than three rows of the ring reach it."""
    order = (pos + np.arange(TREND_ROWS)) % TREND_ROWS    # oldest first
    with np.errstate(invalid="ignore"):
        upto = np.flatnonzero(past_n[order] <= first_n)
    if not len(upto) or upto[-1] < 2:
        return np.zeros(0), np.zeros(0), np.nan
    t, x = past_t[order[:upto[-1] + 1]], past[order[:upto[-1] + 1]]
    t0 = t[-1]
    use = np.isfinite(t) & np.isfinite(x) & (t >= t0 - tau)
    return t[use] - t0, x[use], t0


def held_until(past_t: np.ndarray, past: np.ndarray, past_n: np.ndarray, pos: int, first_n: float,
               tau: float, spread: float) -> float:
    """Until when (s) the held value is read: the sensor's rate fitted (least squares) to its own
    readings (:func:`fitted`) over the ``tau`` seconds before its constant run began; the drift
    that rate projects, over at least the span fitted, within the stand-in's training ``spread``
    (-inf: never, its stand-in)."""
    if not spread > 0:
        return -np.inf
    t, x, t0 = fitted(past_t, past, past_n, pos, first_n, tau)
    if len(t) < 3:
        return -np.inf
    tc = t - t.mean()
    rate = abs(float(tc @ (x - x.mean()) / (tc @ tc))) if tc @ tc > 0 else np.inf
    if not rate * -float(t[0]) <= spread:
        return -np.inf
    return t0 + (spread / rate if rate > 0 else np.inf)
