"""A healthy record the monitor must stay quiet on (monitor53; benchmarks/bench_monitor_healthy.py).

A column without its new source (seed 5305, never tuned on), trained on 30 h (the shipped 40 h:
quiet), tested on 20 h of a 25 % larger, phase-shifted ambient swing.  T_left1's band is 0.41 °C
(3x its training spread, the 99.5th percentile of its 10-sample mean error in sample); its healthy
error reaches 0.41 °C on the test day, and the culprit rule (largest |E|(1 - h)) then excludes
T_right3, whose own error is -0.17 °C, for 35 min (E_X 0.73 -> 0.79 µm).  A spread held out
(the basis of the other training blocks) and of the judged statistic (the smallest of the last 2
errors) quiets it, but is unstable where r is near the sensor count (a cut long_record, r = 11 of
14: held-out spreads up to 16x the in-sample ones)
and silenced tests/apps/test_monitor_blame44.py's leaked drift: not merged, the gap is open.
The judged statistic alone, in sample (monitor54), quiets it too (T_left1's band 0.44 °C) and
silences the same leaked drift (T_xdrive 0.665 °C against a 0.692 band): not merged either.
Excluding instead the sensor out of band whose exclusion explains the others (T_left1) costs more
(T_left1 and its coupled T_left3 out, E_X 0.73 -> 2.93 µm).
Bands widened by the sample's distance from training (shorttrain58,
benchmarks/bench_monitor_shorttrain58.py) cannot quiet it: where T_left1 peaks the sample lies
inside training's cloud (mode coefficients 0.63, the predictors' residual 0.94 of training's
largest distance).
monitor64 (benchmarks/bench_monitor64.py): T_left1's smallest |E| of the last 2 is 0.4068 against
its 0.4052 band on one row; judging the window's mean too, or the last 3 errors, quiets it but
flags drifts later and makes a fresh short-trained mill louder (8 -> 78 / 54 events): refused.
mon86b (benchmarks/bench_mon86b.py): the pick is _lone_fault's first check (T_right3's exclusion
brings T_left1 within band), not mon86's bands; not taking a culprit within band where the likelier
single fault is out of band leaves T_left1's warning (one episode) and excluded a lathe's hovering
healthy offset (test_monitor_regime73): refused.  mon87 (benchmarks/bench_mon87.py): the regime
check asked before that hand-over holds the lathe's offset and quiets the column by mon87's criterion
(one warning, 0.0016 °C past the band against its 0.032 rounding bound, for one sample); kept in
mon87b, once test_export_mon85b was given a record that still reaches its branch under it.

A drifting sensor of high leverage (monitor54): the culprit rule's pick explained the bands only
by raising the drifting sensor's leverage past judging; such an exclusion no longer counts as an
explanation (SensorMonitor._lone_fault)."""

from __future__ import annotations

import json
import re

import numpy as np
import pandas as pd
import pytest
from omegaconf import OmegaConf

from conftest import FAST, ROOT, thermocomp

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


def _excess_at_most(reason: str, band: float) -> float:
    """How far past ``band`` a warning's smallest error is at most, from its reason (3
    significant digits: half the last one added)."""
    shown = float(re.search(r"the smallest ([0-9.]+)", reason).group(1))
    return shown + 0.5 * 10.0 ** (np.floor(np.log10(shown)) - 2) - band


def test_a_healthy_column_record_is_quiet_and_costs_nothing(column, tmp_path):
    """Nothing excluded, no alarm and no new thermal state, the served correction the fixed one;
    a warning only where the reading cannot tell it from rounding (mon87, docs/monitoring.md):
    past its band by less than the sensor's rounding bound and withdrawn before ``confirm``
    samples (measured: T_left1 past its band for one sample)."""
    report = _monitor(column, tmp_path / "mon")
    names, bands = list(report["sensors"]), report["bands"]
    confirm = OmegaConf.load(ROOT / "conf" / "monitor" / "default.yaml")["confirm"]
    assert not [e for e in report["events"] if e["to"] not in ("warning", "ok")]
    for e in report["events"]:
        if e["to"] == "warning":
            i = names.index(e["sensor"])
            assert _excess_at_most(e["reason"], bands["warning_c"][i]) < bands["rounding_c"][i], e
    for name, s in report["sensors"].items():
        assert s["state_counts"]["alarm"] == s["state_counts"]["excluded"] == 0, name
        assert s["state_counts"]["warning"] < confirm, name
    assert report["alarms"]["new_thermal_states"] == 0
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


def test_a_drifting_high_leverage_sensor_is_the_one_excluded(tmp_path):
    """A Swiss lathe (seed 5304, 40 h calibration, the 24 h production run), 1 K/h on
    T_guidebush (leverage 0.71) from 12 h.  The culprit, the largest |E|(1 - h), was the healthy
    T_nc_x1_drive (-0.58 °C, within its 0.68 band), whose exclusion "explained" T_guidebush's
    +0.93 °C (band 0.88) by raising its leverage to 0.96, past judging; then T_toolholder1/2,
    T_frame2 and T_headstock left their bands together, a new thermal state was declared and the
    drift went on unseen (sum over E_X, E_Y of the squared RMSE: fixed 330, adaptive 541 µm²).
    Now an exclusion that leaves a sensor out of band unjudged explains nothing, and
    T_guidebush, which explains the bands and is the larger standardised residual (0.51
    against 0.48), goes out 51 min after the onset (adaptive 5.6 µm², healthy 4.75)."""
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
