"""E_P95 / E_max / E_mean curves and reductions (issue 5), against brute force and closed forms."""

import numpy as np
import pytest
from numpy.lib.stride_tricks import sliding_window_view

from thermocomp.core import metrics as M


def _brute(series, length, statistic):
    parts = []
    for s in series:
        if len(s) >= length:
            w = sliding_window_view(np.asarray(s, float), length)
            parts.append(np.ptp(w, axis=1) if statistic == "range" else w.std(axis=1))
    return np.concatenate(parts)


@pytest.mark.parametrize("statistic", ["range", "std"])
def test_window_curves_match_brute_force_on_pooled_series(statistic):
    rng = np.random.default_rng(7)
    # long enough (> 2048 windows) that the tail-only percentile path is taken
    series = [rng.normal(size=3000).cumsum(), rng.normal(size=700).cumsum(), rng.normal(size=50)]
    lengths = np.array([1, 2, 3, 16, 50, 51, 333, 700, 701, 2999, 3000, 3001])
    got = M.window_curves(series, lengths, statistic)
    for i, n in enumerate(lengths):
        if n > 3000:
            assert np.isnan(got["percentile"][i]) and np.isnan(got["max"][i])
            continue
        v = _brute(series, n, statistic)
        assert got["percentile"][i] == pytest.approx(np.percentile(v, 95), abs=1e-9)
        assert got["max"][i] == pytest.approx(v.max(), abs=1e-9)
        assert got["mean"][i] == pytest.approx(v.mean(), abs=1e-9)
    np.testing.assert_array_equal(M.e_p95(series, lengths, statistic), got["percentile"])
    np.testing.assert_array_equal(M.e_max(series, lengths, statistic), got["max"])
    np.testing.assert_array_equal(M.e_mean(series, lengths, statistic), got["mean"])


def test_percentile_is_exact_whatever_the_guess():
    rng = np.random.default_rng(1)
    v = rng.exponential(size=5001)
    want = np.percentile(v, 95)
    for guess in (None, -1.0, 0.5 * want, want, np.nextafter(want, np.inf), 10 * want):
        got, low = M._percentile(v.copy(), 95.0, guess)
        assert got == pytest.approx(want, rel=0, abs=1e-12)
        assert low <= got


def test_sine_sampled_at_its_peaks_closed_form():
    # x_k = A sin(2 pi k / P), P = 24 samples: every window of >= P samples holds both
    # peaks, so range = 2A exactly in every window -> E_P95 = E_max = E_mean = 2A; a
    # window of one period P has population sigma A / sqrt(2).
    A, P = 3.0, 24
    x = A * np.sin(2 * np.pi * np.arange(10 * P) / P)
    lengths = [P, P + 1, 3 * P, 10 * P]
    got = M.window_curves([x], lengths, "range")
    for key in ("percentile", "max", "mean"):
        np.testing.assert_allclose(got[key], 2 * A, rtol=1e-12)
    sd = M.window_curves([x], [P, 2 * P], "std")
    np.testing.assert_allclose(sd["max"], A / np.sqrt(2), rtol=1e-9)
    np.testing.assert_allclose(sd["mean"], A / np.sqrt(2), rtol=1e-9)


def test_e_mean_and_e_max_of_a_ramp_with_a_step():
    # ramp of slope s per sample, then flat: windows fully on the ramp have range s (n-1),
    # windows on the flat part 0, so E_max = s (n-1) and E_mean is the hand count.
    s = 2.0
    x = np.concatenate([s * np.arange(10), np.full(10, s * 9)])
    n = 3
    ranges = [np.ptp(x[i:i + n]) for i in range(len(x) - n + 1)]  # 8 of 4, one of 2, 9 of 0
    got = M.window_curves([x], [n], "range")
    assert got["max"][0] == pytest.approx(s * (n - 1))
    assert got["mean"][0] == pytest.approx((8 * 4 + 2 + 0) / 18)
    assert got["mean"][0] == pytest.approx(np.mean(ranges))


def test_reduction_pct_hand_values():
    assert M.reduction_pct(10.0, 2.5) == pytest.approx(75.0)
    assert M.reduction_pct(4.0, 6.0) == pytest.approx(-50.0)
    assert M.reduction_pct(0.0, 1.0) is None
    assert M.reduction_pct(None, 1.0) is None


def test_split_scores_new_keys():
    y = {"A": np.array([0.0, 2.0, 4.0]), "B": np.array([0.0, -2.0])}
    r = {"A": np.array([0.0, 1.0, -1.0]), "B": np.array([0.0, 1.0])}
    s = M.split_scores(y, r, sample_period_s=60.0)
    assert s["p2p_reduction_pct"] == pytest.approx(100 * (1 - 2 / 6))
    assert s["rms_reduction_pct"] == pytest.approx(100 * (1 - np.sqrt(3 / 24)))
    a = s["per_campaign"]["A"]
    assert a["p2p_reduction_pct"] == pytest.approx(50.0)   # 4 -> 2
    assert a["rms_reduction_pct"] == pytest.approx(100 * (1 - np.sqrt(2 / 20)))
    for key in ("e_p95", "e_max", "e_mean"):
        assert s[key]["window_s"] == [60.0, 120.0] and s[key]["statistic"] == "range"
    # length 2 windows of measured A, B: ranges 2, 2, 2 -> max 2, mean 2
    assert s["e_max"]["before"][0] == pytest.approx(2.0)
    # length 3: only A, range 4
    assert s["e_mean"]["before"][1] == pytest.approx(4.0)
    # residual, length 2: |1-0|, |-1-1|, |1-0| -> 1, 2, 1
    assert s["e_mean"]["after"][0] == pytest.approx(4 / 3)
    assert s["e_max"]["after"][0] == pytest.approx(2.0)
