"""A simulated record's runs as a lab's files hold them, one run restarted: the stranger benches
(80, 81, 82) each cut the same way, written once."""

from __future__ import annotations

from datetime import timedelta

import numpy as np


def restarted_runs(windows, step_s: float, split_run: int, split_row: int, split_gap: int,
                   prefix: str = "") -> list:
    """``[(label, local start, rows)]`` of ``windows`` (``(start, slice)`` per run, numbered from
    1): run ``split_run`` restarted (two files, ``<prefix>NNa`` / ``NNb``): its first
    ``split_row`` rows, then after ``split_gap`` rows lost the rest."""
    out = []
    for n, (start, rows) in enumerate(windows, start=1):
        idx = np.arange(rows.start, rows.stop)
        if n == split_run:
            out.append((f"{prefix}{n:02d}a", start, idx[:split_row]))
            out.append((f"{prefix}{n:02d}b", start + timedelta(seconds=(split_row + split_gap) * step_s),
                        idx[split_row + split_gap:]))
        else:
            out.append((f"{prefix}{n:02d}", start, idx))
    return out


def day_runs(first_day, run_days, run_hours: tuple[float, float], step_s: float) -> list:
    """``[(local start, rows)]``: a run on each of ``run_days`` (days after ``first_day``) from
    ``run_hours[0]`` to ``run_hours[1]`` o'clock, its slice of a simulation sampled every
    ``step_s`` seconds from ``first_day``'s midnight (the stranger machines' shifts)."""
    out = []
    for d in run_days:
        start = first_day + timedelta(days=d, hours=run_hours[0])
        k0 = int((d * 24 + run_hours[0]) * 3600.0 / step_s)
        k1 = int((d * 24 + run_hours[1]) * 3600.0 / step_s)
        out.append((start, slice(k0, k1)))
    return out
