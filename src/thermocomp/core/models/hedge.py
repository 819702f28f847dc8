"""``model=auto``'s kept blend hedged towards MLR by a nested convex weight (auto105; gated on
campaign folds, auto105b: ``benchmarks/bench_auto105b.py``; one campaign fold by at most
:data:`MAX_FOLD_BLOCKS` of its blocks, each an equal say, auto106d: ``benchmarks/bench_auto106d.py``):
``lam * W + (1 - lam) * MLR``, ``lam`` from out-of-fold predictions of auto's choice made without
the unit (a fold, or a block of the one fold) they score."""

from __future__ import annotations

import numpy as np

from ..metrics import rmse
from ..model_selection.blocks import cut_blocks, decorrelation_length
from .blend import FOLD_MARGIN, fold_ratios, one_se_mean, vote_weights, zero_margin

# one campaign fold: each block is one nested vote, so the blocks are capped (auto106b's one block
# per decorrelation length cost 108 s CPU a target on a 2,000-row white fold); 8 is the most the
# labs' folds had (3-8), so they keep theirs
MAX_FOLD_BLOCKS = 8


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


def fold_blocks(y, mlr, most: int = MAX_FOLD_BLOCKS) -> np.ndarray:
    """The block of each row of ONE validation fold: contiguous stretches at least as long as MLR's
    residual takes to decorrelate (about one independent look each), and at most ``most`` of them."""
    one = np.zeros(len(y), int)
    length = decorrelation_length(y - mlr, one, np.ones(len(y), bool))
    return cut_blocks(one, one, max(length, -(-len(y) // most)))


def nested_prediction(preds, y, fold, base_column: int, min_folds: int, units=None) -> np.ndarray:
    """On each unit j (default: each fold), the prediction of auto's choice made on the rows
    outside j alone, their folds as they are (one fold cut into blocks stays one fold)."""
    units = fold if units is None else units
    out = np.zeros(len(y))
    for j in np.unique(units):
        on = units == j
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


def one_fold_weight(preds, y, base_column: int, min_folds: int) -> float:
    """``lam`` in [0, 1] for ONE validation fold: least in the MEDIAN over its :func:`fold_blocks`
    of the block's ratio of the mix's squared error to MLR's, the mix ``lam * A + (1 - lam) * MLR``
    with A the prediction of auto's choice made without the block.  Each block has one equal say,
    and neither the blocks where MLR is near right (a mean of ratios: auto106b) nor those where it
    is far off (the pooled error: auto106c) rule; a block where A ~ MLR sits at ratio 1 whatever
    lam.  Ties go to the larger lam (the kept blend); 1 with fewer than 2 blocks."""
    units = fold_blocks(y, preds[:, base_column])
    if np.unique(units).size < 2:
        return 1.0
    mlr = preds[:, base_column]
    e, d = y - mlr, nested_prediction(preds, y, np.zeros(len(y), int), base_column, min_folds, units) - mlr
    # block b's ratio is 1 - 2 lam p_b + lam^2 q_b; their median is one of them, or the mean of two,
    # between the lams where two cross, so its least is at one of the candidates below
    blocks = [units == j for j in np.unique(units)]
    ee = np.array([max(float(e[b] @ e[b]), 1e-300) for b in blocks])
    p = np.array([float(e[b] @ d[b]) for b in blocks]) / ee
    q = np.array([float(d[b] @ d[b]) for b in blocks]) / ee
    with np.errstate(divide="ignore", invalid="ignore"):
        cross = 2 * np.subtract.outer(p, p) / np.subtract.outer(q, q)
        least = np.add.outer(p, p) / np.add.outer(q, q)      # of one r_b (diagonal) or a mean of two
    cand = np.concatenate([[0.0, 1.0], cross.ravel(), least.ravel()])
    cand = np.unique(cand[np.isfinite(cand) & (cand >= 0.0) & (cand <= 1.0)])
    medians = np.median(1.0 - 2.0 * np.outer(cand, p) + np.outer(cand ** 2, q), axis=1)
    return float(cand[np.flatnonzero(medians <= medians.min() * (1 + 1e-12))[-1]])
