"""EMD denoising speed, and how far the causal (deployed) filter is from offline EMD.

Usage::

    python benchmarks/bench_denoise.py [N_SENSORS] [N_SAMPLES] [DATASET]   # default 50 28080

1. Speed: ``EMDDenoiser`` (remove IMF-1; default settings: 10 siftings,
   mirror padding) on ``N_SENSORS`` x ``N_SAMPLES`` (50 x 28,080 = a 234 h
   test at 30 s, paper 000), for each stopping rule; target <= 10 s.  Then a
   full PyEMD decomposition of every sensor (``EMD().emd``, default settings),
   the straightforward way, and the ratio.  Synthetic sensors: warm-up trends,
   a daily cycle, a random walk, 0.03 °C noise and 0.01 °C quantisation.
2. Causal vs offline: RMS difference (°C) between the causal filters
   (``fir`` and sliding-window EMD) and offline EMD, on a noisy synthetic
   sensor (0.2 °C noise) and, when ``DATASET`` (a dataset folder, e.g. from
   ``thermocomp simulate``) is given, on its T_ sensors, causal filters fitted
   on the train split and measured on the test split.

Prints wall times with the machine load (the machine may be shared).
"""

from __future__ import annotations

import os
import sys
import time

import numpy as np
import pandas as pd
from PyEMD import EMD

from thermocomp.core.denoise import EMDDenoiser, denoise_campaigns, fit_denoiser


def sensors(n_sensors: int, n_samples: int, period_s: float = 30.0, noise: float = 0.03,
            seed: int = 0) -> pd.DataFrame:
    rng = np.random.default_rng(seed)
    t = np.arange(n_samples) * period_s
    cols = {}
    for i in range(n_sensors):
        tau = rng.uniform(2e3, 4e4)
        x = (20 + rng.uniform(1, 15) * (1 - np.exp(-t / tau))
             + rng.uniform(0.5, 3) * np.sin(2 * np.pi * t / 86400 + rng.uniform(0, 6))
             + 0.01 * rng.normal(size=n_samples).cumsum() + noise * rng.normal(size=n_samples))
        cols[f"T_{i:02d}"] = np.round(x, 2)
    return pd.DataFrame(cols)


def load() -> str:
    return "load average %.2f %.2f %.2f" % os.getloadavg()


def speed(n_sensors: int, n_samples: int) -> None:
    X = sensors(n_sensors, n_samples)
    print(f"{n_sensors} sensors x {n_samples} samples  ({load()}, {os.cpu_count()} cores)")
    best = None
    for stopping in ("fixed", "s_number", "sd"):
        den = EMDDenoiser(stopping=stopping)
        t0, c0 = time.perf_counter(), time.process_time()
        den.fit_transform(X)
        s, cpu = time.perf_counter() - t0, time.process_time() - c0
        best = s if stopping == "fixed" else best
        print(f"  EMDDenoiser(stopping={stopping!r:10}) fit_transform: {s:7.2f} s wall, "
              f"{cpu:6.2f} s CPU  (target <= 10 s: {'ok' if s <= 10 else 'MISSED'})")
    den = EMDDenoiser().fit(X.iloc[:2000])
    t0 = time.perf_counter()
    den.transform_causal(X)
    print(f"  causal FIR over the whole record:            {time.perf_counter() - t0:7.2f} s")
    t0, c0 = time.perf_counter(), time.process_time()
    for c in X:
        EMD().emd(X[c].to_numpy())
    full, cpu = time.perf_counter() - t0, time.process_time() - c0
    print(f"  full PyEMD decomposition of every sensor:    {full:7.2f} s wall, {cpu:6.2f} s CPU"
          f"  -> ratio full / EMDDenoiser(fixed) = {full / best:.1f}x wall  ({load()})")


def _rms(a) -> float:
    return float(np.sqrt(np.mean(np.square(a))))


def noisy_sensor(n: int = 2000, noise: float = 0.2) -> None:
    rng = np.random.default_rng(1)
    t = np.arange(n) * 30.0
    trend = 5 * (1 - np.exp(-t / 1.5e4)) + 0.5 * np.sin(2 * np.pi * t / 86400)
    groups = np.repeat(["A", "B"], n // 2)
    X = pd.DataFrame({"T_noisy": trend + noise * rng.normal(size=n)})
    fir = EMDDenoiser().fit(X, groups=groups)
    off = fir.transform(X, groups=groups)["T_noisy"]
    c_fir = fir.transform_causal(X, groups=groups)["T_noisy"]
    win = EMDDenoiser(causal="window").fit(X.iloc[:200])
    c_win = win.transform_causal(X.iloc[:600])["T_noisy"]
    print(f"noisy sensor ({noise} °C white noise, 2 x {n // 2} samples at 30 s):")
    print(f"  noise (raw - trend) RMS {_rms(X['T_noisy'] - trend):.3f}; offline - trend "
          f"{_rms(off - trend):.3f}; causal fir - trend {_rms(c_fir - trend):.3f}")
    print(f"  causal - offline RMS: fir {_rms(c_fir - off):.3f} °C; "
          f"window(64) {_rms(c_win - off[:600]):.3f} °C (first 600 samples)")


def dataset(path: str) -> None:
    from thermocomp.core import io
    ds, _ = io.read_dataset(path)
    cols = ds.columns_of("T_")
    train = {c: ds.campaigns[c] for c in ds.ids("train")}
    test = {c: ds.campaigns[c] for c in ds.ids("test")}
    den, _ = fit_denoiser(EMDDenoiser(), train, cols)
    off = denoise_campaigns(den, test, causal=False)
    fir = denoise_campaigns(den, test, causal=True)
    win_den, _ = fit_denoiser(EMDDenoiser(causal="window"), train, cols)
    win = denoise_campaigns(win_den, test, causal=True)

    def pooled(a, b, c):
        return _rms(np.concatenate([a[k][c].to_numpy() - b[k][c].to_numpy() for k in test]))

    print(f"dataset {path}: {len(cols)} T_ sensors, {len(test)} test campaigns "
          f"({sum(len(d) for d in test.values())} samples)")
    print(f"  {'sensor':<14} {'IMF-1 removed':>13} {'fir - offline':>13} {'window - offline':>16}  (RMS °C)")
    rows = [(c, pooled(test, off, c), pooled(fir, off, c), pooled(win, off, c)) for c in cols]
    for c, removed, f, w in rows:
        print(f"  {c:<14} {removed:13.4f} {f:13.4f} {w:16.4f}")
    r = np.array([row[1:] for row in rows])
    print(f"  {'mean':<14} {r[:, 0].mean():13.4f} {r[:, 1].mean():13.4f} {r[:, 2].mean():16.4f}")


def main(argv: list[str]) -> None:
    n_sensors = int(argv[0]) if argv else 50
    n_samples = int(argv[1]) if len(argv) > 1 else 28080
    speed(n_sensors, n_samples)
    noisy_sensor()
    if len(argv) > 2:
        dataset(argv[2])


if __name__ == "__main__":
    main(sys.argv[1:])
