"""CI time (issue 34; stop 108, ci108a): the suite's CPU, group A -- the docs walk (tests/test_*.py)
and the shell modules of pipelines, sweeps and tracking (tests/shell/test_{dvc,sweep,tracking,team,
optuna,lab_sweep,stage,denoise_stages,validation,evaluate,report,promote,config,data,init,own}*.py;
no module of the group's run/compare/hydra/ingest names exists).  45 modules, 514 s of the
durations of /tmp/ci7.log (stop 107's head, 3 xdist workers): test_readme 169, test_dvc_metrics 84,
test_sweep 38, test_tracking 23, test_team 18, test_evaluate_report 16, the rest <= 12 each.

Rule sought: work a test does twice or beyond what it asserts (a repeated fit / simulate / run /
process, a record bigger than asserted, report extras, a subprocess not about the process
boundary), every claim kept asserted.  No seeds (exact computations).

BAR (the brief's, written and committed here before any after-measurement):

1. the group's CPU -- the sum over its modules of user + sys (incl. children, ``/usr/bin/time``)
   of ``python -m pytest -q -n 0 -p no:cacheprovider -m "not full" MODULE``, each module alone,
   OMP/OPENBLAS/MKL_NUM_THREADS=1, ``PYTHONPATH=<tree>/src``; base = a copy of 0dd05741
   (``git archive``, then committed in a git repository of its own: test_readme lists files by
   git) -- down >= 30 % against base, base and after one after the other per changed module
   (paired, same load), a second pair where the difference is < 10 %; modules byte-identical
   to base counted with their base figure in both sums (said so);
2. no test lost without a named replacement that asserts the same claim (checked); a shrunk
   test still fails on what it guards (planted break or the src before it was added);
3. tests/test_lint.py, tests/test_durations.py, tests/test_docs.py pass; ruff clean.

Verdict KEPT if 1-3 hold; else REFUSED (the clean cuts stay on the branch for the lead only if
safe to merge, said so; the diff in benchmarks/ci108a_rule.patch) or TRACED.

Usage (from the repository root; ``PYTHONPATH=<tree>/src``), bench_ci101c's commands::

    python benchmarks/bench_ci108a.py cpu TREE TAG OUT SPEC...      # each spec alone, /usr/bin/time
    python benchmarks/bench_ci108a.py table OUT [BEFORE AFTER BAR]   # means, sum, the bar
    python benchmarks/bench_ci108a.py asserts BASE SPEC...           # asserts per module
    python benchmarks/bench_ci108a.py plant TREE FILE OLD NEW SPEC   # a break, the tests on it
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
