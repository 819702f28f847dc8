"""``model=auto``'s ``lag_fade``: a lag family whose gain over MLR fades over the forward folds
hands its weight to MLR (issue 34; ``benchmarks/bench_auto96.py``).

On one record the forward folds are fitted on more and more rows; a lag family whose slow lags fit
that record's history wins the early folds and less and less the later ones, and loses on new
campaigns (column_moving_source seed 1403 E_Y lagbank, fold ratios 0.33 0.07 1.09 0.40 0.64, 2.1 x
MLR on new campaigns).  A family that will win does not fade (the Swiss lathe's hammerstein).
"""

from __future__ import annotations

import numpy as np
import pandas as pd
import pytest

from thermocomp.base.errors import ParameterError
from thermocomp.core.models import MLR
from thermocomp.core.models.auto import AutoRegressor
from thermocomp.core.models.blend import fading_gain

N = 1000


class Fading(MLR):
    """The quadratic law the record follows (MLR on x and x^2), drawn towards MLR-on-x's straight
    line the more rows it was fitted on: better than MLR on every early fold, less so later."""

    def __init__(self, n_total: int = N, fit_intercept: bool = True):
        super().__init__(fit_intercept=fit_intercept)
        self.n_total = n_total

    def fit(self, X, y, context=None):
        self.pull_ = max(0.0, 2.2 * (len(y) / self.n_total - 0.4))
        self.line_ = MLR().fit(X, y)
        return super().fit(np.column_stack([X, X ** 2]), y, context=context)

    def predict(self, X, context=None):
        quad = super().predict(np.column_stack([X, X ** 2]), context=context)
        return quad + self.pull_ * (self.line_.predict(X) - quad)


class FadingLag(Fading):
    """:class:`Fading` as a lag family: a memory (``tau_max_s``), as lagbank has."""

    def __init__(self, n_total: int = N, fit_intercept: bool = True, tau_max_s: float = 172800.0):
        super().__init__(n_total=n_total, fit_intercept=fit_intercept)
        self.tau_max_s = tau_max_s


def _record():
    t = np.arange(N)
    x = 1.0 + np.sin(t / 40.0)
    y = x + 0.8 * x ** 2 + np.random.default_rng(3).normal(0.0, 0.02, N)
    return x[:, None], y, pd.DataFrame({"campaign": "R1", "time": t * 60.0})


def test_the_fading_gain_is_the_slope_of_the_log_fold_ratios():
    fold = np.repeat(np.arange(5), 4)
    base = np.ones(20)
    ratios = np.array([0.33, 0.07, 1.09, 0.40, 0.64])       # col1403 E_Y's lagbank (bench_auto96)
    slope = fading_gain(np.repeat(ratios, 4), base, fold)
    assert slope == pytest.approx(np.polyfit(np.arange(5), np.log(ratios), 1)[0])
    assert slope == pytest.approx(0.30, abs=0.01)
    steady = np.array([0.47, 0.50, 0.24, 0.30, 0.31])         # swiss303 E_X's hammerstein
    assert fading_gain(np.repeat(steady, 4), base, fold) < 0
    assert fading_gain(np.full(4, 0.5), np.ones(4), np.zeros(4, int)) == 0.0     # one fold: none


def test_a_lag_family_whose_gain_fades_over_the_folds_hands_its_weight_to_mlr():
    X, y, context = _record()
    main = AutoRegressor({"mlr": MLR(), "fading": FadingLag()}, lag_fade=None).fit(X, y, context=context)
    assert main.weights_["fading"] > 0.5                     # it wins the early folds: the votes keep it
    auto = AutoRegressor({"mlr": MLR(), "fading": FadingLag()}).fit(X, y, context=context)
    assert auto.lag_fade == 0.3 and auto.weights_ == {"mlr": 1.0}
    assert "lag_fade: fading's gain over MLR fades over the folds" in auto.reason_
    np.testing.assert_allclose(auto.predict(X, context=context),
                               MLR().fit(X, y).predict(X), atol=1e-9)


def test_a_family_without_memory_keeps_its_weight_however_its_gain_fades():
    X, y, context = _record()
    auto = AutoRegressor({"mlr": MLR(), "fading": Fading()}).fit(X, y, context=context)
    assert auto.weights_.get("fading", 0.0) > 0.5 and "lag_fade" not in auto.reason_


def test_lag_fade_is_checked():
    X, y, context = _record()
    with pytest.raises(ParameterError, match="lag_fade"):
        AutoRegressor({"mlr": MLR()}, lag_fade=-1.0).fit(X, y, context=context)


def test_two_folds_are_one_difference_not_a_fade():
    """auto96b: tsc_a2's winning lag families had two campaign folds, ratios 0.01 0.02 (+0.75 read
    as a fade, 0.376 -> 0.675 x MLR); fewer than three folds read no fade, three or more as before."""
    two = np.array([0.01, 0.02])
    assert fading_gain(np.repeat(two, 4), np.ones(8), np.repeat(np.arange(2), 4)) == 0.0
    three = np.array([0.01, 0.02, 0.04])
    assert fading_gain(np.repeat(three, 4), np.ones(12), np.repeat(np.arange(3), 4)) == pytest.approx(np.log(2))


def test_a_fading_lag_family_on_two_folds_keeps_its_weight():
    X, y, context = _record()
    main = AutoRegressor({"mlr": MLR(), "fading": FadingLag()}, n_folds=2, lag_fade=None).fit(
        X, y, context=context)
    auto = AutoRegressor({"mlr": MLR(), "fading": FadingLag()}, n_folds=2).fit(X, y, context=context)
    assert np.unique(auto.oof_fold_).size == 2
    assert auto.weights_ == main.weights_ and "lag_fade" not in auto.reason_
