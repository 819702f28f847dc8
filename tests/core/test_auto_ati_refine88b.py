"""``model=auto``'s ``ati_refinements`` (auto88, auto88b): ATI of hammerstein validated only where the blend
keeps ``ati`` (ATI of MLR), with ati's interval count per fold, and given ati's share only where its
folds are surely below ati's (one SE).

Tiny data: campaigns at three ambient levels; the error is a first-order lag of the heating whose
gain changes with the ambient (ATI's law), so ATI of MLR beats MLR and ATI of hammerstein (its lag
bank holds the lag) beats both; a static error with the same ambient law leaves ATI of MLR right.
"""

from __future__ import annotations

import numpy as np
import pandas as pd
import pytest

from thermocomp.core.context import AMBIENT_C0, CAMPAIGN

LEVELS = (15.0, 20.0, 25.0)
REFINED = "ati+hammerstein"


def _campaigns(n: int, seed: int, lag_s: float | None):
    """``n`` campaigns of 120 rows at 60 s, ambient cycling over :data:`LEVELS`; ``lag_s``: the
    error a first-order lag of the heating (None: static in it)."""
    rng = np.random.default_rng(seed)
    X, y, ctx = [], [], []
    for k in range(n):
        amb = LEVELS[k % 3] + rng.normal(0, 0.05)
        i = np.arange(120)
        on = ((i >= 10) & (i < rng.integers(50, 90))).astype(float) * rng.uniform(3, 6)
        heat = on.copy()
        if lag_s is not None:
            a = 60.0 / (lag_s + 60.0)
            for i in range(1, 120):
                heat[i] = heat[i - 1] + a * (on[i] - heat[i - 1])
        sensor = amb + on + rng.normal(0, 0.02, 120)
        X.append(np.column_stack([sensor - sensor[0]]))
        y.append((1.0 + 0.08 * (amb - 20.0)) * 2.0 * heat + rng.normal(0, 0.05, 120))
        ctx.append(pd.DataFrame({CAMPAIGN: f"K{k:02d}", AMBIENT_C0: amb}, index=range(120)))
    return np.vstack(X), np.concatenate(y), pd.concat(ctx, ignore_index=True)


def _candidates():
    from thermocomp.core.models.ati import ATIRegressor
    from thermocomp.core.models.hammerstein import Hammerstein
    from thermocomp.core.models.linear import MLR

    ati = {"ambient_interaction": True, "candidates": (1, 2, 3)}
    return {"mlr": MLR(), "ati": ATIRegressor(MLR(), **ati), REFINED: ATIRegressor(Hammerstein(), **ati)}


def _rmse(model, data) -> float:
    X, y, ctx = data
    return float(np.sqrt(np.mean((y - model.predict(X, context=ctx)) ** 2)))


def test_ati_of_hammerstein_takes_atis_share_where_its_folds_are_surely_below_atis():
    from thermocomp.core.models.auto import AutoRegressor

    X, y, ctx = _campaigns(15, seed=1, lag_s=900.0)
    plain = AutoRegressor({n: c for n, c in _candidates().items() if n != REFINED}).fit(X, y, context=ctx)
    assert plain.weights_.get("ati", 0) > 0.5                     # ATI of MLR kept, as on main
    auto = AutoRegressor(_candidates(), ati_refinements=[REFINED]).fit(X, y, context=ctx)
    assert auto.weights_.get(REFINED, 0) >= plain.weights_["ati"] and "ati" not in auto.weights_
    assert "ati+hammerstein takes ati's share" in auto.reason_
    # validated with ati's interval count per fold; refitted with ati's on every train row
    assert len(auto.fold_intervals_["ati"]) == len(auto.oof_folds_[1]) and REFINED in auto.validation_
    refined = auto.estimator_ if auto.family_ == auto.chosen_ else auto.estimator_.estimators_[REFINED]
    ati_all = _candidates()["ati"].fit(X, y, context=ctx)
    assert refined.n_intervals == ati_all.elbow_["chosen"]
    new = _campaigns(9, seed=2, lag_s=900.0)                      # new campaigns of the machine
    assert _rmse(auto, new) < 0.7 * _rmse(plain, new)


def test_where_ati_is_right_or_absent_the_refinement_changes_nothing():
    from thermocomp.core.models.auto import AutoRegressor

    X, y, ctx = _campaigns(15, seed=3, lag_s=None)               # static: ATI of MLR is the law
    plain = AutoRegressor({n: c for n, c in _candidates().items() if n != REFINED}).fit(X, y, context=ctx)
    auto = AutoRegressor(_candidates(), ati_refinements=[REFINED]).fit(X, y, context=ctx)
    assert auto.weights_ == plain.weights_ and auto.weights_.get("ati", 0) > 0.5
    assert "ati+hammerstein (ati's intervals per fold) over ati" in auto.reason_
    # no ambient: neither ATI candidate is validated, the refinement not even tried
    bare = AutoRegressor(_candidates(), ati_refinements=[REFINED]).fit(X, y, context=ctx[[CAMPAIGN]])
    assert "ati" in bare.skipped_ and REFINED not in bare.skipped_ and REFINED not in bare.validation_
    with pytest.raises(Exception, match="not an ati"):
        AutoRegressor(_candidates(), ati_refinements=["mlr"]).fit(X, y, context=ctx)
