"""Scoring a fitted compensator on the train and test splits (pure core)."""

from __future__ import annotations

import numpy as np

from .compensator import Compensator
from .io.contract import TIME, ContractError, Dataset
from .metrics import split_scores


def sample_period(ds: Dataset, ids) -> float:
    """Median sampling step (s) over the campaigns ``ids``."""
    steps = [np.diff(ds.campaigns[c][TIME].to_numpy(float)) for c in ids]
    steps = np.concatenate([s for s in steps if s.size]) if steps else np.empty(0)
    return float(np.median(steps)) if steps.size else float("nan")


def require_split(ds: Dataset, split: str) -> list[str]:
    ids = ds.ids(split)
    if not ids:
        raise ContractError(f"the dataset has no {split!r} campaign (set `split` in the manifest "
                            f"or data.split_overrides)", file="campaigns.csv", column="split")
    return ids


def score(comp: Compensator, ds: Dataset, mode: str = "simulation",
          e_p95_statistic: str = "range", e_p95_points: int | None = 200) -> tuple[dict, dict]:
    """Per-target train/test figures in the layout of ``metrics.json`` (``targets`` key).

    Returns
    -------
    targets : dict
        ``{target: {"train": {...}, "test": {...}}}``.
    predictions : dict
        ``{campaign: (measured DataFrame, predicted DataFrame)}`` for test campaigns.
    """
    out = {t: {} for t in comp.targets_}
    predictions = {}
    for split in ("train", "test"):
        ids = require_split(ds, split)
        camps = {c: ds.campaigns[c] for c in ids}
        pred = comp.predict(camps, mode=mode)
        meas = comp.measured(camps)
        dt = sample_period(ds, ids)
        for t in comp.targets_:
            y = {c: meas[c][t].to_numpy() for c in ids}
            r = {c: y[c] - pred[c][t].to_numpy() for c in ids}
            out[t][split] = split_scores(y, r, dt, e_p95_statistic, e_p95_points,
                                         with_before_after=(split == "test"))
        if split == "test":
            predictions = {c: (meas[c], pred[c]) for c in ids}
    return out, predictions
