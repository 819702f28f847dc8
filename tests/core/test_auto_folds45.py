"""``model=auto`` on one record: folds that leave a block out of the whole record (``one_record``).

Forward chaining grades the extrapolation of a drifting record; where the test is a separate
campaign inside the record's range, leaving blocks out interpolates as the test does (issue 34).
"""

from __future__ import annotations

import numpy as np
import pandas as pd
import pytest
from sklearn.base import clone

from thermocomp.base.errors import ParameterError
from thermocomp.core.model_selection import LeaveBlockOut
from thermocomp.core.models import MLR, LagBank
from thermocomp.core.models.auto import AutoRegressor


def _block_masks(n: int, edges, gap: int):
    rows = np.arange(n)
    return [((rows < a - gap) | (rows >= b + gap), rows < b, (rows >= a) & (rows < b))
            for a, b in zip(edges[:-1], edges[1:])]


def test_each_block_is_held_out_with_a_gap_on_both_sides_and_predicted_from_the_start():
    folds = LeaveBlockOut(n_folds=4, gap_blocks=0.5).folds(40)       # blocks of 10, gaps of 5
    expected = _block_masks(40, [0, 10, 20, 30, 40], 5)
    assert len(folds) == 4
    for got, want in zip(folds, expected):
        for g, w in zip(got, want):
            np.testing.assert_array_equal(g, w)
    assert np.sum([score for *_, score in folds], axis=0).tolist() == [1] * 40   # each row once
    fit, pred, score = folds[1]                                      # the fit on both sides
    assert fit[:5].all() and fit[25:].all() and not fit[5:25].any() and pred[:20].all()


def test_late_blocks_tile_the_last_part_of_the_record_only():
    folds = LeaveBlockOut(n_folds=2, start_fraction=0.5, gap_blocks=0.5).folds(40)
    expected = _block_masks(40, [20, 30, 40], 5)
    for got, want in zip(folds, expected):
        for g, w in zip(got, want):
            np.testing.assert_array_equal(g, w)
    assert not np.any([score[:20] for *_, score in folds])


def _one_record(n: int = 240, dt_s: float = 60.0):
    """A heating/cooling record, the error a slow lag of the sensor (what the lag bank models)."""
    x = np.where((np.arange(n) // 60) % 2 == 0, 30.0, 20.0) + np.random.default_rng(0).normal(0, 0.1, n)
    a = dt_s / (3600.0 + dt_s)
    y = np.empty(n)
    y[0] = x[0]
    for i in range(1, n):
        y[i] = y[i - 1] + a * (x[i] - y[i - 1])
    context = pd.DataFrame({"campaign": "R1", "time": np.arange(n) * dt_s})
    return x[:, None], 2.0 * y, context


def test_one_record_blocks_validate_each_candidate_free_run_from_the_record_start():
    X, y, context = _one_record()
    auto = AutoRegressor({"mlr": MLR(), "lagbank": LagBank()}, one_record="blocks", n_folds=4).fit(
        X, y, context=context)
    assert auto.scheme_ == "leave-block-out (one record)"
    folds = LeaveBlockOut(n_folds=4, gap_blocks=0.5).folds(len(y))
    n, used = auto.oof_folds_
    assert n == len(y) and len(used) == len(folds)
    for (fit_rows, score_rows), (fit, _, score) in zip(used, folds):
        np.testing.assert_array_equal(fit_rows, np.flatnonzero(fit))
        np.testing.assert_array_equal(score_rows, np.flatnonzero(score))
    # block 2 (rows 120-179): the lag bank fitted on rows 0-89 and 210-239, the record predicted
    # from its first row; a prediction started at the block (a fresh start) is not what is scored
    fit, pred, score = folds[2]
    model = clone(LagBank()).fit(X[fit], y[fit], context=context[fit].reset_index(drop=True))
    from_start = model.predict(X[pred], context=context[pred].reset_index(drop=True))[score[pred]]
    fresh = model.predict(X[score], context=context[score].reset_index(drop=True))
    held = auto.oof_fold_ == 2
    np.testing.assert_allclose(auto.oof_["lagbank"][held], from_start)
    assert not np.allclose(auto.oof_["lagbank"][held], fresh)


def test_forward_stays_the_default_for_one_record():
    X, y, context = _one_record()
    auto = AutoRegressor({"mlr": MLR()}, n_folds=2).fit(X, y, context=context)
    assert auto.scheme_ == "forward-chaining (one record)"
    assert all(fit.max() < score.min() for fit, score in auto.oof_folds_[1])      # row indices


@pytest.mark.parametrize("make, says", [
    (lambda: AutoRegressor({"mlr": MLR()}, one_record="middle").fit(*_one_record()[:2]), "one_record"),
    (lambda: LeaveBlockOut(n_folds=1).folds(10), "none to fit on"),
    (lambda: LeaveBlockOut(start_fraction=1.0).folds(10), "start_fraction")])
def test_bad_one_record_folds_are_refused_naming_the_key(make, says):
    with pytest.raises(ParameterError, match=says):
        make()
