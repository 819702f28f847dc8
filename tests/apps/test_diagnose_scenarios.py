"""Issue 6 acceptance on the simulator: each planted undeclared effect is found, named and fixed.

Every dataset is the default year-round scenario (24 campaigns, 16 train / 8
test) with one effect planted, plus an extra ``S_random`` column -- a random
walk with no physical effect -- that must never be accepted.  The truth file
is read here to check the answer; the diagnosis itself only gets the dataset.
"""

from __future__ import annotations

from functools import lru_cache

import numpy as np
import pandas as pd
import pytest
from hydra import compose, initialize_config_dir
from hydra.utils import instantiate
from sklearn.ensemble import RandomForestRegressor

from thermocomp.apps.diagnose import SearchOptions, diagnose
from thermocomp.base.paths import conf_dir
from thermocomp.core.compensator import Compensator
from thermocomp.core.models import ARX, ARXRF, MLR, PCR

EFFECTS = ["door", "hidden_source", "lag_node", "axis_position", "ambient_law"]


@lru_cache(maxsize=None)
def scenario(effect: str | None):
    """(dataset with S_random, truth) of the default scenario with ``effect`` planted (None: clean)."""
    override = f"++sim.generator.effects=[{effect}]" if effect else "++sim.generator.clean=true"
    with initialize_config_dir(config_dir=str(conf_dir()), version_base="1.3"):
        cfg = compose(config_name="config", overrides=[override, "seed=0"])
    ds, truth = instantiate(cfg.sim.generator).generate()
    rng = np.random.default_rng(123)
    for df in ds.campaigns.values():
        df["S_random"] = np.cumsum(rng.standard_normal(len(df)))
    return ds, truth


@lru_cache(maxsize=None)
def diagnosis(effect: str | None, model: str = "mlr", all_targets: bool = False, max_effects: int = 3,
              reference: str = "first_sample", alpha: float = 0.01):
    ds, truth = scenario(effect)
    planted = truth["undeclared_effects"]
    targets = (planted[0]["targets"] if all_targets else planted[0]["targets"][:1]) if planted else ["E_Z"]
    estimator = {"mlr": MLR(), "pcr": PCR(), "arx": ARX(),
                 "arx_rf": ARXRF(state_column=None, forest=RandomForestRegressor(
                     n_estimators=5, min_samples_leaf=20, random_state=0))}[model]
    d = diagnose(ds, Compensator(estimator, reference=reference), targets=targets, model_name=model,
                 options=SearchOptions(max_effects=max_effects, alpha=alpha))
    return truth, {t: d.to_json(t) for t in targets}


def _accepted(j):
    return [e for e in j["effects"] if e["accepted"]]


def _no_random_signal_accepted(j):
    used = {c for e in _accepted(j) for c in e.get("columns", [e["column"]])}
    assert "S_random" not in used
    assert not j["control_ever_clears_bar"]
    for r in j["rounds"]:
        if r["step"] == 0:                       # the sensor-health round has no control
            continue
        control = next(e for e in r["evaluated"] if e.get("control"))
        assert not control["evidence"]["clears_bar"] and not control["accepted"]


@pytest.mark.parametrize("effect", EFFECTS)
def test_planted_effect_is_the_top_accepted_one_and_the_test_error_drops_to_60_percent(effect):
    # the ambient law's every-target diagnosis (the test below's): its E_X answer is the lone
    # target's to the digit (only cv.designs and other_targets name E_Y), ~1.8 s of CPU once
    truth, result = diagnosis(effect, all_targets=True) if effect == "ambient_law" else diagnosis(effect)
    planted = truth["undeclared_effects"][0]
    for target, j in result.items():
        accepted = _accepted(j)
        assert accepted, f"{effect}: nothing accepted for {target}"
        top = accepted[0]
        assert top["kind"] == planted["kind"], (effect, top)
        if planted["column"] is not None:
            assert top["column"] == planted["column"], (effect, top)
        assert j["after"]["test_rmse"] <= 0.6 * j["before"]["test_rmse"], (effect, j["after"], j["before"])
        _no_random_signal_accepted(j)


def test_nothing_is_accepted_on_the_clean_scenario():
    truth, result = diagnosis(None)
    assert truth["clean"] and not truth["undeclared_effects"]
    j = result["E_Z"]
    assert _accepted(j) == []
    assert j["after"]["test_rmse"] == j["before"]["test_rmse"]
    _no_random_signal_accepted(j)


