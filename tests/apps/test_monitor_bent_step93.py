"""A step of a sensor no other predicts, under its jump limit, is read by its own last step
(step93; benchmarks/bench_step93.py): a motor warms along a ramp whose one-sample changes change
little from one sample to the next, so a step off its own last one by more than 3 x the largest
such change in training is the sensor's fault, re-referenced by it, the sensor kept in.  Before,
a step under 3 x its largest training step (taken while it warmed fastest) was read as heat
(audit89: +2 degC on swiss's spindle motor, 3 x 0.73 degC its limit).

The line of ``test_monitor_new_state48.py`` (10 sensors the others predict) and a motor no other
predicts, warming and cooling with its own speed steps (a winding and a housing, first-order each)."""

from __future__ import annotations

import numpy as np
import pytest

from conftest import monitored
from test_monitor_new_state48 import NAMES, _field
from thermocomp.apps.deploy.surveillance import SensorMonitor

AT = 300
MOTOR = "T_motor"


def _motor(m: int, seed: int) -> np.ndarray:
    """A motor's housing temperature: its winding first-order towards 25 + 15 x its speed (a new
    speed every 60-120 samples; 8 samples), the housing first-order towards the winding (30
    samples), a little reading noise."""
    rng = np.random.default_rng([seed, 93])
    speed = np.repeat(rng.uniform(0, 1, 20), rng.integers(60, 120, 20))[:m]
    winding, x = np.empty(m), np.empty(m)
    winding[0] = x[0] = 25 + 15 * speed[0]
    for i in range(1, m):
        winding[i] = winding[i - 1] + (25 + 15 * speed[i] - winding[i - 1]) / 8
        x[i] = x[i - 1] + (winding[i] - x[i - 1]) / 30
    return x + rng.normal(scale=0.01, size=m)


def _record(m: int, seed: int) -> np.ndarray:
    return np.column_stack([_field(m, seed), _motor(m, seed)])


def _monitor() -> SensorMonitor:
    return SensorMonitor.from_training(None, [*NAMES, MOTOR], {"a": _record(600, 0),
                                                               "b": _record(600, 1)})


def test_the_motor_is_predicted_by_no_other_and_its_step_is_tighter_than_its_jump():
    mon = _monitor()
    assert not mon._predictable[-1] and mon._predictable[:-1].all()
    assert 3 * mon.max_bend_c[-1] < mon.max_step_c[-1]


@pytest.mark.parametrize("factor", [1.5, 2.5])
def test_a_step_under_the_jump_limit_of_a_sensor_no_other_predicts_is_re_referenced(factor):
    mon = _monitor()
    healthy = _record(600, 2)
    size = factor * mon.max_step_c[-1]           # under its jump limit (3 x)
    record = healthy.copy()
    record[AT:, -1] += size
    fields, events = monitored(mon, record)
    said = [(e["sensor"], e["time"], e["to"]) for e in events]
    assert said == [(MOTOR, float(AT), "re-referenced")], said      # before: nothing at all
    # the model reads the motor as it warms: the step gone but for one sample's change
    truth = healthy[:, -1] - healthy[0, -1]
    assert np.max(np.abs(fields[AT:, -1] - truth[AT:])) < 3 * mon.max_bend_c[-1]
    assert np.max(np.abs(fields[AT:, -1] - truth[AT:])) < 0.25 * size


def test_the_healthy_record_and_its_speed_changes_say_nothing():
    mon = _monitor()
    healthy = _record(600, 2)
    fields, events = monitored(mon, healthy)
    assert events == []
    np.testing.assert_allclose(fields, healthy - healthy[0], atol=1e-9)


def test_a_monitor_pickled_before_the_rule_reads_as_before():
    mon = _monitor()
    state = dict(mon.__dict__)
    for key in ("max_bend_c", "_bend_lim", "_bends", "_last_step"):
        state.pop(key)
    old = SensorMonitor.__new__(SensorMonitor)
    old.__setstate__(state)
    record = _record(600, 2)
    record[AT:, -1] += 2.0 * mon.max_step_c[-1]
    _, events = monitored(old, record)
    assert events == []


def test_a_step_off_its_own_and_its_return_are_undone_with_the_jumps():
    """(step93b) A step of the motor and its return three samples later (a loose contact): the
    first re-referenced and kept in, the second a jump (a second step off its own since it was
    in), and the sensor's return undoes both, its reference back to its first reading -- where
    each was re-referenced and kept, a noise burst on yearround's ``T_amb`` left it 16 °C off."""
    mon = _monitor()
    healthy = _record(600, 2)
    size = 1.5 * mon.max_step_c[-1]
    record = healthy.copy()
    record[AT:AT + 3, -1] += size
    fields, events = monitored(mon, record)
    said = [(e["sensor"], e["time"], e["to"]) for e in events]
    assert said[:2] == [(MOTOR, float(AT), "re-referenced"), (MOTOR, float(AT + 3), "excluded")], said
    assert said[2:] and said[2][0] == MOTOR and said[2][2] == "ok" and len(said) == 3, said
    assert mon._ref[-1] == record[0, -1]                  # both undone: as first referenced
    back = int(said[2][1])
    np.testing.assert_allclose(fields[back:, -1], healthy[back:, -1] - healthy[0, -1], atol=1e-9)
