"""The warned air of a one-campaign training predicts none of the others (quiet94b;
benchmarks/bench_quiet94b.py).  Kept in the POD operator that judges them (quiet94), its departure
from the day's co-trend leaked onto their errors where they lean on it: on this line (seed 2) a
new thermal state declared on healthy data, and a drifting ``T_3`` alarmed but never excluded.

The record of ``test_monitor_ambient_one_campaign94.py``: 10 sensors warming with a time constant
of 80 samples and an air warming 0.01 °C per sample, trained on the first 120 samples."""

from __future__ import annotations

import numpy as np

from conftest import monitored
from test_monitor_ambient_one_campaign94 import _monitor, _record
from thermocomp.apps.deploy.surveillance import SensorMonitor

LEANING = 2   # a seed whose machine sensors lean on the air in the one-campaign fit


def test_the_warned_airs_column_is_out_of_the_others_operator_and_its_own_row_kept():
    mon = _monitor(_record(seed=LEANING))
    n = len(mon.names)
    every = np.ones(n, dtype=bool)
    M, lev = mon._operator(every)
    air = n - 1
    # the others predicted as with the air excluded, the air from every sensor as before
    rest, h_rest = mon.pod.operator(np.arange(n) != air)
    full, h_full = mon.pod.operator(every)
    np.testing.assert_allclose(M[:, air][:air], 0.0, atol=0)
    np.testing.assert_allclose(M[:air, :air], rest[:air], atol=1e-12)
    np.testing.assert_allclose(lev[:air], h_rest, atol=1e-12)
    np.testing.assert_allclose(M[air], full[air], atol=1e-12)
    assert lev[air] == h_full[air]
    # two campaigns: nothing warned, nothing muted
    two = SensorMonitor.from_training(None, mon.names, {"a": _record(seed=LEANING)[:120],
                                                        "b": _record(120, LEANING + 1)})
    np.testing.assert_allclose(two._operator(every)[0], two.pod.operator(every)[0], atol=1e-12)


def test_the_healthy_air_leaves_its_co_trend_without_a_new_state_on_the_others():
    record = _record(seed=LEANING)
    _, events = monitored(_monitor(record), record)
    assert not [e for e in events if e["to"] in ("excluded", "new thermal state")], events
    assert "alarm" in [e["to"] for e in events if e["sensor"] == "T_amb"]   # still warned


def test_a_drift_beside_the_departing_air_is_excluded():
    record = _record(seed=LEANING)
    record[200:, 3] += 0.02 * np.arange(len(record) - 200)
    _, events = monitored(_monitor(record), record)
    out = [(e["sensor"], e["time"]) for e in events if e["to"] == "excluded"]
    assert len(out) == 1 and out[0][0] == "T_3" and out[0][1] > 200, events
    assert not [e for e in events if e["to"] == "new thermal state"], events

