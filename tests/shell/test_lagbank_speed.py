"""What makes ``lagbank`` fast on a lathe-sized set without changing what it computes
(issue 34, item 5; the timing itself is benchmarks/bench_lagbank.py, never a test).

Mutual prediction's single-campaign models keep the penalty the model chose on all train
campaigns (no CV of their own); the lag features of a stack of rows are computed once for
every target and model that reads them; the fold Gram spectra once for every target.
"""

from __future__ import annotations

import json

import numpy as np
import pytest

from test_hostile import make_dataset
from thermocomp.core import io
from thermocomp.core.compensator import Compensator
from thermocomp.core.frame import stack
from thermocomp.core.metrics import rsd
from thermocomp.core.models import LagBank
from thermocomp.core.models._dynamics import first_order_lags
from thermocomp.shell.cli import main

RUN = ["track=false", "plots=none", "eval.ati_baselines=false", "eval.iso10791_a3=false",
       "eval.validation=false", "model=lagbank", "model.estimator.n_taus=3"]


def test_mutual_prediction_models_keep_the_penalty_chosen_on_all_train_campaigns(tmp_path):
    data = make_dataset(tmp_path / "ds", rows=40)
    out = tmp_path / "out"
    assert main(["run", f"data.path={data}", f"out={out}", *RUN]) == 0
    metrics = json.loads((out / "metrics.json").read_text())
    ds, _ = io.read_dataset(data)
    train = {c: ds.campaigns[c] for c in ds.ids("train")}
    chosen = Compensator(LagBank(n_taus=3)).fit(train).estimators_["E_X"].alpha_
    mutual = metrics["mutual_prediction"]["E_X"]
    ids = mutual["campaigns"]
    for i, trained_on in enumerate(ids):
        single = Compensator(LagBank(n_taus=3, alphas=[chosen])).fit({trained_on: ds.campaigns[trained_on]})
        pred = single.predict({c: ds.campaigns[c] for c in ids})
        meas = single.measured({c: ds.campaigns[c] for c in ids})
        expected = [rsd(meas[c]["E_X"].to_numpy() - pred[c]["E_X"].to_numpy()) for c in ids]
        assert mutual["rsd"][i] == pytest.approx(expected, rel=1e-9)


def test_the_single_campaign_penalties_would_differ_from_the_chosen_one(tmp_path):
    """The test above tells the two apart: a campaign's own CV picks another penalty."""
    ds, _ = io.read_dataset(make_dataset(tmp_path / "ds", rows=40))
    train = {c: ds.campaigns[c] for c in ds.ids("train")}
    chosen = Compensator(LagBank(n_taus=3)).fit(train).estimators_["E_X"].alpha_
    own = {c: Compensator(LagBank(n_taus=3)).fit({c: ds.campaigns[c]}).estimators_["E_X"].alpha_
           for c in ds.ids()}
    assert any(a != chosen for a in own.values())


def _stacked(tmp_path):
    ds, _ = io.read_dataset(make_dataset(tmp_path / "ds", rows=40))
    m = stack(ds.campaigns, ["T_0", "T_amb"], ["E_X"], "first_sample")
    return m.X.to_numpy(), m.Y["E_X"].to_numpy(), m.context


def test_a_second_model_on_the_same_rows_reuses_their_lag_features(tmp_path):
    X, y, context = _stacked(tmp_path)
    a = LagBank(n_taus=3).fit(X, y, context=context)
    b = LagBank(n_taus=3, alphas=[1.0]).fit(X, y, context=context)
    Fa, Fb = a._features(X, context), b._features(X, context)
    assert Fb is Fa and not Fa.flags.writeable                    # computed once, kept read-only
    time, groups = context["time"].to_numpy(float), context["campaign"].to_numpy(object)
    lags = first_order_lags(X, time, groups, a.taus_)
    np.testing.assert_array_equal(Fa, np.hstack([X, lags - np.tile(X, a.taus_.size)]))
    moved = X.copy()
    moved[5, 0] += 1.0                                              # one reading differs: recomputed
    Fm = a._features(moved, context)
    assert Fm is not Fa and not np.array_equal(Fm, Fa)


def test_fold_grams_from_the_whole_gram_equal_those_of_the_training_rows():
    from sklearn.model_selection import GroupKFold

    from thermocomp.core.models.lagbank import ForwardChaining, _training_grams

    rng = np.random.default_rng(3)
    Z = rng.normal(size=(200, 6)) @ rng.normal(size=(6, 6)) + rng.normal(size=6)
    groups = np.repeat(np.arange(8), 25)
    for splitter in (GroupKFold(4), ForwardChaining(4, gap=3, min_train_fraction=0.5)):
        splits = [rows for split in splitter.split(Z, None, groups) for rows in split]
        for (mean, gram), tr in zip(_training_grams(Z, splits), splits[::2]):
            centred = Z[tr] - Z[tr].mean(axis=0)
            np.testing.assert_allclose(mean, Z[tr].mean(axis=0), rtol=1e-12, atol=1e-12)
            np.testing.assert_allclose(gram, centred.T @ centred, rtol=1e-10, atol=1e-9)
