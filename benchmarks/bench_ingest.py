"""Throughput and peak memory of ``thermocomp.core.io.ingest`` on one large campaign.

Usage::

    python benchmarks/bench_ingest.py [ROWS] [SENSORS]     # default 5_000_000 50

Generates a dataset with one campaign CSV (``time``, ``SENSORS`` temperature
columns, ``E_X``; 1 s sampling, a few isolated dropouts) in a temporary folder
outside the repository, then runs ``ingest`` in a fresh subprocess so that its
peak RSS belongs to the ingest alone.  The peak is ``VmHWM`` from
``/proc/self/status``: unlike ``ru_maxrss`` it is not inherited from the
parent across ``exec``.
"""

from __future__ import annotations

import json
import os
import resource
import shutil
import subprocess
import sys
import tempfile
import time
from concurrent.futures import ProcessPoolExecutor
from pathlib import Path

import numpy as np
import pyarrow as pa
import pyarrow.csv as pacsv

SRC = Path(__file__).resolve().parents[1] / "src"
BATCH_ROWS = 250_000
DROPOUT_RATE = 1e-5  # isolated missing cells per temperature sample, repaired by ingest
CFG = {"max_gap_samples": 3}


def generate(folder: Path, rows: int, sensors: int, seed: int = 0) -> Path:
    """Write ``campaigns.csv`` and ``K01.csv`` with ``rows`` samples.

    CSV formatting is the slow part, so each core writes a slice of the rows
    and the slices are concatenated.
    """
    workers = max(1, min(os.cpu_count() or 1, rows // BATCH_ROWS))
    bounds = np.linspace(0, rows, workers + 1).astype(int)
    parts = [folder / f".part{i}" for i in range(workers)]
    with ProcessPoolExecutor(workers) as pool:
        jobs = [pool.submit(_write_part, parts[i], int(bounds[i]), int(bounds[i + 1]), sensors,
                            seed, i == 0) for i in range(workers)]
        for job in jobs:
            job.result()
    with open(folder / "K01.csv", "wb") as out:
        for part in parts:
            with open(part, "rb") as f:
                shutil.copyfileobj(f, out, 16 << 20)
            part.unlink()
    (folder / "campaigns.csv").write_text("campaign,file,split\nK01,K01.csv,train\n")
    return folder


def _write_part(path: Path, first: int, stop: int, sensors: int, seed: int, header: bool) -> None:
    rng = np.random.default_rng([seed, first])
    phase = np.random.default_rng(seed).uniform(0, 6, sensors)  # same sensors in every part
    gain = np.random.default_rng(seed + 1).uniform(-2, 2, sensors)
    names = ["time"] + [f"T_{i:02d}" for i in range(sensors)] + ["E_X"]
    schema = pa.schema([(name, pa.float64()) for name in names])
    options = pacsv.WriteOptions(include_header=header)
    with pacsv.CSVWriter(path, schema, write_options=options) as writer:
        for start in range(first, stop, BATCH_ROWS):
            time_s = np.arange(start, min(start + BATCH_ROWS, stop), dtype=float)
            writer.write_batch(_batch(time_s, phase, gain, rng, schema))


def _batch(time_s, phase, gain, rng, schema) -> pa.RecordBatch:
    # Slow heating cycles, phase-shifted per sensor: sin(a + p) = sin a cos p + cos a sin p.
    angle = time_s / 7200.0
    warm = np.outer(np.sin(angle), np.cos(phase)) + np.outer(np.cos(angle), np.sin(phase))
    # Whole hundredths, so the CSV holds short decimals such as 23.45.
    centi = np.rint(2200.0 + 400.0 * warm) + rng.integers(-5, 6, warm.shape)
    temps = centi / 100.0
    temps[rng.random(temps.shape) < DROPOUT_RATE] = np.nan
    error = np.rint(100.0 * (warm @ gain) + rng.integers(-30, 31, len(time_s))) / 100.0
    columns = [time_s, *temps.T, error]
    return pa.record_batch([pa.array(c, from_pandas=True) for c in columns], schema=schema)


def peak_rss_kb() -> int:
    """High-water mark of this process's resident memory, in kB."""
    try:
        with open("/proc/self/status") as status:
            return next(int(line.split()[1]) for line in status if line.startswith("VmHWM:"))
    except (OSError, StopIteration):  # not Linux: ru_maxrss may include the parent's image
        return resource.getrusage(resource.RUSAGE_SELF).ru_maxrss


def child(src: str, dest: str) -> None:
    """Run one ingest and print its timing and peak RSS as JSON."""
    sys.path.insert(0, str(SRC))
    from thermocomp.core.io import ingest

    baseline_kb = peak_rss_kb()
    start, cpu_start = time.perf_counter(), time.process_time()
    report = ingest(src, dest, CFG)
    seconds, cpu = time.perf_counter() - start, time.process_time() - cpu_start
    peak_kb = peak_rss_kb()
    print(json.dumps({"seconds": seconds, "cpu_seconds": cpu, "peak_kb": peak_kb,
                      "baseline_kb": baseline_kb,
                      "rows": report["rows"], "repairs": sum(report["repairs"].values())}))


def main(rows: int, sensors: int) -> None:
    with tempfile.TemporaryDirectory(prefix="thermocomp-bench-") as tmp:
        raw = Path(tmp) / "raw"
        raw.mkdir()
        start = time.perf_counter()
        generate(raw, rows, sensors)
        generated = time.perf_counter() - start
        csv_mb = (raw / "K01.csv").stat().st_size / 1e6
        run = subprocess.run([sys.executable, __file__, "--child", str(raw), str(Path(tmp) / "out")],
                             capture_output=True, text=True)
        if run.returncode:
            sys.exit(f"ingest failed (exit {run.returncode}):\n{run.stderr}")
        result = json.loads(run.stdout.strip().splitlines()[-1])
        parquet_mb = sum(p.stat().st_size for p in (Path(tmp) / "out").iterdir()) / 1e6
    data_mb = rows * (sensors + 2) * 8 / 1e6
    peak_mb, base_mb = result["peak_kb"] / 1e3, result["baseline_kb"] / 1e3
    print(f"campaign      {rows:,} rows x {sensors + 2} columns (time, {sensors} T_, E_X)")
    print(f"generated     {csv_mb:,.0f} MB of CSV in {generated:.1f} s")
    print(f"ingest        {result['seconds']:.2f} s wall ({result['cpu_seconds']:.1f} s CPU on "
          f"{os.cpu_count()} cores), {rows / result['seconds']:,.0f} rows/s, "
          f"{csv_mb / result['seconds']:,.0f} MB/s of CSV")
    print(f"output        {parquet_mb:,.0f} MB of Parquet; {result['repairs']} cells repaired")
    print(f"peak RSS      {peak_mb:,.0f} MB = {peak_mb / data_mb:.2f} x the float64 data "
          f"({data_mb:,.0f} MB); {base_mb:,.0f} MB after imports, so ingest added "
          f"{(peak_mb - base_mb) / data_mb:.2f} x the data")


if __name__ == "__main__":
    if sys.argv[1:2] == ["--child"]:
        child(*sys.argv[2:4])
    else:
        main(int(float(sys.argv[1])) if len(sys.argv) > 1 else 5_000_000,
             int(sys.argv[2]) if len(sys.argv) > 2 else 50)
