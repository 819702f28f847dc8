"""A lag from the initial thermal state is taken only where its gain holds within the campaigns
or across their means on its own (diag92c; ``benchmarks/bench_diag92c.py``).

The transient ``1 - exp(-t/tau)`` is near a constant per campaign, so a start lag can fit the held-out
campaigns' offsets; the pooled test blocks then count one campaign's offset many times.
"""

from __future__ import annotations

from test_diagnose_few import few
from thermocomp.apps.diagnose import SearchOptions, diagnose
from thermocomp.core.compensator import Compensator
from thermocomp.core.models import MLR


def _diagnosis(seed: int):
    ds, _ = few("axis_position", seed)
    assert len(ds.ids("train")) == 8
    return diagnose(ds, Compensator(MLR()), options=SearchOptions(max_effects=2))


def _start_lags(j: dict) -> list:
    return [e for e in j["effects"] if e["kind"] == "dynamics" and "p_value_within" in e["evidence"]]


def test_a_start_lag_gaining_in_the_campaigns_offsets_is_refused_and_a_held_one_kept():
    # planted 8969 E_X: T_bearing_f1's 7200 s start lag gains ~25 % in CV, ~9 % of it within the
    # campaigns (not 5 % with confidence) and the campaigns' means short of alpha: main took it and
    # the test error rose ~22 %; now nothing is taken and the test error is as before
    j = _diagnosis(8969).to_json("E_X")
    assert not any(e["accepted"] for e in j["effects"])
    assert j["after"]["test_rmse"] <= 1.02 * j["before"]["test_rmse"]
    lags = _start_lags(j)
    assert lags
    top = max(lags, key=lambda e: e["evidence"]["cv_rmse_gain_pct"])
    ev = top["evidence"]
    assert ev["cv_rmse_gain_pct_within"] < 0.5 * ev["cv_rmse_gain_pct"]
    assert ev["p_value_between"] > j["bar"]["alpha"] and not ev["clears_bar"]
    # planted 8885 E_Y: round 2's T_motor1 start lag gains mostly in the means too, but every
    # campaign's mean gains (p 1/128 over 8): it is kept after the position effect
    j = _diagnosis(8885).to_json("E_Y")
    kept = [e for e in _start_lags(j) if e["accepted"]]
    assert kept and kept[0]["evidence"]["p_value_between"] <= j["bar"]["alpha"]
    assert j["after"]["test_rmse"] < 0.5 * j["before"]["test_rmse"]
