"""Time and peak memory of a fleet against its size: generate, then one model per machine.

Usage::

    python benchmarks/bench_scale.py [MACHINES ...] [--jobs N] [--group-jobs N] [--no-validation]
                                     [--keep DIR]                           # default 1 10 100

For each fleet size: the ``fleet`` scenario (30 days at 30 s, 40 sensors per
machine, Parquet partitions) is written in a temporary folder outside the
repository by ``Fleet.write`` (``--jobs`` processes), then ``thermocomp run
data.group_by=machine data.group_jobs=<--group-jobs> track=false plots=none``
(``eval.validation=false`` with ``--no-validation``: the cross-validation refits
each machine's model 5 times) runs in a child process.  Peak memory is that of the run's
whole process tree: the sum of the RSS of the process and its children, sampled every 0.1 s (psutil), and
the largest single process (``ru_maxrss`` of the waited-for children, in this
process's fresh child accounting per size).  Time per machine stays flat and
peak memory stays at one machine's when the run streams the fleet.
"""

from __future__ import annotations

import argparse
import json
import shutil
import subprocess
import sys
import tempfile
import threading
import time
from pathlib import Path

import psutil

from thermocomp.apps.sim.fleet import Fleet

BIN = Path(sys.executable).parent


def _tree_rss(proc: psutil.Process) -> int:
    total = 0
    for p in [proc, *proc.children(recursive=True)]:
        try:
            total += p.memory_info().rss
        except psutil.NoSuchProcess:
            pass
    return total


def run_measured(args: list[str]) -> tuple[float, int, int]:
    """Wall time (s), peak tree RSS and peak single-process RSS (bytes) of a child command."""
    t0 = time.perf_counter()
    child = subprocess.Popen(args, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    proc, peak, single = psutil.Process(child.pid), [0], [0]

    def watch():
        while child.poll() is None:
            try:
                peak[0] = max(peak[0], _tree_rss(proc))
                single[0] = max(single[0], max((p.memory_info().rss for p in
                                                [proc, *proc.children(recursive=True)]), default=0))
            except psutil.Error:
                pass
            time.sleep(0.1)

    thread = threading.Thread(target=watch, daemon=True)
    thread.start()
    out, err = child.communicate()
    thread.join()
    if child.returncode:
        sys.exit(f"thermocomp run failed ({child.returncode}):\n{err[-3000:]}")
    return time.perf_counter() - t0, peak[0], single[0]


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("machines", nargs="*", type=int, default=[1, 10, 100])
    parser.add_argument("--jobs", type=int, default=2, help="processes generating the fleet")
    parser.add_argument("--group-jobs", type=int, default=1, help="machines fitted at once")
    parser.add_argument("--no-validation", action="store_true", help="eval.validation=false")
    parser.add_argument("--keep", type=Path, help="keep the datasets under this folder")
    opts = parser.parse_args()
    base = Path(opts.keep or tempfile.mkdtemp(prefix="thermocomp-bench-scale-"))
    rows = []
    print(f"{'machines':>8} {'rows':>10} {'disk MB':>8} {'gen s':>7} {'run s':>7} {'run s/machine':>13} "
          f"{'peak tree MB':>12} {'peak proc MB':>12}", flush=True)
    try:
        for n in opts.machines:
            data, out = base / f"fleet{n}", base / f"out{n}"
            t0 = time.perf_counter()
            truth = Fleet(n_machines=n, n_jobs=opts.jobs).write(data)
            gen_s = time.perf_counter() - t0
            disk = sum(f.stat().st_size for f in data.rglob("*") if f.is_file()) / 2**20
            run_s, peak, single = run_measured(
                [str(BIN / "thermocomp"), "-q", "run", f"data.path={data}", "data.group_by=machine",
                 f"data.group_jobs={opts.group_jobs}", "track=false", "plots=none", f"out={out}",
                 *(["eval.validation=false"] if opts.no_validation else [])])
            row = {"machines": n, "rows": truth["rows"], "disk_mb": disk, "generate_s": gen_s,
                   "run_s": run_s, "run_s_per_machine": run_s / n, "peak_tree_mb": peak / 2**20,
                   "peak_process_mb": single / 2**20}
            rows.append(row)
            print(f"{n:8d} {truth['rows']:10d} {disk:8.0f} {gen_s:7.1f} {run_s:7.1f} {run_s / n:13.2f} "
                  f"{peak / 2**20:12.0f} {single / 2**20:12.0f}", flush=True)
            if not opts.keep:
                shutil.rmtree(data, ignore_errors=True)
                shutil.rmtree(out, ignore_errors=True)
    finally:
        if not opts.keep:
            shutil.rmtree(base, ignore_errors=True)
    print(json.dumps(rows))


if __name__ == "__main__":
    main()
