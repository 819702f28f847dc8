"""``model=auto`` scoring its candidates where the folds do not extrapolate (``validation_rows``).

Forward folds of one drifting record grade extrapolation: the late folds' inputs leave the range
the fold was fitted on, while a separate test campaign inside the record's range interpolates.
A family that extrapolates well there by luck (here: one that saturates, as the truth happens to)
should not win votes it has not earned where its inputs have been seen (issue 34).
"""

from __future__ import annotations

import numpy as np
import pandas as pd
import pytest

from thermocomp.base.errors import ParameterError
from thermocomp.core.model_selection.extrapolation import within_range
from thermocomp.core.models import MLR
from thermocomp.core.models.auto import AutoRegressor, in_range_rows


class Lucky(MLR):
    """MLR, its predictions stopped at the largest target of its fit and 0.01 off: a little worse
    than MLR where its inputs have been seen, a saturation beyond them (the truth's, by luck)."""

    def fit(self, X, y, context=None):
        self.cap_ = float(np.max(y))
        return super().fit(X, y, context=context)

    def predict(self, X, context=None):
        return np.minimum(super().predict(X, context=context), self.cap_) + 0.01


def _record(n: int = 1000, wide_from: float = 0.9):
    """A sensor cycling in [0, 1], swinging twice as wide over the last tenth (the last forward
    fold); the error follows it linearly up to 1 and saturates beyond."""
    t = np.arange(n)
    x = 0.5 + np.where(t < wide_from * n, 0.5, 1.0) * np.sin(t / 15.0)
    y = np.minimum(x, 1.0) + np.random.default_rng(1).normal(0.0, 0.05, n)
    return x[:, None], y, pd.DataFrame({"campaign": "R1", "time": t * 60.0})


def test_a_fold_swinging_beyond_its_fit_rows_is_flagged_where_it_extrapolates():
    X, y, context = _record()
    auto = AutoRegressor({"mlr": MLR(), "lucky": Lucky()}, validation_rows="in_range").fit(
        X, y, context=context)
    share = [auto.oof_in_range_[auto.oof_fold_ == f].mean() for f in range(5)]
    assert share[:4] == [1.0] * 4 and 0.2 < share[4] < 0.5     # the wide swings: a third in range
    n, folds = auto.oof_folds_
    fit, score = folds[4]
    fitted, scored = np.isin(np.arange(n), fit), np.isin(np.arange(n), score)
    np.testing.assert_array_equal(auto.oof_in_range_[auto.oof_fold_ == 4],
                                  within_range(X, fitted, scored)[score])


def test_the_rows_in_range_are_found_only_where_they_choose():
    # an SVD per fold per target, spent on every fit when only validation_rows='in_range' reads it
    X, y, context = _record()
    auto = AutoRegressor({"mlr": MLR(), "lucky": Lucky()})
    assert auto.fit(X, y, context=context).oof_in_range_ is None
    kept = auto.set_params(keep_oof=True).fit(X, y, context=context).oof_in_range_    # for later rules
    assert kept.shape == auto.oof_y_.shape and 0 < kept.mean() < 1


def test_a_family_lucky_where_the_folds_extrapolate_wins_no_votes_on_the_rows_in_range():
    X, y, context = _record()
    fits = {rows: AutoRegressor({"mlr": MLR(), "lucky": Lucky()}, validation_rows=rows,
                                fallback="none").fit(X, y, context=context) for rows in ("all", "in_range")}
    assert fits["all"].weights_["lucky"] > 0.3         # its luck in the last fold
    # the one-SE fallback (the default) keeps MLR there too: one lucky fold of five is not sure
    assert AutoRegressor({"mlr": MLR(), "lucky": Lucky()}).fit(X, y, context=context).weights_ == {"mlr": 1.0}
    assert fits["in_range"].weights_ == {"mlr": 1.0}    # a little worse than MLR where seen
    assert "on the 436 of 500 rows where the fold does not extrapolate" in fits["in_range"].reason_


def test_folds_with_too_few_rows_in_range_are_dropped_or_scored_whole():
    fold = np.repeat([0, 1, 2], 30)
    inside = np.ones(90, bool)
    inside[60:] = np.arange(30) < 5                      # fold 2: 5 rows in range
    dropped = in_range_rows(inside, fold, min_rows=20, thin="drop")
    assert dropped[:60].all() and not dropped[60:].any()
    whole = in_range_rows(inside, fold, min_rows=20)
    assert whole.all()
    inside[60:] = np.arange(30) < 25                     # 25 in range: those alone
    assert in_range_rows(inside, fold, min_rows=20)[60:].sum() == 25
    inside[30:] = False                                  # one fold left: every row
    assert in_range_rows(inside, fold, min_rows=20, thin="drop").all()


def test_an_unknown_validation_rows_is_refused_naming_the_key():
    X, y, context = _record(200)
    with pytest.raises(ParameterError, match="validation_rows"):
        AutoRegressor({"mlr": MLR()}, validation_rows="some").fit(X, y, context=context)
