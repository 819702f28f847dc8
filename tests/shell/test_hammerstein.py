"""The Hammerstein lag bank: machine states through a power law, then the lag bank's dynamics."""

from __future__ import annotations

import numpy as np
import pandas as pd
import pytest
from sklearn.metrics import mean_squared_error

from conftest import refused, stream_context
from test_hostile import CAMPAIGNS, FAST, edit_csv, make_dataset
from thermocomp.base.errors import ContractError, ParameterError
from thermocomp.core.models import MLR, Hammerstein, LagBank
from thermocomp.core.models._dynamics import first_order_lag

PERIOD_S = 60.0


def _spindle_problem(seed: int, n_campaigns: int = 8, n: int = 240, heat_gain: float = 6.0):
    """Campaigns of a spindle stepping between speeds; the sensors see only the hall (a random
    walk) and a noisy far sensor; the error is the hall's expansion plus the structure's response
    (a 30-min lag) to friction heat growing as the square of the speed."""
    rng = np.random.default_rng(seed)
    groups = np.repeat([f"C{i}" for i in range(n_campaigns)], n)
    time = np.tile(np.arange(n) * PERIOD_S, n_campaigns)
    speeds = rng.choice([0.0, 2000.0, 4000.0, 8000.0], size=(n_campaigns * n // 30,))
    rpm = np.repeat(speeds, 30)[:len(groups)]
    hall = 20 + np.cumsum(rng.normal(0, 0.02, len(groups)))
    heat = first_order_lag((rpm / 8000.0) ** 2, time, groups, 1800.0)
    X = np.column_stack([hall, hall + rng.normal(0, 0.3, len(groups))])
    y = 2.0 * (hall - 20) + heat_gain * heat + rng.normal(0, 0.05, len(groups))
    context = pd.DataFrame({"campaign": groups, "time": time, "S_spindle_rpm": rpm})
    return X, y, context


def _split(X, y, context, n_train: int):
    train = context["campaign"].isin([f"C{i}" for i in range(n_train)]).to_numpy()
    return tuple((X[rows], y[rows], context[rows].reset_index(drop=True)) for rows in (train, ~train))


def _test_rmse(est, data) -> float:
    (Xtr, ytr, ctr), (Xte, yte, cte) = data
    est.fit(Xtr, ytr, context=ctr)
    return float(np.sqrt(mean_squared_error(yte, est.predict(Xte, context=cte))))


def test_the_square_law_of_a_state_is_found_on_train_and_wins_on_held_out_campaigns():
    """The error follows speed² through a lag the sensors never see: CV on the train campaigns
    picks the power 2, and on held-out campaigns the model beats the lag bank and MLR, which
    only have the sensors."""
    data = _split(*_spindle_problem(seed=0), n_train=6)
    ham = Hammerstein(lagbank=LagBank(n_taus=4))
    rmse = {"hammerstein": _test_rmse(ham, data), "lagbank": _test_rmse(LagBank(n_taus=4), data),
            "mlr": _test_rmse(MLR(), data)}
    assert 2.0 in ham.exponents_ and ham.state_columns_ == ["S_spindle_rpm"]
    assert ham.cv_results_["chosen"].sum() == 1 and len(ham.cv_results_) == 4   # {}, {1}, {2}, {1, 2}
    assert rmse["hammerstein"] < 0.5 * min(rmse["lagbank"], rmse["mlr"]), rmse
    assert "S_spindle_rpm" in ham.context_columns_ and "time" in ham.context_columns_


def test_without_a_state_effect_it_is_no_worse_than_the_lag_bank():
    """A speed that does nothing to the error: the candidate without states is in the CV table,
    and whatever wins on train, the held-out error is the lag bank's to within its noise."""
    data = _split(*_spindle_problem(seed=1, heat_gain=0.0), n_train=6)
    ham = Hammerstein(lagbank=LagBank(n_taus=4))
    ours, plain = _test_rmse(ham, data), _test_rmse(LagBank(n_taus=4), data)
    assert [] in ham.cv_results_["exponents"].tolist()
    assert ours <= plain * 1.1, (ours, plain, ham.exponents_)


def test_without_a_context_it_is_the_plain_lag_bank():
    (Xtr, ytr, ctr), (Xte, _, cte) = _split(*_spindle_problem(seed=2), n_train=6)
    context = ctr[["campaign", "time"]]
    ham = Hammerstein(lagbank=LagBank(n_taus=3)).fit(Xtr, ytr, context=context)
    plain = LagBank(n_taus=3).fit(Xtr, ytr, context=context)
    assert ham.exponents_ == () and ham.state_columns_ == []
    np.testing.assert_allclose(ham.predict(Xte, context=cte[["campaign", "time"]]),
                               plain.predict(Xte, context=cte[["campaign", "time"]]))


def test_it_streams_as_it_predicts_with_a_missing_state_sample_held():
    (Xtr, ytr, ctr), (Xte, _, cte) = _split(*_spindle_problem(seed=3), n_train=6)
    ham = Hammerstein(lagbank=LagBank(n_taus=3)).fit(Xtr, ytr, context=ctr)
    assert ham.exponents_
    cte.loc[[5, 6, 300], "S_spindle_rpm"] = np.nan      # a gap inside a campaign
    cte.loc[cte.index[cte["campaign"] == "C7"][0], "S_spindle_rpm"] = np.nan   # and at a start
    batch = ham.predict(Xte, context=cte)
    assert np.all(np.isfinite(batch))
    np.testing.assert_allclose(stream_context(ham, Xte, cte), batch, rtol=0, atol=1e-9)


def test_a_state_it_was_fitted_on_missing_at_prediction_names_the_column():
    (Xtr, ytr, ctr), (Xte, _, cte) = _split(*_spindle_problem(seed=0), n_train=6)
    ham = Hammerstein(lagbank=LagBank(n_taus=3)).fit(Xtr, ytr, context=ctr)
    with pytest.raises(ContractError, match="S_spindle_rpm"):
        ham.predict(Xte, context=cte.drop(columns=["S_spindle_rpm"]))


def test_a_campaign_that_never_measures_a_state_is_left_out_in_fit_and_refused_in_predict():
    """Holding 0 through a campaign without the speed would read as a machine at rest: a state
    some train campaign lacks is not used, and a campaign to predict that lacks a used one is
    refused, naming both."""
    (Xtr, ytr, ctr), (Xte, _, cte) = _split(*_spindle_problem(seed=0), n_train=6)
    ctr = ctr.assign(S_door=np.where(ctr["campaign"] == "C0", np.nan, ctr["time"] % 1200 < 600))
    ham = Hammerstein(lagbank=LagBank(n_taus=3)).fit(Xtr, ytr, context=ctr)
    assert ham.state_columns_ == ["S_spindle_rpm"]
    cte.loc[cte["campaign"] == "C7", "S_spindle_rpm"] = np.nan
    with pytest.raises(ContractError, match="campaign 'C7' has no value of 'S_spindle_rpm'"):
        ham.predict(Xte, context=cte)


def _with_speed(ds, test_has_it: bool = True):
    """``make_dataset`` with a spindle speed S_rpm whose square heats the error."""
    for i, (cid, split) in enumerate(CAMPAIGNS):
        def add(df, i=i, split=split):
            rpm = np.where(np.arange(len(df)) % 10 < 5, 0.0, 1000.0 * (i + 1))
            df["E_X"] = df["E_X"] + 3.0 * (rpm / 4000.0) ** 2
            if test_has_it or split != "test":
                df["S_rpm"] = rpm
        edit_csv(ds / f"{cid}.csv", add)
    return ds


def test_run_refuses_a_test_campaign_without_the_state_the_model_reads(tmp_path, capsys):
    ds = _with_speed(make_dataset(tmp_path / "ds", rows=40), test_has_it=False)
    refused(["run", f"data.path={ds}", f"out={tmp_path / 'out'}", "model=hammerstein", *FAST],
            capsys, "'S_rpm'", "Hammerstein")
    assert not (tmp_path / "out").exists()


def test_an_output_feedback_lag_bank_is_refused():
    X, y, context = _spindle_problem(seed=0, n_campaigns=2, n=30)
    with pytest.raises(ParameterError, match="Hammerstein.lagbank=.*ar=false"):
        Hammerstein(lagbank=LagBank(ar=True)).fit(X, y, context=context)


@pytest.mark.parametrize(("override", "says"), [
    ("model.estimator.exponents=[0]", "model.estimator.exponents=[0]: must be"),
    ("model.estimator.states=[]", "model.estimator.states=[]: must be"),
    ("model.estimator.lagbank.ar=true", "model.estimator.lagbank="),
    ("model.estimator.lagbank.n_taus=0", "model.estimator.lagbank.n_taus=0"),
])
def test_a_bad_key_is_one_line_and_exit_2(tmp_path, capsys, override, says):
    ds = make_dataset(tmp_path / "ds")
    refused(["run", f"data.path={ds}", f"out={tmp_path / 'out'}", "model=hammerstein", override, *FAST],
            capsys, says)
    assert not (tmp_path / "out").exists()


def test_run_on_campaigns_without_a_state_column(tmp_path, capsys):
    """``model=hammerstein`` runs end to end where the data carry no S_ column (the lag bank)."""
    from thermocomp.shell.cli import main

    ds = make_dataset(tmp_path / "ds", rows=40)
    assert main(["run", f"data.path={ds}", f"out={tmp_path / 'out'}", "model=hammerstein", *FAST]) == 0
    assert "model=hammerstein" in capsys.readouterr().out
