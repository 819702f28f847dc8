"""LagBank: inputs through a bank of first-order lags, ridge penalty chosen by time-series CV."""

from __future__ import annotations

import pickle

import numpy as np
import pandas as pd
import pytest
import sklearn
from sklearn.linear_model import RidgeCV
from sklearn.model_selection import GroupKFold
from sklearn.preprocessing import StandardScaler
from sklearn.utils.estimator_checks import check_estimator

from conftest import FAST, poisoned_copy, stream_context, thermocomp
from thermocomp.base.errors import ParameterError
from thermocomp.core.models import MLR, LagBank
from thermocomp.core.models._dynamics import first_order_lags
from thermocomp.core.models.lagbank import ForwardChaining, default_splitter, forward_gap, ridge_path_cv

ORDER_CHECKS = {"check_methods_sample_order_invariance": "depends on earlier rows by design",
                "check_methods_subset_invariance": "depends on earlier rows by design"}
NOISE_UM = 0.1
TAU_TRUE_S = 3600.0


def _lagged_system(seed=0, n_campaigns=8, n=240, dt=60.0, jitter=0.5, drift_um=0.0):
    """``y = 3 L_3600[x0] + noise`` (x1 is a distractor), irregular sampling, inputs referenced
    to each campaign's first sample; ``drift_um`` adds an unmeasured random walk to y."""
    rng = np.random.default_rng(seed)
    groups = np.repeat([f"C{i}" for i in range(n_campaigns)], n)
    steps = rng.uniform(1 - jitter, 1 + jitter, (n_campaigns, n)) * dt
    steps[:, 0] = 0.0
    time = np.cumsum(steps, axis=1).ravel()
    X = np.cumsum(rng.normal(0, 0.3, (n_campaigns, n, 2)), axis=1)
    X = (X - X[:, :1]).reshape(-1, 2)
    y = 3.0 * first_order_lags(X[:, 0], time, groups, [TAU_TRUE_S])[:, 0]
    if drift_um:
        walk = np.cumsum(rng.normal(0, drift_um, (n_campaigns, n)), axis=1)
        y += (walk - walk[:, :1]).ravel()
    y += rng.normal(0, NOISE_UM, len(y))
    return X, y, pd.DataFrame({"campaign": groups, "time": time})


def _split(context, n_train):
    train = context["campaign"].isin([f"C{i}" for i in range(n_train)]).to_numpy()
    return train, context[train].reset_index(drop=True), context[~train].reset_index(drop=True)


def _rmse(a, b):
    return float(np.sqrt(np.mean((np.asarray(a) - np.asarray(b)) ** 2)))


@pytest.mark.parametrize("ar", [False, True])
def test_check_estimator_with_metadata_routing_on(ar):
    with sklearn.config_context(enable_metadata_routing=True):
        check_estimator(LagBank(n_taus=3, ar=ar), expected_failed_checks=ORDER_CHECKS)
        routing = LagBank().get_metadata_routing()
        for method in ("fit", "predict", "score"):
            assert routing.consumes(method, ["context"]) == {"context"}


@pytest.mark.parametrize("ar", [False, True])
def test_stream_equals_batch_over_campaigns_with_irregular_time(ar):
    X, y, context = _lagged_system(seed=1, drift_um=0.05)
    train, c_train, c_test = _split(context, 5)
    est = LagBank(ar=ar).fit(X[train], y[train], context=c_train)
    assert est.context_columns_ == ["time"]
    assert (est.ar_coef_ != 0.0) == ar
    batch = est.predict(X[~train], context=c_test)
    np.testing.assert_allclose(stream_context(est, X[~train], c_test), batch, rtol=0, atol=1e-9)
    again = pickle.loads(pickle.dumps(est))   # deployable: the pickled model streams the same
    np.testing.assert_allclose(stream_context(again, X[~train], c_test), batch, rtol=0, atol=1e-9)


def test_without_time_samples_are_sample_period_apart_in_batch_andstream_context():
    X, y, context = _lagged_system(seed=2, jitter=0.0)
    groups = context[["campaign"]]
    est = LagBank(sample_period_s=60.0).fit(X, y, context=groups)
    assert est.context_columns_ == [] and est.sample_period_s_ == 60.0
    with_time = LagBank(sample_period_s=1.0).fit(X, y, context=context)   # period read from time
    assert with_time.sample_period_s_ == pytest.approx(60.0)
    np.testing.assert_allclose(est.predict(X, context=groups), with_time.predict(X, context=context),
                               atol=1e-9)
    np.testing.assert_allclose(stream_context(est, X, groups), est.predict(X, context=groups), atol=1e-9)


