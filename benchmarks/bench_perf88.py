"""perf88: where ``export`` (C with its check pack) spends its CPU after perf87b, and what was cut.

    PYTHONPATH=<tree>/src .venv/bin/python benchmarks/bench_perf88.py export LAB MODEL OUT
    PYTHONPATH=<tree>/src .venv/bin/python benchmarks/bench_perf88.py csv ROWS COLUMNS

``export``: ``thermocomp export`` (C, ``export.check=true``, ``track=false``) of ``MODEL`` on the
lab folder ``LAB`` (bench_audit87's ``lab``, its ``hydra.searchpath`` folder ``LAB/../conf``) into
``OUT``: the child's user and system CPU (``OMP_NUM_THREADS=1``), as bench_perf87b's ``export``.
``csv``: the pack's CSV text (:func:`~thermocomp.apps.deploy.export.pack.csv_text`) of a random
float frame of ``ROWS`` x ``COLUMNS`` (NaN, inf, -0.0 and integers among the values) against
pandas' ``to_csv`` at ``%.17g``: equal or not, and the CPU of each.

The record: bench_audit87's ``lab`` (``simulate sim=fleet sim.generator.n_machines=2
sim.generator.days=12 sim.generator.test_days=3 seed=9136``, machine M002, 12 days of 2,880 rows
at 30 s, the last held out; ``thermocomp init``), its ``run model=mlr`` and ``run model=auto``
``model.pkl``.  The pack: the test day and five planted copies, each 34,560 rows with the
31,680-row lead-in of perf87b's ``_Lead`` (streamed once).

The bar, written before scoring (22:55 UTC, before any timed run of a change): the ``check/``
folder byte-identical to main's (50364abe) on the lab record (mlr and auto) and on test_export's
records (the export tests pass unchanged), and export's CPU (user + sys) of MLR and of auto
each cut by at least a third, in alternated main / branch runs; else REFUSED (or TRACED where no
rule was tried) with the profile below.

SCORED_PLACEHOLDER
"""
from __future__ import annotations

import io
import sys
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))

from _cli import run_commands  # noqa: E402
from bench_perf87b import export  # noqa: E402  (the same child export, its CPU)


def csv(rows: str, columns: str) -> None:
    """:func:`csv_text` of a random float frame against pandas' own ``to_csv``: equal, and CPU."""
    import numpy as np
    import pandas as pd

    from thermocomp.apps.deploy.export.pack import csv_text

    rng = np.random.default_rng(88)
    n, m = int(rows), int(columns)
    values = rng.normal(size=(n, m)) * 10.0 ** rng.integers(-300, 300, size=(n, m))
    values[rng.random(values.shape) < 0.05] = np.nan
    values[0, :min(m, 4)] = [np.inf, -np.inf, -0.0, 3.0][:min(m, 4)]
    frame = pd.DataFrame(values, columns=[f"c{k}" for k in range(m)])
    start = time.process_time()
    text = csv_text(frame)
    ours = time.process_time() - start
    start, buf = time.process_time(), io.StringIO()
    frame.to_csv(buf, index=False, float_format="%.17g", na_rep="", lineterminator="\n")
    theirs = time.process_time() - start
    print(f"equal {text == buf.getvalue()}; csv_text {ours:.2f} s, pandas to_csv {theirs:.2f} s")


def main(argv: list[str]) -> int:
    return run_commands(__doc__, {"export": export, "csv": csv}, argv, cpu=sys.stderr)


if __name__ == "__main__":
    raise SystemExit(main(sys.argv[1:]))
