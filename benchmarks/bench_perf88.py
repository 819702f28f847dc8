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

Profiled (2026-12-04, main 50364abe, cProfile of the mlr export: 376 s under the profiler on 2
cores at load 15-21, so shares only).  ``conformance_pack`` 88 %: the numpy model of the code
(``_parted``, ``Simulator.step``, 48,960 rows = the lead-in once + 6 x 2,880) 57 %, of it the
code monitor (``CodeMonitor.step``) 31 % and the model's step (``Simulator._model``) 13 %; its
``_set`` (the active set, asked some seven times a row, 342,729 calls, rebuilt each time) 8 %;
the served model's steps (``_stepped``) 15 %; CSV text (pandas' per-value formatter and NaN
test, 2.6 M values) 15 %; 65 % of the rows stepped are the lead-in's, streamed once (perf87b).
py-spy (80 s of auto's main export, in its lead-in pass): ``Simulator.step`` 98 %,
``CodeMonitor.step`` 49 %, ``Simulator._model`` 34 %, ``CodeMonitor._set`` 16 %, the LSTM
cells (``Cells.step``) 7 %.  Nothing in that pass is LTI between monitor actions in a way that
gives the same bits: the served and the code's models are stepped by float64 sums whose order a
batched product would change (the pack's ``expected.csv`` is the served stream to the bit).

The rule tried (``perf88_rule.patch``: src and its test, which fails on main): (1) ``csv_text``
formats a float64 frame's body in one ``%`` of all rows (``%.17g``, "nan" emptied: %g writes
nothing else so), the header pandas'; pandas' whole where a column is not float64 or there is
one column (the csv module's ``""``); 2.1x less CPU than ``to_csv`` (``csv 31680 40``: 1.10 s
against 2.37 s), equal to the byte (NaN, inf, -0.0, 5e-324, names needing quotes).  (2)
``CodeMonitor._set`` kept for its key (out, out2 and the operator's arrays, by identity),
its arrays read-only: made 12 times for 1,688 asks on test_export's planted pack.

Scored (2026-12-04, 2 cores shared by 7 sessions, load 15-21; main = 50364abe unpacked under
/tmp, branch 6d686edb; ``OMP_NUM_THREADS=1``; user + sys of the child), in turn:

  model  run                      user     sys    user + sys
  mlr    main 1                   29.3 s   1.1 s    30.4 s
  mlr    branch 1                 24.3 s   1.3 s    25.6 s
  mlr    main 2                   29.9 s   1.0 s    30.9 s
  mlr    branch 2                 23.3 s   1.3 s    24.6 s
  auto   main 1                   61.4 s   1.8 s    63.2 s
  auto   branch 1                 53.2 s   2.5 s    55.7 s
  auto   main 2                   52.9 s   4.5 s    57.4 s
  auto   main 2b (*)              57.2 s   4.3 s    61.5 s
  auto   branch 3                 44.7 s   4.6 s    49.3 s
  auto   main 3                   50.3 s   3.3 s    53.6 s

(*) meant as branch 2, but run after the src was reverted (ea58de98): main's code, so a main
run; branch 3 ran 6d686edb unpacked under /tmp.  The load fell from ~20 to ~4 during the runs.

MLR 30.4 / 30.9 -> 25.6 / 24.6 s (x 0.84 / 0.80); auto (this record's, test E_dX 0.20124 as
audit87's) 63.2 -> 55.7 s and 53.6 -> 49.3 s (x 0.88 / 0.92), main's own runs spreading
53.6-63.2 s.  ``check/`` (133 MB mlr, 134 MB auto; six campaigns) byte-identical main vs branch
for both models (``diff -r``; auto in pairs 1 and 3); the code files differ by their
``exported`` stamp only.  Export tests with the rule: test_export, lead_perf87b, cmon85,
cmon86, mon86, check61, freeze84, dropout53 and the rule's own: 55 passed.

Verdict: REFUSED by its bar (a cut of 8-20 %, not a third; the pack byte-identical).  The
src is main's; the rule is ``perf88_rule.patch``.  What remains: the code monitor's Python
per row (``CodeMonitor._step`` and its ``_judgement``, ``_judge``, ``_errors``) and the
Simulator's ``_model``: a third needs them rewritten with fewer numpy calls per row on small
arrays (n ~ 40), each bit checked, or the pack's lead-in pass kept across exports of one model.
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
