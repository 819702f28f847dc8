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

Measured (2026-12-07, load 7-17 from the other helpers; CPU s user + sys incl. children, ``cpu``):

- base, each module alone (stopped after 11 of 142 modules: at this load one module a minute):
  bits85 13.9, deploy88 9.7, deploy88b 11.6, deploy89 8.9, deploy_diagnosed 5.6,
  deployed_as_scored 9.8, deployed_guarded 4.3, export 29.9, export_ambient62 6.9 (+ mon98b,
  cmon89b below): 126.4 s.  A module's fixed start (``--collect-only`` of deploy_diagnosed:
  1.65 + 0.29 s) is paid 142 times in this measure, once per xdist worker in CI.  Fitted
  (fixed 1.94 s + 1.02 x its setup+call+teardown seconds of /tmp/ci7.log), the group is ~1000 s.
- the 20 costliest modules in one process under py-spy (289.7 s CPU, 258 passed): share of the
  samples -- in-process commands 29 % (monitor_cli's simulate + monitor per fault), the
  conformance pack 19 % (its mirror of the campaigns and the planted copies 10.6 %, the served
  lead-ins 6.6 %), the numpy mirror's steps 18 % in all, imports 9 %, Hydra composition 8 %
  (test_export's 27 distinct group-override sets, each composed once: first-time misses, the
  cache works), fits 5 %, the tests' own mirror passes 5 %.
- the cut (test_export_cmon87.held_as_served: the served stream keyed on the record's campaign
  id; mon98b and cmon89b streamed their column record under "test" and again under "R1b"),
  paired base then after, 2 reps: mon98b 13.7 -> 11.5, 13.6 -> 12.0; cmon89b 12.3 -> 13.8,
  14.6 -> 13.0; sum 27.1 -> 25.1 s (-7.1 %), the group ~1000 -> ~998 s (-0.2 %).

Against the bar: (1) NOT met (-0.2 % of the group, against >= 30 %); (2) met: no test, assert or
tolerance changed, no data shrunk; plants: watch.py ``"second_range": 0`` fails mon98b's held
test, ``"blind_range": 0`` fails cmon89b's; (3) met: lint, durations, docs pass (with cmon87,
cmon88 and cmon93, the other readers of ``held_as_served``: 57 passed); ruff clean.  REFUSED; the
cut (tests only, exact) stays on the branch for the lead's call: benchmarks/ci108b_rule.patch.

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
