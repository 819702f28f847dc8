"""Issue 34, item 4: the closed loop with few campaigns.

With 8 train campaigns a sign-flip test over campaigns has 256 outcomes (smallest p 1/256) and,
family-wise over a round, no effect could clear alpha = 0.01 however strong.  The gains are now
tested on time blocks within the held-out campaigns, as long as the residual takes to decorrelate
(thermocomp.core.model_selection.blocks), and a change must also gain where no fold extrapolates and,
on blocks finer than the campaigns, reach min_gain_pct in its 1 - alpha lower bound, and be
within one standard error of the best CV error of the round, cleared or not
(benchmarks/bench_diagnose_few.py).
"""

from __future__ import annotations

from functools import lru_cache

import numpy as np
import pandas as pd
import pytest
from hydra import compose, initialize_config_dir
from hydra.utils import instantiate

from thermocomp.apps.diagnose import SearchOptions, diagnose
from thermocomp.apps.diagnose.cv import CVResult, sign_flip_maxt, smallest_p
from thermocomp.apps.diagnose.features import Effect
from thermocomp.apps.diagnose.search import Evaluation, choose
from thermocomp.base.paths import conf_dir
from thermocomp.core.compensator import Compensator
from thermocomp.core.io.contract import Dataset
from thermocomp.core.model_selection.blocks import DECORRELATED, cut_blocks, decorrelation_length
from thermocomp.core.model_selection.extrapolation import within_range
from thermocomp.core.models import MLR


@lru_cache(maxsize=None)
def few(effect: str | None, seed: int):
    """The year-round machine with 12 campaigns (8 train, 4 test); ``effect`` planted on the Y
    axis (None: clean)."""
    overrides = [f"seed={seed}", "sim.generator.n_campaigns=12",
                 f"++sim.generator.effects=[{effect}]" if effect else "++sim.generator.clean=true"]
    if effect == "axis_position":
        overrides.append("sim.generator.effect_params.axis_position.axis=Y")
    with initialize_config_dir(config_dir=str(conf_dir()), version_base="1.3"):
        cfg = compose(config_name="config", overrides=overrides)
    return instantiate(cfg.sim.generator).generate()


@lru_cache(maxsize=None)
def diagnosis(effect: str | None, seed: int) -> dict:
    ds, _ = few(effect, seed)
    assert len(ds.ids("train")) == 8
    d = diagnose(ds, Compensator(MLR()), targets=["E_Y"], options=SearchOptions(max_effects=2))
    return d.to_json("E_Y")


def _accepted(j):
    return [e for e in j["effects"] if e["accepted"]]


def _control_never_clears(j):
    assert not j["control_ever_clears_bar"]
    assert not any(e.get("control") for e in _accepted(j))


def test_a_planted_position_effect_is_accepted_with_8_train_campaigns():
    ds, truth = few("axis_position", 0)
    planted = truth["undeclared_effects"][0]
    j = diagnosis("axis_position", 0)
    assert j["cv"]["scheme"] == "campaigns" and j["cv"]["units"] == 8
    top = _accepted(j)[0]
    assert (top["kind"], top["column"]) == ("interaction", planted["column"]) == (
        "interaction", "S_pos_Y")
    assert top["evidence"]["p_value_family"] <= 0.01
    # finer units than the 8 campaigns, so a p below 1/256 (family-wise: alpha) is reachable
    assert j["cv"]["test_blocks"] > 8 and j["cv"]["min_p"] < 1 / 256
    assert top["evidence"]["cv_rmse_gain_pct_in_range"] > 0
    assert j["after"]["test_rmse"] <= 0.6 * j["before"]["test_rmse"]
    _control_never_clears(j)


@pytest.mark.parametrize("seed", [0, 1, 2])
def test_nothing_is_accepted_on_clean_data_nor_the_control(seed):
    j = diagnosis(None, seed)
    assert _accepted(j) == [] and j["after"]["test_rmse"] == j["before"]["test_rmse"]
    _control_never_clears(j)


