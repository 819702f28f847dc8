"""LSTM residual over whole campaigns: sklearn API, a static baseline, determinism, streaming."""

import pickle

import numpy as np
import pytest
from sklearn.utils.estimator_checks import check_estimator

from conftest import FAST, ctx, poisoned_copy, stream_predictions, thermocomp
from thermocomp.base.errors import ParameterError
from thermocomp.core.models import LSTM, MLR
from thermocomp.core.models._dynamics import free_run

STATE_CHECKS = {
    "check_methods_sample_order_invariance":
        "the state carried from the campaign start feeds each prediction",
    "check_methods_subset_invariance": "the state carried from the campaign start feeds each prediction",
}


def lagged_data(n_campaigns=8, n=60, p=4, seed=0):
    """The error lags the temperatures (first order): a static map cannot follow it."""
    rng = np.random.default_rng(seed)
    X, y, g = [], [], []
    for c in range(n_campaigns):
        T = np.cumsum(rng.normal(0, 0.3, (n, p)), axis=0)
        T -= T[0]
        X.append(T)
        y.append(free_run(0.8, 0.2 * (2 * T[:, 0] - T[:, 2]), None) + rng.normal(0, 0.02, n))
        g.extend([c] * n)
    return np.vstack(X), np.concatenate(y), np.array(g)


def quick(**kw):
    return LSTM(**{"hidden_size": 8, "chunk": 32, "max_epochs": 80, "patience": 15, "batch_size": 4,
                   "learning_rate": 1e-2, **kw})


def rmse(a, b):
    return float(np.sqrt(np.mean((np.asarray(a) - np.asarray(b)) ** 2)))


def test_lstm_passes_sklearn_checks_but_the_documented_state_ones():
    check_estimator(LSTM(hidden_size=4, max_epochs=3), expected_failed_checks=STATE_CHECKS)


def test_lstm_beats_the_static_baseline_on_held_out_campaigns():
    X, y, g = lagged_data()
    train, test = g < 6, g >= 6
    lstm = quick().fit(X[train], y[train], context=ctx(g[train]))
    mlr = MLR().fit(X[train], y[train])
    lstm_rmse = rmse(y[test], lstm.predict(X[test], context=ctx(g[test])))
    mlr_rmse = rmse(y[test], mlr.predict(X[test]))
    # epoch 0 is the least-squares linear model (the MLR): training must have improved on it,
    # by more than rounding (an untrained network ties the MLR to 1e-15)
    assert lstm.best_epoch_ > 0 and lstm.best_epoch_ == int(np.argmin(lstm.validation_curve_))
    assert lstm.validation_curve_[lstm.best_epoch_] < 0.9 * lstm.validation_curve_[0]
    assert lstm_rmse < 0.95 * mlr_rmse, (lstm_rmse, mlr_rmse)   # and on held-out campaigns
    assert len(lstm.validation_curve_) == lstm.n_epochs_ + 1 and lstm.n_epochs_ == len(lstm.loss_curve_)


def test_an_untrained_network_is_ordinary_least_squares():
    """The read-out starts at zero and the skip path is refitted on every row: OLS exactly."""
    X, y, g = lagged_data(n_campaigns=3, n=30)
    est = quick(max_epochs=1, learning_rate=0.0).fit(X, y, context=ctx(g))
    np.testing.assert_allclose(est.predict(X, context=ctx(g)), MLR().fit(X, y).predict(X), atol=1e-9)


def test_fit_is_deterministic_per_seed_and_leaves_torch_globals_alone():
    import torch  # in the tests that use it: not imported at collection (~2 s of CPU per worker)

    X, y, g = lagged_data(n_campaigns=5)
    torch.manual_seed(123)
    before_rng, before_threads = torch.get_rng_state(), torch.get_num_threads()
    a = quick(max_epochs=10).fit(X, y, context=ctx(g))
    assert torch.equal(torch.get_rng_state(), before_rng) and torch.get_num_threads() == before_threads
    b = quick(max_epochs=10).fit(X, y, context=ctx(g))
    pred = a.predict(X, context=ctx(g))
    np.testing.assert_array_equal(pred, b.predict(X, context=ctx(g)))
    other = quick(max_epochs=10, random_state=1).fit(X, y, context=ctx(g))
    assert not np.array_equal(other.predict(X, context=ctx(g)), pred)


