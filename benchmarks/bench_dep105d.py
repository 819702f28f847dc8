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
