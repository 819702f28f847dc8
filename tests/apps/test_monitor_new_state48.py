"""A new thermal state is no faulty sensor (monitor48): several sensors leaving the field together
are reported as a new thermal state and none is excluded for drift; one drifting sensor still is.

A small line of 10 sensors: trained on a warm-up plus a swinging gradient (two modes), streamed
with a source training never saw (a bump between T_6 and T_7, warming from sample 100 to 200,
cooling for 60 more) or with one sensor drifting."""

from __future__ import annotations

import numpy as np
import pytest

from thermocomp.apps.deploy.guard import CorrectionGuard
from thermocomp.apps.deploy.report import alarm_rate
from thermocomp.apps.deploy.surveillance import NEW_STATE, TRAINED, SensorMonitor

NAMES = [f"T_{k}" for k in range(10)]
ON, OFF = 100, 200


def _field(m: int, seed: int) -> np.ndarray:
    rng = np.random.default_rng(seed)
    t = np.arange(m)
    warm = 3 * (1 - np.exp(-t / 80)) + 0.5 * np.sin(t / 37)
    gradient = 1.5 * np.sin(t / 53 + seed)
    x = np.linspace(-0.5, 0.5, len(NAMES))
    return 20 + warm[:, None] + gradient[:, None] * x + rng.normal(scale=0.02, size=(m, len(NAMES)))


def _stream(record: np.ndarray, **options) -> list[dict]:
    mon = SensorMonitor.from_training(None, NAMES, {"a": _field(400, 0), "b": _field(400, 1)},
                                      **options)
    events = []
    for i, row in enumerate(record):
        events += mon.update(row, float(i))[1]
    return events


def _new_source() -> np.ndarray:
    t = np.arange(400)
    power = np.interp(t, [ON, OFF, OFF + 60], [0.0, 3.0, 0.0])   # warms while on, cools after
    bump = np.exp(-((np.arange(len(NAMES)) - 6.5) / 1.5) ** 2)
    return _field(400, 2) + power[:, None] * bump


def _changes(events: list[dict]) -> list[tuple]:
    return [(e["sensor"], e["to"]) for e in events
            if e["to"] in ("excluded", NEW_STATE, TRAINED) or e["from"] == "excluded"]


def test_several_sensors_leaving_the_band_together_are_a_new_thermal_state_not_a_drift():
    events = _stream(_new_source())
    # one new state while the source is on, over once the field is trained again; nobody out
    # for long: at its first samples the bump reads as T_9 alone off the field (with T_9 out
    # every other within band; a lone fault), until the field follows it within a window
    changes = [c for c in _changes(events) if c[0] != "T_9"]
    assert changes == [(None, NEW_STATE), (None, TRAINED)]
    lone = [e for e in events if e["sensor"] == "T_9" and "excluded" in (e["from"], e["to"])]
    assert len(lone) in (0, 2) and all(ON < e["time"] < OFF for e in lone)
    assert not lone or lone[1]["time"] - lone[0]["time"] <= 10       # back within a window
    start, end = (e for e in events if e["to"] in (NEW_STATE, TRAINED))
    assert ON < start["time"] < OFF < end["time"]
    # the sensors either side of the source, the far end of the line still within band
    assert len(start["sensors"]) >= 2 and set(start["sensors"]) <= {f"T_{k}" for k in range(4, 10)}
    assert "new thermal state" in start["reason"]
    assert alarm_rate([{"campaign": "c", **e} for e in events], 1.0)["new_thermal_states"] == 1
    # the monitor of before (new_state off) blamed the source's sensors one after the other
    before = _changes(_stream(_new_source(), new_state=False))
    assert len([s for s, to in before if to == "excluded"]) >= 2
    assert all(s is not None for s, _ in before)


@pytest.mark.parametrize("new_state", [True, False])
def test_one_drifting_sensor_is_still_excluded(new_state):
    drifting = _field(400, 2)
    drifting[ON:, 3] += np.arange(400 - ON) * 0.02              # 0.02 °C per sample on T_3
    events = _stream(drifting, new_state=new_state)
    out = [e for e in events if e["to"] == "excluded"]
    assert out and out[0]["sensor"] == "T_3" and out[0]["reason"].startswith("drift")
    assert ON < out[0]["time"] < ON + 30
    assert not [e for e in events if e["to"] == NEW_STATE]


def test_a_fault_during_the_new_state_is_still_caught_by_its_own_signature():
    jumping = _new_source()
    jumping[150:, 1] += 3.0                                     # T_1 jumps while the source is on
    events = _stream(jumping)
    assert (None, NEW_STATE) in _changes(events)
    out = [e for e in events if e["to"] == "excluded" and e["sensor"] != "T_9"]
    assert [(e["time"], e["sensor"]) for e in out] == [(150.0, "T_1")]
    assert out[0]["reason"].startswith("jump")