def test_stream_with_its_first_time_missing_steps_as_the_complete_record():
    # the stream's time rule (core/timerule.py) in the estimator's own streaming: a logger's
    # first cell blank and its clock at 150000 s; the lag bank's own rule had taken the first
    # sample as 0 s and thrown every lag state 150000 s ahead at the second
    X, y, context = _lagged_system(seed=4, n_campaigns=3, jitter=0.0)
    est = LagBank(ar=True).fit(X, y, context=context)
    one = context[context["campaign"] == "C2"].reset_index(drop=True)
    rows = np.flatnonzero(context["campaign"] == "C2")
    logger = one.assign(time=one["time"] + 150000.0)
    complete = stream_context(est, X[rows], logger)
    logger.loc[0, "time"] = np.nan
    np.testing.assert_allclose(stream_context(est, X[rows], logger), complete, rtol=0, atol=1e-9)


def test_a_stream_state_saved_before_the_time_rule_goes_on():
    # an end state pickled with its last time ('t', no clock) streams on as it did
    X, y, context = _lagged_system(seed=5, n_campaigns=2, jitter=0.0)
    est = LagBank().fit(X, y, context=context)
    state = est.stream_init()
    for i in range(3):
        state = est.stream_step(X[i], state, {"time": 60.0 * i})[1]
    old = {"z": state["z"], "t": 120.0, "y_prev": state["y_prev"]}
    for i in range(3, 6):
        y_new, state = est.stream_step(X[i], state, {"time": 60.0 * i})
        y_old, old = est.stream_step(X[i], old, {"time": 60.0 * i})
        assert y_old == y_new


@pytest.mark.parametrize("ar", [False, True])
def test_predictions_are_causal(ar):
    X, y, context = _lagged_system(seed=3, n_campaigns=4)
    est = LagBank(ar=ar).fit(X, y, context=context)
    t0 = 500   # inside the third campaign
    changed = X.copy()
    changed[t0:] += 5.0
    before, after = est.predict(X, context=context), est.predict(changed, context=context)
    np.testing.assert_array_equal(after[:t0], before[:t0])
    assert np.all(after[t0:720] != before[t0:720])   # ... the rest of that campaign does change


def test_recovers_a_lagged_system_far_better_than_a_static_model_on_held_out_campaigns():
    X, y, context = _lagged_system(seed=4)
    train, c_train, c_test = _split(context, 5)
    lag = LagBank().fit(X[train], y[train], context=c_train)
    mlr = MLR().fit(X[train], y[train])
    rmse_lag = _rmse(lag.predict(X[~train], context=c_test), y[~train])
    rmse_mlr = _rmse(mlr.predict(X[~train]), y[~train])
    assert rmse_lag < 0.25 * rmse_mlr
    assert rmse_lag < 2 * NOISE_UM   # close to the noise floor, although 3600 s is off the grid
    assert not np.any(np.isclose(lag.taus_, TAU_TRUE_S, rtol=0.05))


@pytest.mark.parametrize("ar", [True, "auto"])
def test_one_step_mode_uses_the_measured_previous_error(ar):
    """An unmeasured drift: free run cannot follow it, one-step prediction (the measured previous
    error an input, design and penalty chosen on the one-step CV error) can."""
    X, y, context = _lagged_system(seed=5, drift_um=0.2)
    train, c_train, c_test = _split(context, 5)
    est = LagBank(ar=ar).fit(X[train], y[train], context=c_train)
    table = est.cv_results_
    assert np.isinf(table.loc[table["design"] == "increments", "cv_mse_free_run"]).all()
    candidates = table[table["design"] != "lags"]
    pick = candidates.loc[candidates["cv_mse_one_step"].idxmin()]
    assert (est.one_step_design_, est.alpha_one_step_) == (pick["design"], pick["alpha"])
    assert 0.0 < est.ar_coef_one_step_ <= 1.0 and not table.loc[table["chosen"], "design"].eq(
        "increments").any()
    free = est.predict(X[~train], context=c_test)
    one_step = est.predict(X[~train], context=c_test.assign(y_measured=y[~train]))
    assert _rmse(one_step, y[~train]) < 0.5 * _rmse(free, y[~train])
    static = LagBank(ar=False).fit(X[train], y[train], context=c_train)   # no AR: modes coincide
    np.testing.assert_array_equal(static.predict(X[~train], context=c_test.assign(y_measured=y[~train])),
                                  static.predict(X[~train], context=c_test))


