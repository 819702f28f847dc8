"""A late first probe: the estimators' own validation scores as the run scores (firstfold63).

In the first-sample frame a campaign first measured at row m > 0 is scored as
label - (y_hat(t) - y_hat(m)) (:mod:`thermocomp.core.first_probe`).  model=auto's folds (its
votes) and the lag bank's CV scored label - y_hat(t): a family whose y_hat(m) is far from 0 paid
a constant no score the user sees contains.
"""

from __future__ import annotations

import numpy as np
import pandas as pd
import pytest
from sklearn.base import clone
from sklearn.linear_model import Ridge

from test_first_probe62 import campaign, dataset
from thermocomp.core.compensator import Compensator
from thermocomp.core.context import subset
from thermocomp.core.first_probe import completed
from thermocomp.core.frame import stack
from thermocomp.core.io.contract import Dataset
from thermocomp.core.models import MLR
from thermocomp.core.models.auto import AutoRegressor
from thermocomp.core.models.lagbank import LagBank, ridge_path_cv

INPUTS = ["T_a", "T_b"]


def first_fits(monkeypatch, cls, comp: Compensator, ds):
    """``[(estimator, X, y, context)]`` of every ``cls.fit`` the compensator's fit makes, in
    order: the first is on the label as measured, the others the refits on completed labels."""
    seen, fit = [], cls.fit

    def recorded(self, X, y, context=None):
        seen.append((self, np.asarray(X, float), np.asarray(y, float), context))
        return fit(self, X, y, context=context)

    monkeypatch.setattr(cls, "fit", recorded)
    comp.fit({c: ds.campaigns[c] for c in ds.ids("train")})
    return seen


def auto(**kw) -> AutoRegressor:
    return AutoRegressor(candidates={"mlr": MLR(), "lagbank": LagBank()}, keep_oof=True, **kw)


def test_autos_folds_score_the_change_since_the_first_probe(monkeypatch):
    """Each candidate's out-of-fold residual (what its votes and the run's validation of the
    kept blend read) is label - (y_hat(t) - y_hat(m)) of the fold model: Compensator.
    scored_label's residual, the label completed by the fold model's prediction at row m."""
    ds = dataset()
    est, X, y, context = first_fits(monkeypatch, AutoRegressor, Compensator(auto()), ds)[0]
    groups = context["campaign"].to_numpy(object)
    moved = 0.0
    for name in ("mlr", "lagbank"):
        got = est.oof_y_ - est.oof_[name]
        want, raw = [], []
        for fit, score in est.oof_folds_[1]:
            pred = np.isin(groups, groups[score])           # the held-out campaigns, whole
            model = clone(est.candidates[name]).fit(X[fit], y[fit], context=subset(context, fit))
            yhat = model.predict(X[pred], context=subset(context, pred))
            kept = np.isin(np.flatnonzero(pred), score)
            want.append((completed(y[pred], yhat, groups[pred]) - yhat)[kept])
            raw.append((y[pred] - yhat)[kept])
        np.testing.assert_allclose(got, np.concatenate(want), rtol=0, atol=1e-9)
        moved = max(moved, np.max(np.abs(np.concatenate(want) - np.concatenate(raw))))
    assert moved > 0.1     # the fold models' y_hat(m) is not 0 (else both rules agree)


def staggered():
    """The exact law, each campaign first measured at another row (10 to 120 rows in): their
    unmeasured E(m) - E(0) differ by several um."""
    ids = [f"c{i}" for i in range(5)]
    manifest = pd.DataFrame({"file": [f"{c}.csv" for c in ids],
                             "split": ["train"] * 4 + ["test"]}, index=pd.Index(ids, name="campaign"))
    firsts = (10, 40, 80, 120, 40)
    return Dataset(manifest, {c: campaign(i, f) for i, (c, f) in enumerate(zip(ids, firsts))})


def test_the_lag_banks_cv_scores_the_change_since_the_first_probe(monkeypatch):
    """The lag bank's CV on the label as measured (the compensator's first fit): scored against
    y_hat(t), each held-out campaign's unmeasured E(m) - E(0) was its error; in frame, only what
    the fold's fit misses.  Measured: chosen CV MSE 2.65 (alpha 10) in frame against 25.7
    (alpha 1e-4) as the label is (the same rows and folds, fitted without the frame)."""
    ds = staggered()
    est = first_fits(monkeypatch, LagBank, Compensator(LagBank()), ds)[0][0]
    m = stack({c: ds.campaigns[c] for c in ds.ids("train")}, INPUTS, ["E_X"])
    plain = LagBank().fit(m.X.to_numpy(), m.Y["E_X"].to_numpy(), context=m.context)

    def chosen(e):
        return float(e.cv_results_.loc[e.cv_results_["chosen"], "cv_mse_free_run"].iloc[0])

    assert chosen(est) < 0.25 * chosen(plain)


def test_ridge_path_cv_scores_each_validation_row_from_its_first_measurement():
    """The CV's numbers in frame: per fold and penalty scikit-learn's Ridge, its error on the
    validation rows less its error at the row of the campaign's first measurement (which may
    lie among the fit rows)."""
    rng = np.random.default_rng(63)
    Z, y = rng.normal(size=(60, 4)), rng.normal(size=60)
    first = np.repeat([5, -1, 33], 20)          # campaign 0 first measured at 5, 1 at its start
    splits = [(np.arange(20, 60), np.arange(0, 20)), (np.r_[0:20, 40:60], np.arange(20, 40)),
              (np.r_[0:30], np.arange(40, 60))]
    alphas = np.array([0.1, 10.0])
    got = ridge_path_cv(Z, y, splits, alphas, first_measured=first)["free_run"]
    for f, (tr, va) in enumerate(splits):
        for i, a in enumerate(alphas):
            model = Ridge(alpha=a).fit(Z[tr], y[tr])
            error = model.predict(Z) - y
            error = np.where(first >= 0, error - error[np.maximum(first, 0)], error)
            assert got[f, i] == pytest.approx(np.mean(error[va] ** 2), rel=1e-9)


@pytest.mark.parametrize("first, reference", [(0, "first_sample"), (40, "none")])
def test_a_first_probe_at_row_0_and_the_none_frame_score_as_before(monkeypatch, first, reference):
    """Measured from the first row, or read absolute: the folds score the label as it is, and
    the compensator's fit is the plain estimator's, bit for bit.  (A guard: passes on the old
    code too.)"""
    ds = dataset(first)
    est, X, y, context = first_fits(monkeypatch, AutoRegressor,
                                    Compensator(auto(), reference=reference), ds)[0]
    m = stack({c: ds.campaigns[c] for c in ds.ids("train")}, INPUTS, ["E_X"], reference)
    plain = auto().fit(m.X.to_numpy(), m.Y["E_X"].to_numpy(), context=m.context)
    assert np.array_equal(est.oof_y_, plain.oof_y_)
    assert np.array_equal(est.oof_y_, np.concatenate([y[s] for _, s in est.oof_folds_[1]]))
    for name in ("mlr", "lagbank"):
        assert np.array_equal(est.oof_[name], plain.oof_[name])
    assert est.weights_ == plain.weights_
