"""ARX: selection by information criteria, free-run vs one-step prediction, streaming."""

import pickle

import numpy as np
import pandas as pd
import pytest
from sklearn.utils.estimator_checks import check_estimator

from conftest import ctx, stream_predictions
from thermocomp.base.errors import ParameterError
from thermocomp.core.compensator import Compensator
from thermocomp.core.models import ARX

DYNAMIC_CHECKS = {
    "check_methods_sample_order_invariance": "an AR term / delays make predictions depend on row order",
    "check_methods_subset_invariance": "an AR term / delays make predictions depend on earlier rows",
}


def arx_data(a, n_campaigns=6, n=200, p=8, delay=0, noise=0.05, seed=0):
    """Random-walk temperatures; truth y(t) = a*y(t-1) + (1-a)*(2*T1(t-delay) - T4(t)) + e(t)."""
    rng = np.random.default_rng(seed)
    X, y, groups = [], [], []
    for c in range(n_campaigns):
        T = np.cumsum(rng.normal(0, 0.1, (n, p)), axis=0)
        T -= T[0]
        T1_lag = T[np.maximum(np.arange(n) - delay, 0), 1]
        u = (1 - a) * (2.0 * T1_lag - 1.0 * T[:, 4])
        out, prev = np.empty(n), 0.0
        for t in range(n):
            out[t] = prev = a * prev + u[t] + rng.normal(0, noise)
        X.append(T), y.append(out), groups.extend([f"K{c}"] * n)
    return np.vstack(X), np.concatenate(y), np.array(groups)


def test_arx_passes_sklearn_checks():
    check_estimator(ARX())


def test_arx_with_ar_and_delays_passes_all_but_documented_order_checks():
    check_estimator(ARX(ar=True, delays=(0, 2)), expected_failed_checks=DYNAMIC_CHECKS)


@pytest.mark.parametrize("selection_error", ["simulation", "equation"])
def test_arx_selects_the_ar_term_only_when_the_truth_has_one(selection_error):
    X, y, g = arx_data(a=0.9)
    dyn = ARX(selection_error=selection_error).fit(X, y, context=ctx(g))
    assert dyn.chosen_["ar"] is True
    assert dyn.ar_coef_ == pytest.approx(0.9, abs=0.03)
    assert sorted(dyn.inputs_[:2]) == ["x1", "x4"]

    X, y, g = arx_data(a=0.0, seed=1)
    static = ARX(selection_error=selection_error).fit(X, y, context=ctx(g))
    assert static.chosen_["ar"] is False and static.ar_coef_ == 0.0
    assert {"x1", "x4"} <= set(static.inputs_)
    np.testing.assert_allclose(static.coef_[[static.inputs_.index("x1"), static.inputs_.index("x4")]],
                               [2.0, -1.0], atol=0.05)
    # the table says why: every (n_inputs, ar) model with its criterion, one winner
    table = static.selection_
    assert table["chosen"].sum() == 1
    assert set(table["ar"]) == {True, False}
    assert table.loc[table["chosen"], "bicc"].item() == table["bicc"].min()
    assert "without AR term" in static.chosen_["reason"]


def test_arx_finds_the_input_delay():
    X, y, g = arx_data(a=0.0, delay=3, seed=6)
    est = ARX(delays=(0, 1, 2, 3, 4, 5)).fit(X, y, context=ctx(g))
    assert "x1[t-3]" in est.inputs_
    assert not any(name.startswith("x1") and name != "x1[t-3]" for name in est.inputs_)