def test_validation_split_whole_campaigns_or_the_tail_of_one():
    est = LSTM(validation_fraction=0.25, random_state=0)
    g = np.repeat([0, 1, 2, 3], 10)
    val = est._validation_rows(g, 40)
    assert val.sum() == 10 and len(set(g[val])) == 1           # one whole campaign
    tail = est._validation_rows(None, 40)
    assert tail.tolist() == [False] * 30 + [True] * 10          # contiguous block at the end


def test_streaming_reproduces_predict_and_pickle_round_trip():
    X, y, g = lagged_data(n_campaigns=4)
    est = quick(max_epochs=5).fit(X, y, context=ctx(g))
    batch = est.predict(X, context=ctx(g))
    stream = stream_predictions(est, X, g)
    np.testing.assert_allclose(stream, batch, rtol=0, atol=1e-9)
    again = pickle.loads(pickle.dumps(est))
    np.testing.assert_array_equal(again.predict(X, context=ctx(g)), batch)


def test_state_never_crosses_campaigns():
    X, y, g = lagged_data(n_campaigns=3)
    est = quick(max_epochs=5).fit(X, y, context=ctx(g))
    joint = est.predict(X, context=ctx(g))
    for c in range(3):
        own = g == c
        np.testing.assert_allclose(joint[own], est.predict(X[own]), atol=1e-12)


def test_a_single_record_validates_on_its_tail_with_the_state_carried_in():
    X, y, _ = lagged_data(n_campaigns=1, n=300)
    est = quick(max_epochs=5, chunk=64).fit(X, y)
    assert len(est.validation_curve_) == est.n_epochs_ + 1
    np.testing.assert_allclose(stream_predictions(est, X, np.zeros(len(X))), est.predict(X), atol=1e-9)


@pytest.mark.parametrize("bad", [{"hidden_size": 0}, {"chunk": 0}, {"validation_fraction": 1.0},
                                 {"max_epochs": 0}])
def test_bad_hyperparameters_are_config_errors(bad):
    X, y, g = lagged_data(n_campaigns=2, n=10)
    with pytest.raises(ParameterError):
        LSTM(**bad).fit(X, y, context=ctx(g))


@pytest.mark.slow
def test_poisoned_test_campaigns_do_not_change_the_fitted_network(tmp_path):
    """Early stopping holds out train campaigns only: the test split never reaches ``fit``."""
    import torch

    clean = tmp_path / "clean"
    thermocomp("simulate", f"data.path={clean}", "track=false", "sim.generator.n_campaigns=6",
               "sim.generator.duration_h=[2.0,3.0]")
    poisoned = poisoned_copy(clean, tmp_path / "poisoned")
    fitted = {}
    for name, path in (("clean", clean), ("poisoned", poisoned)):
        thermocomp("run", f"data.path={path}", f"out={tmp_path / 'out' / name}", "model=lstm",
                   "model.estimator.hidden_size=4", "model.estimator.max_epochs=3",
                   "data.targets=[E_X]", *FAST)
        with open(tmp_path / "out" / name / "model.pkl", "rb") as fh:
            fitted[name] = pickle.load(fh).estimators_
    assert fitted["clean"].keys() == fitted["poisoned"].keys()
    for target, est in fitted["clean"].items():
        other = fitted["poisoned"][target]
        assert est.validation_curve_ == other.validation_curve_
        for name, value in est.net_.state_dict().items():
            torch.testing.assert_close(value, other.net_.state_dict()[name], rtol=0, atol=0)
