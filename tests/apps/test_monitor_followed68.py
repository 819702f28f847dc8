"""A jump the whole machine follows is real (monitor68): a sensor no other predicts (the air),
excluded for a jump, comes back as measured when every other sensor's course turns with the jump
beyond anything training shows at once; an offset of that sensor alone stays re-referenced.

A small machine of 8 structure sensors, each following the air at its own rate, the first three
also warmed by a spindle switched on and off; the air's own slow drift makes it a mode no other
sensor predicts.  Streamed: the air really stepped +5 K at sample 150 (the structure follows it),
or the air's reading alone offset +5 K (nothing follows)."""

from __future__ import annotations

import numpy as np

from conftest import monitored
from thermocomp.apps.deploy.surveillance import SensorMonitor

NAMES = ["T_amb", *(f"T_{k}" for k in range(8))]
RATE = np.linspace(0.005, 0.015, 8)          # each sensor's coupling to the air, per sample
HEAT = np.array([0.03, 0.02, 0.01, 0, 0, 0, 0, 0])   # the spindle's, per sample while on
STEP, AT = 5.0, 150


def _machine(m: int, seed: int, air_step: float = 0.0) -> np.ndarray:
    rng = np.random.default_rng(seed)
    t = np.arange(m)
    drift = np.cumsum(rng.normal(scale=0.08, size=m))
    air = 20 + 1.0 * np.sin(t / 90 + seed) + drift - drift.mean() + np.where(t >= AT, air_step, 0)
    on = (t // 40 + seed) % 2 == 0
    T = np.empty((m, 8))
    T[0] = air[0]
    for k in range(1, m):
        T[k] = T[k - 1] + RATE * (air[k - 1] - T[k - 1]) + HEAT * on[k - 1]
    return np.column_stack([air, T]) + rng.normal(scale=0.01, size=(m, 9))


def _monitor() -> SensorMonitor:
    return SensorMonitor.from_training(None, NAMES, {k: _machine(300, k) for k in range(4)})


def test_the_air_is_a_sensor_no_other_predicts():
    assert not _monitor()._predictable[0]


def test_a_real_step_of_the_air_is_re_admitted_as_measured():
    mon = _monitor()
    record = _machine(300, 7, air_step=STEP)
    fields, events = monitored(mon, record)
    air = [e for e in events if e["sensor"] == "T_amb"]
    assert [e["to"] for e in air] == ["excluded", "ok"]
    assert air[1]["reason"].startswith("re-admitted as measured")
    back = int(air[1]["time"])
    # from its return the model reads the air as it is, the step included
    assert np.allclose(fields[back:, 0], record[back:, 0] - record[0, 0])


def test_an_offset_of_the_air_sensor_stays_re_referenced():
    mon = _monitor()
    record = _machine(300, 7)
    record[AT:, 0] += STEP
    fields, events = monitored(mon, record)
    air = [e for e in events if e["sensor"] == "T_amb"]
    assert [e["to"] for e in air] == ["excluded", "ok"]
    assert "as measured" not in air[1]["reason"]
    back = int(air[1]["time"])
    assert np.abs(fields[back:, 0] - (record[back:, 0] - STEP - record[0, 0])).max() < 0.5
