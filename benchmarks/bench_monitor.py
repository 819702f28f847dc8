"""Cost of monitoring + compensating one sample for 50 sensors (issue 14).

Builds a synthetic 50-sensor field (4 thermal modes + noise, 10 training campaigns), fits
MLR, wraps it in the AdaptiveCompensator (POD self-prediction, detectors, guard) and times
``_step`` per sample on a healthy stream and on one where a sensor drops out (excluded and
rebuilt from the field every sample), against a bare NumPy 50×50 matrix-vector product.

    .venv/bin/python benchmarks/bench_monitor.py
"""

from __future__ import annotations

import time

import numpy as np
import pandas as pd

from thermocomp.compensator import Compensator
from thermocomp.deploy import StreamingCompensator
from thermocomp.models import MLR
from thermocomp.monitor import AdaptiveCompensator

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


if __name__ == "__main__":
    main()