def test_ar_auto_decides_on_the_free_run_cv_error():
    X, y, context = _lagged_system(seed=6, n_campaigns=6)
    est = LagBank(ar="auto").fit(X, y, context=context)
    table = est.cv_results_
    assert set(table["ar"]) == {False, True}
    best = table.loc[table["cv_mse_free_run"].idxmin()]
    chosen = table[table["chosen"]].iloc[0]
    assert chosen["ar"] == best["ar"] and est.alpha_ == chosen["alpha"]
    assert (est.ar_coef_ != 0.0) == bool(chosen["ar"])


def test_cv_path_matches_scikit_learn_ridgecv_with_the_same_splits():
    X, y, context = _lagged_system(seed=7, n_campaigns=5, n=120)
    groups = context["campaign"].to_numpy()
    est = LagBank(n_taus=4, alphas=np.logspace(-3, 4, 8)).fit(X, y, context=context)
    Z = StandardScaler().fit_transform(est._features(X, context))
    splits = list(GroupKFold(5).split(Z, y, groups))
    ours = ridge_path_cv(Z, y, splits, est.alphas)["one_step"].mean(axis=0)
    ref = RidgeCV(alphas=est.alphas, cv=splits, scoring="neg_mean_squared_error").fit(Z, y)
    assert est.alpha_ == ref.alpha_
    np.testing.assert_allclose(ours.min(), -ref.best_score_, rtol=1e-8)


def _ridge_with_level_penalty(Z, y, alpha, levels, ratio):
    """Reference: solve (Z_c^T Z_c + alpha D) w = Z_c^T y_c, D = ratio on the levels, 1 elsewhere."""
    mean, y_mean = Z.mean(axis=0), y.mean()
    Zc = Z - mean
    D = np.ones(Z.shape[1])
    D[:levels] = ratio
    w = np.linalg.solve(Zc.T @ Zc + alpha * np.diag(D), Zc.T @ (y - y_mean))
    return w, y_mean - mean @ w


def test_cv_path_leaves_the_free_columns_unpenalised():
    X, y, context = _lagged_system(seed=7, n_campaigns=4, n=80)
    Z = StandardScaler().fit_transform(LagBank(n_taus=3).fit(X, y, context=context)._features(X, context))
    splits = list(GroupKFold(4).split(Z, y, context["campaign"]))
    alphas = np.array([0.1, 1e3, 1e7])
    ours = ridge_path_cv(Z, y, splits, alphas, free_columns=2)["one_step"]
    for f, (tr, va) in enumerate(splits):
        for i, alpha in enumerate(alphas):
            w, c = _ridge_with_level_penalty(Z[tr], y[tr], alpha, 2, 0.0)
            np.testing.assert_allclose(ours[f, i], np.mean((Z[va] @ w + c - y[va]) ** 2), rtol=1e-6)


@pytest.mark.parametrize("ratio", [0.0, 0.01])
def test_level_penalty_is_that_share_of_the_penalty_on_the_levels(ratio):
    X, y, context = _lagged_system(seed=3, n_campaigns=4, n=80)
    est = LagBank(n_taus=3, alphas=[30.0], level_penalty=ratio).fit(X, y, context=context)
    scaler = StandardScaler().fit(est._features(X, context))
    w, c = _ridge_with_level_penalty(scaler.transform(est._features(X, context)), y, 30.0, 2, ratio)
    np.testing.assert_allclose(est.coef_, w / scaler.scale_, rtol=1e-6, atol=1e-9)
    np.testing.assert_allclose(est.intercept_, c - scaler.mean_ @ (w / scaler.scale_), atol=1e-9)
    assert est.chosen_params()["level_penalty"] == [ratio]


