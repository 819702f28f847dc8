"""A frozen sensor whose coupled partner, paper 002's culprit, would hide it (mon84c;
benchmarks/bench_mon84c.py, kept by bench_mon85.py).

column_moving_source seed 8774 (bench_mon84b's fresh draw), ``T_front1`` held at its reading from
the test campaign's middle row, where the unseen source Q3 sets in.  The frozen sensor is beyond
its band, but its exclusion leaves ``T_edge1`` unjudged (its leverage past ``max_leverage``), and
the culprit ``T_edge1``, within its band, explains the bands only by leaving ``T_front1``
unjudged.  What the tests ask: the frozen sensor out for its freeze alone, its partner in.
Before mon85 the healthy ``T_edge1`` went out with the frozen sensor (a lone fault and its blind
partner, 725-732); now the lone fault is refused (it blinds ``T_edge1``) and so is the culprit's
fallback, which leaves the likelier single fault (``T_front1``) in, unjudged: a new thermal
state, and the freeze detector takes ``T_front1`` out."""

from __future__ import annotations

import json

import pandas as pd
import pytest

from conftest import FAST, thermocomp


@pytest.fixture(scope="module")
def report(tmp_path_factory):
    root = tmp_path_factory.mktemp("hides84c")
    data = root / "data"
    thermocomp("simulate", "sim=column_moving_source", "seed=8774", f"data.path={data}",
               "track=false")
    test = pd.read_csv(data / "test_cycle.csv")
    half = len(test) // 2
    test.loc[half:, "T_front1"] = test.loc[half, "T_front1"]
    test.to_csv(data / "test_cycle.csv", index=False)
    thermocomp("monitor", f"data.path={data}", "sim=column_moving_source", "model=mlr",
               "monitor.fallbacks=unobservable", f"out={root / 'mon'}", *FAST)
    return json.loads((root / "mon" / "monitor.json").read_text())


def test_the_frozen_sensor_goes_out_for_its_freeze_and_its_partner_stays_in(report):
    out = [e for e in report["events"] if e["to"] == "excluded"]
    assert out and {e["sensor"] for e in out} == {"T_front1"}
    assert out[0]["reason"].startswith("freeze")


def test_a_new_thermal_state_is_declared_where_neither_exclusion_is_tested(report):
    state = [e for e in report["events"] if e["to"] == "new thermal state"]
    assert state and state[0]["time"] <= next(e["time"] for e in report["events"]
                                               if e["to"] == "excluded")
