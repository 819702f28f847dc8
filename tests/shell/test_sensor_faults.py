"""The ``sensor_faults`` effect (issue 14): a failing sensor reading on every scenario.

Every fault is checked against the dataset simulated with the same seed and no
effect: outside the faulty samples of the faulty column, every cell (errors,
other sensors, states, the true node temperatures) is the same.
"""

from __future__ import annotations

import functools
import json

import numpy as np
import pandas as pd
import pytest

from conftest import thermocomp
from test_sim_scenarios import small
from thermocomp.apps.sim import SCENARIOS
from thermocomp.apps.sim.effects import FAULT_KINDS, SensorFaults, is_ambient
from thermocomp.base.errors import ConfigError

NAME = "sensor_faults"


@functools.cache
def clean(name: str):
    """(generator, dataset, truth) of ``name`` at its small size, no effect."""
    gen = small(name)
    return (gen, *gen.generate())


def faulty(name: str, **params):
    gen = small(name, effects=[NAME], effect_params={NAME: params})
    return (gen, *gen.generate())


def period(frame: pd.DataFrame) -> float:
    return float(np.median(np.diff(frame["time"])))


@pytest.mark.parametrize("name", list(SCENARIOS))
@pytest.mark.parametrize("kind", FAULT_KINDS)
def test_each_kind_on_every_scenario_is_paired_with_the_clean_data(name, kind):
    gen0, base, _ = clean(name)
    gen, ds, truth = faulty(name, kind=kind)
    json.dumps(truth)
    (record,) = [r for r in truth["undeclared_effects"] if r["name"] == NAME]
    column = record["column"]
    assert record["kind"] == "sensor_fault" and record["params"]["kind"] == kind
    assert column in base.columns_of("T_") and not is_ambient(column)
    # The default hits every test campaign, and only them; per-campaign truth as for sensor_drift.
    assert sorted(record["campaigns"]) == sorted(base.ids("test"))
    assert ds.ids() == base.ids() and list(ds.manifest["split"]) == list(base.manifest["split"])
    for cid in base.ids():
        want, got = base.campaigns[cid], ds.campaigns[cid]
        # The physics is untouched: errors, other columns and the node temperatures.
        pd.testing.assert_frame_equal(got.drop(columns=column), want.drop(columns=column))
        pd.testing.assert_frame_equal(gen.node_temperatures_[cid], gen0.node_temperatures_[cid])
        if cid not in record["campaigns"]:
            np.testing.assert_array_equal(got[column], want[column])
            assert NAME not in truth["campaigns"][cid].get("effects", {})
            continue
        fault = truth["campaigns"][cid]["effects"][NAME]
        assert fault == record["campaigns"][cid]
        assert fault["kind"] == kind and fault["column"] == column
        time, healthy, reading = want["time"].to_numpy(), want[column].to_numpy(), got[column].to_numpy()
        k, end = fault["onset_index"], fault["end_index"]
        assert fault["onset_s"] == time[k]
        if kind == "spike_ref":
            assert (k, end) == (0, 1)
        else:   # half-way through the campaign, on a sample
            assert abs(time[k] - (time[0] + 0.5 * (time[-1] - time[0]))) <= 0.5 * period(want)
            assert end == len(time)
        outside = np.r_[0:k, end:len(time)]
        np.testing.assert_array_equal(reading[outside], healthy[outside])
        inside = slice(k, end)
        if kind == "freeze":
            assert np.ptp(healthy[inside]) > 0                 # the healthy sensor moves ...
            assert np.all(reading[inside] == healthy[k]) and fault["held_c"] == healthy[k]
        elif kind == "jump" or kind == "spike_ref":
            np.testing.assert_allclose(reading[inside] - healthy[inside], 3.0, atol=1e-9)
            assert fault["magnitude_c"] == 3.0
        elif kind == "drift":
            ramp = 1.0 * (time[inside] - time[k]) / 3600.0
            quantum = truth["noise"]["temperature_quantum_c"]
            np.testing.assert_allclose(reading[inside] - healthy[inside], ramp, atol=quantum / 2 + 1e-9)
            assert ramp[-1] > 10 * quantum and fault["rate_K_per_h"] == 1.0
        else:   # dropout: empty cells to the end
            assert np.isnan(reading[inside]).all() and fault["duration_samples"] == end - k


