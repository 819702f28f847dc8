"""LSTM on input windows: sklearn API, determinism, early stopping, streaming."""

import pickle

import numpy as np
import pytest
import torch
from sklearn.utils.estimator_checks import check_estimator

from conftest import ctx, stream_predictions
from thermocomp.errors import ParameterError
from thermocomp.models import LSTM
from thermocomp.models._dynamics import free_run

WINDOW_CHECKS = {
    "check_methods_sample_order_invariance": "a window of preceding rows feeds each prediction",
    "check_methods_subset_invariance": "a window of preceding rows feeds each prediction",
}


def lagged_data(n_campaigns=8, n=60, p=4, seed=0):
    """The error lags the temperatures (first order): a static map cannot follow it."""
    rng = np.random.default_rng(seed)
    X, y, g = [], [], []
    for c in range(n_campaigns):
        T = np.cumsum(rng.normal(0, 0.3, (n, p)), axis=0)
        T -= T[0]
        X.append(T)
        y.append(free_run(0.7, 0.3 * (2 * T[:, 0] - T[:, 2]), None) + rng.normal(0, 0.02, n))
        g.extend([c] * n)
    return np.vstack(X), np.concatenate(y), np.array(g)


def quick(**kw):
    return LSTM(**{"window": 8, "hidden_size": 16, "max_epochs": 60, "patience": 10,
                   "batch_size": 32, "learning_rate": 1e-2, **kw})


def test_lstm_passes_sklearn_checks_but_the_documented_window_ones():
    check_estimator(LSTM(window=3, hidden_size=4, max_epochs=3), expected_failed_checks=WINDOW_CHECKS)


def test_lstm_learns_dynamics_deterministically_and_leaves_torch_globals_alone():
    X, y, g = lagged_data()
    train, test = g < 6, g >= 6
    torch.manual_seed(123)
    before_rng, before_threads = torch.get_rng_state(), torch.get_num_threads()
    a = quick().fit(X[train], y[train], context=ctx(g[train]))
    assert torch.equal(torch.get_rng_state(), before_rng) and torch.get_num_threads() == before_threads
    b = quick().fit(X[train], y[train], context=ctx(g[train]))
    pred = a.predict(X[test], context=ctx(g[test]))
    np.testing.assert_array_equal(pred, b.predict(X[test], context=ctx(g[test])))
    rmse = np.sqrt(np.mean((y[test] - pred) ** 2))
    assert rmse < 0.5 * y[test].std(), (rmse, y[test].std())
    # early stopping kept the best validation epoch
    assert a.best_epoch_ == int(np.argmin(a.validation_curve_)) + 1
    assert a.n_epochs_ == len(a.loss_curve_) <= 60
    assert quick(random_state=1).fit(X[train], y[train], context=ctx(g[train])).predict(X[test]).tolist() \
        != a.predict(X[test]).tolist()


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


def test_windows_never_cross_campaigns():
    X, y, g = lagged_data(n_campaigns=2)
    est = quick(max_epochs=3).fit(X, y, context=ctx(g))
    second = g == 1
    np.testing.assert_allclose(est.predict(X, context=ctx(g))[second], est.predict(X[second]), atol=1e-12)


@pytest.mark.parametrize("bad", [{"window": 0}, {"validation_fraction": 1.0}, {"max_epochs": 0}])
def test_bad_hyperparameters_are_config_errors(bad):
    X, y, g = lagged_data(n_campaigns=2, n=10)
    with pytest.raises(ParameterError):
        LSTM(**bad).fit(X, y, context=ctx(g))
