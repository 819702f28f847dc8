"""A machine hotter than training is no faulty sensor (hold56): a reading beyond its range that
the other sensors' field also puts beyond the training edge stays in; a spike beyond it does not.

The line of ``test_monitor_new_state48.py`` (10 sensors, two modes: a warm-up and a gradient),
streamed with its far end warming 16 °C more than training ever saw, along those two modes (its
near end not at all): the far sensors end beyond their training range (maximum + the 10 °C
margin), the near ones within it, and these predict those."""

from __future__ import annotations

import numpy as np

from test_monitor_new_state48 import NAMES, _field, _new_source
from thermocomp.apps.deploy.surveillance import NEW_STATE, SensorMonitor

SPIKE = (350, 9)     # sample, sensor: +50 °C once, while the sensor is beyond its range


def _hot_line() -> np.ndarray:
    record = _field(400, 2)
    far = np.linspace(0.0, 1.0, len(NAMES))                        # 0 at T_0, 1 at T_9
    record += np.linspace(0.0, 16.0, len(record))[:, None] * far   # at most 0.04 °C per sample
    return record


def _stream(record: np.ndarray) -> tuple[SensorMonitor, np.ndarray, list[dict]]:
    mon = SensorMonitor.from_training(None, NAMES, {"a": _field(400, 0), "b": _field(400, 1)})
    fields, events = [], []
    for i, row in enumerate(record):
        field, ev = mon.update(row, float(i))
        fields.append(field)
        events += ev
    return mon, np.array(fields), events


def test_a_field_beyond_its_range_that_the_others_follow_is_read_as_measured():
    record = _hot_line()
    mon, fields, events = _stream(record)
    out = record[-1] > mon.hi_c + mon.range_margin_c
    assert out[-2:].all() and not out[:5].any()                   # the far end out of range
    assert not [e for e in events if e["to"] == "excluded"]        # before: all of them, held
    np.testing.assert_allclose(fields, record - record[0], atol=1e-9)


def test_a_spike_beyond_the_range_of_a_hotter_machine_is_still_out():
    record = _hot_line()
    k, j = SPIKE
    record[k, j] += 50.0
    _, fields, events = _stream(record)
    out = [e for e in events if e["to"] == "excluded"]
    assert [(e["sensor"], e["time"]) for e in out] == [(NAMES[j], float(k))]
    assert out[0]["reason"].startswith("out of range")
    assert abs(fields[k, j] - (record[k - 1, j] - record[0, j])) < 0.5    # held, not the spike


class _BlamesT0(SensorMonitor):
    """The monitor with its "explaining" rule pinned on T_0 at the first band crossing (the rule
    itself needs a sensor no other predicts; what is checked here is what follows it)."""

    _blamed = False

    def _explaining(self, level):
        if self._blamed:
            return None
        self._blamed = True
        return 0


def test_an_explaining_exclusion_the_field_follows_is_a_new_thermal_state():
    """long4253's T_spindle_rear at twice the training speed: out as "explaining" T_zdrive, then
    T_head_left and T_zdrive left the band with it out; it stayed out (1.1 h once T_motor stayed
    in).  Now the field following it re-admits it, as after any drift exclusion."""
    mon = _BlamesT0.from_training(None, NAMES, {"a": _field(400, 0), "b": _field(400, 1)})
    events = []
    for i, row in enumerate(_new_source()):
        events += mon.update(row, float(i))[1]
    out = [e for e in events if e["sensor"] == "T_0" and e["to"] == "excluded"]
    assert out and out[0]["reason"].startswith("drift: its reading explains")
    back = [e for e in events if e["sensor"] == "T_0" and e["from"] == "excluded"]
    # before: back only after a calm window ("within ±0.2 °C for 10 samples"), no word of the field
    assert back and "the field followed it" in back[0]["reason"]
    assert back[0]["time"] - out[0]["time"] <= mon.window
    assert any(e["to"] == NEW_STATE for e in events)
