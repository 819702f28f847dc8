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
