"""``model=auto``'s level folds: an ATI candidate scored against its family where auto's folds cannot.

Where no fold of auto's own spans the ambient levels the fit on every train campaign spans, each
fold's ATI model is one model of its family and validates as it, row for row (``validated_as``):
the votes give it nothing, whatever the ambient terms of the final fit would buy (hbm75: forward
folds fit on 2 levels, the train split spans 3).  Here each train campaign is held out in turn
where the others still span the levels the interaction needs, ATI and its family are fitted on
the others and scored on it, and the folds vote between the two; the share ATI wins splits the
weight auto's votes gave its family (``benchmarks/bench_auto76.py``).
"""

from __future__ import annotations

import numpy as np
from sklearn.base import clone

from ..context import subset
from ..metrics import rmse
from .blend import vote_weights

MIN_LEVEL_FOLDS = 2      # fewer level folds: nothing to resample, the tie stays
SCHEME = "leave-one-train-campaign-out where the others span {n}+ ambient levels"


def fold_predictions(est, X, y, context, fit, pred, score) -> np.ndarray:
    """``est`` fitted on rows ``fit``, its free-run prediction of rows ``pred`` at rows ``score``."""
    model = clone(est).fit(X[fit], y[fit], context=subset(context, fit))
    return np.asarray(model.predict(X[pred], context=subset(context, pred)), float)[score[pred]]


def level_folds(groups, y: np.ndarray, levels) -> list:
    """``(campaign, fit, held)`` row masks: each train campaign (in order) held out where the others
    span at least ``MIN_AMBIENTS`` levels (``levels(rows)``: the ambient levels of those rows'
    campaigns); ``held`` its measured rows."""
    from .ati import MIN_AMBIENTS

    groups = np.asarray(groups, dtype=object)
    out = []
    for campaign in dict.fromkeys(groups):
        held = groups == campaign
        if levels(~held) >= MIN_AMBIENTS and (held & np.isfinite(y)).any():
            out.append((str(campaign), ~held, held))
    return out


def level_share(ati, family, X, y, context, folds, n_folds: int) -> dict:
    """ATI against its family on the level ``folds``: ``{scheme, folds, held_out, rmse, share}``,
    ``share`` the weight :func:`~thermocomp.core.models.blend.vote_weights` gives ATI of the pair
    (its resample wins, kept as far as the resamples are sure it beats the family); 0 with fewer
    than ``MIN_LEVEL_FOLDS`` folds."""
    from .ati import MIN_AMBIENTS

    said = {"scheme": SCHEME.format(n=MIN_AMBIENTS), "folds": len(folds),
            "held_out": [c for c, *_ in folds], "share": 0.0}
    if len(folds) < MIN_LEVEL_FOLDS:
        return {**said, "why": f"{len(folds)} level fold(s), fewer than {MIN_LEVEL_FOLDS}: the tie stays"}
    cols, ys, fold = [], [], []
    for k, (_, fit, held) in enumerate(folds):
        score = held & np.isfinite(y)
        cols.append([fold_predictions(e, X, y, context, fit, held, score) for e in (family, ati)])
        ys.append(y[score])
        fold.append(np.full(score.sum(), k))
    preds = np.vstack([np.column_stack(c) for c in cols])
    y_held, fold = np.concatenate(ys), np.concatenate(fold)
    w = vote_weights(preds, y_held, fold, preds[:, 0], base_column=0, min_folds=n_folds)
    return {**said, "rmse": {"family": rmse(y_held - preds[:, 0]), "ati": rmse(y_held - preds[:, 1])},
            "share": float(w[1])}

