"""CI time (stop 109, ci109c): MLflow's store and the figures in the tests' tracked runs.

Where they cost (py-spy, 50 Hz, with subprocesses, of tests/shell/test_tracking, test_promote,
test_newcomer, test_evaluate_report, test_sweep, test_validation on 0326e79e; 20 890 samples):
frames under ``mlflow/`` 33.3 % of the six modules, 18.0 % of it importing MLflow (the CLI
subprocesses, loky sweep workers, ``mlflow models serve``); sqlalchemy 8.6 % of leaf samples
(2.4 % the store-template test's own two migrations, 1.0 % ``log_compensator``, 0.8 % a run's
``stage_run`` calls); matplotlib 5.0 % of leaves (``test_report_has_every_key_and_figure`` most).
One tracked run on a new SQLite store, in process (``micro``): 0.21 s CPU, of it the new store's
copy opened by an ``SqlAlchemyStore`` 42 ms, the client's store 40 ms, ``log_dict`` 38 ms.

Cuts tried (exact):
  A. ``store.create_store``: the template holds MLflow's Default experiment; a copy gets its own
     artifact location and time by one SQL ``UPDATE`` instead of an ``SqlAlchemyStore`` opened on
     it (engine, table inspection, Alembic head, Default experiment); an older template without
     it is opened by MLflow as before.
  B. ``plots.save_figure``: the placeholder layout engine ``fig.tight_layout()`` leaves made
     ``savefig`` draw the figure once more (draw disabled, every tick laid out) before drawing
     it; it is dropped before saving (PNG bytes identical).

BAR (the brief's, committed before any after-number): KEPT when the CPU (user + sys incl.
children, ``/usr/bin/time``-equivalent ``resource``) of the chosen modules (``MODULES``) is
<= 0.7 x base, paired base/after, 3 rounds, no assertion changed, the store's runs (params,
metrics, tags, artefact lists) and figure bytes the same; else REFUSED (patch
``benchmarks/ci109c_rule.patch``) with the numbers, or TRACED where the cost is what the tests
assert.

Measured (2026-12-07 18:18-18:42 UTC, load 9-12 on 2 cores; base = ``git archive 0326e79e``,
after = the tree with ``benchmarks/ci109c_rule.patch`` applied; CPU s user + sys)::

  micro, 3 paired rounds     base               after             ratio
  create_store (per store)   45.7 / 51.4 / 61.0  3.4 / 3.7 / 4.2 ms   0.07
  residual_plot (per fig.)  212 / 202 / 248     187 / 196 / 179 ms   0.86
  PNG sha256                 af0cec6289d372ff    af0cec6289d372ff     same bytes
  modules (MODULES, -n 0, one pytest each; 45 passed in both trees)
  round 0 / 1 / 2            67.2 / 58.4 / 57.8  63.1 / 56.5 / 63.4 s 0.939 / 0.967 / 1.097
  sum                        183.4               183.0 s              0.998

Exactness: two ``thermocomp run`` (plots=all + ati=cmeans, plots=test + model=arx) on one new
store in each tree: experiments rows, runs' params, metrics, tags (but pid, time, paths), artefact
lists and the 64 PNGs' sha256 identical (the only schema text that differed, a CHECK order in
``runs``, comes from the template's migration, the same code in both trees).

Against the bar: NOT met (0.998 > 0.7): the cuts are exact and each is large where it acts (A
-92 % of a new store, B -10..-15 % of a figure) but both are 1-3 % of the modules, under the
+-10 % noise of a round.  REFUSED; the cuts and their two tests are ``ci109c_rule.patch``.

Usage (from the repository root; ``PYTHONPATH=<tree>/src``)::

    python benchmarks/bench_ci109c.py micro OUT          # per new store / per figure, this tree
    python benchmarks/bench_ci109c.py modules BASE AFTER ROUNDS OUT   # paired module CPU
"""

from __future__ import annotations

import hashlib
import json
import os
import resource
import subprocess
import sys
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
from _cli import made_folder, run_commands  # noqa: E402

MODULES = ("tests/shell/test_tracking.py", "tests/shell/test_promote.py",
           "tests/shell/test_evaluate_report.py", "tests/shell/test_newcomer.py")


def _cpu(fn, n: int) -> float:
    start = time.process_time()
    for i in range(n):
        fn(i)
    return (time.process_time() - start) / n


def micro(out: str) -> None:
    """CPU of one new store (``create_store``) and of one saved residual figure, this tree."""
    import numpy as np

    from thermocomp.core.figures import plots
    from thermocomp.shell import store

    folder = made_folder(out)

    def new_store(i):
        store.create_store(made_folder(str(folder / f"s{os.getpid()}-{time.time_ns()}-{i}")) / "mlflow.db")

    new_store(-1)          # the template, once

    t = np.arange(0, 86400, 60.0)
    y, yhat = np.sin(t / 5000), np.sin(t / 5000) + 0.01 * np.cos(t / 300)
    digests = set()

    def figure(i):
        path = plots.residual_plot(t, y, yhat, "E_X1", "c1", folder / "residual.png")
        digests.add(hashlib.sha256(path.read_bytes()).hexdigest()[:16])

    figure(0)
    print(f"create_store  {1000 * _cpu(new_store, 20):6.1f} ms CPU per new store")
    print(f"residual_plot {1000 * _cpu(figure, 10):6.1f} ms CPU per figure; PNG sha256 {sorted(digests)}")


def _children_cpu() -> float:
    r = resource.getrusage(resource.RUSAGE_CHILDREN)
    return r.ru_utime + r.ru_stime


def _pytest(tree: Path, log: Path) -> float:
    env = dict(os.environ, PYTHONPATH=str(tree / "src"), OMP_NUM_THREADS="1",
               OPENBLAS_NUM_THREADS="1", MKL_NUM_THREADS="1")
    before = _children_cpu()
    with open(log, "w") as f:
        run = subprocess.run([sys.executable, "-m", "pytest", "-q", "-n", "0", "-p", "no:cacheprovider",
                              *MODULES], cwd=tree, env=env, stdout=f, stderr=subprocess.STDOUT)
    if run.returncode:
        raise SystemExit(f"pytest failed in {tree}: {log}")
    return _children_cpu() - before


def modules(base: str, after: str, rounds: str, out: str) -> None:
    """``MODULES`` in one pytest process per tree, base then after, ``rounds`` pairs."""
    folder, rows = made_folder(out), []
    for r in range(int(rounds)):
        pair = {name: _pytest(Path(tree).resolve(), folder / f"{name}{r}.log")
                for name, tree in (("base", base), ("after", after))}
        rows.append(pair)
        print(f"round {r}: base {pair['base']:7.1f} s  after {pair['after']:7.1f} s  "
              f"ratio {pair['after'] / pair['base']:.3f}", flush=True)
    b, a = sum(p["base"] for p in rows), sum(p["after"] for p in rows)
    print(f"sum: base {b:.1f} s after {a:.1f} s ratio {a / b:.3f} (bar <= 0.7)")
    (folder / "modules.json").write_text(json.dumps(rows))


def main(argv: list[str]) -> int:
    return run_commands(__doc__, {"micro": micro, "modules": modules}, argv, cpu=sys.stdout)


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
