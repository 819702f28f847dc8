"""Replay: stream campaigns row by row through a deployable compensator and check it (pure core).

The deployed object is a :class:`~thermocomp.deploy.StreamingCompensator`
(what ``promote`` registers inside the pyfunc model).  Each campaign is
streamed from a reset, one sample at a time through :meth:`~StreamingCompensator.step`,
as a CNC loop calls it, and compared with the batch prediction of the same
fitted :class:`~thermocomp.compensator.Compensator`.  The result is the
``replay.json`` layout of CLI.md.
"""

from __future__ import annotations

import time as clock
from collections.abc import Mapping

import numpy as np
import pandas as pd

from ..context import TIME
from .streaming import StreamingCompensator


def stream_rows(streaming: StreamingCompensator, campaign: pd.DataFrame) -> tuple[np.ndarray, np.ndarray, float]:
    """Stream one campaign from a reset through ``step``: ``(predictions (n, targets),
    clamped inputs per row, seconds spent in step)``."""
    X = campaign[streaming.columns_].to_numpy(float)
    t = campaign[TIME].to_numpy(float) if TIME in campaign.columns else np.full(len(campaign), np.nan)
    y = np.empty((len(X), len(streaming.targets_)))
    clamped = np.zeros(len(X), dtype=np.int64)
    streaming.reset()
    step = streaming._step   # the body of step() and predict(); returns the clamp count too
    start = clock.perf_counter()
    for i in range(len(X)):
        y[i], clamped[i] = step(X[i], t[i])
    seconds = clock.perf_counter() - start
    streaming.reset()
    return y, clamped, seconds


def replay_report(streaming: StreamingCompensator, campaigns: Mapping[str, pd.DataFrame]) -> dict:
    """Per target: samples, largest |stream − batch| (envelope off), RMSE of the residual left by
    the streamed correction (envelope as deployed), µs per sample, clamped samples.

    Returns the ``targets`` part of ``replay.json``.
    """
    comp = streaming.compensator
    batch = comp.predict(campaigns)
    measured = comp.measured(campaigns)
    targets = streaming.targets_
    diffs, residuals, clamps, seconds, n = [], [], 0, 0.0, 0
    from ..progress import bar

    rows = bar(total=sum(len(df) for df in campaigns.values()), desc="replay", unit="row")
    for cid, df in campaigns.items():
        with streaming.envelope_off():   # the same inputs as batch: any difference is the stream's
            free, _, _ = stream_rows(streaming, df)
        deployed, clamped, s = stream_rows(streaming, df)
        diffs.append(np.abs(free - batch[cid][targets].to_numpy()))
        residuals.append(measured[cid][targets].to_numpy() - deployed)
        clamps += int((clamped > 0).sum())
        seconds += s
        n += len(df)
        rows.update(len(df))
    rows.close()
    diff, resid = np.concatenate(diffs), np.concatenate(residuals)
    us = 1e6 * seconds / max(n, 1)
    return {t: {"n_samples": int(n),
                "max_abs_stream_minus_batch": float(np.max(diff[:, k])) if n else 0.0,
                "rmse": float(np.sqrt(np.nanmean(resid[:, k] ** 2))) if n else None,
                "us_per_sample": us,
                "rmse_batch": float(np.sqrt(np.nanmean(
                    np.concatenate([measured[c][t].to_numpy() - batch[c][t].to_numpy()
                                    for c in campaigns]) ** 2))) if n else None,
                "clamped_samples": clamps}
            for k, t in enumerate(targets)}
