"""A sensor's bands are those of the set it is judged in (mon86): fl_thermal's healthy T_t14,
back once the drifting T_t12 is out, is judged in a set that predicts it worse in training too.

fl_thermal's spindle record, the monitor trained on its first 10003 samples (bench_mon86)."""

from __future__ import annotations

import pickle

import numpy as np
import pandas as pd
import pytest

from thermocomp.apps.deploy.pod import windowed_mean
from thermocomp.apps.deploy.surveillance import SensorMonitor

NAMES = [f"T_t{k}" for k in range(1, 17)]
CUT, ONSET = 10003, 10003 + 240
T12, T14 = NAMES.index("T_t12"), NAMES.index("T_t14")


@pytest.fixture(scope="module")
def record() -> np.ndarray:
    from conftest import ROOT

    frame = pd.read_csv(ROOT / "datasets" / "fl_thermal" / "spindle_test.csv")
    return frame[[f"t{k}(°C)" for k in range(1, 17)]].to_numpy(float)


@pytest.fixture(scope="module")
def mon(record) -> SensorMonitor:
    return SensorMonitor.from_training(None, NAMES, {"train": record[:CUT]})


def _streamed(mon: SensorMonitor, x: np.ndarray) -> list[dict]:
    mon = pickle.loads(pickle.dumps(mon))
    events = []
    for i, row in enumerate(x):
        got = mon.update(row, 15.0 * i)[1]
        events += got if i >= CUT else []
    return events


def test_the_scale_of_a_band_is_the_windowed_errors_rms_in_its_set_against_the_whole_set(record, mon):
    """The moment ``a' C a`` is the training windowed error's mean square, measured here on the
    training snapshots themselves, in the set without T_t12 against every sensor in."""
    snaps = record[:CUT] - record[0]
    W = windowed_mean(snaps, None, mon.pod.window)
    rms = []
    for subset in (np.ones(len(NAMES), bool), np.arange(len(NAMES)) != T12):
        M, lev = mon._operator(subset)
        e = (W[:, T14] - W[:, subset] @ M[T14]) / (1 - lev[T14])
        rms.append(np.sqrt(np.mean(e ** 2)))
    warn, alarm = mon._bands_of(np.arange(len(NAMES)) != T12)
    g = rms[1] / rms[0]
    assert g > 1
    assert warn[T14] == pytest.approx(max(mon.warning_c[T14], mon.floor_c[T14] * g), rel=1e-9)
    assert alarm[T14] == pytest.approx(max(mon.alarm_c[T14], 2 * mon.floor_c[T14] * g), rel=1e-9)
    assert warn[T14] > mon.warning_c[T14]        # the set predicts it worse than its band allows
    assert (warn >= mon.warning_c).all() and (alarm >= mon.alarm_c).all()
    every = mon._bands_of(np.ones(len(NAMES), bool))
    assert (every[0] == mon.warning_c).all() and (every[1] == mon.alarm_c).all()


def test_a_culprit_out_within_its_band_loosens_no_band(mon):
    """Out on the monitor's guess (mon85b's ``_hid``): the set that sets the bands counts it in,
    so the drift it hid (its coupled partner's) is not held to a looser band too."""
    m = pickle.loads(pickle.dumps(mon))
    m._active[T14] = False
    m._set_operator()
    assert m._warn[T12] > m.warning_c[T12]        # out for its own error: the set's band
    m._hid[T14] = True
    m._set_bands()
    assert (m._warn == m.warning_c).all() and (m._alarm == m.alarm_c).all()


def test_the_healthy_sensor_back_after_the_drifting_one_is_out_no_longer_warns(record, mon):
    """T_t14, out within its band while T_t12 drifted, back once T_t12 is out: judged in the set
    without T_t12 against that set's band, it no longer goes to warning to the end (the whole
    set's band, in which training predicts it better, had it warn on the healthy record), and
    T_t12 is still out when it was (its band is the whole set's while T_t14 is out)."""
    x = record.copy()
    x[ONSET:, T12] += np.arange(len(x) - ONSET) * 15 / 3600
    events = _streamed(mon, x)
    out = [e["time"] for e in events if e["sensor"] == "T_t12" and e["to"] == "excluded"]
    back = [e["time"] for e in events if e["sensor"] == "T_t14" and e["from"] == "excluded"]
    assert out and back and back[-1] >= out[0]
    after = [e for e in events if e["sensor"] == "T_t14" and e["time"] >= back[-1]
             and e["to"] in ("warning", "alarm")]
    assert not after, after[:3]
    # the same rule, every sensor in: the clean record says nothing after the train part
    assert not _streamed(mon, record)


def test_a_monitor_pickled_before_the_rule_judges_every_set_by_the_whole_sets_bands(mon):
    state = dict(mon.__dict__)
    for key in ("floor_c", "moment", "_q_full", "_warn", "_alarm"):
        del state[key]
    old = SensorMonitor.__new__(SensorMonitor)
    old.__setstate__(pickle.loads(pickle.dumps(state)))
    old._active[T12] = False
    old._set_operator()
    assert (old._warn == old.warning_c).all() and (old._alarm == old.alarm_c).all()
