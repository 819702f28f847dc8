"""A slow drift caught by a CUSUM of the sensor's self-prediction error (cusum70): on the line of
``test_monitor_new_state48.py`` (10 sensors, two modes, 0.02 °C of noise), a drift far slower
than the band sees is excluded early, a constant offset since the start is not, and the rows
taken in one go (``update_block``) leave the state the rows one by one leave."""

from __future__ import annotations

import numpy as np
import pytest

from test_monitor_new_state48 import NAMES, _field
from thermocomp.apps.deploy.surveillance import SensorMonitor
from thermocomp.apps.deploy.surveillance.cusum import cusum_sums

TRAIN = {"a": _field(400, 0), "b": _field(400, 1)}
SENSOR, ONSET = 3, 100


def _monitor(**options) -> SensorMonitor:
    return SensorMonitor.from_training(None, NAMES, TRAIN, **options)


def _stream(mon: SensorMonitor, record: np.ndarray) -> list[dict]:
    events = []
    for i, row in enumerate(record):
        events += [dict(e, row=i) for e in mon.update(row, float(i))[1]]
    return events


def _drifting(per_sample: float) -> np.ndarray:
    record = _field(400, 2)
    record[ONSET:, SENSOR] += per_sample * np.arange(400 - ONSET)
    return record


def test_the_sums_in_one_go_are_the_recursion():
    rng = np.random.default_rng(0)
    dev, k, start = rng.normal(size=(50, 3)), np.array([0.1, 0.5, 1.0]), np.array([0.0, 2.0, 0.3])
    s, want = start.copy(), []
    for row in dev:
        s = np.maximum(s + row - k, 0.0)
        want.append(s)
    np.testing.assert_allclose(cusum_sums(dev, k, start), want)


def test_a_slow_drift_is_out_long_before_the_band_sees_it():
    # 0.002 °C per sample: the 0.4 °C band is reached 200 samples after the onset (the line stays
    # within its training range until row 270: beyond it the sums are held at 0)
    record = _drifting(0.002)
    out = [e for e in _stream(_monitor(), record) if e["to"] == "excluded"]
    assert out and out[0]["sensor"] == NAMES[SENSOR] and "CUSUM" in out[0]["reason"]
    assert ONSET < out[0]["row"] < ONSET + 100, out[0]
    # without it the band alone: later, if at all
    late = [e for e in _stream(_monitor(cusum_k=None), record) if e["to"] == "excluded"]
    assert not late or late[0]["row"] > out[0]["row"] + 50
    assert not any("CUSUM" in e["reason"] for e in late)


@pytest.mark.parametrize("offset", [0.2, -0.2])
def test_a_constant_offset_since_the_start_is_its_level_not_a_drift(offset):
    # half the band from the first sample after the reference on: the level the sums start from
    record = _field(400, 2)
    record[1:, SENSOR] += offset
    assert [e for e in _stream(_monitor(), record) if e["to"] == "excluded"] == []


def test_the_rows_in_one_go_leave_the_state_of_the_rows_one_by_one():
    record = _drifting(0.002)
    one, block = _monitor(), _monitor()
    fields, events = [], []
    for i, row in enumerate(record):
        field, ev = one.update(row, float(i))
        fields.append(field)
        events += ev
    got, got_events, i = [], [], 0
    while i < len(record):
        taken = block.update_block(record[i:])
        if len(taken):
            got += list(taken)
            i += len(taken)
            continue
        field, ev = block.update(record[i], float(i))
        got.append(field)
        got_events += ev
        i += 1
    np.testing.assert_allclose(got, fields, atol=1e-12)
    assert got_events == events and any("CUSUM" in e["reason"] for e in events)
    for a, b in zip(one.snapshot(), block.snapshot()):
        np.testing.assert_allclose(np.asarray(a, float), np.asarray(b, float), atol=1e-9)
