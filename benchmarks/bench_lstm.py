"""LSTM fit time and test RMSE against MLR on the default simulated data (target: <= 30 s, one core).

    .venv/bin/python benchmarks/bench_lstm.py [dataset_dir] [key=value ...]

Simulates the default year-round dataset when no folder is given, fits the
Compensator with ``LSTM`` (config defaults of ``conf/model/lstm.yaml`` unless
overridden, e.g. ``hidden_size=32``) on the train split, prints fit time,
epochs per target (best 0: the network was dropped, the linear law kept), test
RMSE beside MLR's and the machine load (other processes share the CPU).
"""

from __future__ import annotations

import os
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np
import yaml

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "src"))

from thermocomp import io  # noqa: E402
from thermocomp.core.compensator import Compensator  # noqa: E402
from thermocomp.core.models import MLR  # noqa: E402
from thermocomp.core.models.lstm import LSTM  # noqa: E402


def dataset(argv) -> Path:
    if argv and "=" not in argv[0]:
        return Path(argv[0])
    path = Path(tempfile.mkdtemp()) / "yearround_spindle"
    subprocess.run([str(Path(sys.executable).parent / "thermocomp"), "simulate", f"data.path={path}",
                    "track=false"], check=True, capture_output=True)
    return path


def main(argv: list[str]) -> None:
    path = dataset(argv)
    params = yaml.safe_load((ROOT / "conf/model/lstm.yaml").read_text())["estimator"]
    params = {k: v for k, v in params.items() if not k.startswith("_")}
    params["random_state"] = 0
    for arg in (a for a in argv if "=" in a):
        key, value = arg.split("=", 1)
        params[key] = yaml.safe_load(value)
    ds, _ = io.read_dataset(path, {})
    train = {c: ds.campaigns[c] for c in ds.ids("train")}
    test = {c: ds.campaigns[c] for c in ds.ids("test")}
    print(f"load before: {os.getloadavg()[0]:.2f} (1-min), {os.cpu_count()} cores")
    print(f"LSTM({', '.join(f'{k}={v}' for k, v in params.items())})")
    t0, c0 = time.perf_counter(), time.process_time()
    comp = Compensator(LSTM(**params)).fit(train)
    fit_s, cpu_s = time.perf_counter() - t0, time.process_time() - c0
    pred, meas = comp.predict(test), comp.measured(test)
    mlr_pred = Compensator(MLR()).fit(train).predict(test)

    def rmse(p, t):
        r = np.concatenate([(meas[c][t] - p[c][t]).to_numpy() for c in test])
        return np.sqrt(np.mean(r**2))

    for t, est in comp.estimators_.items():
        print(f"  {t}: {est.n_epochs_} epochs (best {est.best_epoch_}), "
              f"test RMSE {rmse(pred, t):.2f} µm (MLR {rmse(mlr_pred, t):.2f})")
    rows = sum(len(df) for df in train.values())
    print(f"fit {len(comp.targets_)} targets on {len(train)} campaigns / {rows} rows: {fit_s:.1f} s wall, "
          f"{cpu_s:.1f} s CPU "
          f"(target <= 30 s); load after: {os.getloadavg()[0]:.2f}")


if __name__ == "__main__":
    main(sys.argv[1:])
