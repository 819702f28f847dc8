"""EMD denoising: noise reduction, causality, streaming, PyEMD agreement, sklearn contract."""

import pickle

import numpy as np
import pandas as pd
import pytest
from PyEMD import EMD
from sklearn.frozen import FrozenEstimator
from sklearn.utils.estimator_checks import check_estimator

from thermocomp.core.compensator import Compensator
from thermocomp.core.denoise import EMDDenoiser, fit_denoiser, leading_imfs, remove_imfs
from thermocomp.core.denoise.emd import emd_engine
from thermocomp.core.models import MLR

SIGMA = 0.2  # °C, a noisy sensor


def _trend(n, dt=30.0):
    t = np.arange(n) * dt
    return 6 * (1 - np.exp(-t / 1.5e4)) + 0.8 * np.sin(2 * np.pi * t / 86400)


def _moving_average(x, w=61):
    return np.convolve(x, np.ones(w) / w, mode="valid")


def test_imf1_removal_lowers_noise_without_shifting_the_slow_trend():
    rng = np.random.default_rng(0)
    n = 3000
    trend = _trend(n)
    noise = SIGMA * rng.standard_normal(n)
    denoised = remove_imfs(trend + noise, n_imfs=1)
    err_raw, err_den = noise, denoised - trend
    # noise goes down: IMF-1 of white noise carries about half its variance
    assert np.std(err_den) < 0.8 * np.std(err_raw)
    # the slow trend is not shifted by more than the noise: the low-frequency part of the
    # error (1/2-hour moving average), anywhere in the record, stays far below sigma
    assert np.max(np.abs(_moving_average(err_den))) < SIGMA
    assert abs(np.mean(err_den)) < 0.1 * SIGMA
    # removing more IMFs removes more noise
    assert np.std(remove_imfs(trend + noise, n_imfs=2) - trend) < np.std(err_den)


def test_leading_imf_is_pyemd_sifting_with_the_same_stopping_rule():
    rng = np.random.default_rng(1)
    x = _trend(800) + 0.05 * rng.standard_normal(800)
    ours = leading_imfs(x, 1, emd_engine("fixed", 10), end_effect="mirror_extrema")
    ref = EMD(FIXE=10, MAX_ITERATION=11).emd(x, max_imf=1)[0]
    np.testing.assert_allclose(ours[0], ref, atol=1e-12)


def test_constant_or_short_signals_pass_through():
    np.testing.assert_array_equal(remove_imfs(np.full(50, 3.0)), np.full(50, 3.0))
    np.testing.assert_array_equal(remove_imfs(np.array([1.0, 2.0, 1.5])), [1.0, 2.0, 1.5])
    with pytest.raises(ValueError, match="NaN"):
        remove_imfs(np.array([1.0, np.nan, 2.0, 3.0, 1.0]))


def _frame(rng, n=600):
    trend = _trend(n)
    return pd.DataFrame({"T_a": 20 + trend + SIGMA * rng.standard_normal(n),
                         "T_b": 21 + 0.5 * trend + 0.01 * rng.standard_normal(n),
                         "S_door": (rng.random(n) < 0.2).astype(float)})


@pytest.mark.parametrize("causal", ["fir", "window"])
def test_causal_output_ignores_the_future_and_streaming_reproduces_it(causal):
    rng = np.random.default_rng(2)
    X = _frame(rng, 80 if causal == "window" else 600)
    den = EMDDenoiser(causal=causal, causal_window=24).fit(X)
    out = den.transform_causal(X)
    cut = len(X) // 2
    future_changed = X.copy()
    future_changed.iloc[cut:, :2] += rng.normal(0, 1.0, (len(X) - cut, 2))
    np.testing.assert_allclose(den.transform_causal(future_changed).iloc[:cut], out.iloc[:cut])
    state, rows = den.stream_init(), []
    for x in X.to_numpy():
        y, state = den.stream_step(x, state)
        rows.append(y)
    np.testing.assert_allclose(np.array(rows), out.to_numpy(), atol=1e-10)
    # the offline result does look ahead
    assert not np.allclose(den.transform(future_changed).iloc[:cut], den.transform(X).iloc[:cut])


