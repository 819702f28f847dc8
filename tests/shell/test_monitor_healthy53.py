"""A healthy record the monitor must stay quiet on (monitor53; benchmarks/bench_monitor_healthy.py).

A column without its new source (seed 5305, never tuned on), trained on 30 h (the shipped 40 h:
quiet), tested on 20 h of a 25 % larger, phase-shifted ambient swing.  T_left1's band is 0.41 °C
(3x its training spread, the 99.5th percentile of its 10-sample mean error in sample); its healthy
error reaches 0.41 °C on the test day, and the culprit rule (largest |E|(1 - h)) then excludes
T_right3, whose own error is -0.17 °C, for 35 min (E_X 0.73 -> 0.79 µm).  A spread held out
(the basis of the other training blocks) and of the judged statistic (the smallest of the last 2
errors) quiets it, but is unstable where r is near the sensor count (a cut long_record, r = 11 of
14: held-out spreads up to 16x the in-sample ones)
and silenced tests/apps/test_monitor_blame44.py's leaked drift: not merged, the gap is open."""

from __future__ import annotations

import json

import numpy as np
import pandas as pd
import pytest

from conftest import FAST, thermocomp

SIM = ("sim=column_moving_source", "seed=5305", "sim.generator.q3=false",
       "sim.generator.train_hours=30", "sim.generator.test_hours=20")


@pytest.fixture(scope="module")
def column(tmp_path_factory):
    path = tmp_path_factory.mktemp("column53") / "data"
    thermocomp("simulate", *SIM, f"data.path={path}", *FAST)
    return path


def _monitor(path, out) -> dict:
    thermocomp("monitor", f"data.path={path}", "sim=column_moving_source", f"out={out}", *FAST)
    return json.loads((out / "monitor.json").read_text())


@pytest.mark.xfail(strict=True, reason="known gap (monitor53): a training shorter than the "
                   "conditions it is judged in; T_right3 excluded at -0.17 °C for T_left1's 0.41")
def test_a_healthy_column_record_raises_no_event_and_costs_nothing(column, tmp_path):
    report = _monitor(column, tmp_path / "mon")
    assert report["events"] == []
    for t, r in report["targets"].items():
        assert r["rmse_adaptive"] == pytest.approx(r["rmse_fixed"], rel=1e-12), t


def _drifted(path, folder, sensor: str) -> tuple:
    """A copy of the record with 1 K/h on ``sensor`` from half of each test campaign: (copy,
    onset in s from the campaign start)."""
    folder.mkdir()
    manifest = pd.read_csv(path / "campaigns.csv")
    for row in manifest.itertuples():
        df = pd.read_csv(path / row.file)
        if row.split == "test":
            t = df["time"].to_numpy(float)
            onset = t[len(t) // 2]
            df[sensor] += np.clip(t - onset, 0, None) / 3600.0
            since = onset - t[0]
        df.to_csv(folder / row.file, index=False)
    manifest.to_csv(folder / "campaigns.csv", index=False)
    return folder, since


def test_a_drift_on_the_sensor_near_its_band_is_still_excluded(column, tmp_path):
    """1 K/h on T_left1 (the sensor near its band on the healthy test) from half the test
    campaign: out within 50 min (measured 37 min), the adaptive correction better than the fixed
    one on every target (E_X 26.3 -> 5.4 µm): a mend of the gap above must keep this."""
    drifting, onset = _drifted(column, tmp_path / "data", "T_left1")
    report = _monitor(drifting, tmp_path / "mon")
    out = {e["sensor"]: e["time"] for e in report["events"] if e["to"] == "excluded"}
    # its coupled neighbour T_left3 goes out with it (a known limit)
    assert set(out) <= {"T_left1", "T_left3"}
    assert 0 <= out["T_left1"] - onset <= 50 * 60
    for name, r in report["targets"].items():
        assert r["rmse_adaptive"] < r["rmse_fixed"], name


@pytest.mark.xfail(strict=True, reason="known gap (monitor53): the culprit rule (largest "
                   "|E|(1 - h)) passes over a drifting high-leverage sensor")
def test_a_drifting_high_leverage_sensor_is_the_one_excluded(tmp_path):
    """A Swiss lathe (seed 5304, 40 h calibration, the 24 h production run), 1 K/h on
    T_guidebush from 12 h.  The culprit is the largest |E|(1 - h), which passes over a
    high-leverage sensor: the healthy T_nc_x1_drive goes out at 0.58 °C, then T_toolholder1/2,
    T_frame2 and T_headstock leave their bands together, a new thermal state is declared and the
    drift goes on unseen (sum over E_X, E_Y of the squared RMSE: fixed 330, adaptive 541 µm²).
    Taking, once one exclusion explains every band, the largest standardised residual
    |E|·sqrt(1 - h) instead puts T_guidebush out 51 min after the onset (adaptive 5.6 µm²,
    healthy 4.75), but picks T_toolholder1 for a drifting T_toolholder2 (0.33 against 0.32;
    test_monitor_cli's lathe drift: 3.4x the healthy RMSE): not merged."""
    path = tmp_path / "lathe"
    thermocomp("simulate", "sim=swiss_lathe_door", "seed=5304", "sim.generator.calibration_hours=40",
               f"data.path={path}", *FAST)
    drifting, onset = _drifted(path, tmp_path / "data", "T_guidebush")
    report = _monitor(drifting, tmp_path / "mon")
    out = [e for e in report["events"] if e["to"] in ("excluded", "new thermal state")]
    assert out and out[0]["sensor"] == "T_guidebush" and out[0]["time"] - onset <= 60 * 60
    assert not any(e["to"] == "new thermal state" for e in out)
    fixed = sum(r["rmse_fixed"] ** 2 for r in report["targets"].values())
    adaptive = sum(r["rmse_adaptive"] ** 2 for r in report["targets"].values())
    assert adaptive < 0.05 * fixed