def test_a_gain_barely_over_the_bar_on_many_short_blocks_is_not_accepted():
    # clean seed 11: the residual is at the noise floor and decorrelates at lag 1, so 609
    # one-sample blocks; a lag of the inputs gains 5.4 % in CV (bar 5 %) at a family-wise p far
    # below alpha, but 2 of 8 campaigns lose and the test error rose 8 % when it was accepted.
    # The gain must reach the bar with confidence (its 1 - alpha lower bound), not in the
    # point estimate
    j = diagnosis(None, 11)
    assert _accepted(j) == [] and j["after"]["test_rmse"] == j["before"]["test_rmse"]
    bar = j["bar"]
    assert j["cv"]["test_blocks"] > 10 * j["cv"]["units"]           # ranked blocks
    first = next(r for r in j["rounds"] if r["step"] == 1)
    top = max((e for e in first["evaluated"] if not e.get("control")),
              key=lambda e: e["evidence"]["cv_rmse_gain"])
    ev = top["evidence"]
    assert ev["cv_rmse_gain_pct"] >= bar["min_gain_pct"] and ev["p_value_family"] <= bar["alpha"]
    assert 0 < ev["cv_rmse_gain_lcb_alpha"] < ev["cv_rmse_gain_lcb"] < ev["cv_rmse_gain"]
    assert 100 * ev["cv_rmse_gain_lcb_alpha"] / first["cv_rmse"] < bar["min_gain_pct"]
    assert not ev["clears_bar"]
    _control_never_clears(j)


def test_a_stand_in_the_cv_finds_clearly_worse_than_another_effect_is_not_accepted():
    # planted seed 737: the residual keeps its memory over a campaign, so one test block per
    # campaign (p >= 1/256).  The ambient law (inputs x ambient_c0, 10 regressors) gains in all 8
    # campaigns at 1/256; the planted position product gains more in CV but makes 3 campaigns
    # worse and is not confirmed.  The ambient law, accepted, stood in for it and raised the test
    # error 4 %.  It cleared the bar and the one-standard-error rule kept it out (choose, tested
    # above); its 10 regressors with the intercept can match each of the 7 campaigns a fold trains
    # on, so on campaign blocks it no longer clears (Search.saturates)
    j = diagnosis("axis_position", 737)
    assert j["cv"]["test_blocks"] == j["cv"]["units"] == 8
    first = next(r for r in j["rounds"] if r["step"] == 1)
    family = [e for e in first["evaluated"] if not e.get("control")]
    top = max(family, key=lambda e: e["evidence"]["cv_rmse_gain"])
    assert top["column"] == "S_pos_Y" and not top["evidence"]["clears_bar"]
    ambient = [e["evidence"] for e in family if e["kind"] == "ambient_interval"
               and e["evidence"]["p_value_family"] <= j["bar"]["alpha"]]
    assert ambient and all(ev["n_features"] + 1 >= 7 and not ev["clears_bar"] for ev in ambient)
    # planted72: only the planted tilt's product over the air clears, and it is taken
    cleared = [(e["column"], e["effect"].get("over")) for e in family if e["evidence"]["clears_bar"]]
    assert cleared == [("S_pos_Y", "T_amb")]
    assert [(e["column"], e["effect"].get("over")) for e in _accepted(j)][:1] == cleared
    assert j["after"]["test_rmse"] < 0.5 * j["before"]["test_rmse"]
    _control_never_clears(j)


def _evaluation(label: str, unit_mse, n_features: int = 1, clears: bool = True) -> Evaluation:
    mse = np.asarray(unit_mse, float)
    result = CVResult(np.zeros(1), np.zeros(1), float(np.sqrt(mse.mean())), mse)
    return Evaluation(Effect("signal", "raw", label), result.rmse, 10.0 - result.rmse, 0.0, 0.0,
                      0.0, clears, result=result, n_features=n_features)


def test_the_one_standard_error_rule_measures_from_the_best_candidate_cleared_or_not():
    rng = np.random.default_rng(3)
    base = rng.uniform(1.0, 2.0, 8)
    confirmed = _evaluation("T_a", 4 * base)                        # mean ~6, SE ~0.4
    better = _evaluation("T_b", base, clears=False)                 # far better, not confirmed
    close = _evaluation("T_c", 4 * base - 0.1, clears=False)        # within one SE
    assert choose([confirmed]) == [confirmed]
    assert choose([confirmed], rivals=[confirmed, better]) == []
    assert choose([confirmed], rivals=[confirmed, close]) == [confirmed]
    # among the ones that clear, the simplest within one SE of the best goes first
    simple = _evaluation("T_d", 4 * base + 0.05, n_features=1)
    rich = _evaluation("T_e", 4 * base, n_features=10)
    assert choose([rich, simple], rivals=[rich, simple, close])[0] is simple


