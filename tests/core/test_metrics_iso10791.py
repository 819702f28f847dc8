"""ISO 10791-10 A.3 virtual test on long synthetic series with closed-form answers."""

import numpy as np
import pytest

from thermocomp.core.scoring import iso10791 as iso

H = 3600.0


def test_linear_drift_slot_errors_and_moving_ranges():
    a = 2.0 / H  # 2 µm/h
    t = np.arange(0, 40 * H + 1, 30.0)  # 30 s sampling, 40 h
    y = a * t
    res = 0.1 * y
    rel = iso.slot_errors(t, y, start_s=t[0])
    np.testing.assert_allclose(rel, 2.0 * np.arange(1, 16))  # slots 2..16: 2, 4, ... 30 µm
    out = iso.a3_campaign(t, y, res)
    assert out["available"]
    ft = out["first_test"]
    assert len(ft["before"]) == 15 and ft["slot_time_s"][0] == H and ft["slot_time_s"][-1] == 15 * H
    assert ft["range_before"] == pytest.approx(30.0) and ft["range_after"] == pytest.approx(3.0)
    mv = out["moving"]
    # a start at every sample up to 40 h - 15 h
    assert mv["n_starts"] == int(25 * H / 30.0) + 1
    assert mv["range_before_mean"] == pytest.approx(30.0) and mv["range_before_max"] == pytest.approx(30.0)
    assert mv["mean_reduction_pct"] == pytest.approx(90.0)
    assert mv["max_reduction_pct"] == pytest.approx(90.0)


def test_quadratic_error_range_grows_with_start_time():
    c = 0.05 / H**2  # µm/h²
    t = np.arange(0, 30 * H + 1, 60.0)
    y = c * t**2  # on a 1-min grid, slot times are samples: no interpolation error
    starts, ranges = iso.slot_ranges(t, y)
    want = c * ((starts + 15 * H) ** 2 - starts**2)
    np.testing.assert_allclose(ranges, want, rtol=1e-12)
    rep = iso.a3_report({"L": t}, {"L": y}, {"L": np.zeros_like(y)})
    s = rep["summary"]
    assert s["range_before_max"] == pytest.approx(c * (30 * H) ** 2 - c * (15 * H) ** 2)
    assert s["range_before_mean"] == pytest.approx(c * (30 * H * starts.mean() + 225 * H**2))
    assert s["range_after_max"] == 0.0 and s["max_reduction_pct"] == pytest.approx(100.0)
    assert "start_s" not in rep["per_campaign"]["L"]["moving"]  # curves dropped for JSON


def test_nonuniform_sampling_interpolates():
    rng = np.random.default_rng(0)
    t = np.sort(np.concatenate([[0.0, 16 * H], rng.uniform(0, 16 * H, 500)]))
    rel = iso.slot_errors(t, 3.0 * t / H + 1.0, start_s=0.5 * H)
    np.testing.assert_allclose(rel, 3.0 * np.arange(1, 16))


def test_short_campaigns_are_reported_not_invented():
    t = np.arange(0, 8 * H, 300.0)
    y = np.sin(t / H)
    out = iso.a3_campaign(t, y, y / 2)
    assert out == {"available": False, "reason": out["reason"]}
    assert "15 h" in out["reason"] and "7.9 h" in out["reason"]
    rep = iso.a3_report({"K1": t}, {"K1": y}, {"K1": y / 2})
    assert rep["summary"] is None and "no campaign" in rep["reason"]
    with pytest.raises(ValueError, match="does not cover"):
        iso.slot_errors(t, y, start_s=0.0)
    starts, ranges = iso.slot_ranges(t, y)
    assert starts.size == 0 and ranges.size == 0


def test_report_pools_long_and_skips_short_campaigns():
    t_long = np.arange(0, 20 * H + 1, 600.0)
    t_short = np.arange(0, 5 * H, 600.0)
    times = {"L": t_long, "S": t_short}
    meas = {"L": t_long / H, "S": t_short / H}
    res = {"L": 0.5 * t_long / H, "S": 0 * t_short}
    rep = iso.a3_report(times, meas, res)
    assert rep["per_campaign"]["S"]["available"] is False
    assert rep["summary"]["n_campaigns"] == 1
    assert rep["summary"]["range_before_mean"] == pytest.approx(15.0)
    assert rep["summary"]["range_after_mean"] == pytest.approx(7.5)
