"""``model.estimator.hedge=campaigns`` (auto105b; benchmarks/bench_auto105b.py): auto's kept blend
mixed with MLR by the nested convex weight (auto105's), only where the folds are >= 3 campaigns."""

from __future__ import annotations

import numpy as np
import pandas as pd

from thermocomp.core.models import MLR
from thermocomp.core.models.auto import MIN_HEDGE_FOLDS, AutoRegressor
from thermocomp.core.models.hedge import hedge_weight


def _folds(spread: float, seed: int = 0, n: int = 400, k: int = 5):
    """MLR (column 0) and a candidate (column 1), each y plus independent noise; the candidate's
    noise ``spread`` times MLR's."""
    rng = np.random.default_rng(seed)
    y = rng.normal(0.0, 5.0, n)
    preds = np.column_stack([y + rng.normal(0.0, 1.0, n), y + rng.normal(0.0, spread, n)])
    return preds, y, np.repeat(np.arange(k), n // k)


def test_a_candidate_a_little_better_than_mlr_is_mixed_with_it_a_clear_winner_kept():
    # the nested choice keeps the candidate alone in both; independent errors of variance 1 and
    # s^2 mix best at 1 / (1 + s^2): 0.61 of a candidate with 0.8 of MLR's noise, 0.92 at 0.3
    lam_near = hedge_weight(*_folds(0.8), base_column=0, min_folds=5)
    lam_clear = hedge_weight(*_folds(0.3), base_column=0, min_folds=5)
    assert 0.45 <= lam_near <= 0.8, lam_near
    assert 0.85 <= lam_clear <= 1.0, lam_clear


def test_one_fold_or_a_candidate_never_chosen_leaves_the_blend_as_it_is():
    preds, y, _ = _folds(1.0)
    assert hedge_weight(preds, y, np.zeros(len(y), int), base_column=0, min_folds=5) == 1.0
    preds[:, 1] = preds[:, 0]                     # nested choice = MLR on every fold: d = 0
    assert hedge_weight(preds, y, _folds(1.0)[2], base_column=0, min_folds=5) == 1.0


class _Quadratic(MLR):
    """MLR on the inputs and their squares: a candidate a little better than MLR on a weak curve."""

    def fit(self, X, y, context=None):
        return super().fit(np.column_stack([X, np.square(X)]), y, context=context)

    def predict(self, X, context=None):
        return super().predict(np.column_stack([X, np.square(X)]), context=context)


def _record(k: int, seed: int = 0, n: int = 100):
    """``k`` campaigns of a weak quadratic law of T1 (T2 no part of it) plus probe noise."""
    rng = np.random.default_rng(seed)
    t, X, y = np.linspace(0.0, 1.0, n), [], []
    for c in range(k):
        base = 3 * np.sin(np.pi * t * (1 + 0.2 * c) + rng.normal(0.0, 1.0))
        x = np.column_stack([base + rng.normal(0.0, 0.1, n), 2 * np.cos(3 * t + c) + rng.normal(0.0, 0.1, n)])
        X.append(x)
        y.append(0.7 * x[:, 0] + 0.06 * x[:, 0] ** 2 + rng.normal(0.0, 0.5, n))
    campaign = np.repeat([f"K{c}" for c in range(k)], n)
    return np.vstack(X), np.concatenate(y), pd.DataFrame({"campaign": campaign})


def _fit(X, y, context, hedge: str) -> AutoRegressor:
    return AutoRegressor({"mlr": MLR(), "quadratic": _Quadratic()}, hedge=hedge).fit(X, y, context=context)


def test_campaign_folds_mix_the_blend_with_mlr_one_record_s_blocks_leave_it():
    X, y, context = _record(k=8)
    plain, hedged = _fit(X, y, context, "none"), _fit(X, y, context, "campaigns")
    folds = np.unique(hedged.oof_fold_).size
    assert hedged.scheme_ == "blocked forward" and folds >= MIN_HEDGE_FOLDS
    assert set(plain.weights_) == {"mlr", "quadratic"}
    preds = np.column_stack([hedged.oof_["mlr"], hedged.oof_["quadratic"]])
    lam = hedge_weight(preds, hedged.oof_y_, hedged.oof_fold_, 0, hedged.n_folds)
    assert 0.0 < lam < 1.0, lam
    assert hedged.weights_["quadratic"] == np.float64(lam * plain.weights_["quadratic"])
    assert np.isclose(hedged.weights_["mlr"], 1.0 - lam + lam * plain.weights_["mlr"])
    assert "hedged towards MLR" in hedged.reason_
    # the same rows as one record: time blocks, no campaign evidence -- the votes' blend as it is
    one_plain, one_hedged = _fit(X, y, None, "none"), _fit(X, y, None, "campaigns")
    assert np.unique(one_hedged.oof_fold_).size >= MIN_HEDGE_FOLDS
    assert one_hedged.weights_ == one_plain.weights_ and "hedged" not in one_hedged.reason_
