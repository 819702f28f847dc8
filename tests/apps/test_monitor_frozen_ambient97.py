"""A frozen slow ambient (mon97, benchmarks/bench_mon97.py; audit96's sw9776): a stuck logger
holds ``T_amb`` while the room warms 0.2 °C an hour, less than the warning band in the hour the
field's freeze rule would need.  Its readings dither over their 0.01 °C resolution (0.03 °C
noise), so a constant run longer than ``blind_run`` is a freeze whatever the field did: out at
the onset + ``blind_run`` + 1, served and in the export's mirror alike (before mon97: never).  A
noiseless 0.1 K logger's readings do not dither: its sensors are judged as before (flat for
hours on a settled machine, tests/apps/test_monitor_rounding83.py)."""

from __future__ import annotations

import numpy as np

from test_monitor_long_freeze91 import code_freezes
from thermocomp.apps.deploy.surveillance import SensorMonitor

NAMES = ["T_amb"] + [f"T_{k}" for k in range(6)]
AT, HELD = 300, 60           # the freeze's onset and length (rows of 60 s)


def _field(m: int, seed: int, noise: float = 0.03, quantum: float = 0.01) -> np.ndarray:
    """The room warming 0.2 °C an hour with a slow swing, six machine sensors following it
    and a duty cycle's heat, each read with ``noise`` on a ``quantum`` logger."""
    rng = np.random.default_rng(seed)
    hours = np.arange(m) / 60
    room = 20 + 0.2 * hours + 0.1 * np.sin(hours / 2 + seed)
    heat = 1.5 * (1 - np.exp(-hours / 1.5)) + 0.4 * np.sin(hours * 1.3 + seed)
    gains = np.linspace(0.3, 1.2, 6)
    x = np.c_[room, room[:, None] + heat[:, None] * gains]
    x = x + rng.normal(scale=noise, size=x.shape)
    return np.round(x / quantum) * quantum


def _monitor(**field) -> SensorMonitor:
    return SensorMonitor.from_training(None, NAMES, {"a": _field(600, 0, **field),
                                                     "b": _field(600, 1, **field)})


def _record(frozen: bool, **field) -> np.ndarray:
    record = _field(480, 2, **field)
    if frozen:
        record[AT:AT + HELD, 0] = record[AT, 0]
    return record


def _served(mon: SensorMonitor, record: np.ndarray) -> list[dict]:
    events = []
    for i, row in enumerate(record):
        events += mon.update(row, float(i))[1]
    return events


def _code(record: np.ndarray, drop: tuple = ()) -> list[tuple[float, str]]:
    return code_freezes(_monitor(), record, drop)


def test_the_frozen_ambient_goes_out_for_its_freeze_once_constant_past_blind_run():
    mon = _monitor()
    events = _served(mon, _record(frozen=True))
    out = [(e["time"], e["sensor"], e["reason"]) for e in events if e["to"] == "excluded"]
    assert [(t, name) for t, name, _ in out] == [(AT + mon._blind_run[0] + 1, "T_amb")], out
    assert "its noise spans its resolution" in out[0][2]
    assert mon.dithered.all() and mon._blind_run[0] < HELD


def test_the_healthy_record_stays_quiet():
    assert _served(_monitor(), _record(frozen=False)) == []


def test_the_exported_monitor_takes_it_out_as_served_and_an_older_export_does_not():
    record = _record(frozen=True)
    served = [(e["time"], e["sensor"]) for e in _served(_monitor(), record) if e["to"] == "excluded"]
    assert served and _code(record) == served
    assert _code(record, drop=("dither_run",)) == []       # an export before the key: as before


def test_a_noiseless_logger_does_not_dither_and_is_judged_as_before():
    mon = _monitor(noise=0.0, quantum=0.1)
    assert not mon.dithered.any() and np.isinf(mon._dither_run).all()


def test_a_monitor_pickled_before_the_rule_keeps_its_last_steps_and_judges_as_before():
    """A monitor pickled after step93, before mon97 (no ``dithered``): loaded, its last one-sample
    steps mid-stream are kept (the bend test reads them) and no freeze is judged by the run alone."""
    import pickle

    mon = _monitor()
    record = _record(frozen=True)
    for i, row in enumerate(record[:AT]):
        mon.update(row, float(i))
    state = {k: v for k, v in mon.__dict__.items() if k not in ("dithered", "_dither_run")}
    old = SensorMonitor.__new__(SensorMonitor)
    old.__setstate__(pickle.loads(pickle.dumps(state)))
    np.testing.assert_array_equal(old._last_step, mon._last_step)
    assert np.isfinite(old._last_step).all()
    events = [e for i, row in enumerate(record[AT:], AT) for e in old.update(row, float(i))[1]]
    assert not [e for e in events if e["to"] == "excluded" and e["sensor"] == "T_amb"]