def test_a_drifting_sensor_is_reported_as_a_fault_and_left_out_of_the_inputs():
    truth, result = diagnosis("sensor_drift")
    faulty = truth["undeclared_effects"][0]["column"]
    j = next(iter(result.values()))
    faults = [e for e in _accepted(j) if e["kind"] == "sensor_fault"]
    assert [e["column"] for e in faults] == [faulty]
    assert j["excluded_inputs"] == [faulty]
    for e in _accepted(j):                       # nothing else is built on the broken sensor
        if e["kind"] == "sensor_fault":
            continue
        assert faulty not in e.get("columns", [e["column"]])
        assert faulty not in e["effect"].get("initial_state", [])
    assert j["self_prediction"][0]["sensor"] == faulty
    # found on the train campaigns (the drift starts mid-year, in train and test campaigns alike):
    # the search never sees the test split
    assert j["self_prediction"][0]["worst_unit_split"] == "train"
    # half the train campaigns drift, so the MLR had learnt to distrust the sensor (before 0.71 µm,
    # 0.75 on the scenario without the drift): leaving it out costs no test accuracy
    assert j["after"]["test_rmse"] <= 1.02 * j["before"]["test_rmse"]
    _no_random_signal_accepted(j)


@lru_cache(maxsize=None)
def faulty_in_test(kind: str):
    """The default scenario with one sensor failing in the test files only (``sensor_faults``)."""
    with initialize_config_dir(config_dir=str(conf_dir()), version_base="1.3"):
        cfg = compose(config_name="config", overrides=[
            "++sim.generator.effects=[sensor_faults]", "seed=0",
            f"++sim.generator.effect_params.sensor_faults.kind={kind}"])
    return instantiate(cfg.sim.generator).generate()


@pytest.mark.parametrize("kind", ["freeze", "drift", "jump"])
def test_a_sensor_broken_only_in_the_test_split_is_said_and_left_in(kind):
    # the test split chooses nothing: removing the sensor because its test temperatures break
    # would flatter "after" with a choice made on the data it is scored on (before, it was removed
    # and E_Z's test RMSE fell with it); `monitor` is what meets this sensor online
    ds, truth = faulty_in_test(kind)
    faulty = truth["undeclared_effects"][0]["column"]
    d = diagnose(ds, Compensator(MLR()), targets=["E_X", "E_Z"], options=SearchOptions(max_effects=1))
    for t in ("E_X", "E_Z"):
        j = d.to_json(t)
        assert j["excluded_inputs"] == [] and not any(e["kind"] == "sensor_fault" for e in _accepted(j))
        assert all(s["worst_unit_split"] == "train" for s in j["self_prediction"])
        warned = j["test_sensor_warnings"]
        assert [w["sensor"] for w in warned] == [faulty], warned
        assert warned[0]["campaign"] in ds.ids("test") and not warned[0]["acted_on"]


def test_every_target_of_the_ambient_law_gets_its_own_diagnosis():
    truth, result = diagnosis("ambient_law", all_targets=True)
    assert list(result) == truth["undeclared_effects"][0]["targets"] and len(result) == 2
    for j in result.values():
        assert _accepted(j)[0]["kind"] == "ambient_interval"
        assert j["after"]["test_rmse"] <= 0.6 * j["before"]["test_rmse"]


@pytest.mark.parametrize("model", ["pcr", "arx", "arx_rf"])
def test_every_model_family_is_diagnosed_the_same_way(model):
    # one search round each (the first accepted effect is decided there; keeps the test short)
    truth, result = diagnosis("hidden_source", model, max_effects=1)
    planted = truth["undeclared_effects"][0]
    j = next(iter(result.values()))
    top = _accepted(j)[0]
    assert (top["kind"], top["column"]) == (planted["kind"], planted["column"])
    assert j["model"] == model
    assert j["after"]["test_rmse"] < 0.8 * j["before"]["test_rmse"]
    _no_random_signal_accepted(j)


