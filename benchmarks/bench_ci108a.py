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

Trace (0dd05741, each module alone, base copy; CPU s user + sys incl. children, load 6-17 from
the other helpers): test_readme 135.0 (its blocks 125.9 by readme_run.log: README 23.7, sweeps.md
33.5, diagnose.md 19.2, own-data.md 21.4, simulation.md 12.8, monitoring.md 14.4, outputs.md 0.0,
the prepared dataset 1.7), test_dvc_metrics 72.2 (its fixture's ``dvc repro`` 25.4 for 7 stage
processes; alone in its project: train 2.4, evaluate 5.4, diagnose 4.0; each ``dvc`` show
0.8-1.6), test_evaluate_report 26.6, test_config_schema 15.5, test_denoise_stages 13.7, the
other modules 2-12 each.  ``import mlflow`` alone is 2.6 s CPU, sklearn 2.0, scipy.signal 1.4
(same load): the docs walk's ~25 ``thermocomp`` processes and the DVC stages are bound by the
stack's imports, one process each, which the pages and ``dvc repro`` exist to run.

Rule built (tests only, exact): the README's page, first in a test process, hands what its
``make run`` wrote under data/ (``$(BIN)/thermocomp simulate``, PREPARE's very command) to the
docs pages as the prepared default dataset, instead of the first docs page running PREPARE again
(``keep_written``; a docs page run without the README's page still runs PREPARE).  Checked: the
README's data/ after its whole page and a PREPARE's output, 26 files, byte-identical (``cmp``,
base run vs after run).  Saved as benchmarks/ci108a_rule.patch (applies to 0dd05741).

Measured (test_readme, the only changed module; ``-n 0``, base then after, one after the other;
the twins' and servers' fixed ports forbid running two test_readme at once)::

  pair 1 (14:28-15:01, load 6-17; base = the worktree at 0dd05741): 135.0 -> 136.1 (+0.8 %);
         blocks 125.9 -> 125.2 (the prepared simulate 1.7 -> 0: the cut; the rest is noise)
  pair 2 (15:02-15:28; base = a git copy of 0dd05741): 158.8 -> 124.0 (-21.9 %), NOT the rule's:
         the load fell under the after run (wall 812 -> 240 s) and its blocks 145.6 -> 113.4 where
         the cut is the prepared simulate alone (2.0 s CPU in base's log)

Group (45 modules, each alone, base): 631.8 s (test_readme 135.0 of pair 1, test_dvc_metrics 72.2,
the other 43 424.6); after = the same but test_readme, whose cut is ~1.7-2.0 s: ~0.3 % of the group
against the bar's 30 % (190 s).  Verdict: REFUSED.  The cut is exact and safe (kept on the branch,
the lead decides); nothing in src to revert.


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
