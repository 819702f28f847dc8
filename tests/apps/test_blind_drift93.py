"""A slow drift of a sensor no other predicts, found by a ridge on the others and the states (monb93).

The monitor's POD has no band for a sensor with its own mode: a column sensor drifting +0.5 °C/h
was read by the model unseen (bench_audit89).  ``monitor.blind_drift`` fits, for each such sensor
with a fallback, a ridge of its change on the judged temperatures and the states' low-pass
responses; where its windowed residual is beyond max(0.4 °C, 3 x its CV spread) and kept growing
over twice the sensor's own e-folding time, the sensor is excluded and its fallback corrects.
Here a column that warms over hours from the spindle's load and from a source no state reads.
"""

from __future__ import annotations

import numpy as np
import pandas as pd
import pytest

import thermocomp.apps.deploy.blind_drift as blind_drift
from thermocomp.apps.deploy import AdaptiveCompensator, StreamingCompensator
from thermocomp.apps.deploy.export import not_in_code
from thermocomp.apps.deploy.report import stream_rows
from thermocomp.core.compensator import Compensator
from thermocomp.core.models import MLR

N, DT = 720, 100.0


def _campaign(seed: int, source: float = 1.0, block: int = 120) -> pd.DataFrame:
    """20 h: five structure sensors warming together, a spindle (fast), a column (4 h) heated by
    the spindle's load and by a source no state reads, switched every ``block`` rows up to
    ``source``."""
    rng = np.random.default_rng(seed)
    t = np.arange(N) * DT
    warm = 3 * (1 - np.exp(-t / 8000)) + 0.5 * np.sin(t / 4000 + seed)
    temps = 20 + warm[:, None] * np.linspace(0.8, 1.2, 5) + rng.normal(0, 0.02, (N, 5))
    speed = np.repeat(rng.uniform(0, 1, N // 60), 60)
    heat = np.repeat(rng.uniform(0, source, -(-N // block)), block)[:N]
    spindle, column = np.zeros(N), np.zeros(N)
    for i in range(1, N):
        spindle[i] = spindle[i - 1] + (8 * speed[i] - spindle[i - 1]) * DT / 900
        column[i] = column[i - 1] + (4 * speed[i] + 3 * heat[i] - column[i - 1]) * DT / 14400
    frame = pd.DataFrame(temps, columns=[f"T_{j}" for j in range(5)])
    frame["T_spindle"] = 20 + spindle + rng.normal(0, 0.02, N)
    frame["T_col"] = 20 + 0.3 * warm + column + rng.normal(0, 0.02, N)
    frame.insert(0, "time", t)
    frame["S_speed"] = speed
    frame["E_Z"] = (3.0 * spindle + 2.0 * column + (frame["T_1"] - frame["T_1"][0])
                    + rng.normal(0, 0.05, N))
    return frame


@pytest.fixture(scope="module")
def train():
    return {f"K{i}": _campaign(i) for i in range(3)}


def _deployed(train, **kw) -> AdaptiveCompensator:
    comp = Compensator(MLR(), inputs=["T_*", "S_*"]).fit(train)
    return AdaptiveCompensator.from_training(StreamingCompensator.from_training(comp, train),
                                             train, **kw)


def _rule_events(deployed, frame) -> list:
    s = stream_rows(deployed, frame, "T")
    return s, [(e["sensor"], e["time"]) for e in s.events
               if str(e.get("reason", "")).startswith("blind drift")]


def test_a_blind_sensors_slow_drift_is_excluded_and_its_fallback_corrects(train):
    deployed, off = _deployed(train), _deployed(train, blind_drift=False)
    assert sorted(deployed.fallbacks_) == ["T_col", "T_spindle"]      # no other predicts them
    assert deployed.blind_drift_.sensors == ["T_spindle", "T_col"]
    assert off.blind_drift_ is None
    # served only: the C names it among the rules it does not follow
    assert "monitor.blind_drift: T_spindle, T_col" in not_in_code(deployed, "c")[-1]
    assert not any("blind_drift" in rule for rule in not_in_code(off, "c"))
    test = _campaign(77)
    h = N // 2
    drifted = test.copy()
    drifted.loc[h:, "T_col"] += 0.5 * (test["time"][h:] - test["time"][h]) / 3600
    error = (test["E_Z"] - test["E_Z"][0]).to_numpy()
    s, found = _rule_events(deployed, drifted)
    assert [sensor for sensor, _ in found] == ["T_col"]
    assert found[0][1] > test["time"][h]
    s_off, none = _rule_events(off, drifted)
    assert none == []
    def rmse(y, start):
        return float(np.sqrt(np.mean((error[start:] - y[start:, 0]) ** 2)))
    out = int(np.searchsorted(test["time"], found[0][1]))
    assert rmse(s.y, out) < 0.5 * rmse(s_off.y, out)     # 1.17 against 6.81 µm once out
    assert rmse(s.y, h) < rmse(s_off.y, h)               # 4.34 against 4.86 after the fault
    # in one go (replay) as row by row (served); a saved state streams on as the stream did
    deployed.reset()
    X, t = drifted[deployed.columns_].to_numpy(float), drifted["time"].to_numpy(float)
    np.testing.assert_allclose(deployed.run_rows(X, t)[0][:, 0], s.y[:, 0], atol=1e-9)
    deployed.reset()
    deployed.run_rows(X[:h + 100], t[:h + 100])
    snap = deployed._snapshot()
    rest = deployed.run_rows(X[h + 100:], t[h + 100:])[0]
    deployed._restore(snap)
    np.testing.assert_array_equal(deployed.run_rows(X[h + 100:], t[h + 100:])[0], rest)


def test_a_healthy_column_warming_over_hours_is_not_excluded(train, monkeypatch):
    deployed, off = _deployed(train), _deployed(train, blind_drift=False)
    # a test campaign whose unseen source heats the column 2.5x training's, switched every
    # 40 rows: the column's residual grows for an hour or two and comes back
    test = _campaign(102, source=2.5, block=40)
    s, found = _rule_events(deployed, test)
    assert found == []
    np.testing.assert_array_equal(s.y, _rule_events(off, test)[0].y)   # main's stream, to the bit
    # the growth read over twice the column's own e-folding time is what keeps it in: read every
    # 10 samples (monb92b's grow6) the same residual crosses
    monkeypatch.setattr(blind_drift, "SPAN_SHARE", np.inf)
    ten = _deployed(train)
    assert list(ten.blind_drift_.spacing_) == [10, 10]
    assert [sensor for sensor, _ in _rule_events(ten, test)[1]] == ["T_col"]
