"""A step shared by every sensor at once is the logger's fault, not the machine's (commonjump56):
each sensor is re-referenced by its own step and none is excluded; a jump on one sensor alone is
still that sensor's fault.

The line of ``test_monitor_new_state48.py`` (10 sensors, a warm-up and a gradient), streamed
healthy with every reading offset by the same amount from sample ``AT`` on."""

from __future__ import annotations

import numpy as np
import pytest

from conftest import monitored
from test_monitor_new_state48 import NAMES, _field
from thermocomp.apps.deploy.surveillance import SensorMonitor

AT = 200


def _stream(record: np.ndarray) -> tuple[np.ndarray, list[dict]]:
    mon = SensorMonitor.from_training(None, NAMES, {"a": _field(400, 0), "b": _field(400, 1)})
    return monitored(mon, record)


@pytest.mark.parametrize("size", [2.0, -5.0])
def test_a_step_on_every_sensor_at_once_is_re_referenced_and_excludes_none(size):
    healthy = _field(400, 2)
    record = healthy.copy()
    record[AT:] += size
    fields, events = _stream(record)
    assert not [e for e in events if e["to"] == "excluded"]       # before: every sensor, at AT
    again = [e for e in events if e["to"] == "re-referenced"]
    assert sorted(e["sensor"] for e in again) == sorted(NAMES)
    assert {e["time"] for e in again} == {float(AT)}
    # the model sees the healthy field (less one sample's change, taken with the step)
    np.testing.assert_allclose(fields, healthy - healthy[0], atol=0.15)


def test_a_jump_on_one_sensor_alone_still_excludes_it():
    record = _field(400, 2)
    record[AT:, 4] += 2.0
    _, events = _stream(record)
    out = [(e["sensor"], e["time"]) for e in events if e["to"] == "excluded"]
    assert out == [("T_4", float(AT))]
    assert not [e for e in events if e["to"] == "re-referenced"]
