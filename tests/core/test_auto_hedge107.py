"""``model.estimator.hedge=campaigns_or_fold`` (auto107, the default; benchmarks/bench_auto107.py):
where the folds are ONE held-out campaign, the blend moves toward MLR only where the fold's <= 8
blocks show the choice made without each block worse than MLR by a one-sided paired t test."""

from __future__ import annotations

import numpy as np
from scipy import stats

from test_auto_hedge105b import _Quadratic, _record
from thermocomp.core.models import MLR, hedge
from thermocomp.core.models.auto import AutoRegressor
from thermocomp.core.models.blend import fold_ratios


def test_the_evidence_is_student_s_one_sided_paired_test_at_5_percent():
    cases = {"one block rules the mean (year4_10072 E_Z)": [2.537, 0.362, 0.377],
             "1 % inside a 2 % spread (year4_10099 E_Z)": [0.996, 1.001, 1.001, 1.046, 1.008, 1.010, 1.0],
             "4 % worse on every block": [1.044, 1.039, 1.044, 1.059, 1.042, 1.037, 1.037],
             "better on every block": [0.8, 0.7, 0.9, 0.85]}
    got = {k: hedge.worse_than_mlr(r) for k, r in cases.items()}
    for k, r in cases.items():     # scipy's test of the same hypothesis, an independent implementation
        assert got[k] == (stats.ttest_1samp(r, 1.0, alternative="greater").pvalue < hedge.EVIDENCE_LEVEL), k
    assert list(got.values()) == [False, False, True, False]
    assert not hedge.worse_than_mlr([3.0])             # one block: no test


def _fold(scale_of_block):
    """One white fold of 400 rows (8 blocks): MLR's error e, and a candidate whose error is e
    scaled per block by ``scale_of_block(block)``."""
    rng = np.random.default_rng(0)
    n = 400
    y = 5 * np.sin(np.linspace(0.0, 12.0, n))
    e = rng.normal(0.0, 1.0, n)
    scale = np.array([scale_of_block(b) for b in np.arange(n) * 8 // n])
    return np.column_stack([y - e, y - scale * e]), y


def test_a_candidate_right_on_one_block_and_worse_on_the_rest_is_hedged_to_mlr():
    # the votes give it weight (the first block's 0.04 pulls any mean that draws it below 1), but the
    # choice made without each later block loses there: 7 of 8 blocks worse than MLR, the evidence
    preds, y = _fold(lambda b: 0.2 if b == 0 else 1.06)
    units = hedge.fold_blocks(y, preds[:, 0])
    assert np.unique(units).size == 8
    e = y - preds[:, 0]
    d = hedge.nested_prediction(preds, y, np.zeros(len(y), int), 0, 5, units) - preds[:, 0]
    ratios = fold_ratios((e - d) ** 2, e ** 2, units)
    assert np.sum(ratios > 1.0) == 7 and hedge.worse_than_mlr(ratios)
    lam = hedge.one_fold_weight(preds, y, 0, 5)
    assert lam < 1.0 and lam == hedge._least_mean_ratio(e, d, units)


def test_blocks_that_disagree_leave_the_blend_where_the_mean_measure_would_move_it():
    # a candidate far better on 6 blocks, far worse on 2: the mean measure's optimum is inside (0, 1)
    # (auto106e would mix), but the blocks' spread is no evidence that the choice is worse than MLR
    preds, y = _fold(lambda b: 3.0 if b in (2, 5) else 0.3)
    units = hedge.fold_blocks(y, preds[:, 0])
    e = y - preds[:, 0]
    d = hedge.nested_prediction(preds, y, np.zeros(len(y), int), 0, 5, units) - preds[:, 0]
    assert hedge._least_mean_ratio(e, d, units) < 1.0
    assert hedge.one_fold_weight(preds, y, 0, 5) == 1.0


def test_a_one_fold_record_without_evidence_keeps_the_votes_blend_two_folds_are_not_hedged():
    for k, seed in ((3, 0), (4, 5)):       # 3 campaigns forward: one fold; 4: two folds
        X, y, context = _record(k=k, seed=seed)
        fit = {h: AutoRegressor({"mlr": MLR(), "quadratic": _Quadratic()}, hedge=h).fit(X, y, context=context)
               for h in ("none", "campaigns_or_fold")}
        assert np.unique(fit["none"].oof_fold_).size == k - 2
        assert len(fit["none"].weights_) == 2             # a blend: the hedge is asked
        assert fit["campaigns_or_fold"].weights_ == fit["none"].weights_
        assert "hedged" not in fit["campaigns_or_fold"].reason_
