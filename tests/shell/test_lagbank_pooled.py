"""The lag bank's fit from per-campaign moments (thermocomp.core.models._pooled) is its fit over
the rows, and each campaign's moments are computed once for every fit that holds it (what makes
``model=lagbank ati=cmeans`` cheaper; the timing is in benchmarks/bench_climate_room.py, never a
test)."""

from __future__ import annotations

import numpy as np
import pandas as pd
import pytest

from thermocomp.core.models import LagBank, _pooled
from thermocomp.core.models.ati import ATIRegressor


def _campaigns(k: int = 9, p: int = 3, seed: int = 0):
    """``k`` campaigns of slowly drifting inputs, the target a lagged response of them plus a
    per-campaign offset (rows, context)."""
    rng = np.random.default_rng(seed)
    X, y, groups, time = [], [], [], []
    for c in range(k):
        n = int(rng.integers(40, 90))
        x = np.cumsum(rng.normal(size=(n, p)), axis=0) * 0.2 + rng.normal(size=p)
        slow = np.cumsum(x[:, 0]) / np.arange(1, n + 1)
        X.append(x)
        y.append(x @ rng.normal(size=p) + 2.0 * slow + 0.1 * c + 0.05 * rng.normal(size=n))
        groups += [f"C{c:02d}"] * n
        time.append(np.arange(n) * 60.0)
    context = pd.DataFrame({"campaign": np.array(groups, dtype=object), "time": np.concatenate(time)})
    return np.vstack(X), np.concatenate(y), context


@pytest.mark.parametrize("params", [{}, {"level_penalty": [1.0, 0.25, 0.0]}, {"alphas": [0.3]}])
def test_the_fit_from_campaign_moments_is_the_fit_over_the_rows(monkeypatch, params):
    X, y, context = _campaigns()
    pooled = LagBank(n_taus=3, **params).fit(X, y, context=context)
    with monkeypatch.context() as m:
        m.setattr(LagBank, "_campaign_folds", staticmethod(lambda *a: None))
        rows = LagBank(n_taus=3, **params).fit(X, y, context=context)
    assert pooled.alpha_ == rows.alpha_ and pooled.level_penalty_ == rows.level_penalty_
    for column in ("cv_mse_one_step", "cv_mse_one_step_sd"):
        assert pooled.cv_results_[column].to_numpy() == pytest.approx(
            rows.cv_results_[column].to_numpy(), rel=1e-8)
    assert pooled.coef_ == pytest.approx(rows.coef_, rel=1e-9, abs=1e-12 * np.abs(rows.coef_).max())
    assert pooled.intercept_ == pytest.approx(rows.intercept_, rel=1e-9, abs=1e-12)


def _ambient_campaigns():
    """8 campaigns, each at its own initial ambient (as the ATI wrapper reads it)."""
    X, y, context = _campaigns(k=8)
    a0 = np.repeat([12.0, 16.0, 20.0, 24.0, 28.0, 32.0, 14.0, 30.0],
                   np.bincount(np.unique(context["campaign"], return_inverse=True)[1]))
    return X, y, context.assign(ambient_c0=a0)


def test_a_campaigns_moments_are_computed_once_for_every_fit_that_holds_it(monkeypatch):
    """The ATI elbow refits the lag bank on the same campaigns in many combinations."""
    X, y, context = _ambient_campaigns()
    computed = []
    memo = _pooled.ArrayMemo(lambda *a: computed.append(1) or _pooled._feature_moments(*a), size=256)
    monkeypatch.setattr(_pooled, "_campaign_moments", memo)
    ati = ATIRegressor(LagBank(n_taus=3), candidates=(1, 2, 3)).fit(X, y, context=context)
    assert ati.elbow_["reason"] is None
    # the elbow fits 3 x 8 lag banks and the final one; each campaign featurised once per design
    # (with or without the ambient interaction)
    assert len(computed) <= 2 * 8


def test_forward_chaining_and_the_ar_term_keep_the_fit_over_the_rows(monkeypatch):
    """One record is cut into folds, an AR term feeds the output back: no campaign moments."""
    from thermocomp.core.models import lagbank

    def refuse(*args):
        raise AssertionError("campaign moments where the folds cut a record or y(t-1) enters")

    monkeypatch.setattr(lagbank, "CampaignMoments", refuse)
    X, y, context = _campaigns(k=3)
    assert "lags+ar" in set(LagBank(n_taus=3, ar="auto").fit(X, y, context=context).cv_results_["design"])
    one = LagBank(n_taus=3).fit(X, y, context=pd.DataFrame({"time": np.arange(len(y)) * 60.0}))
    assert type(one.splitter_).__name__ == "ForwardChaining"


def test_a_second_targets_elbow_reuses_the_folds_factorisations(monkeypatch):
    """They depend on the inputs alone; an ATI elbow's lag banks come back target after target."""
    X, y, context = _ambient_campaigns()
    computed = []
    memo = _pooled.ArrayMemo(lambda *a: computed.append(1) or _pooled._compute_spectra(*a),
                             size=_pooled._spectra.size, max_bytes=_pooled._spectra.max_bytes)
    monkeypatch.setattr(_pooled, "_spectra", memo)
    first = ATIRegressor(LagBank(n_taus=3), candidates=(1, 2, 3)).fit(X, y, context=context)
    once = len(computed)
    second = ATIRegressor(LagBank(n_taus=3), candidates=(1, 2, 3)).fit(X, -2.0 * y, context=context)
    assert once > 8 and len(computed) == once
    assert second.elbow_["chosen"] == first.elbow_["chosen"]


def test_the_memo_forgets_the_oldest_beyond_its_bytes():
    memo = _pooled.ArrayMemo(lambda n: np.zeros(int(n)), size=100, max_bytes=8 * 250)
    for n in (100.0, 101.0, 102.0):   # about 800 bytes each: the third pushes the first out
        memo(n)
    assert len(memo._results) == 2
    assert memo(1000.0).size == 1000 and len(memo._results) == 1   # the newest kept whatever its size
