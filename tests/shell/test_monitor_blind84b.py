"""A healthy column whose served monitor took a pair out at an unseen source's onset (mon84b;
benchmarks/bench_mon84b.py, kept by bench_mon85.py).

column_moving_source seed 8703, healthy (bench_freeze84's fresh draw): the unseen source Q3 sets
in at the test half.  ``T_left1`` (leverage 0.77) is the one sensor out of band at its onset and
the likelier single fault, but with it out ``T_left3`` is no longer judged (its leverage past
``max_leverage``): before mon85 both went out to the end of Q3 (served E_Y about 6x the fixed
model's).  A lone fault is now taken over paper 002's culprit only if its exclusion leaves every
judged sensor judged: the culprit's verdict stands, a new thermal state, nothing out."""

from __future__ import annotations

import json

import pytest

from conftest import FAST, thermocomp

SIM = ("sim=column_moving_source", "seed=8703")
@pytest.fixture(scope="module")
def report(tmp_path_factory):
    root = tmp_path_factory.mktemp("blind84b")
    thermocomp("simulate", *SIM, f"data.path={root / 'data'}", "track=false")
    thermocomp("monitor", f"data.path={root / 'data'}", "sim=column_moving_source", "model=mlr",
               "monitor.fallbacks=unobservable", f"out={root / 'mon'}", *FAST)
    return json.loads((root / "mon" / "monitor.json").read_text())


def test_the_onset_of_an_unseen_source_takes_no_sensor_out(report):
    assert not [e for e in report["events"] if e["to"] == "excluded"]
    state = [e for e in report["events"] if e["to"] == "new thermal state"]
    assert len(state) == 1 and "T_left1" in state[0]["sensors"]


def test_the_served_correction_is_the_fixed_models(report):
    for target, r in report["targets"].items():
        assert r["rmse_adaptive"] == pytest.approx(r["rmse_fixed"], rel=1e-9), target
