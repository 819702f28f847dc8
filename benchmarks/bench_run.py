"""Wall time of ``thermocomp run track=false`` on the default data, phase by phase (issue 11).

Usage::

    python benchmarks/bench_run.py [key=value ...]   # e.g. plots=test; default: the default run

Uses the default simulated dataset (``data/raw/yearround_spindle``, what ``make run`` writes;
simulated into a temp folder when missing) and writes the run's outputs to a temp folder.
Each repeat times, side by side, the bare import of the scientific stack
(``python -c "import numpy, pandas, scipy, sklearn, matplotlib"``) and the run as a user
starts it (a fresh process), and reads the phases from the timing line the run logs on stderr
(``time (s): <total> = read .. + fit .. + ...``); ``startup`` is the rest of the wall time
(interpreter, imports, config composition).  Prints the median of 3 repeats, the ratio of the
run to the bare import (issue 11 acceptance: <= 3), both CPU times and the machine load (it may
be shared).
"""

from __future__ import annotations

import os
import re
import resource
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
BIN = Path(sys.executable).parent
REPEATS = 3
IMPORTS = "import numpy, pandas, scipy, sklearn, matplotlib"
PHASES = re.compile(r"time \(s\): [\d.]+ = (.*)$", re.M)


def load() -> str:
    one, five, fifteen = os.getloadavg()
    return f"load average (1, 5, 15 min): {one:.2f} {five:.2f} {fifteen:.2f} on {os.cpu_count()} cores"


def wall(cmd: list[str]) -> tuple[float, float, subprocess.CompletedProcess]:
    """Wall time, CPU time (user + sys, the process and its figure workers) and the result."""
    cpu0, t0 = resource.getrusage(resource.RUSAGE_CHILDREN), time.perf_counter()
    proc = subprocess.run(cmd, cwd=ROOT, capture_output=True, text=True, check=True)
    seconds, cpu = time.perf_counter() - t0, resource.getrusage(resource.RUSAGE_CHILDREN)
    return seconds, cpu.ru_utime - cpu0.ru_utime + cpu.ru_stime - cpu0.ru_stime, proc


def phases(stderr: str) -> dict[str, float]:
    """``{phase: seconds}`` from the run's timing line."""
    match = PHASES.search(stderr)
    if match is None:
        raise RuntimeError(f"no timing line in the run's stderr:\n{stderr}")
    return {name: float(s) for name, s in (p.rsplit(" ", 1) for p in match[1].split(" + "))}


def main(overrides: list[str]) -> None:
    with tempfile.TemporaryDirectory() as tmp:
        data = ROOT / "data" / "raw" / "yearround_spindle"
        if not (data / "campaigns.csv").is_file():
            data = Path(tmp) / "yearround_spindle"
            wall([str(BIN / "thermocomp"), "simulate", f"data.path={data}", "track=false"])
        run = [str(BIN / "thermocomp"), "run", "track=false", f"data.path={data}",
               f"out={Path(tmp) / 'out'}", *overrides]
        print(f"thermocomp run track=false {' '.join(overrides)} on {data}")
        print(load())
        bare, total, runs, cpu = [], [], [], {"bare": [], "run": []}
        for _ in range(REPEATS):
            seconds, busy, _ = wall([sys.executable, "-c", IMPORTS])
            bare.append(seconds)
            cpu["bare"].append(busy)
            seconds, busy, proc = wall(run)
            total.append(seconds)
            cpu["run"].append(busy)
            runs.append({"startup": seconds - sum(phases(proc.stderr).values()),
                         **phases(proc.stderr)})
        print(load())
    names = list(dict.fromkeys(n for r in runs for n in r))
    print(f"\n{'phase':<20} {'median (s)':>10}   all repeats")
    for name in names:
        values = [r.get(name, 0.0) for r in runs]
        print(f"{name:<20} {statistics.median(values):>10.2f}   "
              + " ".join(f"{v:.2f}" for v in values))
    run_s, bare_s = statistics.median(total), statistics.median(bare)
    print(f"{'total (wall)':<20} {run_s:>10.2f}   " + " ".join(f"{v:.2f}" for v in total))
    print(f"\nbare `python -c \"{IMPORTS}\"`: {bare_s:.2f} s (median; "
          + " ".join(f"{v:.2f}" for v in bare) + ")")
    print(f"run / bare import: {run_s / bare_s:.1f}x  (issue 11 acceptance: <= 3x)")
    run_cpu, bare_cpu = statistics.median(cpu["run"]), statistics.median(cpu["bare"])
    print(f"CPU time (user + sys, median): run {run_cpu:.2f} s, bare import {bare_cpu:.2f} s "
          f"({run_cpu / bare_cpu:.1f}x; less sensitive to a shared machine than wall time)")


if __name__ == "__main__":
    main(sys.argv[1:])