def test_the_guard_bound_widens_only_while_a_new_state_is_declared():
    y = [np.array([[0.0], [10.0]])]
    t = [np.array([0.0, 1.0])]
    guard = CorrectionGuard.from_training(["E_X"], y, t, margin=0.2, rate_margin=1e6,
                                          new_state_margin=1.0)
    assert guard.step(np.array([0.0]), 1.0, 0.0)[0] == 0.0
    assert guard.step(np.array([15.0]), 1.0, 1.0)[0] == pytest.approx(12.0)    # 10 + 20 %
    assert guard.step(np.array([15.0]), 1.0, 2.0, new_state=True)[0] == pytest.approx(15.0)
    assert guard.step(np.array([25.0]), 1.0, 3.0, new_state=True)[0] == pytest.approx(20.0)
    plain = CorrectionGuard.from_training(["E_X"], y, t, margin=0.2, rate_margin=1e6)
    plain.step(np.array([0.0]), 1.0, 0.0)
    assert plain.step(np.array([15.0]), 1.0, 1.0, new_state=True)[0] == pytest.approx(12.0)


def test_a_monitor_pickled_before_the_rule_judges_as_it_did():
    import pickle

    mon = SensorMonitor.from_training(None, NAMES, {"a": _field(400, 0), "b": _field(400, 1)})
    state = dict(mon.__dict__)
    for key in ("new_state", "new_state_others", "_novel", "_calm_field", "_since"):
        del state[key]
    old = SensorMonitor.__new__(SensorMonitor)
    old.__setstate__(pickle.loads(pickle.dumps(state)))
    events = []
    for i, row in enumerate(_new_source()):
        events += old.update(row, float(i))[1]
    assert old.new_state is False and not [e for e in events if e["to"] == NEW_STATE]
    assert [s for s, to in _changes(events) if to == "excluded"]


def test_one_drifting_sensor_of_a_measured_record_is_excluded_not_called_a_new_state():
    """fl_thermal (measured spindle) streamed from its start, trained on its first 90 %, t12
    drifting 1 K/h from 1 h into the last 10 % (the monitor of `thermocomp monitor`, warmed on
    the train part).  The largest error is its coupled neighbours' (T_t14, then T_t15), and with
    T_t15 out T_t12 stays out of band: read as a new thermal state that never ended (the drifting
    sensor kept the field out), no drift excluded for the rest of the record.  Now the one
    sensor whose exclusion brings every other back, T_t12, is excluded as a lone fault."""
    import pandas as pd

    from conftest import ROOT

    record = pd.read_csv(ROOT / "datasets" / "fl_thermal" / "spindle_test.csv")
    names = [f"T_t{k}" for k in range(1, 17)]
    x = record[[f"t{k}(°C)" for k in range(1, 17)]].to_numpy(float)
    cut, onset = 10003, 10003 + 240
    mon = SensorMonitor.from_training(None, names, {"train": x[:cut]})
    x[onset:, names.index("T_t12")] += np.arange(len(x) - onset) * 15 / 3600
    events = []
    for i, row in enumerate(x):                    # warmed on the train part, as deployed
        got = mon.update(row, 15.0 * i)[1]
        events += got if i >= cut else []
    changes = [(e["sensor"], e["to"]) for e in events if e["to"] in ("excluded", NEW_STATE)]
    assert (None, NEW_STATE) not in changes
    out = [e for e in events if e["sensor"] == "T_t12" and e["to"] == "excluded"]
    assert out and out[0]["reason"].startswith("drift")
    assert out[0]["time"] - 15.0 * onset < 2 * 3600      # < 2 K of drift
    # the healthy T_t14, out within its band as the culprit that hid T_t9 while the drift pulled
    # the field, is back once T_t12 is out (mon85b: within its whole band, not half), not before
    back = [e for e in events if e["sensor"] == "T_t14" and e["from"] == "excluded"]
    assert "T_t14" not in mon.excluded and back and back[0]["time"] >= out[0]["time"]


def test_judge_only_names_the_new_state_and_excludes_nothing():
    """monitor.adaptive=false: the same new thermal state is declared (and ends), no sensor is
    excluded; a lone drifting sensor is judged in alarm, no new state."""
    events = _stream(_new_source(), adaptive=False)
    states = [e for e in events if e["to"] in (NEW_STATE, TRAINED)]
    assert [e["to"] for e in states] == [NEW_STATE, TRAINED]
    assert ON < states[0]["time"] < OFF < states[1]["time"]
    assert "drift judged again" in states[1]["reason"]
    assert not [e for e in events if e["to"] == "excluded"]
    assert [e for e in events if e["to"] == "alarm"]           # judged, as before
    drifting = _field(400, 2)
    drifting[ON:, 3] += np.arange(400 - ON) * 0.02
    events = _stream(drifting, adaptive=False)
    assert not [e for e in events if e["to"] in (NEW_STATE, "excluded")]
    assert [e["sensor"] for e in events if e["to"] == "alarm"][0] == "T_3"
    assert not [e for e in _stream(_field(400, 2), adaptive=False) if e["sensor"] is None]
