"""``model=auto``'s kept blend hedged towards MLR by a nested convex weight (auto105; gated on
campaign folds, auto105b: ``benchmarks/bench_auto105b.py``): ``lam * W + (1 - lam) * MLR``, ``lam``
from out-of-fold predictions of auto's choice made without the fold they score."""

from __future__ import annotations

import numpy as np

from ..metrics import rmse
from .blend import FOLD_MARGIN, fold_ratios, one_se_mean, vote_weights, zero_margin


def chosen_weights(preds, y, fold, base_column: int, min_folds: int) -> np.ndarray:
    """Auto's choice on these rows: the votes, the one-SE fallback, the zero rule
    (``AutoRegressor._blend`` with ``fallback='one_se'``, ``uncompensated='zero'``)."""
    mlr = preds[:, base_column]
    w = vote_weights(preds, y, fold, mlr, base_column=base_column, min_folds=min_folds)
    alone = np.eye(preds.shape[1])[base_column]
    if not np.allclose(w, alone):
        read = one_se_mean(fold_ratios((y - preds @ w) ** 2, (y - mlr) ** 2, fold))
        if read is not None and sum(read) >= 1.0:
            w = alone
    if rmse(y - preds @ w) >= rmse(y):
        q_kept, q_none = zero_margin(y, preds @ w, mlr, fold)
        if not FOLD_MARGIN * q_kept < q_none:
            w = np.zeros_like(w)
    return w


def nested_prediction(preds, y, fold, base_column: int, min_folds: int) -> np.ndarray:
    """On each fold j, the prediction of auto's choice made on the other folds alone."""
    out = np.zeros(len(y))
    for j in np.unique(fold):
        on = fold == j
        w = chosen_weights(preds[~on], y[~on], np.unique(fold[~on], return_inverse=True)[1],
                           base_column, min_folds)
        out[on] = preds[on] @ w
    return out


def hedge_weight(preds, y, fold, base_column: int, min_folds: int) -> float:
    """``lam`` in [0, 1] least in the mean over the folds of the mix's squared error over MLR's
    (the votes' measure), the mix of the nested prediction A and MLR: with e = y - MLR and
    d = A - MLR, ``sum_j <e,d>_j/|e|_j^2 / sum_j |d|_j^2/|e|_j^2``; 1 with fewer than 2 folds."""
    if np.unique(fold).size < 2:
        return 1.0
    e = y - preds[:, base_column]
    d = nested_prediction(preds, y, fold, base_column, min_folds) - preds[:, base_column]
    num = den = 0.0
    for j in np.unique(fold):
        on = fold == j
        ee = max(float(e[on] @ e[on]), 1e-300)
        num, den = num + float(e[on] @ d[on]) / ee, den + float(d[on] @ d[on]) / ee
    return 1.0 if den <= 0 else float(np.clip(num / den, 0.0, 1.0))
