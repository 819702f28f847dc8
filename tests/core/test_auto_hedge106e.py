"""``model.estimator.hedge=campaigns_or_fold`` (auto106e, the default; benchmarks/bench_auto106e.py):
where the folds are ONE held-out campaign, auto105b's nested weight (the mean of the units' error
ratios) over at most 8 of that fold's blocks."""

from __future__ import annotations

import numpy as np

from test_auto_hedge105b import _Quadratic, _record
from thermocomp.core.models import MLR
from thermocomp.core.models.auto import AutoRegressor
from thermocomp.core.models.hedge import MAX_FOLD_BLOCKS, fold_blocks, hedge_weight


def _fit(X, y, context, **hedge) -> AutoRegressor:
    return AutoRegressor({"mlr": MLR(), "quadratic": _Quadratic()}, **hedge).fit(X, y, context=context)


def test_one_campaign_fold_mixes_the_blend_with_mlr_by_the_choice_made_without_each_block():
    X, y, context = _record(k=3)                  # 3 campaigns forward: the last one is the one fold
    main, auto = _fit(X, y, context, hedge="campaigns"), _fit(X, y, context)
    assert auto.scheme_ == "blocked forward" and np.unique(auto.oof_fold_).size == 1
    assert set(main.weights_) == {"mlr", "quadratic"} and "hedged" not in main.reason_
    units = fold_blocks(auto.oof_y_, auto.oof_["mlr"])
    assert np.unique(units).size >= 2
    preds = np.column_stack([auto.oof_["mlr"], auto.oof_["quadratic"]])
    lam = hedge_weight(preds, auto.oof_y_, auto.oof_fold_, 0, auto.n_folds, units)
    assert 0.0 < lam < 1.0, lam
    assert np.isclose(auto.weights_["quadratic"], lam * main.weights_["quadratic"])
    assert np.isclose(auto.weights_["mlr"], 1.0 - lam + lam * main.weights_["mlr"])
    assert "one campaign fold's" in auto.reason_


def test_a_candidate_right_on_every_block_keeps_its_weight_one_block_leaves_the_blend():
    rng = np.random.default_rng(0)
    t = np.linspace(0.0, 6.0, 300)
    y = 4 * np.sin(t) + rng.normal(0.0, 0.1, t.size)
    preds = np.column_stack([y + 2 * np.cos(3 * t), y])    # MLR off by a slow wave; the other exact
    fold = np.zeros(t.size, int)
    units = fold_blocks(y, preds[:, 0])
    assert np.unique(units).size >= 2
    assert hedge_weight(preds, y, fold, 0, 5, units) == 1.0
    assert hedge_weight(preds, y, fold, 0, 5, np.zeros(t.size, int)) == 1.0    # < 2 units


def test_two_campaign_folds_and_one_record_s_time_blocks_are_left_as_the_votes_keep_them():
    for k, context in ((4, True), (3, False)):    # 4 campaigns forward: 2 folds; one record
        X, y, ctx = _record(k=k, seed=5)
        ctx = ctx if context else None
        plain, auto = _fit(X, y, ctx, hedge="none"), _fit(X, y, ctx)
        assert auto.weights_ == plain.weights_ and "hedged" not in auto.reason_


def test_a_long_white_fold_gets_at_most_8_blocks_and_a_mix_near_the_right_one():
    # white residuals decorrelate in one row: uncapped, 600 one-row blocks (auto106b) whose ratios
    # pulled lam toward 0; two independent errors of variance 1 and 0.81 mix best at 1 / 1.81
    rng = np.random.default_rng(1)
    y = rng.normal(0.0, 5.0, 600)
    preds = np.column_stack([y + rng.normal(0.0, s, y.size) for s in (1.0, 0.9, 1.1)])
    units = fold_blocks(y, preds[:, 0])
    assert np.unique(units).size == MAX_FOLD_BLOCKS
    assert np.all(np.diff(units) >= 0)                       # contiguous, in time order
    lam = hedge_weight(preds, y, np.zeros(y.size, int), 0, 5, units)
    assert 0.35 < lam < 0.75, lam
