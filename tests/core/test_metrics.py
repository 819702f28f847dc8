import numpy as np
import pytest

from thermocomp.core import metrics as M


def test_rsd_is_not_mean_centred_and_uses_n_minus_1():
    r = np.array([1.0, 1.0, 1.0, 1.0])
    assert M.rsd(r) == pytest.approx(np.sqrt(4 / 3))
    assert M.rmse(r) == pytest.approx(1.0)


def test_p2p_rms_hand_values():
    x = np.array([3.0, -1.0, 2.0, 0.0])
    assert M.p2p(x) == 4.0
    assert M.rms(x) == pytest.approx(np.sqrt((9 + 1 + 4 + 0) / 4))


def test_sm_sd_single_campaign_has_no_sd():
    assert M.sm_sd([2.0]) == (2.0, None)
    sm, sd = M.sm_sd([1.0, 3.0])
    assert sm == 2.0 and sd == pytest.approx(np.sqrt(2.0))


def test_e_p95_range_of_a_ramp_is_slope_times_window():
    slope, dt = 0.5, 30.0  # µm/s, s
    x = slope * dt * np.arange(400)
    lengths = np.array([2, 3, 17, 100, 400])
    got = M.e_p95([x], lengths, "range")
    np.testing.assert_allclose(got, slope * dt * (lengths - 1))


def test_e_p95_std_of_a_ramp_closed_form():
    step = 0.2
    x = step * np.arange(300)
    lengths = np.array([2, 5, 50, 300])
    got = M.e_p95([x], lengths, "std")
    np.testing.assert_allclose(got, step * np.sqrt((lengths**2 - 1) / 12), rtol=1e-7)


def test_window_statistic_matches_brute_force():
    rng = np.random.default_rng(3)
    x = rng.normal(size=97).cumsum()
    for n in (1, 2, 7, 32, 33, 64, 97):
        brute = np.array([np.ptp(x[i:i + n]) for i in range(len(x) - n + 1)])
        np.testing.assert_allclose(M.window_statistic(x, n, "range"), brute)
        brute_sd = np.array([np.std(x[i:i + n]) for i in range(len(x) - n + 1)])
        np.testing.assert_allclose(M.window_statistic(x, n, "std"), brute_sd, atol=1e-6)


def test_e_p95_pools_campaigns_and_skips_too_long_windows():
    a = np.arange(10.0)
    b = np.zeros(5)
    got = M.e_p95([a, b], [2, 10, 11], "range")
    # length 2: 9 windows of range 1 and 4 of range 0 -> 95th percentile is 1
    assert got[0] == pytest.approx(1.0)
    assert got[1] == pytest.approx(9.0)  # only a is long enough
    assert np.isnan(got[2])


def test_split_scores_layout_and_values():
    y = {"A": np.array([0.0, 2.0, 4.0]), "B": np.array([0.0, -2.0])}
    r = {"A": np.array([0.0, 1.0, -1.0]), "B": np.array([0.0, 1.0])}
    s = M.split_scores(y, r, sample_period_s=60.0)
    assert s["rmse"] == pytest.approx(np.sqrt(3 / 5))
    assert s["mae"] == pytest.approx(3 / 5)                 # |0|+|1|+|-1|+|0|+|1| over 5
    assert s["per_campaign"]["A"]["mae"] == pytest.approx(2 / 3)
    assert M.split_scores(y, r, 60.0, with_before_after=False)["mae"] == pytest.approx(3 / 5)
    assert s["rms_before"] == pytest.approx(np.sqrt(24 / 5))
    assert s["p2p_before"] == 6.0 and s["p2p_after"] == 2.0
    assert s["rsd_mean"] == pytest.approx((1.0 + 1.0) / 2)
    assert s["per_campaign"]["B"]["p2p_before"] == 2.0
    assert s["e_p95"]["window_s"] == [60.0, 120.0]
    assert s["e_p95"]["before"][1] == pytest.approx(4.0)


@pytest.mark.parametrize("target, unit", [("E_Z", "µm"), ("E_XX1", "µm"), ("E_AZ1", "µm/m"),
                                          ("E_CZY1", "µm/m"), ("E_BX", "µm/m"), ("E_Amp", "µm")])
def test_an_angular_error_is_in_um_per_m(target, unit):
    assert M.unit(target) == unit


def test_the_result_table_gives_the_unit_of_angular_targets():
    from thermocomp.core.scoring.results import EvaluationResult

    block = {"rsd_mean": 1.0, "rsd_sd": 0.5, "rms_before": 4.0, "rms_after": 1.0, "rmse": 1.0}
    table = {"model": "mlr", "mode": "simulation", "targets": {}}
    table["targets"]["E_X"] = {"test": dict(block)}
    assert EvaluationResult(table).summary().splitlines()[1].endswith("(µm)")
    table["targets"]["E_AZ"] = {"test": dict(block)}
    assert EvaluationResult(table).summary().splitlines()[1].endswith("(µm; E_AZ in µm/m)")