def test_the_axis_position_is_found_when_the_data_are_read_absolute():
    # data.reference=none, as a long record is run: the position acts through its lever p - p(0)
    # on a temperature rise, so the state is only found when tried referenced to the first sample.
    # Read so, it is the round's best candidate by far; one product (family-wise p 0.06 over the
    # round's 14 candidates, 0.009 alone) cleared alpha=0.01 only at 0.1; the state times the
    # rises of all the inputs (diagpos61) clears the family-wise test at 0.01, and its margin (a
    # gain of 5 % at 0.01) by the blocks' sign flips too (margin67; Student's t gave p 0.024 and
    # it was taken at alpha=0.1 only)
    truth, result = diagnosis("axis_position", reference="none")
    planted = truth["undeclared_effects"][0]
    j = next(iter(result.values()))
    best = j["rounds"][0]["evaluated"][0]
    assert (best["kind"], best["column"], best["effect"]["frame"]) == (
        "interaction", planted["column"], "referenced")
    assert j["cv"]["test_blocks"] > j["cv"]["units"]            # ranked blocks: the margin asked
    assert best["evidence"]["p_value_family"] <= 0.01 and best["evidence"]["p_value_margin"] <= 0.01
    assert best["accepted"]
    first = next(e for e in _accepted(j) if e["kind"] != "ambient_interval")
    assert (first["kind"], first["column"]) == ("interaction", planted["column"])
    assert first["effect"]["frame"] == "referenced"
    assert j["after"]["test_rmse"] <= 0.6 * j["before"]["test_rmse"]
    _no_random_signal_accepted(j)
    # at alpha=0.1 the random walk clears the bar in round 3 (after the position and two lags:
    # CV gain 12 %, p 0.035 alone, margin p < 0.1 by Student's t and by sign flips; the bound
    # before diagpos61 had 3.5 % < 5 %); it is not accepted
    truth, result = diagnosis("axis_position", reference="none", alpha=0.1)
    j = next(iter(result.values()))
    first = next(e for e in _accepted(j) if e["kind"] != "ambient_interval")
    assert (first["kind"], first["column"]) == ("interaction", planted["column"])
    assert j["after"]["test_rmse"] <= 0.6 * j["before"]["test_rmse"]
    assert "S_random" not in {c for e in _accepted(j) for c in e.get("columns", [e["column"]])}
    for r in j["rounds"][:2]:
        control = next(e for e in r["evaluated"] if e.get("control"))
        assert not control["evidence"]["clears_bar"] and not control["accepted"]
    assert not any(e.get("control") and e["accepted"] for r in j["rounds"] for e in r["evaluated"])


@lru_cache(maxsize=None)
def long_record(days: float = 6.0):
    with initialize_config_dir(config_dir=str(conf_dir()), version_base="1.3"):
        cfg = compose(config_name="config", overrides=["sim=long_record", "seed=0",
                                                         f"sim.generator.duration_days={days}"])
    ds, _ = instantiate(cfg.sim.generator).generate()
    return ds, str(cfg.data.reference)


def carried_test_rmse(model, ds) -> float:
    """Test RMSE of R1b predicted as the continuation of R1a (the model's states carried over)."""
    train, test = ds.campaigns["R1a"], ds.campaigns["R1b"]
    shifted = test.assign(time=test["time"] + float(ds.manifest.loc["R1b", "record_offset_s"]))
    whole = pd.concat([train, shifted], ignore_index=True)
    pred = model.predict({"R1": whole})["R1"]["E_Z"].to_numpy()[len(train):]
    return float(np.sqrt(np.mean((test["E_Z"].to_numpy() - pred) ** 2)))


def test_one_long_record_is_cross_validated_forward_and_a_dynamic_effect_is_accepted():
    ds, reference = long_record()
    assert reference == "none"
    d = diagnose(ds, Compensator(MLR(), reference=reference), options=SearchOptions(max_effects=2))
    j = d.to_json("E_Z")
    assert j["cv"]["scheme"] == "forward" and j["cv"]["units"] == 16 and j["cv"]["gap_samples"] > 0
    assert _accepted(j)[0]["kind"] == "dynamics"
    assert j["after"]["cv_rmse"] < 0.8 * j["before"]["cv_rmse"]
    # the CV scores what follows the training rows, states carried over: so is the test part
    assert carried_test_rmse(d.after_model, ds) < 0.9 * carried_test_rmse(d.before_model, ds)
    _no_random_signal_accepted(j)
