"""With ``static_candidate`` the lag bank's CV also scores its own static special case, the
least-squares model of the sensors (MLR), and keeps it where the folds say it is the best
(lagbank62).

Its penalty path (``level_penalty=1``) shrinks the levels towards a constant and never reaches
MLR: on two machines whose error is a static law of correlated sensors (``bench_probe61``'s
grinder, ``bench_labfiles62``'s Swiss lathe) its best CV error was 3.1x and 1.26x MLR's on the
same folds, and it tested 3.0x and 2.0x MLR's.
"""

from __future__ import annotations

import numpy as np
import pandas as pd
import pytest
from sklearn.linear_model import LinearRegression

from thermocomp.core.models import LagBank


def _static_law(k: int = 6, n: int = 120, seed: int = 0):
    """``k`` campaigns of four sensors that share one warm-up (so they are strongly correlated),
    the error a static law of their small differences with large gains (rows, target, context)."""
    rng = np.random.default_rng(seed)
    X, y, groups = [], [], []
    for c in range(k):
        rise = 3.0 * (1.0 - np.exp(-np.arange(n) / rng.uniform(20, 60)))
        x = 20.0 + rng.normal(0, 0.5) + rise[:, None] * rng.uniform(0.8, 1.2, 4) \
            + np.cumsum(rng.normal(0, 0.03, (n, 4)), axis=0)
        X.append(x)
        y.append(15.0 * (x[:, 0] - x[:, 1]) - 9.0 * (x[:, 2] - x[:, 3]) + rng.normal(0, 0.05, n))
        groups += [f"C{c}"] * n
    time = np.tile(np.arange(n) * 60.0, k)
    return np.vstack(X), np.concatenate(y), pd.DataFrame({"campaign": groups, "time": time})


def _one_record(X, y, context):
    return X, y, context[["time"]].assign(time=np.arange(len(y)) * 60.0)


def _measured_now_and_then(X, y, context):
    y = y.copy()
    y[np.arange(len(y)) % 7 != 0] = np.nan
    return X, y, context


@pytest.mark.parametrize("record", [lambda *a: a, _one_record, _measured_now_and_then],
                         ids=["campaigns", "one record", "measured now and then"])
def test_a_static_law_of_correlated_sensors_is_fitted_as_mlr(record):
    X, y, context = record(*_static_law())
    model = LagBank(n_taus=3, static_candidate=True).fit(X, y, context=context)
    rows = ~np.isnan(y)
    mlr = LinearRegression().fit(X[rows], y[rows])
    # the lag bank's predictions are MLR's (its lags at a vanishing weight), not a shrunk law
    assert model.predict(X, context=context) == pytest.approx(mlr.predict(X), abs=1e-3)
    chosen = model.cv_results_.loc[model.cv_results_["chosen"]].iloc[0]
    assert chosen["level_penalty"] == 0.0
    assert chosen["cv_mse_free_run"] == model.cv_results_["cv_mse_free_run"].min()


def test_the_chosen_static_model_refits_alone():
    """``chosen_params`` fixes the static choice: the copy scores it alone and fits the same."""
    X, y, context = _static_law()
    model = LagBank(n_taus=3, static_candidate=True).fit(X, y, context=context)
    assert model.level_penalty_ == 0.0
    again = LagBank(n_taus=3, **model.chosen_params()).fit(X, y, context=context)
    assert len(again.cv_results_) == 1
    assert again.coef_ == pytest.approx(model.coef_, rel=1e-9, abs=1e-12)
    assert again.intercept_ == pytest.approx(model.intercept_, rel=1e-9)
