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

Usage (from the repository root; ``PYTHONPATH=<tree>/src``)::

    python benchmarks/bench_ci102j.py cpu TREE TAG OUT SPEC...      # bench_ci100b's cpu
    python benchmarks/bench_ci102j.py table OUT [BEFORE AFTER BAR]   # bench_ci100b's table
    python benchmarks/bench_ci102j.py asserts BASE SPEC...           # bench_ci101c's asserts
    python benchmarks/bench_ci102j.py plant TREE FILE OLD NEW SPEC   # bench_ci101c's plant

``cpu`` writes OUT/cpu.txt (``TAG SPEC user sys wall result``) and pytest's output to OUT/log/;
paired: a shell starts the base's and the branch's ``cpu`` at once, each on its tree.
"""
from __future__ import annotations

import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
from _cli import run_commands  # noqa: E402
from bench_ci100b import cpu, table  # noqa: E402
from bench_ci101c import asserts, plant  # noqa: E402


def main(argv: list[str]) -> int:
    return run_commands(__doc__, {"cpu": cpu, "table": table, "asserts": asserts, "plant": plant},
                        argv, cpu=sys.stdout)


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
