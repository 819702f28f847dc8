"""Issue 34 (diag100): in the ``campaigns`` scheme, where the campaigns cannot resolve a lag from
the initial thermal state (a "start lag") by its gain in their MEANS -- the sign-flip test's
smallest p with one unit per campaign, times the round's start lags screened, above ``alpha`` --
the start lag clears only if its gain within the campaigns is at least 2/3 of its pooled CV gain,
in % (``search.START_WITHIN_SHARE``; benchmarks/bench_diag100.py).

Past its transient a start lag is one constant per campaign: on 8 train campaigns, picked among
~110 start lags, it fitted their offsets and left 8 of bench_diag92's 70 seen draws 6.6-52.5 %
worse on test (within / pooled 0.28-0.90); real round-1 start lags read 0.96-1.30, and diag98's
bound of 1 lost two of them (0.96-0.98); make run's scenario trains on 16 campaigns, and its real
T_motor1 start lag on ``E_Y`` (-25.3 % on test) is weighed as before.
"""

from __future__ import annotations

import dataclasses
from types import SimpleNamespace

import numpy as np
import pytest
from hydra import compose, initialize_config_dir
from hydra.utils import instantiate

from test_diagnose_few import few
from test_diagnose_within67 import N_UNITS, ROWS, _evaluation, _result, _search
from thermocomp.apps.diagnose import SearchOptions, diagnose
from thermocomp.apps.diagnose.cv import smallest_p
from thermocomp.apps.diagnose.features import Effect
from thermocomp.apps.diagnose.search import forward_first
from thermocomp.base.paths import conf_dir
from thermocomp.core.compensator import Compensator
from thermocomp.core.models import MLR

START_LAG = Effect("dynamics", "first_order_lag", "T_nose", tau_s=900.0,
                   initial_state=("T_nose", "T_box1"), initial_directions=2)


def _residuals():
    """The current CV residual (campaign offsets + motion within) and three candidates' residuals:
    one takes 60 % of the offsets and 15 % of the motion (within / pooled ~0.3), one 30 % of
    the offsets and 20 % of the motion (~0.7), one 15 % of both (1)."""
    rng = np.random.default_rng(11)
    units = np.repeat(np.arange(N_UNITS), ROWS)
    offsets = rng.choice([-1.0, 1.0], N_UNITS)[units] * rng.uniform(0.6, 1.2, N_UNITS)[units]
    motion = rng.normal(0.0, 0.5, N_UNITS * ROWS)
    motion -= (np.bincount(units, motion) / ROWS)[units]      # no part of it in the means
    return (offsets + motion, 0.4 * offsets + 0.85 * motion, 0.7 * offsets + 0.8 * motion,
            0.85 * (offsets + motion))


@pytest.mark.parametrize("start_lags", [1, 110])
def test_a_start_lag_clears_on_its_means_only_where_resolved_else_by_two_thirds_within(start_lags):
    current, means, mostly_within, even = (_result(r) for r in _residuals())
    s = _search("campaigns")
    s.start_lags_screened = start_lags
    resolved = smallest_p(N_UNITS) * start_lags <= s.options.alpha    # 9 units: 1 / 512
    assert resolved == (start_lags == 1)
    lag = _evaluation(START_LAG, current, means)
    lag_07 = _evaluation(START_LAG, current, mostly_within)
    same_shares = _evaluation(START_LAG, current, even)
    other_kind = _evaluation(Effect("signal", "raw", "S_pos_Y"), current, means)
    s._family_bar([lag, lag_07, same_shares, other_kind], current)
    margin = s.options.min_gain_pct
    for ev in (lag, lag_07, same_shares, other_kind):    # every other check of the bar holds
        assert ev.gain_pct >= margin and ev.p_family <= s.options.alpha
        assert ev.gain_pct_within >= margin and ev.gain_pct_within_rest >= margin
    assert lag.gain_pct_within / lag.gain_pct < 0.5
    assert 2.0 / 3.0 < lag_07.gain_pct_within / lag_07.gain_pct < 0.9
    assert lag.clears_bar == resolved              # mostly in the means: only where resolved
    assert lag_07.clears_bar                       # 2/3 within or more: clears (diag98's 1 refused it)
    assert same_shares.gain_pct_within == pytest.approx(same_shares.gain_pct) and same_shares.clears_bar
    assert other_kind.clears_bar                   # the rule asks start lags only


