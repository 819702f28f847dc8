"""The ambient sensor of a one-campaign training is warned, not excluded, by the drift rule
(quiet94; benchmarks/bench_quiet94.py).  Trained on one campaign, the POD learns the day's
co-trend of the air with the warming machine, which breaks as soon as the stream leaves the rows
it was fitted on: a healthy ``T_amb`` then left its band and was excluded by drift on 7 of 15
short simulated records (quiet93), and the model read the air rebuilt from the machine.

The line of ``test_monitor_new_state48.py`` (10 sensors the others predict, warming with a time
constant of 80 samples) and an air that warms with the day, 0.01 °C per sample: trained on the
first 120 samples, the machine nearly warm by then, the air still rising."""

from __future__ import annotations

import numpy as np

from conftest import monitored
from test_monitor_new_state48 import NAMES, _field
from thermocomp.apps.deploy.surveillance import SensorMonitor

AMBIENT = [*NAMES, "T_amb"]
TRAIN, SEED = 120, 1


def _record(m: int = 360, seed: int = SEED) -> np.ndarray:
    noise = np.random.default_rng([seed, 94]).normal(scale=0.02, size=m)
    return np.column_stack([_field(m, seed), 21 + 0.01 * np.arange(m) + noise])


def _monitor(record: np.ndarray, **options) -> SensorMonitor:
    return SensorMonitor.from_training(None, AMBIENT, {"a": record[:TRAIN]}, **options)


def test_one_training_campaign_marks_the_ambient_and_two_mark_none():
    record = _record()
    assert _monitor(record).drift_warn_only.tolist() == [False] * len(NAMES) + [True]
    two = SensorMonitor.from_training(None, AMBIENT, {"a": record[:TRAIN],
                                                      "b": _record(TRAIN, SEED + 1)})
    assert not two.drift_warn_only.any()


def test_the_healthy_air_leaving_the_days_co_trend_is_warned_and_read_as_read():
    record = _record()
    # the contrast (main's rule, no sensor warn-only): the healthy air out by drift
    _, before = monitored(_monitor(record, drift_warn_only=None), record)
    assert [(e["sensor"], e["to"]) for e in before if e["to"] == "excluded"] == [("T_amb",
                                                                                 "excluded")]
    fields, events = monitored(_monitor(record), record)
    assert not [e for e in events if e["to"] == "excluded"], events
    said = [e["to"] for e in events if e["sensor"] == "T_amb"]
    assert said[:2] == ["warning", "alarm"], said        # judged: the user is told
    # the model reads the air as measured, not rebuilt from the machine's field
    np.testing.assert_allclose(fields[:, -1], record[:, -1] - record[0, -1], atol=1e-12)


def test_a_machine_sensor_drifting_beside_the_warned_air_is_still_excluded():
    record = _record()
    record[200:, 3] += 0.02 * np.arange(len(record) - 200)
    _, events = monitored(_monitor(record), record)
    out = [(e["sensor"], e["time"]) for e in events if e["to"] == "excluded"]
    assert len(out) == 1 and out[0][0] == "T_3" and out[0][1] > 200, out


def test_a_monitor_pickled_before_the_rule_excludes_the_air_as_before():
    record = _record()
    state = dict(_monitor(record).__dict__)
    state.pop("drift_warn_only")
    old = SensorMonitor.__new__(SensorMonitor)
    old.__setstate__(state)
    _, events = monitored(old, record)
    assert ("T_amb", "excluded") in [(e["sensor"], e["to"]) for e in events]


def test_the_exported_c_holds_the_warned_air_and_no_longer_names_it():
    """(quiet94c) The C holds the rule (``warn_only``): the export names no such drift, one
    sentence as with two campaigns; the arrays carry the flag of T_amb alone."""
    from thermocomp.apps.deploy.adaptive import AdaptiveCompensator
    from thermocomp.apps.deploy.export import not_in_code

    record = _record()
    deployed = AdaptiveCompensator.__new__(AdaptiveCompensator)   # what not_in_code reads
    deployed.monitor = _monitor(record)
    one = not_in_code(deployed, "c")
    deployed.monitor = SensorMonitor.from_training(None, AMBIENT, {"a": record[:TRAIN],
                                                                   "b": _record(TRAIN, SEED + 1)})
    assert one == not_in_code(deployed, "c") and len(one) == 1
    assert "a drift of T_amb" not in one[0]
