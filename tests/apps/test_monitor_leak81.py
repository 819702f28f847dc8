"""A sensor no other predicts is re-admitted only once its leak onto the others is within their
re-admission band (mon81): a jig borer's hydraulic tank drifting 1 K/h came back by the band it
had left by (0.99 of ``Bett rechts``'s) and went out again 40 s later, three times; a lathe's
gearbox, out of range, came back inside the range's margin 14.8 K off ("no detector fired").
Here: a nut heated by its own axis, which the others follow a little (its weight in their
field), drifts out of range and comes back within the margin still 8 K off (stays out) or on its
true reading (re-admitted)."""

from __future__ import annotations

import numpy as np
import pytest

from thermocomp.apps.deploy.surveillance import SensorMonitor

NAMES = [f"T_{k}" for k in range(6)] + ["T_nut"]


def _field(m: int, seed: int) -> np.ndarray:
    rng = np.random.default_rng(seed)
    t = np.arange(m)
    warm = 3 * (1 - np.exp(-t / 80)) + 0.5 * np.sin(t / 37)
    gradient = 1.5 * np.sin(t / 53 + seed)
    nut = 2.5 * np.clip(np.sin(t / (23 + 5 * seed) + 2 * seed), 0, None)   # the axis' own heat
    near = 2.0 * nut[:, None] * np.linspace(1, 0, 6)          # the others near it follow it
    x = np.c_[warm[:, None] + gradient[:, None] * np.linspace(-0.5, 0.5, 6) + near, nut]
    return 20 + np.round(x + rng.normal(scale=0.02, size=x.shape), 2)


def _nut_events(off: float) -> tuple[SensorMonitor, list[dict]]:
    """The nut drifting 0.1 K a sample from sample 150 to +13 K (out of range), then ``off`` K
    off its true reading from sample 300."""
    mon = SensorMonitor.from_training(None, NAMES, {f"c{s}": _field(400, s) for s in range(3)})
    record = _field(400, 5)
    record[150:, 6] += np.minimum(0.1 * np.arange(250), 13.0)
    record[300:, 6] -= 13.0 - off
    events = []
    for i, row in enumerate(record):
        events += mon.update(row, float(i))[1]
    return mon, [e for e in events if e["sensor"] == "T_nut"]


@pytest.fixture(scope="module")
def still_off():
    return _nut_events(8.0)


def test_the_nut_is_one_no_other_predicts_and_goes_out_of_range(still_off):
    mon, events = still_off
    assert not mon._predictable[6] and mon._predictable[:6].all()
    assert events[0]["to"] == "excluded" and events[0]["reason"].startswith("out of range"), events


def test_back_within_the_margin_but_off_the_others_field_it_stays_out(still_off):
    mon, events = still_off
    # its reading is back inside the range's margin and no detector fires: shipped re-admitted it
    assert [e["to"] for e in events] == ["excluded"], events
    assert "T_nut" in mon.excluded
    # what keeps it out: its reading moves the others' self-prediction errors by more than half
    # their warning band (with it in the fit against without it)
    trial = np.ones(len(NAMES), dtype=bool)
    M, lev = mon._operator(trial)
    H = np.where(np.isfinite(mon._hist), mon._hist, 0.0)
    assert mon._leak(6, trial, H, M, lev) >= 0.5


def test_back_on_its_true_reading_it_is_re_admitted_and_says_its_leak():
    mon, events = _nut_events(0.0)
    assert [e["to"] for e in events] == ["excluded", "ok"], events
    reason = events[1]["reason"]
    assert reason.startswith("re-admitted: no detector fired for 10 samples, its leak onto them "
                             "within "), reason
    assert float(reason.split("within ")[1].split(" ")[0]) < 0.5
    assert not mon.excluded
