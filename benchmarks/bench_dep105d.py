"""dep105b's whole-dropout rule re-scored after dep105c (issue 34; stop 105, dep105d).

dep105b (bench_dep105b.py, dep105b_rule.patch) made the mirror and the C hold served's last field
where no monitored sensor is left in, instead of refusing (``MISSING_SECOND``).  It met W1-W4 and
failed W5 on fresh pt10044 only: the C had parted from served at W3's first row, before the planted
fault (four sensors jumping in one sample).  dep105c mended that record (C = served <= 8.53e-13 um).
Here the patch is applied on a4796752 (conflicts with dep105c and mon105d resolved: mon105d's
freeze hold and ring kept beside the last field) and dep105b's bar re-run UNCHANGED.

Usage (from the repository root; ``PYTHONPATH=<tree>/src``)::

    python benchmarks/bench_dep105d.py whole ROOT RECORD [RECORD ...]

``whole``: bench_dep105b's ``whole`` lines, :data:`FRESH` among its records.

BAR (dep105b's W1-W5, restated; committed BEFORE fresh seeds 10050-10052 are simulated and before
the rule is measured; scored once; base = a4796752's src, the rule this branch's)
---
W1 whole dropout, seen (pt9851 / tr9891 / cr9892 as dep105 simulated them, and pt10044, seen now:
   dep105b scored it) and the test fixtures (kelvin97 ``whole_dropout``, cdrop77 ``every``, lab75's
   line 15): no row refused, max|C - served| <= 1e-9 um on every row (held AND after the return),
   0 rows past it, 0 rows ``NOT_IN_CODE``, compiled C - mirror <= 1e-9 um; ``cascade`` the same.
W2 bench_dep105 ``returns`` on pt9851: its lines identical base / rule (CPU aside).
W3 every tests/shell/test_export_* module importing watch / watch_c passes, with kelvin97, cdrop77,
   lab75_deploy (the patch's changed assertions), tests/apps/test_warm_batch59.py,
   tests/shell/test_replay*.py, test_lint, test_benchmarks_cli -k dep105d.
W4 healthy frames: 0 rows flagged (W1/W2's healthy lines).
W5 fresh pt10050 (PORTAL), tr10051 (TRUNNION), cr10052 (CR), ``whole``: as W1, scored once.
KEPT if W1-W5 hold; else REFUSED (benchmarks/dep105d_rule.patch, src as a4796752).

SCORED (bar a0a8e539, committed 07:46 UTC before the rule was measured and before fresh 10050-10052
were simulated from 07:48; unchanged.  base = ``git archive a4796752 src``, rule = 1014b62b; roots:
dep105c's rB (seen records) copied twice without C, each tree building its own; fresh simulated by
base, the rule reading a copy.  CPU (user + sys, /usr/bin/time, load 0.6-1.4) base / rule: seen
``whole`` 23.4 / 22.9 s, ``returns`` 10.4 / 9.6 s, fresh ``whole`` 22.2 (with simulation) / 18.8 s.)

W1 MET: pt9851 / tr9891 / cr9892 / pt10044: base refuses ``every`` at the fault row and ``cascade``
at the last sensor (``MISSING_SECOND``, stream exit 2); the rule refuses none: ``every`` max|C -
served| <= 3.06e-13 um, ``cascade`` <= 1.46e-11 um, 0 rows past 1e-9, 0 ``NOT_IN_CODE``, compiled -
mirror <= 1.11e-12 um (pt10044: 3.06e-13 / 1.31e-12 um; dep105b's 14.7 / 53.4 um are gone).
Fixtures: kelvin97 ``whole_dropout``, cdrop77 ``every``, lab75 line 15 pass; all 3 fail on a4796752.
W2 MET: bench_dep105 ``returns`` pt9851: 7 lines identical base / rule (``diff``).
W3 MET: 44 test_export_* modules (watch / watch_c) + lab75_deploy + test_warm_batch59 +
test_replay*.py + test_lint: 168 passed (CPU 127.3 s); test_docs + test_benchmarks_cli -k dep105d:
47 passed.  The 3 changed modules, paired x2: base 5.9 / 5.3 vs rule 5.8 / 5.7 s CPU; no new test.
W4 MET: pt9851's healthy line 0 rows flagged, C = served 0 um.
W5 MET (fresh, scored once): pt10050 / tr10051 / cr10052: base refuses both plants; the rule none:
``every`` <= 2.42e-13 um, ``cascade`` <= 2.32e-11 um, 0 rows past, 0 ``NOT_IN_CODE``, compiled -
mirror <= 1.22e-12 um.  (pt10050's W3 first row steps 8 temperatures: the reader's restart warning;
C = served there on base too, dep105c's rule.)
VERDICT: KEPT.  C state + NM doubles: 6400 -> 6424 bytes at 3 monitored (sizeof(tc_state)).
"""

from __future__ import annotations

import sys
from pathlib import Path

HERE = Path(__file__).resolve().parent
sys.path[:0] = [str(HERE), str(HERE.parent / "tests"), str(HERE.parent / "tests" / "shell")]
import bench_dep105b  # noqa: E402
from _cli import run_commands  # noqa: E402
from bench_audit97 import TRUNNION  # noqa: E402
from bench_audit98 import PORTAL  # noqa: E402
from bench_mon97 import CR  # noqa: E402

FRESH = {"pt10050": [*PORTAL, "seed=10050"], "tr10051": [*TRUNNION[1:], "seed=10051"],
         "cr10052": [*CR, "seed=10052"]}


def whole(root: str, *records: str) -> None:
    """bench_dep105b's ``whole`` lines, :data:`FRESH` among its records."""
    bench_dep105b.FRESH.update(FRESH)
    bench_dep105b.whole(root, *records)


def main(argv: list[str]) -> int:
    return run_commands(__doc__, {"whole": whole}, argv, cpu=sys.stderr)


if __name__ == "__main__":
    raise SystemExit(main(sys.argv[1:]))
