"""CI time (issue 34; stop 104, ci104a): the docs slice of the suite (the pages run as written and
the docs checks) made cheaper.

The slice: tests/test_readme.py, test_docs.py, shell/test_newcomer.py, shell/test_cli_shell.py,
test_docs_site.py (130.3 + 11.4 + 5.8 + 4.8 + 2.9 s wall in the morning's CI run).

Trace (c8b21182 alone, test_readme.py, ``-n 0``, load 5-14, CPU s user + sys incl. children):
the module 107.1 (9 passed); its blocks (readme_run.log) 94.2: README.md 20.1, sweeps.md 23.1
(the 2-job sweep + compare + 2 promotes 16.6, the lathe's simulate + replay 6.5), own-data.md
14.7 (5 commands + the export), diagnose.md 13.6, monitoring.md 11.0, simulation.md 10.5,
outputs.md 0.0, the prepared dataset 1.2; a page's fresh copy 0.6-0.7 each (7 pages), the venv's
copy 1.0 once.  A ``thermocomp`` command's start costs ~2 s of it (``import mlflow`` alone 1.75 s
CPU in a page's venv): about 20 of the docs pages' commands are processes, and the process is
those pages' point (run as written, venv not activated).

BAR (the brief's, written and committed here before any after-measurement):

1. every test of the slice passes in the after tree (``-n 0 -p no:cacheprovider -m "not full"``),
   the same test ids as c8b21182; no assertion removed (``asserts``: no fewer per module), no
   tolerance loosened, no page's ``expect``/``output`` directive changed;
2. the slice's summed CPU (``cpu``: user + sys of ``/usr/bin/time`` over ``python -m pytest -q
   -n 0 -p no:cacheprovider -m "not full" MODULE``, each module alone, run from its tree with
   ``PYTHONPATH=<tree>/src`` and OMP/OPENBLAS/MKL_NUM_THREADS=1) down >= 15 %: KEPT; base = a
   git clone of c8b21182 (test_readme copies a tree by ``git ls-files``), both trees' src byte
   compiled first (``python -m compileall -q src``, as ``make install`` leaves CI's tree); base
   and after started together (paired), a second pair when the cut is under 15 %;
3. below 15 %: the exact cuts stay committed on the branch (the lead decides), said so.

Cuts built (tests only, exact; committed on the branch, 386f73f8; the same diff saved as
benchmarks/ci104a_rule.patch, which applies to c8b21182):

- test_readme: the pages copy one committed copy of the tree made once per test process
  (``project_copy``, a session fixture; ``cp -a`` a page): a page's copy 0.63 -> 0.10 s CPU
  (self + children, 3 copies each, probe), the committed copy 0.58 once; the same file list
  (``find`` of two copies compared), one commit, ``git status`` clean;
- test_docs: the stdin monitor of ``test_every_key_of_a_real_monitor_json...`` in this process
  (``sys.stdin`` a StringIO, conftest's ``thermocomp``), the same command and assertions; its
  ``time`` event (asserted) comes from the piped rows alone; a piped stdin read by a real process
  stays docs/monitoring.md's page (test_readme) and the other stdin tests.

Seen and not cut: ~20 of the docs pages' commands are ``thermocomp`` processes of ~2 s start each
(imports: mlflow 1.75 s CPU alone; a promote's profile is mostly imports), the process being the
pages' point; the pages' heavier examples (diagnose.md, monitoring.md, simulation.md) print
numbers the pages quote; a skipped block covered elsewhere was the lead's refusal on ci102d.

Measured (2026-12-07, CPU s user + sys, ``cpu``; both trees' src compiled first; load 14-22):
pair 1 started together (04:00-04:27)::

  module                    base -> after
  test_readme.py           114.8 -> 112.2   -2.3 %   9 passed / 9 passed
  test_docs.py              10.4 ->   8.6  -17.6 %   45 / 45
  shell/test_newcomer.py    12.8 ->  12.7   -1.0 %   12 / 12
  shell/test_cli_shell.py   11.3 ->  11.1   -1.9 %   19 passed + 1 failed / the same
  test_docs_site.py          2.9 ->   3.1   +5.5 %   3 / 3
  sum                      152.2 -> 147.5   -3.0 %   bar (-15 %) not met

(test_cli_shell's ``test_launcher_without_venv...`` fails in both trees alike: neither has a
``.venv`` for it to link; untouched here.)
Pair 2, one after the other per module (base then after; 04:08-04:36), the load falling from
~20 to ~1 during after's test_readme (wall 1040 -> 329 s), so its cut is overstated::

  test_readme 114.2 -> 104.4 (-8.6 %), test_docs 8.7 -> 7.2, test_newcomer 10.5 -> 10.4,
  test_cli_shell 8.8 -> 8.7, test_docs_site 2.5 -> 2.5; sum 144.6 -> 133.2 (-7.9 %): not met

Pair 3, test_readme alone started together at load ~1 (04:36-04:39): 90.2 -> 87.1 (-3.4 %), but
INVALID as a whole page: both README pages failed at line 118 (the twins of the two trees on the
same 127.0.0.1:4840), so both stopped there alike.  Pair 1 was started together too, under load
~20, and passed; test_readme's pairs are safer one after the other (fixed ports).

Verdict: REFUSED against the bar (pair 1, the clean same-load pair: -3.0 %; pair 2 -7.9 % with
the load falling under the after run).  The exact cuts stay committed on the branch (the brief:
below 15 % the lead decides); no src was changed, so none is reverted.

Usage (from the repository root; ``PYTHONPATH=<tree>/src``), bench_ci101c's commands::

    python benchmarks/bench_ci104a.py cpu TREE TAG OUT SPEC...      # each spec alone, /usr/bin/time
    python benchmarks/bench_ci104a.py table OUT [BEFORE AFTER BAR]   # means, sum, the bar
    python benchmarks/bench_ci104a.py asserts BASE SPEC...           # asserts per module
    python benchmarks/bench_ci104a.py plant TREE FILE OLD NEW SPEC   # a break, the tests on it
"""

from __future__ import annotations

import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
from bench_ci101c import measured  # noqa: E402

SLICE = ("test_readme.py", "test_docs.py", "shell/test_newcomer.py", "shell/test_cli_shell.py",
         "test_docs_site.py")


def main(argv: list[str]) -> int:
    return measured(__doc__, argv)


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
