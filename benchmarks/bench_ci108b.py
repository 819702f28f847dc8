"""CI time (issue 34; stop 108, ci108b): the suite's CPU, group B -- the deployed forms (export, C,
ST, served, monitor): tests/shell/test_{export,deploy,serve,repeat,bits,monitor,st,restart,stdin,
mon}*.py, 142 modules (test_stage_imports left to group A, whose "stage" it is).

BAR (the brief's, written and committed here before any after-measurement):

1. the group's summed pytest CPU (``cpu``: user + sys incl. children of ``/usr/bin/time nice
   pytest -q -n 0 -p no:cacheprovider -m "not full"``, each module alone, from its tree with
   PYTHONPATH=<tree>/src and the three *_NUM_THREADS=1; base tree = ``git archive 0dd05741`` into
   /tmp/ci108b_base) down >= 30 %; changed modules measured base then after, one after the other,
   the pair repeated where the difference is under 10 %; modules whose files and imports are
   byte-identical to the base counted at their base figure on both sides;
2. no test lost without a named replacement; every assertion kept (same or stronger); no
   tolerance loosened, no skip; a shrunk test fails on the src before it was added or on the
   mutation its docstring names; ``full`` moves only where the docstring names the cheaper tests
   that assert the same claim;
3. tests/test_lint.py, tests/test_durations.py, tests/test_docs.py pass; ruff clean.

KEPT when 1-3 hold; otherwise REFUSED (exact cuts left on the branch only where the lead could
merge them) or TRACED.  No seeds: nothing is scored.

Usage (from the repository root; ``PYTHONPATH=<tree>/src``)::

    python benchmarks/bench_ci108b.py cpu TREE TAG OUT SPEC...      # bench_ci100b's cpu
    python benchmarks/bench_ci108b.py table OUT [BEFORE AFTER BAR]   # bench_ci100b's table
    python benchmarks/bench_ci108b.py asserts BASE SPEC...           # bench_ci101c's asserts
    python benchmarks/bench_ci108b.py plant TREE FILE OLD NEW SPEC   # bench_ci101c's plant
"""
from __future__ import annotations

import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
from bench_ci101c import measured  # noqa: E402


def main(argv: list[str]) -> int:
    return measured(__doc__, argv)


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
