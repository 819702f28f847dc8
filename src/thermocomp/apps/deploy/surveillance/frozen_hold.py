"""(mon105c/d) How long a sensor just out for a freeze by its run alone is read at its held value
instead of its stand-in: one arithmetic for the served monitor (:mod:`.monitor`) and the code's
mirror (:class:`~thermocomp.apps.deploy.export.watch.CodeMonitor`), which the C repeats."""

from __future__ import annotations

import numpy as np

from .states import TREND_ROWS


def held_until(past_t: np.ndarray, past: np.ndarray, pos: int, run: int, tau: float,
               spread: float) -> float:
    """Until when (s) the held value is read: the sensor's rate fitted (least squares) to its own
    readings ``past`` (a ring of ``TREND_ROWS`` at ``pos``, times ``past_t``) over the ``tau``
    seconds before its constant run of ``run`` rows began; the drift that rate projects, over at
    least the span fitted, within the stand-in's training ``spread`` (-inf: never, its stand-in)."""
    order = (pos + np.arange(TREND_ROWS)) % TREND_ROWS    # oldest first
    first = TREND_ROWS - int(run)      # the run's first reading (this row not kept yet)
    if first < 2 or not spread > 0:
        return -np.inf
    t, x = past_t[order[:first + 1]], past[order[:first + 1]]
    t0 = t[-1]
    use = np.isfinite(t) & np.isfinite(x) & (t >= t0 - tau)
    if use.sum() < 3:
        return -np.inf
    t, x = t[use] - t0, x[use]
    tc = t - t.mean()
    rate = abs(float(tc @ (x - x.mean()) / (tc @ tc))) if tc @ tc > 0 else np.inf
    if not rate * -float(t[0]) <= spread:
        return -np.inf
    return t0 + (spread / rate if rate > 0 else np.inf)