def test_simulation_free_runs_and_one_step_uses_the_measured_error():
    X, y, g = arx_data(a=0.9, seed=7)
    est = ARX(ar=True).fit(X, y, context=ctx(g))
    a, u = est.ar_coef_, est._exogenous(X, g)
    sim = est.predict(X, context=ctx(g))
    one = est.predict(X, context=ctx(g, y_measured=y))
    starts = np.flatnonzero(np.r_[True, g[1:] != g[:-1]])
    # campaign starts: previous error is 0 in both modes (nothing crosses campaigns)
    np.testing.assert_allclose(sim[starts], u[starts])
    np.testing.assert_allclose(one[starts], u[starts])
    inner = np.setdiff1d(np.arange(len(y)), starts)
    np.testing.assert_allclose(sim[inner], a * sim[inner - 1] + u[inner])
    np.testing.assert_allclose(one[inner], a * y[inner - 1] + u[inner])
    assert np.sqrt(np.mean((y - one) ** 2)) < np.sqrt(np.mean((y - sim) ** 2))
    # a gap in the measurement falls back on the model's own previous estimate
    y_gap = y.copy()
    y_gap[50] = np.nan
    gap = est.predict(X, context=ctx(g, y_measured=y_gap))
    assert gap[51] == pytest.approx(a * gap[50] + u[51])
    np.testing.assert_allclose(np.delete(gap, 51), np.delete(one, 51))


def test_streaming_reproduces_simulation_predict():
    X, y, g = arx_data(a=0.9, n_campaigns=3, seed=8)
    est = ARX(ar=True, delays=(0, 2)).fit(X, y, context=ctx(g))
    batch = est.predict(X, context=ctx(g))
    stream = stream_predictions(est, X, g)
    np.testing.assert_allclose(stream, batch, rtol=0, atol=1e-9)


def test_pickle_round_trip_identical_predictions():
    X, y, g = arx_data(a=0.9, n_campaigns=3, seed=9)
    est = ARX().fit(X, y, context=ctx(g))
    again = pickle.loads(pickle.dumps(est))
    np.testing.assert_array_equal(est.predict(X, context=ctx(g)), again.predict(X, context=ctx(g)))
    np.testing.assert_array_equal(est.predict(X, context=ctx(g, y_measured=y)),
                                  again.predict(X, context=ctx(g, y_measured=y)))


def test_compensator_one_step_mode_is_the_law_over_the_arx_simulation():
    X, y, g = arx_data(a=0.9, n_campaigns=4, p=5, seed=10)
    names = ["T_a", "T_b", "T_c", "T_d", "T_e"]
    camps = {}
    for cid in np.unique(g):
        rows = g == cid
        camps[cid] = pd.DataFrame({"time": np.arange(rows.sum()) * 60.0,
                                   **{name: X[rows, j] for j, name in enumerate(names)}, "E_Z": y[rows]})
    comp = Compensator(ARX()).fit(camps)
    est, law = comp.estimators_["E_Z"], comp.one_step_["E_Z"]
    assert est.chosen_["ar"] is True and comp.selected_["E_Z"] == names
    sim, one = comp.predict(camps), comp.predict(camps, mode="one_step")
    meas = comp.measured(camps)
    for cid in camps:
        Xc = camps[cid][names].to_numpy()
        s = est.predict(Xc)
        np.testing.assert_allclose(sim[cid]["E_Z"], s)
        y_c = meas[cid]["E_Z"].to_numpy()
        np.testing.assert_allclose(one[cid]["E_Z"], law.predict(s[:, None], context=ctx(y_measured=y_c)))
        # the law: persistence, the simulated change, the model's miss; the simulation at the start
        np.testing.assert_allclose(one[cid]["E_Z"].to_numpy()[1:],
                                   y_c[:-1] + law.k_ * np.diff(s) - law.g_ * (y_c[:-1] - s[:-1]))
        assert one[cid]["E_Z"].iloc[0] == pytest.approx(s[0])
    y_all = np.concatenate([meas[c]["E_Z"] for c in camps])
    assert np.sqrt(np.mean((y_all - np.concatenate([one[c]["E_Z"] for c in camps])) ** 2)) < \
        np.sqrt(np.mean((y_all - np.concatenate([sim[c]["E_Z"] for c in camps])) ** 2))


@pytest.mark.parametrize("bad", [{"criterion": "hqic"}, {"ar": "maybe"}, {"search": "random"},
                                 {"max_inputs": 0}, {"delays": [-1]}])
def test_bad_hyperparameters_are_config_errors(bad):
    X, y, g = arx_data(a=0.0, n_campaigns=1, n=30)
    with pytest.raises(ParameterError):
        ARX(**bad).fit(X, y, context=ctx(g))
