"""A lone fault is taken over paper 002's culprit only where it is the likelier single fault (mon84).

A line of 6 sensors trained on a warm-up and a swinging gradient (two modes).  A source training
never saw warms the line's near end (a bump at ``T_0``/``T_1``): at its onset the far end's
``T_5``, predicted from the others with a high leverage, is the one sensor beyond its band, on a
small residual that the leave-one-out division amplifies.  The culprit (the largest residual)
does not explain the bands, and ``T_5``'s exclusion does; it used to go out as a lone fault
(column_moving_source 8546's ``T_left1``, ``benchmarks/bench_mon84.py``).  It is not the likelier
single fault (the largest standardised residual ``|E| sqrt(1 - h)``, which a fault's own sensor
always has): a new thermal state, nobody out.  A drift of ``T_5`` still goes out."""

from __future__ import annotations

import numpy as np
import pytest

from thermocomp.apps.deploy.adaptive import AdaptiveCompensator
from thermocomp.apps.deploy.export.watch import DRIFT_OUT, EXCLUDED, NOT_IN_CODE, CodeMonitor, monitor_fields
from thermocomp.apps.deploy.surveillance import NEW_STATE, SensorMonitor

NAMES = [f"T_{k}" for k in range(6)]
ON, OFF = 100, 200


def _field(m: int, seed: int) -> np.ndarray:
    rng = np.random.default_rng(seed)
    t = np.arange(m)
    warm = 3 * (1 - np.exp(-t / 80)) + 0.5 * np.sin(t / 37)
    gradient = 1.5 * np.sin(t / 53 + seed)
    x = np.linspace(-0.5, 0.5, len(NAMES))
    return 20 + warm[:, None] + gradient[:, None] * x + rng.normal(scale=0.02, size=(m, len(NAMES)))


def _monitor() -> SensorMonitor:
    return SensorMonitor.from_training(None, NAMES, {"a": _field(400, 0), "b": _field(400, 1)})


def _record(kind: str) -> np.ndarray:
    x = _field(400, 2)
    if kind == "drift":
        x[ON:, 5] += np.arange(400 - ON) * 0.02              # 0.02 °C per sample on T_5
        return x
    power = np.interp(np.arange(400), [ON, OFF, OFF + 60], [0.0, 3.0, 0.0])
    return x + power[:, None] * np.exp(-((np.arange(len(NAMES)) - 0.5) / 1.5) ** 2)


def _run(mon: SensorMonitor, record: np.ndarray) -> list[dict]:
    events = []
    for i, row in enumerate(record):
        events += mon.update(row, float(i))[1]
    return events


def test_a_high_leverage_sensor_alone_out_at_a_new_sources_onset_is_no_lone_fault():
    mon = _monitor()
    record = _record("source")
    M, h = mon.pod.operator(np.ones(len(NAMES), dtype=bool))
    E = (record - record[0]) @ (np.eye(len(NAMES)) - M).T / (1 - h)
    # the scenario: T_5 the one sensor beyond its band first (two samples), on the largest
    # leverage, its residual |E|(1 - h) not the largest, nor its standardised one
    beyond = (np.abs(E[1:]) >= mon.warning_c) & (np.abs(E[:-1]) >= mon.warning_c)
    first = int(np.argmax(beyond.any(axis=1))) + 1
    assert np.flatnonzero(beyond[first - 1]).tolist() == [5] and np.argmax(h) in (0, 5)
    mean = np.abs(E[first - 1:first + 1]).mean(axis=0)
    assert np.argmax(mean * (1 - h)) != 5 and np.argmax(mean * np.sqrt(1 - h)) != 5
    events = _run(mon, record)
    assert not [e for e in events if e["to"] == "excluded"]
    state = [e for e in events if e["to"] == NEW_STATE]
    assert len(state) == 1 and state[0]["time"] == first


def test_a_drift_of_the_high_leverage_sensor_still_goes_out():
    out = [e for e in _run(_monitor(), _record("drift")) if e["to"] == "excluded"]
    assert out and out[0]["sensor"] == "T_5" and out[0]["reason"].startswith("drift")
    assert ON < out[0]["time"] < ON + 30


def _code(mon: SensorMonitor, record: np.ndarray) -> list[tuple[float, str]]:
    """The exported monitor's numpy mirror (``export/watch.py``, the C's arithmetic): its drift
    exclusions on ``record``; it must flag nothing it does not hold."""
    deployed = AdaptiveCompensator.__new__(AdaptiveCompensator)     # its monitor is all it reads
    deployed.monitor, deployed.period_s = mon, 1.0
    code = CodeMonitor(monitor_fields(deployed, NAMES)["monitor"])
    out = []
    for i, row in enumerate(record):
        code.step(row, i == 0, 1.0)
        assert not code.flags & NOT_IN_CODE, (i, code.missed)
        if code.flags & EXCLUDED and code.rule == DRIFT_OUT:
            out.append((float(i), NAMES[code.sensor]))
    return out


@pytest.mark.parametrize("kind", ["source", "drift"])
def test_the_exported_monitor_judges_the_lone_fault_as_served(kind):
    record = _record(kind)
    served = [(e["time"], e["sensor"]) for e in _run(_monitor(), record)
              if e["to"] == "excluded" and e["reason"].startswith("drift")]
    assert _code(_monitor(), record) == served
