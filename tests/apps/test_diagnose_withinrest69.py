"""Issue 34, item 4 (clean69): in the ``campaigns`` scheme a candidate's gain within the held-out
campaigns must hold without the one campaign that gains most there (benchmarks/bench_clean69.py).

A within gain one campaign carries is one unit's evidence, however many ranked test blocks it
spans: on clean seed 6953 a lag from the initial state passed within67's check on one campaign's
gain and raised the error on new campaigns of the same machine 17 %.
"""

from __future__ import annotations

import numpy as np
import pytest

from test_diagnose_few import diagnosis
from test_diagnose_within67 import N_UNITS, ROWS, _evaluation, _result, _search
from thermocomp.apps.diagnose.features import Effect


def _residuals():
    rng = np.random.default_rng(7)
    units = np.repeat(np.arange(N_UNITS), ROWS)
    offsets = rng.normal(0.0, 0.8, N_UNITS)[units]
    noise = rng.normal(0.0, 0.4, N_UNITS * ROWS) * np.where(units == 0, 2.0, 1.0)   # 0: the worst
    one = np.where(units == 0, 0.3, 1.0)           # the error within campaign 0 alone cut to 30 %
    return offsets + noise, offsets + noise * one, offsets + noise * 0.85   # every campaign 15 %


def test_the_within_gain_less_the_best_campaign_discounts_a_gain_one_campaign_carries():
    current, one, spread = (_result(r) for r in _residuals())
    s = _search("campaigns")
    assert s._within_gain(current, one) > 5.0                      # pooled: passes within67
    assert s._within_gain(current, one, less_best=True) == pytest.approx(0.0, abs=1e-9)
    assert s._within_gain(current, spread, less_best=True) == pytest.approx(15.0)


def test_a_candidate_gaining_within_one_campaign_does_not_clear():
    current, one, spread = (_result(r) for r in _residuals())
    lag = _evaluation(Effect("dynamics", "lowpass_inputs", tau_s=3600.0), current, one)
    real = _evaluation(Effect("signal", "raw", "S_pos_Y"), current, spread)
    _search("campaigns")._family_bar([lag, real], current)
    assert lag.gain_pct_within >= 5.0 and lag.gain_pct_within_rest < 5.0 and not lag.clears_bar
    assert real.gain_pct_within_rest == pytest.approx(15.0) and real.clears_bar
    forward = _evaluation(Effect("dynamics", "lowpass_inputs", tau_s=3600.0), current, one)
    s = _search("forward")
    s.problem.campaigns = np.repeat(np.arange(N_UNITS), ROWS)
    s._family_bar([forward], current)
    assert forward.gain_pct_within_rest is None                     # forward: not asked


def test_clean_6953s_lag_from_the_initial_state_is_one_campaigns_within_gain():
    # clean 8-campaign seed 6953 (bench_planted69's fresh): a 1 h lag of the inputs from the
    # initial state (12 regressors) passed the shipped bar on 14 ranked blocks with a 7.7 % within
    # gain, 86 % of it one campaign's; accepted, it raised the test error 17 %
    j = diagnosis(None, 6953)
    assert j["cv"]["test_blocks"] > j["cv"]["units"]          # ranked blocks, finer than campaigns
    assert not any(e["accepted"] for e in j["effects"])
    lags = [e["evidence"] for e in j["rounds"][0]["evaluated"]
            if e["effect"].get("initial_state") and e["evidence"]["n_features"] == 12]
    assert lags, "the 12-regressor lag from the initial state was not weighed: nothing tested"
    v, margin = lags[0], 5.0
    assert v["cv_rmse_gain_pct"] >= margin and v["p_value_family"] <= 0.01
    assert v["p_value_margin"] <= 0.01 and v["cv_rmse_gain_pct_within"] >= margin
    assert v["cv_rmse_gain_pct_within_rest"] < margin and not v["clears_bar"]
    assert j["after"]["test_rmse"] == j["before"]["test_rmse"]