def test_named_column_campaigns_onset_and_dropout_length():
    _, base, _ = clean("yearround_spindle")
    target = base.ids("test")[-1]
    _, ds, truth = faulty("yearround_spindle", kind="dropout", column="T_motor1", onset_fraction=0.25,
                          duration_samples=3, campaigns=[target])
    (record,) = truth["undeclared_effects"]
    assert record["column"] == "T_motor1" and list(record["campaigns"]) == [target]
    fault = record["campaigns"][target]
    reading, time = ds.campaigns[target]["T_motor1"].to_numpy(), ds.campaigns[target]["time"].to_numpy()
    k = fault["onset_index"]
    assert np.flatnonzero(np.isnan(reading)).tolist() == [k, k + 1, k + 2] and fault["end_index"] == k + 3
    assert abs(time[k] - 0.25 * time[-1]) <= 0.5 * period(ds.campaigns[target])
    for cid in base.ids():
        if cid != target:
            pd.testing.assert_frame_equal(ds.campaigns[cid], base.campaigns[cid])


def test_the_drawn_sensor_is_never_an_ambient_one_and_follows_the_seed():
    machine = SCENARIOS["large_mill_week"]().machine()     # 48 structure sensors, 4 T_amb_*

    def draw(seed):
        effect = SensorFaults(seed)
        effect.modify_machine(machine)
        return effect.column

    drawn = [draw(seed) for seed in range(200)]
    assert not [c for c in drawn if is_ambient(c)]
    assert len(set(drawn)) > 20
    assert drawn == [draw(seed) for seed in range(200)]


def test_works_with_no_scenario_entry_for_its_parameters():
    """The class defaults are complete: a scenario whose effect_params has no sensor_faults key."""
    _, ds, truth = faulty("column_moving_source")
    assert truth["undeclared_effects"][0]["params"] == SensorFaults.defaults
    gen = small("column_moving_source", effects=[NAME], effect_params={"door": {"rate_per_h": 1.0}})
    _, again = gen.generate()
    assert again["undeclared_effects"][0]["campaigns"] == truth["undeclared_effects"][0]["campaigns"]


@pytest.mark.parametrize("params, match", [
    ({"kind": "stuck"}, "kind='stuck': must be one of freeze, jump, dropout, drift, spike_ref"),
    ({"column": "T_nowhere"}, r"'T_nowhere' is no sensor \(have \[.*'T_box1'"),
    ({"campaigns": ["K99"]}, "unknown.*K99"),
    ({"splits": ["val"]}, "hits no campaign"),
    ({"onset_fraction": 1.5}, "onset_fraction"),
    ({"duration_samples": 0}, "duration_samples"),
    ({"magnitude": 3.0}, "unknown key"),
])
def test_bad_parameters_are_config_errors(params, match):
    with pytest.raises(ConfigError, match=match):
        faulty("yearround_spindle", **params)


@pytest.mark.slow
def test_cli_override_plants_a_freeze(tmp_path):
    path = tmp_path / "col"
    thermocomp("simulate", "sim=column_moving_source", "sim.generator.effects=[sensor_faults]",
               "sim.generator.effect_params.sensor_faults.kind=freeze",
               "sim.generator.effect_params.sensor_faults.column=T_front3",
               "sim.generator.train_hours=6", "sim.generator.test_hours=6",
               f"data.path={path}", "track=false")
    truth = json.loads(path.with_name("col.truth.json").read_text())
    (record,) = truth["undeclared_effects"]
    assert record["name"] == NAME and record["column"] == "T_front3"
    manifest = pd.read_csv(path / "campaigns.csv")
    (test,) = manifest.loc[manifest["split"] == "test", "campaign"]
    fault = record["campaigns"][test]
    written = pd.read_csv(path / f"{test}.csv")["T_front3"].to_numpy()
    assert np.unique(written[fault["onset_index"]:]).tolist() == [fault["held_c"]]
    assert len(np.unique(written[:fault["onset_index"]])) > 1
