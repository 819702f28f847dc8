"""A one-sample spike of a sensor the others predict is no jump (mon89's rule, kept by bar91b;
benchmarks/bench_bar91b.py): the sensor, out at the spike, is in again at the next sample, its
reference before the spike put back, so the model reads its reading as it was referenced from
the start.  Re-referenced by the return's whole step instead (as before), it kept the others'
one-sample prediction noise in its reference and waited out its calm window.

The line of ``test_monitor_new_state48.py`` (10 sensors, a warm-up and a gradient), streamed
healthy with a spike on one sensor at sample ``AT``."""

from __future__ import annotations

import numpy as np
import pytest

from test_monitor_common_step56 import AT, _stream
from test_monitor_new_state48 import _field


@pytest.mark.parametrize(("sensor", "size"), [(4, -3.0), (7, 2.5)])
def test_a_one_sample_spike_is_over_at_the_next_sample(sensor, size):
    record = _field(400, 2)
    record[AT, sensor] += size
    fields, events = _stream(record)
    moves = [(e["to"], e["time"]) for e in events if e.get("sensor") == f"T_{sensor}"]
    assert moves == [("excluded", float(AT)), ("ok", float(AT + 1))], moves
    # its reference is the one it started with: the model reads it as referenced from the start
    after = (record - record[0])[AT + 1:, sensor]
    np.testing.assert_allclose(fields[AT + 1:, sensor], after, rtol=0, atol=1e-12)
