"""Alarms a shop floor can live with (issue 36 item 5): healthy campaigns unlike the training ones
raise at most one exclusion per 100 h, and a sensor cannot flap in and out.

The fault matrix (freeze, jump, drift flagged within the time they become observable) is in
tests/shell/test_monitor.py and tests/shell/test_monitor_cli.py and runs with the same defaults.
"""

from __future__ import annotations

import json
import shutil
from pathlib import Path

import numpy as np
import pandas as pd
import pytest

from conftest import thermocomp
from thermocomp.apps.deploy.surveillance import SensorMonitor

MAX_PER_100H = 1.0


def _field(seed, n=12, m=3000, r=3):
    """A field of ``r`` fixed modes (the same on every campaign), slow random-walk amplitudes."""
    rng = np.random.default_rng(seed)
    modes = np.linalg.qr(np.random.default_rng(0).normal(size=(n, r)))[0]
    coef = np.cumsum(rng.normal(size=(m, r)), axis=0) * [0.5, 0.2, 0.1]
    return 20 + coef @ modes.T + rng.normal(scale=0.01, size=(m, n))


def test_a_sensor_wandering_in_and_out_of_the_band_cannot_flap():
    """Each exclusion by its error after the first makes the sensor wait twice as long to return:
    over n samples at most about log2(n / window) exclusions, not one per excursion (50 of 50
    excursions were an exclusion before)."""
    names = [f"T_{j}" for j in range(12)]
    mon = SensorMonitor.from_training(None, names, {f"K{k}": _field(k) for k in range(4)},
                                      window=10)
    x = _field(9)
    period = 60                    # an offset of twice the band, on for 20 samples in every 60
    on = (np.arange(len(x)) % period) >= period - 20
    x[:, 3] += np.where(on, 2 * mon.warning_c[3], 0.0)
    events = []
    for row in x:
        events += mon.update(row)[1]
    excluded = [e for e in events if e["sensor"] == "T_3" and e["to"] == "excluded"]
    assert {e["sensor"] for e in events} == {"T_3"}
    excursions = int(np.sum(on[1:] & ~on[:-1]))
    assert excursions >= 40
    assert 1 <= len(excluded) <= 1 + np.log2(len(x) / mon.window), len(excluded)


def _monitor(out: Path, *args: str) -> dict:
    thermocomp("monitor", "track=false", "plots=none", f"out={out}", *args)
    return json.loads((out / "monitor.json").read_text())


def test_the_measured_record_s_healthy_test_part_excludes_no_sensor(tmp_path):
    """fl 90/10 with ARX: the healthy T_13 was excluded 21 times after the warm-up (a loosely
    predicted T_9 left the band, and the culprit pick took T_13), and the adaptive ch2 error was
    4.04 µm against the fixed 2.70.  Nor is the healthy correction rate-limited: the guard's rate
    came from the measured error alone, which the model fed by noisy sensors outpaces (MLR: 113
    rate_limited/free pairs in 4.6 h)."""
    report = _monitor(tmp_path, "data=fl_thermal", "data.test_fraction=0.1", "model=arx")
    assert not [e for e in report["events"] if e["sensor"] is None], "a guard event"
    excluded = [e for e in report["events"] if e["sensor"] and e["to"] == "excluded"]
    hours = 1111 * 15 / 3600           # the test part: 1112 rows at 15 s
    assert len(excluded) <= MAX_PER_100H * hours / 100, excluded[:3]
    for target, r in report["targets"].items():
        assert r["rmse_adaptive"] <= 1.05 * r["rmse_fixed"], (target, r)
    assert report["alarms"]["hours"] == pytest.approx(hours, rel=0.01)
    assert report["alarms"]["exclusions_per_100h"] == 0.0


SIM = ["track=false", "sim.generator.sample_period_s=60", "sim.generator.n_campaigns=12",
       "sim.generator.duration_h=[8.0,8.0]"]


def test_healthy_campaigns_of_another_machine_and_season_stay_under_the_rate(tmp_path):
    """Trained on one simulated machine, streamed on the test campaigns of another (new seed, an
    ambient 5.5 °C warmer with a larger daily swing): never tuned on."""
    a, b, mixed = tmp_path / "a", tmp_path / "b", tmp_path / "mixed"
    thermocomp("simulate", f"data.path={a}", "seed=31", *SIM)
    thermocomp("simulate", f"data.path={b}", "seed=32", *SIM,
               "sim.generator.ambient={annual_mean_c:24.0,daily_amplitude_c:5.0}")
    mixed.mkdir()
    ma, mb = pd.read_csv(a / "campaigns.csv"), pd.read_csv(b / "campaigns.csv")
    ma, mb = ma[ma.split == "train"], mb[mb.split == "test"].copy()
    for row in ma.itertuples():
        shutil.copy(a / row.file, mixed / row.file)
    for row in mb.itertuples():
        shutil.copy(b / row.file, mixed / f"B{row.file}")
    mb["campaign"], mb["file"] = "B" + mb.campaign, "B" + mb.file
    pd.concat([ma, mb]).to_csv(mixed / "campaigns.csv", index=False)
    alarms = _monitor(tmp_path / "out", f"data.path={mixed}")["alarms"]
    assert alarms["hours"] == pytest.approx(4 * 8, rel=0.01)
    assert alarms["exclusions"] <= MAX_PER_100H * alarms["hours"] / 100, alarms
