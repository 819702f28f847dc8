"""Two sensors jumping in the same sample (jumps57): each is re-referenced by its step less its
change as the sensors that did NOT jump predict it, so it returns as it read before; one's
prediction from the others had leaned on its jumping partner (offsets of 0.19-0.44 K left, the
sensors never re-admitted).

The line of ``test_monitor_new_state48.py`` (10 sensors, a warm-up and a gradient), streamed
healthy with two sensors offset by +2 K from sample ``AT`` on."""

from __future__ import annotations

import numpy as np
import pytest

from test_monitor_common_step56 import AT, _stream
from test_monitor_new_state48 import _field


@pytest.mark.parametrize("pair", [(4, 5), (0, 9)])   # neighbours; the line's two ends
def test_two_sensors_jumping_at_once_come_back_as_they_read_before(pair):
    healthy = _field(400, 2)
    record = healthy.copy()
    record[AT:, list(pair)] += 2.0
    fields, events = _stream(record)
    names = {f"T_{k}" for k in pair}
    out = [(e["sensor"], e["time"]) for e in events if e["to"] == "excluded"]
    assert sorted(out) == sorted((s, float(AT)) for s in names)
    back = {e["sensor"]: e["time"] for e in events if e["from"] == "excluded" and e["to"] == "ok"}
    assert set(back) == names and max(back.values()) <= AT + 20, back   # calm for a window, twice
    # re-referenced by the sensor's offset alone: the model sees the healthy field again, within
    # the line's sample-to-sample noise (0.02 K on each reading)
    after = int(max(back.values()))
    np.testing.assert_allclose(fields[after:], (healthy - healthy[0])[after:], atol=0.1)
