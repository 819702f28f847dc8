"""Wall time of ``thermocomp run`` for ``model=lagbank`` against ``model=mlr`` on a lathe-sized set
(issue 34, item 5: lagbank no more than 3x mlr).

Usage::

    python benchmarks/bench_lagbank.py [--campaigns 30] [--rows 600] [--sensors 24] [key=value ...]

Writes a synthetic campaign set in a temp folder (``--campaigns`` campaigns of ``--rows``
samples a minute apart, ``--sensors`` temperatures driven by a few heat sources through
first-order lags, two error columns, the last tenth of the campaigns the test split), then
runs ``thermocomp run track=false plots=none`` with each model in a fresh process (median
of ``--repeats``, 3), prints each run's phases (the ``time (s): ...`` line it logs), the wall
times and their ratio (acceptance: <= 3).  ``--blas-threads 1`` runs both single-threaded: on
a shared, loaded machine multi-threaded BLAS on small matrices is many times slower, which
favours whichever model limits its threads; the single-threaded ratio is the models' own.
"""

from __future__ import annotations

import argparse
import os
import re
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np
import pandas as pd

ROOT = Path(__file__).resolve().parents[1]
BIN = Path(sys.executable).parent
MODELS = ("mlr", "lagbank")
PHASES = re.compile(r"time \(s\): [\d.]+ = (.*)$", re.M)


def write_campaigns(root: Path, n_campaigns: int, rows: int, sensors: int, seed: int = 0) -> Path:
    """A lathe-like set: each campaign its own ambient level and duty cycle of 3 heat sources."""
    rng = np.random.default_rng(seed)
    root.mkdir(parents=True)
    t = np.arange(rows) * 60.0
    gains = rng.normal(0.0, 1.0, (3, sensors))                # source -> sensor
    taus = rng.uniform(600.0, 7200.0, sensors)                 # sensor's thermal lag (s)
    weights = rng.normal(0.0, 1.5, (2, sensors))               # sensor -> error (µm/K)
    n_test = max(1, n_campaigns // 10)
    manifest = []
    for i in range(n_campaigns):
        ambient = 15.0 + 20.0 * rng.random()
        # piecewise-constant source powers: a duty cycle switched every 30-120 min
        power = np.zeros((rows, 3))
        k = 0
        while k < rows:
            step = int(rng.integers(30, 120))
            power[k:k + step] = rng.uniform(0.0, 5.0, 3)
            k += step
        drive = power @ gains                                  # (rows, sensors) steady rise
        temps = np.empty_like(drive)
        z = np.zeros(sensors)
        a = np.exp(-60.0 / taus)
        for j in range(rows):
            z = a * z + (1.0 - a) * drive[j]
            temps[j] = z
        errors = temps @ weights.T
        df = pd.DataFrame(ambient + temps + rng.normal(0.0, 0.05, temps.shape),
                          columns=[f"T_{s}" for s in range(sensors)])
        df.insert(0, "time", t)
        df["E_X"] = errors[:, 0] + rng.normal(0.0, 0.3, rows)
        df["E_Z"] = errors[:, 1] + rng.normal(0.0, 0.3, rows)
        cid = f"c{i:02d}"
        df.to_csv(root / f"{cid}.csv", index=False)
        manifest.append((cid, f"{cid}.csv", "test" if i >= n_campaigns - n_test else "train", ""))
    pd.DataFrame(manifest, columns=["campaign", "file", "split", "notes"]).to_csv(
        root / "campaigns.csv", index=False)
    return root


def phases(stderr: str) -> dict[str, float]:
    match = PHASES.search(stderr)
    if match is None:
        raise RuntimeError(f"no timing line in the run's stderr:\n{stderr}")
    return {name: float(s) for name, s in (p.rsplit(" ", 1) for p in match[1].split(" + "))}


def timed_run(data: Path, out: Path, model: str, overrides: list[str],
              env: dict) -> tuple[float, float, dict]:
    """Wall seconds, CPU seconds (user + sys of the child and its reaped children) and phases."""
    cmd = [str(BIN / "thermocomp"), "run", "track=false", "plots=none", f"data.path={data}",
           f"out={out}", f"model={model}", *overrides]
    with tempfile.TemporaryFile("w+") as err:
        t0 = time.perf_counter()
        proc = subprocess.Popen(cmd, cwd=ROOT, stdout=subprocess.DEVNULL, stderr=err, env=env)
        _, status, usage = os.wait4(proc.pid, 0)   # this child's own rusage, not the bench's
        seconds = time.perf_counter() - t0
        err.seek(0)
        stderr = err.read()
    if os.waitstatus_to_exitcode(status) != 0:
        raise RuntimeError(f"{' '.join(cmd)} failed:\n{stderr[-2000:]}")
    return seconds, usage.ru_utime + usage.ru_stime, phases(stderr)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--campaigns", type=int, default=30)
    parser.add_argument("--rows", type=int, default=600)
    parser.add_argument("--sensors", type=int, default=24)
    parser.add_argument("--repeats", type=int, default=3)
    parser.add_argument("--models", nargs="+", default=list(MODELS),
                        help="families to run (the ratio needs mlr and lagbank)")
    parser.add_argument("--blas-threads", type=int, default=None,
                        help="BLAS threads of both runs (default: the library's own choice)")
    args, overrides = parser.parse_known_args()
    env = dict(os.environ)
    if args.blas_threads is not None:   # both models alike: the ratio without thread contention
        env.update({k: str(args.blas_threads) for k in
                    ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS")})
    one, five, _ = os.getloadavg()
    print(f"{args.campaigns} campaigns x {args.rows} rows x {args.sensors} sensors; "
          f"load average {one:.2f} {five:.2f} on {os.cpu_count()} cores; BLAS threads "
          f"{args.blas_threads or 'default'}")
    with tempfile.TemporaryDirectory() as tmp:
        data = write_campaigns(Path(tmp) / "data", args.campaigns, args.rows, args.sensors)
        walls: dict[str, list[float]] = {m: [] for m in args.models}
        cpus: dict[str, list[float]] = {m: [] for m in args.models}
        parts: dict[str, list[dict]] = {m: [] for m in args.models}
        for _ in range(args.repeats):
            for model in args.models:
                seconds, cpu, split = timed_run(data, Path(tmp) / f"out_{model}", model, overrides, env)
                walls[model].append(seconds)
                cpus[model].append(cpu)
                parts[model].append(split)
    for model in args.models:
        names = list(dict.fromkeys(n for p in parts[model] for n in p))
        line = " + ".join(f"{n} {statistics.median(p.get(n, 0.0) for p in parts[model]):.2f}"
                          for n in names)
        print(f"{model:<8} wall {statistics.median(walls[model]):6.2f} s (median of {args.repeats}: "
              + " ".join(f"{w:.2f}" for w in walls[model])
              + f"); CPU {statistics.median(cpus[model]):6.2f} s ("
              + " ".join(f"{c:.2f}" for c in cpus[model]) + f"); phases: {line}")
    if {"mlr", "lagbank"} <= set(args.models):
        for name, values in (("wall", walls), ("CPU", cpus)):
            ratio = statistics.median(values["lagbank"]) / statistics.median(values["mlr"])
            print(f"lagbank / mlr {name}: {ratio:.2f}x  (issue 34 acceptance: <= 3x)")


if __name__ == "__main__":
    main()
