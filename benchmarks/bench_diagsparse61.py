"""``thermocomp diagnose`` on a probe-cycle record: dense vs 1 row in 10 vs 1 in 30 (prints numbers).

Two year-round records of 12 campaigns of 3-4 h at 1 min (8 train, 4 test; ``sim=yearround_spindle``),
one with the undeclared door planted (``sim.generator.effects=[door]``), one clean, and copies of
each whose ``E_`` cells are blanked on every row but every N-th (read as a probe cycle,
``data.sparse_targets=auto``).  ``diagnose`` of ``mlr`` on E_Y for each: what it accepts, the test
RMSE before -> after (as deployed; on the measured rows: every test row for the dense record,
1 in N for a copy, so the columns compare the diagnoses, not one set of rows), the acceptance
test's design (blocks x measured samples, smallest reachable p) and the CPU (user + sys of the
``diagnose`` process, imports included).

Run: ``PYTHONPATH=src .venv/bin/python benchmarks/bench_diagsparse61.py [WORK_DIR] [seed ...]``
"""

from __future__ import annotations

import json
import resource
import subprocess
import sys
from pathlib import Path

from thermocomp.apps.sim.probe import probe_cycle_copy

EVERY = (1, 10, 30)
RECORD = ("sim.generator.n_campaigns=12", "sim.generator.duration_h=[3.0,4.0]",
          "sim.generator.sample_period_s=60.0")
PLANTED = {"door": ["sim.generator.effects=[door]"], "clean": []}


def thermocomp(*args: str) -> float:
    """Run ``thermocomp <args>`` in a child process; its CPU seconds (user + sys)."""
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    subprocess.run([sys.executable, "-m", "thermocomp", *args], check=True, capture_output=True)
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    return (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)


def main(work: Path, seeds: list[int]) -> None:
    print("seed record  every  accepted                                  test before -> after  "
          "blocks x samples  min_p    CPU s")
    for seed in seeds:
        for name, extra in PLANTED.items():
            dense = work / f"{name}-{seed}"
            if not dense.is_dir():
                thermocomp("simulate", f"data.path={dense}", "track=false", f"seed={seed}",
                           *RECORD, *extra)
            for every in EVERY:
                data = (dense if every == 1 else
                        probe_cycle_copy(dense, work / f"{name}-{seed}-s{every}", every))
                out = work / f"out-{name}-{seed}-s{every}"
                cpu = thermocomp("diagnose", f"data.path={data}", f"out={out}", "track=false",
                                 "plots=none", "diagnose.targets=[E_Y]")
                j = json.loads((out / "diagnosis.json").read_text())
                accepted = ", ".join(f"{e['kind']}:{e['column'] or ''}:{e['transform'][:18]}"
                                     for e in j["effects"] if e["accepted"]) or "-"
                cv = j["cv"]
                print(f"{seed:4d} {name:6s} {every:5d}  {accepted[:40]:40s}  "
                      f"{j['before']['test_rmse']:6.3f} -> {j['after']['test_rmse']:6.3f}   "
                      f"{cv['test_blocks']:4d} x {cv['block_samples']:4d}   {cv['min_p']:.2g}   "
                      f"{cpu:5.1f}", flush=True)


if __name__ == "__main__":
    work = Path(sys.argv[1]) if len(sys.argv) > 1 else Path("/tmp/bench_diagsparse61")
    main(work, [int(s) for s in sys.argv[2:]] or [1, 2])
