"""``model=auto``'s kept blend hedged towards MLR by a nested convex weight (auto105; gated on
campaign folds, auto105b: ``benchmarks/bench_auto105b.py``; one campaign fold, only where its
blocks show the choice worse than MLR, auto107: ``benchmarks/bench_auto107.py``):
``lam * W + (1 - lam) * MLR``, ``lam`` from out-of-fold predictions of auto's choice made without
the unit (a fold, or a block of the one fold) they score."""

from __future__ import annotations

import numpy as np

from ..metrics import rmse
from ..model_selection.blocks import cut_blocks, decorrelation_length
from .blend import FOLD_MARGIN, fold_ratios, one_se_mean, vote_weights, zero_margin

# one campaign fold: each block is one nested vote, so the blocks are capped (auto106b's one block
# per decorrelation length cost 108 s CPU a target on a 2,000-row white fold, and one-row blocks
# pulled lam toward MLR); 8 is the most the labs' folds had (3-8), so they keep theirs
MAX_FOLD_BLOCKS = 8
# one campaign fold: lam leaves 1 only where a one-sided paired t test at this level says the
# choice made without each block is worse than MLR there (auto107: the refused measures moved lam
# on blocks that disagree, year4_10072, or on margins of 1 % near a tie, year4_10099)
EVIDENCE_LEVEL = 0.05


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


def _least_mean_ratio(e, d, units) -> float:
    """``lam`` in [0, 1] least in the mean over the units of ``|e - lam d|^2 / |e|^2``:
    ``sum_j <e,d>_j/|e|_j^2 / sum_j |d|_j^2/|e|_j^2``; 1 where d is 0."""
    num = den = 0.0
    for j in np.unique(units):
        on = units == j
        ee = max(float(e[on] @ e[on]), 1e-300)
        num, den = num + float(e[on] @ d[on]) / ee, den + float(d[on] @ d[on]) / ee
    return 1.0 if den <= 0 else float(np.clip(num / den, 0.0, 1.0))


def hedge_weight(preds, y, fold, base_column: int, min_folds: int) -> float:
    """``lam`` in [0, 1] least in the mean over the folds of the mix's squared error over MLR's
    (the votes' measure), the mix of the nested prediction A and MLR: with e = y - MLR and
    d = A - MLR, ``sum_j <e,d>_j/|e|_j^2 / sum_j |d|_j^2/|e|_j^2``; 1 with fewer than 2 folds."""
    if np.unique(fold).size < 2:
        return 1.0
    e = y - preds[:, base_column]
    d = nested_prediction(preds, y, fold, base_column, min_folds) - preds[:, base_column]
    return _least_mean_ratio(e, d, fold)


def worse_than_mlr(ratios, level: float = EVIDENCE_LEVEL) -> bool:
    """Whether independent per-block ratios (a model's squared error over MLR's) show the model
    worse than MLR: their mean exceeds 1 by more than the one-sided ``level`` quantile of
    Student's t (k - 1 degrees of freedom) times their standard error; False with < 2 blocks."""
    from scipy.special import stdtrit

    ratios = np.asarray(ratios, float)
    if ratios.size < 2:
        return False
    excess = float(np.mean(ratios)) - 1.0
    se = float(np.std(ratios, ddof=1)) / np.sqrt(ratios.size)
    return excess > 0 and excess > float(stdtrit(ratios.size - 1, 1.0 - level)) * se


def one_fold_weight(preds, y, base_column: int, min_folds: int) -> float:
    """``lam`` on ONE campaign fold: its blocks (:func:`fold_blocks`) are the units, A the choice
    made without each block.  1 unless A's per-block error over MLR's is worse than MLR's by the
    paired test (:func:`worse_than_mlr`); there, the mean measure's lam over the same blocks."""
    mlr = preds[:, base_column]
    units = fold_blocks(y, mlr)
    if np.unique(units).size < 2:
        return 1.0
    e = y - mlr
    d = nested_prediction(preds, y, np.zeros(len(y), int), base_column, min_folds, units) - mlr
    if not worse_than_mlr(fold_ratios((e - d) ** 2, e ** 2, units)):
        return 1.0
    return _least_mean_ratio(e, d, units)
