"""A sensor the others predict, frozen while the field hardly moves: out for its freeze once
constant past ``blind_run`` (mon97: benchmarks/bench_mon97.py).  Its readings dither over their
resolution (0.02 °C noise, no healthy reading repeats itself), so a constant run longer than
``blind_run`` (``freeze_factor`` times its longest constant run in training) is a freeze whatever
the field did.  Before mon97 a predicted sensor was frozen only where the others' prediction of
it moved by its warning band, so one frozen on a still field was read as healthy for ever (a
known gap held by a strict xfail here: freeze91's rule, frozen by the run alone for every sensor,
and freeze92's took a noiseless 0.1 K logger's settled sensors out, tests/apps/
test_monitor_rounding83.py, which mon97's rule leaves as before: such a reading does not dither).

The line of ``test_monitor_new_state48.py`` (10 sensors, a warm-up and a gradient, readings with
0.02 °C noise: no healthy reading repeats itself), streamed as drawn until ``AT``, then the field
still (each reading its value at ``AT`` plus noise) and one sensor frozen at its value at ``AT``."""

from __future__ import annotations

import numpy as np
import pytest

from test_monitor_new_state48 import NAMES, _field
from thermocomp.apps.deploy.adaptive import AdaptiveCompensator
from thermocomp.apps.deploy.export.watch import EXCLUDED, FREEZE, NOT_IN_CODE, CodeMonitor, monitor_fields
from thermocomp.apps.deploy.surveillance import SensorMonitor

AT = 200


def _monitor() -> SensorMonitor:
    return SensorMonitor.from_training(None, NAMES, {"a": _field(400, 0), "b": _field(400, 1)})


def _record(sensor: int) -> np.ndarray:
    record = _field(400, 2)
    noise = np.random.default_rng(7).normal(scale=0.02, size=record[AT:].shape)
    record[AT:] = record[AT] + noise             # the field still: no prediction moves by a band
    record[AT:, sensor] = record[AT, sensor]     # the sensor frozen
    return record


def _served(record: np.ndarray) -> list[tuple[float, str, str]]:
    mon, events = _monitor(), []
    for i, row in enumerate(record):
        events += mon.update(row, float(i))[1]
    return [(e["time"], e["sensor"], e["reason"].split(":")[0]) for e in events
            if e["to"] == "excluded"]


def code_freezes(monitor: SensorMonitor, record: np.ndarray, drop: tuple = ()) -> list[tuple[float, str]]:
    """The exported ``monitor``'s numpy mirror on ``record`` (its arrays less the keys ``drop``,
    1 s rows): its freeze exclusions; it must flag nothing it does not hold."""
    deployed = AdaptiveCompensator.__new__(AdaptiveCompensator)     # its monitor is all it reads
    deployed.monitor, deployed.period_s = monitor, 1.0
    arrays = monitor_fields(deployed, monitor.names)["monitor"]
    code, out = CodeMonitor({k: v for k, v in arrays.items() if k not in drop}), []
    for i, row in enumerate(record):
        code.step(row, i == 0, 1.0)
        assert not code.flags & NOT_IN_CODE, (i, code.missed)
        if code.flags & EXCLUDED and code.rule == FREEZE:
            out.append((float(i), monitor.names[code.sensor]))
    return out


def _code(record: np.ndarray, drop: tuple = ()) -> list[tuple[float, str]]:
    return code_freezes(_monitor(), record, drop)


@pytest.mark.parametrize("sensor", [2, 7])
def test_a_predicted_sensor_frozen_on_a_still_field_goes_out_alone(sensor):
    out = _served(_record(sensor))
    # it alone, for a freeze, once constant past blind_run (before mon97: never, nobody out)
    blind_run = _monitor()._blind_run[sensor]
    assert [(name, why) for _, name, why in out] == [(f"T_{sensor}", "freeze")], out
    assert out[0][0] == AT + blind_run + 1      # the first sample constant for more than it


def test_the_exported_monitor_takes_it_out_as_served_and_an_older_export_does_not():
    record = _record(7)
    served = [(t, name) for t, name, _ in _served(record)]
    assert served and _code(record) == served
    assert _code(record, drop=("dither_run",)) == []        # an export before the key: as before