def test_with_free_levels_the_strongest_penalty_leaves_the_static_model_not_a_constant():
    """large_mill_week (session 50): forward chaining on its one training week picked the grid's
    strongest penalty, which shrinks the levels too -- E_X 7.5 µm against MLR's 2.0."""
    X, y, context = _lagged_system(seed=5, n_campaigns=3)
    mlr = MLR().fit(X, y)
    free = LagBank(alphas=[1e9], level_penalty=0.0).fit(X, y, context=context)
    np.testing.assert_allclose(free.predict(X, context=context), mlr.predict(X), atol=1e-3 * np.std(y))
    shrunk = LagBank(alphas=[1e9]).fit(X, y, context=context)          # the default shrinks all
    assert np.std(shrunk.predict(X, context=context)) < 1e-3 * np.std(mlr.predict(X))
    both = LagBank(level_penalty=[1.0, 0.0]).fit(X, y, context=context)  # the CV chooses
    assert set(both.cv_results_["level_penalty"]) == {0.0, 1.0}
    assert both.level_penalty_ == both.cv_results_.loc[both.cv_results_["chosen"], "level_penalty"].item()


def test_splitters_leave_campaigns_out_or_chain_forward_with_a_gap():
    groups = np.repeat(["A", "B", "C"], 10)
    cv = default_splitter(groups, 30, gap=4)
    for train, valid in cv.split(np.zeros((30, 1)), None, groups):
        assert not set(groups[train]) & set(groups[valid])
    one = default_splitter(np.repeat(["A"], 120), 120, gap=7)
    assert isinstance(one, ForwardChaining) and one.get_n_splits() == 5
    folds = list(one.split(np.zeros((120, 1)), None, None))
    assert len(folds) == 5 and folds[-1][1].max() == 119
    for train, valid in folds:   # validation blocks tile the second half, training precedes them
        assert valid.min() >= 60 and train.min() == 0 and train.max() + 8 == valid.min()
    # the gap is the longest lag in samples, capped at half a validation block
    assert forward_gap(10.2, 1200, 5) == 11
    assert forward_gap(2880, 1200, 5) == (1200 // 2) // 5 // 2


def test_single_record_uses_forward_chaining_with_the_capped_gap():
    X, y, context = _lagged_system(seed=8, n_campaigns=1, n=600, jitter=0.0)
    est = LagBank(tau_max_s=1200.0).fit(X, y, context=context)   # 20 samples of memory
    assert isinstance(est.splitter_, ForwardChaining) and est.gap_ == 20
    est = LagBank().fit(X, y, context=context)                   # 2 days: capped
    assert est.gap_ == (600 // 2) // 5 // 2
    est = LagBank().fit(X, y, context=context.assign(campaign=np.repeat(["A", "B"], 300)))
    assert isinstance(est.splitter_, GroupKFold) and est.gap_ == 0


@pytest.mark.parametrize("params", [
    {"ar": "yes"}, {"ar": 1}, {"n_taus": 0}, {"n_taus": 2.5}, {"n_splits": 1},
    {"tau_max_s": -1.0}, {"tau_min_s": 0.0}, {"tau_min_s": 10.0, "tau_max_s": 5.0},
    {"alphas": [1.0, -1.0]}, {"alphas": []}, {"sample_period_s": 0.0}, {"level_penalty": -1.0},
    {"level_penalty": []},
])
def test_bad_parameters_raise_parameter_error(params):
    X, y, context = _lagged_system(seed=9, n_campaigns=2, n=30)
    with pytest.raises(ParameterError):
        LagBank(**params).fit(X, y, context=context)


@pytest.fixture(scope="session")
def small_data(short_dataset, tmp_path_factory):
    """9 short campaigns (6 train, 3 test) and a copy whose test campaigns' errors are poisoned."""
    root = tmp_path_factory.mktemp("lagbank")
    return root, short_dataset, poisoned_copy(short_dataset, root / "poisoned")


@pytest.mark.slow
def test_the_test_split_does_not_choose_the_penalty_through_the_cli(small_data):
    root, clean, poisoned = small_data
    fitted = {}
    for name, path in (("clean", clean), ("poisoned", poisoned)):
        thermocomp("run", f"data.path={path}", f"out={root / 'out' / name}", "model=lagbank", *FAST)
        with open(root / "out" / name / "model.pkl", "rb") as fh:
            fitted[name] = pickle.load(fh)
    clean_est, poisoned_est = fitted["clean"].estimators_, fitted["poisoned"].estimators_
    assert clean_est.keys() == poisoned_est.keys()
    for target, est in clean_est.items():
        assert est.alpha_ == poisoned_est[target].alpha_
        np.testing.assert_array_equal(est.coef_, poisoned_est[target].coef_)
