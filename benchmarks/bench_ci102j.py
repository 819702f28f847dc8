"""CI time (issue 34; stop 102, ci102j): in-process test modules that computed more than their
assertions read, made cheaper.

ci102e (bench_ci102e.py) took the cuts of replay/volumetric/calibrate; this bench reads the
other nine in-process modules of the group (shell/test_monitor_cli, hostile_numeric,
adaptive_deploy, evaluate_report, model_auto, monitor, one_step, twin;
apps/test_diagnose_scenarios) and cuts where a test computes what no assertion reads.

Rule (tests only, no src change, no key):

- test_one_step: the long-record runs of ``model=mlr`` and ``model=lagbank`` (the same FAST
  overrides in three tests: the persistence test's two cases, the lag-bank/diagnose test, and
  the law test's clean run) made once, in a session fixture, and read by each; the diagnose of
  the lag-bank test streams its before/after through the plain deployed stream
  (conftest.PLAIN_DIAGNOSE): the record is healthy, no assertion reads the adaptive stream.
- test_evaluate_report: the ``[none-all]`` report case and the plots=none test score six of the
  nine campaigns (the first four train, the first two test of ``small_year``,
  ``Dataset.subset``): plots=all still draws every campaign's residual, for two targets, and
  mutual prediction still has a matrix (6 x 6) whose diagonal the assertion compares; the
  ``[cmeans-test]`` case (ATI on the train campaigns' ambient spread) keeps all nine.

BAR (the brief's, written and committed here before any after-measurement):

1. every test id stays and passes (``-n 0 -p no:cacheprovider -m "not full"``); every
   assertion stays (``asserts``: no fewer ``assert`` statements and ``refused(`` calls, the
   same test functions; the diff shows none removed or weakened); a test whose data shrinks
   still holds its subject and its docstring says what the smaller data holds;
2. the changed modules' summed pytest CPU (user + sys incl. children, ``/usr/bin/time``, each
   module alone, ``-n 0``, ``nice``; base tree = ``git archive 506ffb01`` in /tmp/ci102j/base)
   down >= 30 %, base and after started together (paired), one rep of the set;
3. one planted break per changed module (``plant``: a one-line change in src of what the changed
   tests check) fails a changed test of that module.

No seeds: nothing is scored (exact cuts of the same commands, or a smaller subject).

Usage (from the repository root; ``PYTHONPATH=<tree>/src``), bench_ci100b's CPU runs::

    python benchmarks/bench_ci102j.py cpu TREE TAG OUT SPEC...      # each spec alone, /usr/bin/time
    python benchmarks/bench_ci102j.py table OUT [BEFORE AFTER BAR]   # means, sum, the bar

and bench_ci101c's assertion counts and planted breaks (a copy of TREE, OLD -> NEW in FILE)::

    python benchmarks/bench_ci102j.py asserts BASE SPEC...
    python benchmarks/bench_ci102j.py plant TREE FILE OLD NEW SPEC

Rule built (tests only; REFUSED, saved as benchmarks/ci102j_rule.patch, which applies to
506ffb01; the two modules are back to 506ffb01 on the branch).

Trace (seen: the fresh clone's per-test CPU, /work/notes/prof102; base --durations, load ~9):
test_one_step's lag-bank test ran the mlr and lagbank runs the persistence test had run, and a
diagnose through the adaptive stream (21.3 s wall of the module's ~37); the law test ran the mlr
run a third time.  test_monitor_cli's fault tests (cProfile, base): the monitor stage is 42 of
58 s, of it read_streamed 11.7 and the report's streaming 17.2 (src/thermocomp/shell/: another
helper's this stop); hostile_numeric's [defaults] is the 27 compositions already made once;
adaptive_deploy, twin, model_auto, monitor, diagnose_scenarios: cut at stops 100-101 or on
purpose (twin's process test); test_evaluate_report's [cmeans-test] on the six campaigns fails
(ATI on four train campaigns), so it keeps nine.

Measured (2026-12-06 22:33-22:38, base = git archive of 506ffb01, after = bf54498e; paired:
base and after started together by a shell loop of ``cpu``; load ~9; CPU s user + sys incl.
children)::

  module                    rep 1            rep 2            mean           same tests pass
  test_one_step             10.30 -> 7.34    10.06 -> 7.35    10.2 -> 7.3    -27.8 %  13 / 13
  test_evaluate_report      20.04 -> 19.16   (one rep)        20.0 -> 19.2   -4.4 %    4 / 4
  sum (the means, bench_ci100b's table)                       30.2 -> 26.5   -12.3 %

Against the bar: (1) met: ``asserts`` 32 -> 32 and 37 -> 37, refused( 0 -> 0, test functions
11 / 3 on both sides; no assert edited (the diff moves runs into a fixture and gives two tests
a ``Dataset.subset`` of six campaigns, each docstring says so); the same counts pass.
(2) NOT met: -12.3 % against >= 30 %.  (3) met, each plant on a copy of bf54498e (``plant``):
run_report.py ``plots == "all"`` -> ``"al"`` failed [none-all]; ``plots != "none"`` ->
``True`` failed the plots=none test; the run's ``carry_over`` -> ``{}`` failed the persistence
test [mlr] (reads the shared runs); conf/diagnose ``min_gain_pct`` 5 -> 500 failed the
lag-bank test (its diagnose, PLAIN_DIAGNOSE); chain.py's fit on every campaign, not the train
split, errored the law test (1 error: the shared runs' setup).

Why so little: test_evaluate_report's CPU is fixed cost (the CLI pipeline with MLflow and a
``dvc plots show`` process, the ATI case) and its figure/fit work on nine campaigns was a small
share; the plots=none test's three fits are cheap either way.  test_one_step alone reached
-27.8 % (two reps): exact (the same commands; the diagnose's ``before`` equals the mlr run to
1e-9 as asserted), a candidate for the lead's exact cut.

``cpu`` writes OUT/cpu.txt (``TAG SPEC user sys wall result``) and pytest's output to OUT/log/;
paired: a shell starts the base's and the branch's ``cpu`` at once, each on its tree.
"""
from __future__ import annotations

import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
import bench_ci100b  # noqa: E402
import bench_ci101c  # noqa: E402
from _cli import run_commands  # noqa: E402

# bench_ci100b's per-module CPU runs and their table, bench_ci101c's assertion counts and plants
COMMANDS = {"cpu": bench_ci100b.cpu, "table": bench_ci100b.table,
            "asserts": bench_ci101c.asserts, "plant": bench_ci101c.plant}


def main(argv: list[str]) -> int:
    return run_commands(__doc__, COMMANDS, argv, cpu=sys.stdout)


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
