"""The rows whose correction the deployed stream's guard changed: one key, one sum (small71).

The guard is the deploy app's (:mod:`thermocomp.apps.deploy.guard`, ``monitor.guard``); its count
per campaign travels as a vector (``guard_changes`` after minus before the campaign) or in a
replayed frame's attrs under :data:`GUARDED`.  ``replay``, ``promote``, ``monitor`` and
``diagnose`` (which may not import the deploy app) sum it over campaigns here, so the figure each
reports is one computation.
"""

from __future__ import annotations

from collections.abc import Iterable, Sequence

import numpy as np
import pandas as pd

GUARDED = "guarded"     # a replayed frame's attrs: {target: rows the guard changed}


def mark_guarded(frame: pd.DataFrame, targets: Sequence[str], rows: np.ndarray) -> None:
    """Store ``rows`` (per target, in ``targets``' order) in ``frame.attrs``."""
    frame.attrs[GUARDED] = dict(zip(targets, rows.tolist()))


def summed(per_campaign: Iterable[Sequence[int] | None], targets: Sequence[str]
           ) -> dict[str, int] | None:
    """``{target: rows}`` summed over campaigns, each a vector in ``targets``' order; None where
    a campaign has none (no guard: the plain stream)."""
    rows = list(per_campaign)
    if any(r is None for r in rows):
        return None
    total = np.sum(rows, axis=0, dtype=np.int64) if rows else np.zeros(len(targets), np.int64)
    return {t: int(n) for t, n in zip(targets, total)}


def summed_frames(frames: Iterable[pd.DataFrame], targets: Sequence[str]) -> dict[str, int] | None:
    """:func:`summed` of replayed frames (their attrs, :func:`mark_guarded`)."""
    return summed(([f.attrs[GUARDED][t] for t in targets] if GUARDED in f.attrs else None
                   for f in frames), targets)
