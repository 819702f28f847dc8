"""A sensor no other predicts whose level settles off its own is re-referenced, served, numpy
mirror and compiled C (jump94b; benchmarks/bench_jump94b.py, the prototype bench_jump94.py).

fl_thermal (the measured spindle, ``data=fl_thermal``) deployed as replay does (adaptive MLR):
``T_t16``, which no other sensor predicts, reads healthy bursts of 2-3 °C, so its jump limit is
8.6 °C and a +3 °C step from row ``ONSET`` (1 h into the test campaign) was read as heat.  Its
last window then lies wholly above the window before, by far more than any two successive
windows of its training: it is re-referenced a window after the step and the corrections return
to the healthy campaign's."""

from __future__ import annotations

import copy
import dataclasses

import numpy as np
import pytest

from conftest import fl_thermal_served
from test_export import needs_cc
from test_export_cmon80 import streamed_as_served
from thermocomp.apps.deploy.export import Simulator, watch
from thermocomp.apps.deploy.export.pack import corrections
from thermocomp.apps.deploy.report import stream_rows

SENSOR, ONSET, SIZE = "T_t16", 240, 3.0


@pytest.fixture(scope="module")
def served():
    """``(deployed, its system with the monitor, the test campaign, it with T_t16 stepped)``."""
    deployed, ss, frame = fl_thermal_served()
    stepped = frame.copy()
    stepped.loc[ONSET:, SENSOR] += SIZE
    return deployed, ss, frame, stepped


@pytest.fixture(scope="module")
def stepped_run(served):
    """The deployed stream of the stepped campaign, run once: both tests assert on it."""
    deployed, _, _, stepped = served
    return stream_rows(deployed, stepped, "K06")


def _events(run, frame) -> list[tuple[int, str, str]]:
    times = frame["time"].to_numpy(float) - frame["time"].iloc[0]
    return [(int(np.searchsorted(times, e["time"])), e["sensor"], e["to"]) for e in run.events
            if e.get("sensor")]


def _without_rule(deployed):
    """The deployed model with the rule off (the monitor as before jump94b)."""
    old = copy.deepcopy(deployed)
    old.monitor._settles = False
    return old


def test_the_stepped_sensor_is_re_referenced_and_the_healthy_campaign_is_quiet(served, stepped_run):
    deployed, ss, frame, stepped = served
    mon = deployed.monitor
    healthy = stream_rows(deployed, frame, "K06")
    assert _events(healthy, frame) == []
    run = stepped_run
    said = _events(run, stepped)
    assert said == [(ONSET + mon.window - 1, SENSOR, "re-referenced")], said
    j = mon.names.index(SENSOR)
    assert not mon._predictable[j] and SIZE < mon._jump_lim[j]   # under its jump limit
    assert "settled off its own" in run.events[0]["reason"]
    # the corrections back to the healthy campaign's, the rule off they stay off them
    before = stream_rows(_without_rule(deployed), stepped, "K06")
    assert _events(before, stepped) == []
    want = corrections(ss, healthy.y)
    got, old = corrections(ss, run.y), corrections(ss, before.y)
    after = slice(ONSET + mon.window, None)
    assert np.sqrt(np.mean((got[after] - want[after]) ** 2)) < 0.1 * np.sqrt(
        np.mean((old[after] - want[after]) ** 2))


def _mirror(ss, frame) -> tuple[np.ndarray, list[int]]:
    """The numpy mirror's corrections and the rows it re-references a settled sensor."""
    sim = Simulator(ss)
    sim.reset()
    got, rows = [], []
    for i, (u, t) in enumerate(zip(frame[ss.inputs].to_numpy(float), frame["time"])):
        got.append(sim.step(u, t))
        if sim.watch.flags & watch.REREFERENCED and sim.watch.rule == getattr(watch, "SETTLED", -1):
            rows.append(i)
    return np.array(got), rows


@needs_cc
def test_the_code_re_references_the_step_as_served(served, stepped_run, tmp_path):
    deployed, ss, _, stepped = served
    run = stepped_run
    want = corrections(ss, run.y)
    got, rows = _mirror(ss, stepped)
    assert rows == [ONSET + deployed.monitor.window - 1]
    assert np.max(np.abs(got - want)) < 1e-9
    _, said = streamed_as_served(tmp_path, deployed, ss, "K06", stepped, want)
    assert "settled off its own" in said
    # an export before jump94b (no ``settled``): the mirror reads the step as heat
    old = dataclasses.replace(ss, monitor={k: v for k, v in ss.monitor.items() if k != "settled"})
    assert _mirror(old, stepped)[1] == []