def test_only_matching_sensors_are_denoised_and_causal_fir_is_closer_than_raw():
    rng = np.random.default_rng(3)
    X = _frame(rng)
    den = EMDDenoiser(sensors=["T_a"])
    off = den.fit_transform(X)
    assert list(den.denoised_) == [True, False, False]
    pd.testing.assert_series_equal(off["T_b"], X["T_b"])
    pd.testing.assert_series_equal(off["S_door"], X["S_door"])
    assert np.isclose(den.fir_[:, 0].sum(), 1.0)  # unit DC gain: offsets pass unchanged
    causal = den.transform_causal(X)["T_a"]
    assert np.std(causal - off["T_a"]) < np.std(X["T_a"] - off["T_a"])


def test_per_campaign_groups_are_denoised_separately():
    rng = np.random.default_rng(4)
    A, B = _frame(rng, 300), _frame(rng, 300) + 5.0
    X = pd.concat([A, B], ignore_index=True)
    groups = np.repeat(["A", "B"], 300)
    den = EMDDenoiser().fit(X, groups=groups)
    both = den.transform(X, groups=groups)
    np.testing.assert_allclose(both.iloc[300:].to_numpy(), den.transform(B).to_numpy())


def test_bad_parameters_are_refused():
    X = _frame(np.random.default_rng(5), 50)
    for kwargs in ({"n_imfs": 0}, {"stopping": "never"}, {"end_effect": "wrap"},
                   {"causal": "oracle"}, {"max_siftings": 0}):
        with pytest.raises(ValueError):
            EMDDenoiser(**kwargs).fit(X)


def test_sklearn_checks_except_the_two_a_time_series_filter_cannot_pass():
    # A filter's output for a sample depends on its neighbours in time: transforming a
    # subset, or the rows in another order, changes the result by design.
    expected = {"check_methods_subset_invariance": "time-series filter: needs the whole record",
                "check_methods_sample_order_invariance": "time-series filter: order is time"}
    check_estimator(EMDDenoiser(), expected_failed_checks=expected)


def _campaigns(rng, k=4, n=200):
    out = {}
    for i in range(k):
        X = _frame(rng, n)
        X.insert(0, "time", np.arange(n) * 30.0)
        X["E_Z"] = 3 * (X["T_a"] - X["T_a"].iloc[0]) + rng.normal(0, 0.1, n)
        out[f"K{i}"] = X
    return out


def test_compensator_denoises_before_stacking_and_round_trips_through_pickle():
    rng = np.random.default_rng(6)
    camps = _campaigns(rng)
    comp = Compensator(MLR(), denoiser=EMDDenoiser()).fit(camps)
    assert comp.denoiser_ is not None and comp.denoiser_ is not comp.denoiser
    again = pickle.loads(pickle.dumps(comp))
    pd.testing.assert_frame_equal(comp.predict(camps)["K1"], again.predict(camps)["K1"])
    offline = Compensator(MLR(), denoiser=EMDDenoiser(online=False)).fit(camps)
    assert not np.allclose(comp.predict(camps)["K1"], offline.predict(camps)["K1"])
    plain = Compensator(MLR()).fit(camps)
    assert not np.allclose(comp.estimators_["E_Z"].coef_, plain.estimators_["E_Z"].coef_)


def test_prefitted_denoiser_gives_the_same_model():
    """The `denoise` stage path (a fitted denoiser passed frozen) equals in-process denoising."""
    rng = np.random.default_rng(7)
    camps = _campaigns(rng)
    inputs = ["T_a", "T_b"]
    direct = Compensator(MLR(), inputs=inputs, denoiser=EMDDenoiser()).fit(camps)
    den, _ = fit_denoiser(EMDDenoiser(), camps, inputs)
    staged = Compensator(MLR(), inputs=inputs, denoiser=FrozenEstimator(den)).fit(camps)
    np.testing.assert_array_equal(direct.estimators_["E_Z"].coef_, staged.estimators_["E_Z"].coef_)
    np.testing.assert_array_equal(direct.denoiser_.fir_, staged.denoiser_.fir_)
    assert staged.denoiser_ is den          # used as fitted, not refitted
    with pytest.raises(ValueError, match="fitted on"):
        Compensator(MLR(), inputs=["T_a"], denoiser=FrozenEstimator(den)).fit(camps)
