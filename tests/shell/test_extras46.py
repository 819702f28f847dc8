"""The report extras of ``run`` on many campaigns (issue 34, item 5; the CPU table is
benchmarks/bench_extras.py, never a test): mutual prediction fits at most
``eval.mutual_prediction_max_models`` single-campaign models, on campaigns spread over its
ambient order, and says so; a Hammerstein's single-campaign models keep the powers and the
penalty it chose on all train campaigns (one lag bank each, no choice of their own); an ARX+RF's
forest predicts each distinct state once; an LSTM predicts campaigns of like length in one batch."""

from __future__ import annotations

import json

import numpy as np
import pandas as pd
import pytest
from sklearn.base import clone
from sklearn.ensemble import RandomForestRegressor

from test_arx_rf import door_campaign, small_forest
from test_hammerstein import _spindle_problem
from test_hostile import make_dataset
from test_stats import _campaign
from thermocomp.core.compensator import Compensator, with_chosen_hyperparameters
from thermocomp.core.metrics import rsd
from thermocomp.core.models import ARXRF, LSTM, MLR, Hammerstein, LagBank
from thermocomp.core.models.lstm import _like_lengths
from thermocomp.core.scoring.evaluation import spread_campaigns
from thermocomp.core.scoring.stats import mutual_prediction
from thermocomp.shell.cli import main

RUN = ["track=false", "eval.ati_baselines=false", "eval.iso10791_a3=false", "eval.validation=false"]


def test_a_capped_matrix_is_the_full_ones_rows_of_the_campaigns_spread_over_its_order():
    camps = {f"K{i}": _campaign(1.0 + 0.5 * i, seed=i) for i in range(7)}
    rows = spread_campaigns(list(camps), 3)
    assert rows == ["K0", "K3", "K6"]            # the first, the middle, the last
    assert spread_campaigns(list(camps), 7) == spread_campaigns(list(camps), None) == list(camps)
    full = mutual_prediction(camps, lambda: Compensator(MLR()))["E_Z"]
    capped = mutual_prediction(camps, lambda: Compensator(MLR()), trained_on=rows)["E_Z"]
    assert list(capped.index) == rows and list(capped.columns) == list(camps)
    pd.testing.assert_frame_equal(capped, full.loc[rows])


def _run(tmp_path, name, *args) -> dict:
    out = tmp_path / name
    assert main(["run", f"data.path={tmp_path / 'ds'}", f"out={out}", *RUN, *args]) == 0
    return json.loads((out / "metrics.json").read_text())["mutual_prediction"]["E_X"]


def test_run_caps_the_models_says_so_and_leaves_a_small_study_as_it_was(tmp_path, capsys):
    make_dataset(tmp_path / "ds")                 # four campaigns
    full = _run(tmp_path, "full", "plots=none")   # the default cap (24) is above four campaigns
    assert "mutual prediction: 4 single-campaign models\n" in capsys.readouterr().err
    assert full["trained_on"] == full["campaigns"] and np.shape(full["rsd"]) == (4, 4)
    capped = _run(tmp_path, "capped", "plots=test", "eval.mutual_prediction_max_models=2")
    assert "2 single-campaign models of 4 campaigns (eval.mutual_prediction_max_models=2" \
        in capsys.readouterr().err
    ids = full["campaigns"]
    assert capped["campaigns"] == ids and capped["trained_on"] == [ids[0], ids[-1]]
    assert capped["max_models"] == 2 and np.shape(capped["rsd"]) == (2, 4)
    assert capped["rsd"] == [full["rsd"][0], full["rsd"][-1]]
    assert (tmp_path / "capped" / "plots" / "mutual_prediction_E_X.png").stat().st_size > 10_000


def _spindle_campaigns(seed: int) -> dict[str, pd.DataFrame]:
    X, y, context = _spindle_problem(seed=seed, n_campaigns=5, n=120)
    frame = pd.DataFrame({"time": context["time"], "T_hall": X[:, 0], "T_far": X[:, 1],
                          "S_spindle_rpm": context["S_spindle_rpm"], "E_X": y})
    return {c: part.reset_index(drop=True) for c, part in frame.groupby(context["campaign"])}


