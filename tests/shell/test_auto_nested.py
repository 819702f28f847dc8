"""``model=auto``'s votes judged by nested folds (``blend.nested_rmse``; bench_nested63)."""

from __future__ import annotations

import numpy as np
import pandas as pd
import pytest

from test_model_auto import _AsRead


def _offsets(n_campaigns: int, seed: int):
    """``y = s + o`` (``o`` a campaign's offset, s.d. 0.3, that no sensor sees); sensor 0 reads
    ``s``, sensor 1 ``s + d`` (``d`` its own campaign offset, s.d. 0.1, independent of ``o``): the
    twin is worse than sensor 0 on average and ahead only where ``d`` happens to follow ``o``."""
    rng = np.random.default_rng(seed)
    campaign = np.repeat(np.arange(n_campaigns), 100)
    s = rng.uniform(-1.0, 1.0, campaign.size)
    o, d = rng.normal(0.0, 0.3, n_campaigns)[campaign], rng.normal(0.0, 0.1, n_campaigns)[campaign]
    X = np.column_stack([s + rng.normal(0.0, 0.02, s.size), s + d + rng.normal(0.0, 0.02, s.size)])
    return X, s + o, pd.DataFrame({"campaign": [f"K{c:02d}" for c in campaign]})


CANDIDATES = {"mlr": _AsRead(0), "twin": _AsRead(1)}     # "mlr": the baseline


def test_each_fold_is_blended_with_the_weights_the_other_folds_vote_for():
    from thermocomp.core.models.auto import AutoRegressor
    from thermocomp.core.models.blend import vote_weights

    X, y, context = _offsets(20, seed=2)
    auto = AutoRegressor(CANDIDATES).fit(X, y, context=context)
    preds = np.column_stack([auto.oof_["mlr"], auto.oof_["twin"]])
    fold, y_oof = auto.oof_fold_, auto.oof_y_
    assert np.unique(fold).size == 5
    squared = []
    for k in range(5):
        others = fold != k
        # the other four folds drawn as the five are (folds, not blocks): min_folds one fewer
        w = vote_weights(preds[others], y_oof[others], fold[others], auto.oof_["mlr"][others],
                         base_column=0, min_folds=auto.n_folds - 1)
        squared.append((y_oof[fold == k] - preds[fold == k] @ w) ** 2)
    report = auto.report()
    assert report["nested_rmse"] == pytest.approx(np.sqrt(np.mean(np.concatenate(squared))), rel=1e-12)
    assert report["mlr_rmse"] == pytest.approx(np.sqrt(np.mean((y_oof - auto.oof_["mlr"]) ** 2)))


def test_a_blend_that_won_the_folds_by_chance_falls_back_to_mlr():
    from thermocomp.core.models.auto import AutoRegressor
    from thermocomp.core.models.blend import vote_weights

    X_new, y_new, _ = _offsets(400, seed=999)
    # the twin loses on fresh campaigns: its wins on a record's folds are chance
    assert np.mean((y_new - X_new[:, 1]) ** 2) > np.mean((y_new - X_new[:, 0]) ** 2)
    won = []
    for seed in range(12):
        X, y, context = _offsets(20, seed=seed)
        auto = AutoRegressor(CANDIDATES).fit(X, y, context=context)
        preds = np.column_stack([auto.oof_["mlr"], auto.oof_["twin"]])
        voted = vote_weights(preds, auto.oof_y_, auto.oof_fold_, auto.oof_["mlr"], base_column=0,
                             min_folds=auto.n_folds)
        blended = np.sqrt(np.mean((auto.oof_y_ - preds @ voted) ** 2))
        if voted[1] > 0 and blended < auto.validation_["mlr"]:     # the votes' blend won the folds
            won.append(seed)
            report = auto.report()
            assert auto.weights_ == {"mlr": 1.0} and report["decision"] == "mlr"
            assert report["nested_rmse"] >= report["mlr_rmse"]
            assert "MLR alone kept" in report["reason"]
    assert len(won) >= 2


def test_a_candidate_better_in_every_fold_keeps_its_votes():
    from thermocomp.core.models.auto import AutoRegressor

    X, y, context = _offsets(20, seed=2)
    X[:, 1] = y + 0.3 * (X[:, 0] - y)        # the twin's error 0.3 of sensor 0's, every campaign
    auto = AutoRegressor(CANDIDATES).fit(X, y, context=context)
    report = auto.report()
    assert auto.weights_ == {"twin": 1.0} and report["decision"] == "votes"
    assert report["nested_rmse"] < report["mlr_rmse"]