@pytest.mark.parametrize("seed", [1, 2, 6])
def test_a_position_effect_too_weak_to_show_leaves_the_model_as_it_was_or_better(seed):
    # the 2 % rule, checked where it can be (the acceptance never looks at the test split)
    j = diagnosis("axis_position", seed)
    assert j["after"]["test_rmse"] <= 1.02 * j["before"]["test_rmse"]
    _control_never_clears(j)


def test_block_length_is_where_the_residual_forgets_itself():
    rng = np.random.default_rng(0)
    phi, n = 0.9, 4000
    r = np.zeros(n)
    e = rng.standard_normal(n)
    for i in range(1, n):
        r[i] = phi * r[i - 1] + e[i]
    campaigns = np.repeat(["A", "B"], n // 2)
    expected = np.log(DECORRELATED) / np.log(phi)             # phi^k = DECORRELATED
    assert abs(decorrelation_length(r, campaigns, np.ones(n, bool)) - expected) <= 3
    assert decorrelation_length(rng.standard_normal(n), campaigns, np.ones(n, bool)) == 1
    # a campaign-wide offset never decorrelates within the campaign: one block per campaign
    offset = np.repeat(rng.choice([-5.0, 5.0], 8), 50) + 0.1 * rng.standard_normal(400)
    eight = np.repeat([f"C{k}" for k in range(8)], 50)
    assert decorrelation_length(offset, eight, np.ones(400, bool)) == 50


def test_blocks_cut_each_scored_stretch_of_a_unit_and_never_cross_a_campaign():
    units = np.array([-1, -1, 0, 0, 0, 0, 0, 1, 1, 1, 1, 1, 1, 1])
    campaigns = np.array(["A"] * 7 + ["B"] * 3 + ["C"] * 4)
    blocks = cut_blocks(units, campaigns, 2)
    assert list(blocks[:2]) == [-1, -1]
    assert len(set(blocks[2:7])) == 2                 # 5 rows of A: two blocks (3 + 2)
    for b in set(blocks[blocks >= 0]):
        assert len(set(campaigns[blocks == b])) == 1 and len(set(units[blocks == b])) == 1
    assert blocks.max() + 1 == 2 + 1 + 2              # B (3 rows): one; C (4 rows): two


def test_the_smallest_p_is_what_the_family_wise_test_gives_when_every_unit_gains():
    rng = np.random.default_rng(1)
    for n in (8, 12):
        D = np.vstack([rng.uniform(1, 2, n), rng.normal(0, 1, (3, n))])
        assert sign_flip_maxt(D)[0] >= smallest_p(n) and smallest_p(n) == 2.0 ** -n
    assert smallest_p(40) == pytest.approx(1 / 20001) and smallest_p(1) == 1.0


def test_rows_beyond_the_training_data_are_not_within_range():
    rng = np.random.default_rng(2)
    X = rng.normal(size=(300, 3))
    X[250:, 0] += 8.0                                  # the held-out rows leave the cloud
    X[200:250] *= 0.5                                  # these stay inside it
    train = np.arange(300) < 200
    inside = within_range(X, train, ~train)
    assert inside[200:250].all() and not inside[250:].any() and not inside[:200].any()


def climate_room(seed: int = 0, n: int = 60) -> Dataset:
    """13 runs of a climate room (10 train, 3 test), five sensors on two thermal modes and a
    healthy sensor ``T_x`` near the air intake that also sees a slow air drift ``d``: a little in
    every run, 15 K in the first one.  The error saturates in ``d``, so a linear model that uses
    ``T_x`` extrapolates badly on that run alone (the lathe record's climate room: 15-35 °C)."""
    rng = np.random.default_rng(seed)
    t = np.arange(n) * 300.0
    frames, rows = {}, []
    for k, split in enumerate(["train"] * 10 + ["test"] * 3):
        amb = 15.0 + 2 * k
        m = rng.uniform(2, 5) * (1 - np.exp(-t / 3600))
        m2 = rng.uniform(1, 3) * (1 - np.exp(-t / 9000)) + 0.3 * np.sin(t / 7000 + k)
        d = (15.0 if k == 0 else rng.uniform(0.5, 2.0)) * (1 - np.exp(-t / 7200))
        noise = lambda s: s * rng.standard_normal(n)               # noqa: E731
        df = pd.DataFrame({"time": t, "T_x": amb + 0.8 * m + d + noise(0.02),
                           "T_amb": amb + noise(0.02)})
        for i, (w, v) in enumerate([(1.0, 0.1), (0.9, 0.3), (0.6, 0.6), (0.4, 0.8), (0.2, 1.0)]):
            df[f"T_h{i}"] = amb + w * m + v * m2 + noise(0.02)
        df["E_Z"] = 3 * m + 4 * np.tanh(d / 2) + noise(0.1)
        frames[f"C{k + 1:02d}"] = df
        rows.append({"campaign": f"C{k + 1:02d}", "file": f"C{k + 1:02d}.csv", "split": split})
    return Dataset(pd.DataFrame(rows).set_index("campaign"), frames, name="climate_room")


def test_a_healthy_sensor_is_not_excluded_on_a_cv_that_only_extrapolation_improves():
    # its self-prediction jumps in the extreme run (ratio ~7) and leaving it out improves the CV
    # by ~77 % -- all of it on that run, where the fold extrapolates; on the rows within the
    # training data the model without it is ~24 % worse, and so is the test (before: excluded,
    # test RMSE +29 %)
    j = diagnose(climate_room(), Compensator(MLR()), options=SearchOptions(max_effects=1)).to_json("E_Z")
    assert j["self_prediction"][0]["sensor"] == "T_x" and j["self_prediction"][0]["jump_ratio"] >= 3
    fault = next(e for r in j["rounds"] if r["step"] == 0 for e in r["evaluated"])
    assert fault["column"] == "T_x" and fault["evidence"]["cv_rmse_gain_pct"] > 50
    assert j["excluded_inputs"] == [] and not fault["accepted"]
    assert j["after"]["test_rmse"] <= 1.02 * j["before"]["test_rmse"]
    assert fault["evidence"]["cv_rmse_gain_pct_in_range"] < -5


def test_a_candidate_that_can_match_every_training_campaign_is_not_accepted_on_campaign_blocks():
    # clean seed 4004: the probe noise of each campaign's first sample is an offset over the whole
    # campaign (reference=first_sample), so the residual never forgets within a campaign and the
    # test blocks are the 8 campaigns.  A lag of the 10 inputs from the initial thermal state
    # (12 regressors, more than the 7 campaigns a fold trains on) gained in each held-out
    # campaign (p 1/256) by matching those offsets, and raised the test error 39 % when accepted
    j = diagnosis(None, 4004)
    assert _accepted(j) == [] and j["after"]["test_rmse"] == j["before"]["test_rmse"]
    assert j["cv"]["test_blocks"] == j["cv"]["units"] == 8
    first = next(r for r in j["rounds"] if r["step"] == 1)
    lags = [e for e in first["evaluated"] if e["effect"].get("initial_directions")
            and e["transform"].endswith("of the model inputs, from the initial thermal state (2 directions)")]
    assert lags
    for e in lags:
        ev = e["evidence"]
        assert ev["cv_rmse_gain_pct"] >= j["bar"]["min_gain_pct"]
        assert ev["p_value_family"] <= j["bar"]["alpha"]
        assert ev["n_features"] + 1 >= 7 and not ev["clears_bar"]
    # a one-regressor candidate on the same blocks is not refused as saturating: it clears on its
    # family-wise p alone if it gains within the held-out campaigns too (within67; the spindle's
    # 900 s lag gains ~20 % in CV, nearly all of it in the campaigns' means, and is refused there)
    small = [e for e in first["evaluated"] if not e.get("control") and e["evidence"]["n_features"] == 1
             and e["evidence"]["p_value_family"] <= j["bar"]["alpha"]
             and e["evidence"]["cv_rmse_gain_pct"] >= j["bar"]["min_gain_pct"]]
    assert small and all(e["evidence"]["clears_bar"] == (e["evidence"]["cv_rmse_gain_pct_within"]
                                                         >= j["bar"]["min_gain_pct"]) for e in small)
    _control_never_clears(j)


def test_the_campaigns_a_fold_trains_on_bound_a_candidate_tested_on_campaign_blocks():
    from thermocomp.apps.diagnose.cv import Problem

    def problem(n_units, scheme="campaigns"):
        units = np.repeat([f"C{k:02d}" for k in range(n_units)], 5)
        n = len(units)
        return Problem(pd.DataFrame({"T_a": np.arange(n, dtype=float)}), np.zeros(n),
                       pd.DataFrame({"time": np.arange(n, dtype=float)}), units, units, "E_X",
                       scheme=scheme, n_blocks=4)
    assert problem(8).units_trained == 7             # one campaign out per fold
    assert problem(16).units_trained == 14           # 10 folds: some hold two out
    assert problem(8, "forward").units_trained is None