def test_a_hammersteins_single_campaign_models_fit_one_lag_bank_as_chosen(monkeypatch):
    camps = _spindle_campaigns(seed=0)
    template = Compensator(Hammerstein(lagbank=LagBank(n_taus=3)))
    fitted = clone(template).fit({c: camps[c] for c in list(camps)[:4]})
    ham = fitted.estimators_["E_X"]
    assert ham.exponents_ and len(ham.cv_results_) == 4    # the main fit chose among four sets
    single = with_chosen_hyperparameters(clone(template), fitted)
    fits = []
    real_fit = LagBank.fit
    monkeypatch.setattr(LagBank, "fit", lambda self, *a, **k: fits.append(1) or real_fit(self, *a, **k))
    got = mutual_prediction(camps, lambda: clone(single))["E_X"]
    assert len(fits) == len(camps)                # one lag bank per campaign, not one per power set
    monkeypatch.undo()
    ids = list(camps)
    for i in ids:                                 # the same as a model fixed by hand
        by_hand = Compensator(Hammerstein(lagbank=LagBank(n_taus=3, alphas=[ham.lagbank_.alpha_]),
                                          exponents=list(ham.exponents_), choose_exponents=False))
        by_hand.fit({i: camps[i]})
        pred, meas = by_hand.predict(camps), by_hand.measured(camps)
        want = [rsd(meas[c]["E_X"].to_numpy() - pred[c]["E_X"].to_numpy()) for c in ids]
        assert got.loc[i].to_list() == pytest.approx(want, rel=1e-9)


def test_an_arx_rf_forest_predicts_each_distinct_state_once_with_the_same_numbers():
    rng = np.random.default_rng(0)
    camps = {f"K{i}": door_campaign(rng) for i in range(3)}
    seen = []

    class Counted(RandomForestRegressor):
        def predict(self, X):
            seen.append(len(X))
            return super().predict(X)

    comp = Compensator(ARXRF(forest=Counted(**small_forest().get_params()))).fit(camps)
    est, m = comp.estimators_["E_X"], comp.stacked(camps, [])
    X = m.X[comp.selected_["E_X"]].to_numpy()
    got = est.predict(X, context=m.context)
    assert 0 < seen[-1] < len(X) / 5          # the door is shut most of the time: a few states
    every_row = RandomForestRegressor.predict(est.forest_, est._state_features(len(X), m.context))
    np.testing.assert_array_equal(got, est.arx_.predict(X, context=m.context) + every_row)


def test_an_lstm_predicts_campaigns_of_like_length_in_one_pass_with_the_same_numbers(monkeypatch):
    from thermocomp.core.models._lstm_net import _Net  # torch: not imported at collection

    rng = np.random.default_rng(1)
    camps = {f"K{i}": door_campaign(rng, n=n) for i, n in enumerate((200, 300, 480))}
    comp = Compensator(LSTM(hidden_size=4, max_epochs=3, chunk=64)).fit(camps)
    alone = {c: comp.predict({c: camps[c]})[c] for c in camps}     # a batch of one campaign
    passes = []
    forward = _Net.forward
    monkeypatch.setattr(_Net, "forward", lambda self, *a: passes.append(1) or forward(self, *a))
    together = comp.predict(camps)
    assert len(passes) == 1                       # all three campaigns in one pass, not three
    for c in camps:
        np.testing.assert_allclose(together[c]["E_X"], alone[c]["E_X"], rtol=1e-12, atol=1e-12)


def test_like_lengths_batches_every_campaign_once_shortest_first_within_the_budget():
    bounds = [(0, 10), (10, 15), (15, 40)]
    assert _like_lengths(bounds, width=1, cells=30) == [[(10, 15), (0, 10)], [(15, 40)]]
    assert _like_lengths(bounds, width=1, cells=10) == [[(10, 15)], [(0, 10)], [(15, 40)]]
    assert _like_lengths(bounds, width=1) == [[(10, 15), (0, 10), (15, 40)]]