@pytest.mark.parametrize("forward_gain, clears", [(20.0, False), (40.0, True)])
def test_an_unresolved_start_lag_must_also_gain_forward_within_the_later_campaigns(forward_gain, clears):
    # diag103: where the means are unresolved, a start lag that clears diag100's 2/3 (~0.7 here)
    # must also gain START_FORWARD_WITHIN_PCT (28 %) within the later train campaigns, each fitted
    # on the ones before it (planted 9342 E_X's 1800 s lag: 24.1 %, +13.9 % on test)
    current, _, mostly_within, _ = (_result(r) for r in _residuals())
    s = _search("campaigns")
    s.start_lags_screened, s.declared, s.excluded, s.effects = 110, ["T_nose", "T_box1"], [], []
    share = (1.0 - forward_gain / 100.0) ** 2
    s.cv = SimpleNamespace(closed_form=True, forward_within=lambda inputs, effects, alpha:
                           np.array([2.0, 1.0, 3.0]) * (share if effects else 1.0))
    lag = _evaluation(START_LAG, current, mostly_within)
    s._family_bar([lag], current)
    assert lag.gain_pct_within >= 2.0 / 3.0 * lag.gain_pct and lag.p_family <= s.options.alpha
    assert lag.gain_pct_forward_within == pytest.approx(forward_gain)
    assert lag.clears_bar == clears
    assert lag.entry()["evidence"]["forward_gain_pct_within"] == pytest.approx(forward_gain)


def test_an_unresolved_start_lag_beaten_forward_in_every_later_campaign_gives_way():
    # diag105: lag:9443 E_Y took T_bearing_f3 3600 s (forward within 33.3, test +13.3 %) where
    # T_motor2 beat it forward within in each of the 4 later train campaigns (taken: -0.9 %)
    current, _, mostly_within, _ = (_result(r) for r in _residuals())
    s = _search("campaigns")
    s.start_lags_screened, s.declared, s.excluded, s.effects = 110, ["T_nose", "T_box1"], [], []
    per_campaign = {900.0: [1.0, 0.5, 1.5],     # the first choice: 29 % forward
                    1800.0: [0.2, 0.9, 0.9],    # 42 % in all, but worse in the second campaign
                    3600.0: [0.6, 0.3, 0.9]}    # 45 %: better in every campaign
    s.cv = SimpleNamespace(closed_form=True, forward_within=lambda inputs, effects, alpha: np.array(
        per_campaign[effects[-1].tau_s] if effects else [2.0, 1.0, 3.0]))
    first, uneven, every = (_evaluation(dataclasses.replace(START_LAG, tau_s=tau), current, mostly_within)
                            for tau in per_campaign)
    s._family_bar([first, uneven, every], current)
    assert all(ev.clears_bar for ev in (first, uneven, every))
    assert first.gain_pct_forward_within < every.gain_pct_forward_within
    order = lambda evs: [id(ev) for ev in forward_first(evs)]    # noqa: E731
    assert order([first, uneven, every]) == [id(every), id(first), id(uneven)]
    assert order([first, uneven]) == [id(first), id(uneven)]       # better in sum only: no tie broken
    other = _evaluation(Effect("signal", "raw", "S_pos_Y"), current, mostly_within)
    assert order([other, first, every]) == [id(other), id(first), id(every)]   # the first read no forward


def test_clean_8170s_start_lag_on_8_train_campaigns_is_no_longer_accepted():
    # clean seed 8170, 12 campaigns (8 train): 9bbbb214 accepts T_nose's 900 s start lag on E_X
    # (CV gain 22.4 %, within 6.5 %: 0.29) and the test error rises 0.797 -> 0.916 µm (+14.9 %)
    ds, _ = few(None, 8170)
    d = diagnose(ds, Compensator(MLR()), targets=["E_X"], options=SearchOptions(max_effects=2))
    j = d.to_json("E_X")
    lags = [e["evidence"] for e in j["rounds"][0]["evaluated"]
            if e["effect"].get("initial_state") and e["effect"].get("column") == "T_nose"
            and e["effect"].get("tau_s") == 900.0]
    assert lags, "T_nose's 900 s start lag was not weighed: nothing tested"
    v = lags[0]
    assert v["cv_rmse_gain_pct"] >= 5.0 and v["cv_rmse_gain_pct_within"] < 0.5 * v["cv_rmse_gain_pct"]
    assert not v["clears_bar"]
    assert not j["effects"] or not any(e["accepted"] for e in j["effects"])
    assert j["after"]["test_rmse"] == j["before"]["test_rmse"]


def test_make_runs_start_lag_on_16_train_campaigns_stays():
    # make run's scenario (seed 0, 16 train campaigns): T_motor1's 7200 s start lag on E_Y gains
    # 36.9 % in CV, 28.2 % within (0.76) and takes the test error 1.42 -> 1.06 µm
    with initialize_config_dir(config_dir=str(conf_dir()), version_base="1.3"):
        cfg = compose(config_name="config", overrides=["seed=0"])
    ds = instantiate(cfg.sim.generator).generate()[0]
    d = diagnose(ds, Compensator(MLR()), targets=["E_Y"], options=SearchOptions())
    j = d.to_json("E_Y")
    taken = [e for e in j["effects"] if e["accepted"]]
    assert [(e["effect"]["column"], e["effect"]["tau_s"]) for e in taken][:1] == [("T_motor1", 7200.0)]
    ev = taken[0]["evidence"]
    assert ev["cv_rmse_gain_pct_within"] < ev["cv_rmse_gain_pct"]
    assert j["after"]["test_rmse"] < 0.8 * j["before"]["test_rmse"]
