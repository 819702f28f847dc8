"""Cost of monitoring + compensating one sample for 50 sensors (issue 14).

Builds a synthetic 50-sensor field (4 thermal modes + noise, 10 training campaigns), fits
MLR, wraps it in the AdaptiveCompensator (POD self-prediction, detectors, guard) and times
``_step`` per sample on a healthy stream and on one where a sensor drops out (excluded and
rebuilt from the field every sample), against a bare NumPy 50×50 matrix-vector product.

    .venv/bin/python benchmarks/bench_monitor.py
    .venv/bin/python benchmarks/bench_monitor.py --alarms   # false-alarm rate per scenario

``--alarms`` (issue 36): ``monitor`` on healthy test campaigns unlike the training ones
(other seeds, another ambient level, a coarser logger, a long shop-floor record, the measured
record's 90/10 cut) and the sensor exclusions per 100 h of healthy data (target: at most 1).
"""

from __future__ import annotations

import json
import shutil
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np
import pandas as pd

from thermocomp.apps.deploy import StreamingCompensator
from thermocomp.apps.monitor import AdaptiveCompensator
from thermocomp.core.compensator import Compensator
from thermocomp.core.models import MLR

N_SENSORS, N_ROWS = 50, 300


def campaign(rng, modes, n=N_ROWS):
    t = np.arange(n) * 60.0
    coef = np.cumsum(rng.normal(scale=0.05, size=(n, modes.shape[1])), axis=0)
    T = 20 + coef @ modes.T + rng.normal(scale=0.02, size=(n, N_SENSORS))
    df = pd.DataFrame(T, columns=[f"T_s{j:02d}" for j in range(N_SENSORS)])
    df.insert(0, "time", t)
    df["E_Z"] = (T - T[0]) @ rng.normal(size=N_SENSORS) * 0 + coef @ [3.0, -2.0, 1.0, 0.5]
    return df


def per_sample_us(model, df, repeats=3):
    X, t = df[model.columns_].to_numpy(float), df["time"].to_numpy(float)
    best = np.inf
    for _ in range(repeats):
        model.reset()
        start = time.perf_counter()
        for i in range(len(X)):
            model._step(X[i], t[i])
        best = min(best, (time.perf_counter() - start) / len(X))
    return 1e6 * best


def main():
    rng = np.random.default_rng(0)
    modes = np.linalg.qr(rng.normal(size=(N_SENSORS, 4)))[0] * 8
    train = {f"K{k:02d}": campaign(rng, modes) for k in range(10)}
    test = campaign(rng, modes, 2000)
    comp = Compensator(MLR()).fit(train)
    streaming = StreamingCompensator.from_training(comp, train)
    adaptive = AdaptiveCompensator.from_training(StreamingCompensator.from_training(comp, train), train)
    faulty = test.copy()
    faulty.loc[100:, "T_s07"] = float("nan")        # a dropout: excluded, rebuilt every sample
    M, x = rng.normal(size=(N_SENSORS, N_SENSORS)), rng.normal(size=N_SENSORS)
    n = 200_000
    start = time.perf_counter()
    for _ in range(n):
        M @ x
    matvec = 1e6 * (time.perf_counter() - start) / n
    bare = per_sample_us(streaming, test)
    healthy = per_sample_us(adaptive, test)
    fault = per_sample_us(adaptive, faulty)
    print(f"sensors {N_SENSORS}, POD modes r={adaptive.monitor.r_}")
    print(f"numpy 50x50 matvec          {matvec:8.2f} µs")
    print(f"streaming compensator (MLR) {bare:8.2f} µs  ({bare / matvec:.0f}x matvec)")
    print(f"monitor + compensation      {healthy:8.2f} µs  ({healthy / matvec:.0f}x matvec) healthy")
    print(f"monitor + compensation      {fault:8.2f} µs  ({fault / matvec:.0f}x matvec) "
          "one sensor out (dropout)")


ROOT = Path(__file__).resolve().parents[1]
YEAR = ["sim.generator.sample_period_s=60", "sim.generator.n_campaigns=12",
        "sim.generator.duration_h=[8.0,8.0]"]
# name -> (train simulation, test simulation or None: its own test split, monitor overrides)
SCENARIOS = {
    "yearround, test 5.5 °C warmer": (
        ["seed=31", *YEAR],
        ["seed=32", *YEAR, "sim.generator.ambient={annual_mean_c:24.0,daily_amplitude_c:5.0}"], []),
    "yearround, 0.1 °C logger, cooler": (
        ["seed=41", *YEAR, "sim.generator.temp_quantum_c=0.1", "sim.generator.temp_noise_c=0.05"],
        ["seed=42", *YEAR, "sim.generator.temp_quantum_c=0.1", "sim.generator.temp_noise_c=0.05",
         "sim.generator.ambient={annual_mean_c:12.0}"], []),
    "long_record (shop floor, 3 weeks)": (["sim=long_record", "seed=5"], None, ["sim=long_record"]),
    "column, no new source": (["sim=column_moving_source", "sim.generator.q3=false", "seed=8"], None,
                              ["sim=column_moving_source"]),
    "fl_thermal 90/10, ARX": (None, None, ["data=fl_thermal", "data.test_fraction=0.1", "model=arx"]),
}


def thermocomp(*args):
    subprocess.run([str(Path(sys.executable).parent / "thermocomp"), "-q", *args, "track=false"],
                   cwd=ROOT, check=True, capture_output=True)


def mixed(root: Path, train: list, test: list) -> Path:
    """The train campaigns of one simulation with the test campaigns of another."""
    a, b, out = root / "a", root / "b", root / "mixed"
    thermocomp("simulate", f"data.path={a}", *train)
    thermocomp("simulate", f"data.path={b}", *test)
    out.mkdir()
    ma, mb = pd.read_csv(a / "campaigns.csv"), pd.read_csv(b / "campaigns.csv")
    ma, mb = ma[ma.split == "train"], mb[mb.split == "test"].copy()
    for row in ma.itertuples():
        shutil.copy(a / row.file, out / row.file)
    for row in mb.itertuples():
        shutil.copy(b / row.file, out / f"B{row.file}")
    mb["campaign"], mb["file"] = "B" + mb.campaign, "B" + mb.file
    pd.concat([ma, mb]).to_csv(out / "campaigns.csv", index=False)
    return out


def alarms():
    print(f"{'scenario':<36} {'hours':>7} {'exclusions':>10} {'per 100 h':>9}  {'worst sensor':<14}")
    for name, (train, test, extra) in SCENARIOS.items():
        with tempfile.TemporaryDirectory() as tmp:
            root = Path(tmp)
            path = []
            if train is not None and test is not None:
                path = [f"data.path={mixed(root, train, test)}"]
            elif train is not None:
                thermocomp("simulate", f"data.path={root / 'data'}", *train)
                path = [f"data.path={root / 'data'}"]
            thermocomp("monitor", *path, *extra, "plots=none", f"out={root / 'out'}")
            a = json.loads((root / "out" / "monitor.json").read_text())["alarms"]
        worst = max(a["exclusions_by_sensor"].items(), key=lambda kv: kv[1], default=("-", 0))
        print(f"{name:<36} {a['hours']:7.1f} {a['exclusions']:10d} "
              f"{a['exclusions_per_100h']:9.2f}  {worst[0]} ({worst[1]})")


if __name__ == "__main__":
    alarms() if "--alarms" in sys.argv else main()
