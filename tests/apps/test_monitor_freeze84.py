"""A sensor out for a freeze alone comes back on readings off the value it held (freeze84).

A healthy sensor at the top of a slow hump can read one value for a few samples while the field
the others predict for it moves past its band (an unseen source: bench_freeze83b's s8613); the
freeze takes it out.  Once it reads on (``THAW`` readings in a row off the held value) the
freeze's evidence is gone and it is back at once, judged as an active sensor, not after a window
against a field that may have left it.  A logger stuck but for one step every few samples, each
step returning to the held value, is still held: it stays out."""

from __future__ import annotations

import numpy as np

from thermocomp.apps.deploy.surveillance import SensorMonitor
from thermocomp.apps.deploy.surveillance.states import THAW

NAMES = [f"T_{k}" for k in range(6)]
START, HELD = 150, 12          # the sensor T_2 holds its reading from START for HELD samples


def _field(m: int, seed: int) -> np.ndarray:
    rng = np.random.default_rng(seed)
    t = np.arange(m)
    warm = 3 * (1 - np.exp(-t / 80)) + 1.5 * np.sin(t / 23 + seed)
    gradient = 1.5 * np.sin(t / 53 + seed)
    x = warm[:, None] + gradient[:, None] * np.linspace(-0.5, 0.5, 6)
    return 20 + np.round(x + rng.normal(scale=0.02, size=x.shape), 2)    # a logger's 0.01 °C


def _events(record: np.ndarray) -> list[tuple[int, dict]]:
    mon = SensorMonitor.from_training(None, NAMES, {"a": _field(400, 0), "b": _field(400, 1)})
    return [(i, e) for i, row in enumerate(record) for e in mon.update(row, float(i))[1]
            if e["sensor"] == "T_2"]


def _held(catch_up: int) -> np.ndarray:
    """T_2 held, then back to its true reading over ``catch_up`` samples (no jump)."""
    record = _field(300, 5)
    x = record[:, 2].copy()
    end = START + HELD
    record[START:end, 2] = x[START]
    w = np.arange(1, catch_up + 1) / catch_up
    record[end:end + catch_up, 2] = np.round(x[START] * (1 - w) + x[end:end + catch_up] * w, 2)
    return record


def test_a_sensor_held_while_the_field_moved_is_back_once_it_reads_on():
    record = _held(6)
    events = _events(record)
    out = [i for i, e in events if e["to"] == "excluded"]
    back = [i for i, e in events if e["from"] == "excluded"]
    assert [e["reason"].split(":")[0] for i, e in events if e["to"] == "excluded"] == ["freeze"]
    first_off = START + int(np.argmax(record[START:, 2] != record[START, 2]))
    assert out[0] < first_off
    assert back[0] == first_off + THAW - 1          # not a window against the field later


def test_a_logger_stuck_but_for_one_step_every_few_samples_stays_out():
    record = _field(300, 5)
    record[START:, 2] = record[START, 2]
    record[START + HELD::6, 2] += 0.01       # one logger step up, back at the next sample
    events = _events(record)
    assert [e["reason"].split(":")[0] for _, e in events if e["to"] == "excluded"] == ["freeze"]
    assert not [i for i, e in events if e["from"] == "excluded"]
