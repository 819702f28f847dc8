"""diag88c's kept rule (rule 2: in diagnose's one-SE choice an uncleared lag of every model input
is the same effect as a lag of one of them that clears, ``search._same_effect``) scored once more
on draws nobody had seen (stop 88, diag88d; issue 34: "diagnose accepts a planted position effect
with 8 train campaigns, accepts nothing on clean data, and never leaves a record's test error more
than 2 % worse").  Scoring only: no design, no src change.

Usage (from the repository root, ``PYTHONPATH=<tree>/src``: the code measured is that tree's)::

    python benchmarks/bench_diag88d.py fresh ROOT LABEL    # FRESH draws -> ROOT/fresh-LABEL.jsonl
    python benchmarks/bench_diag88d.py compare ROOT A B    # two labels' rows: the bar's counts

``fresh``: :data:`FRESH` through bench_diag88c's (so bench_diag86's) ``fresh``: the same generators
(bench_diag86's ``draw``), MLR, every target diagnosed, ``max_effects=2``, test figures as
deployed.  ``compare``: bench_diag86's: per label the planted draws' position found, the clean
draws that accept anything, the rows more than 2 % over diagnose's own before; then every
(draw, target) where the two labels differ.  Both imported, nothing copied.

Why: diag88c's rule 2 was designed after rule 1's FRESH scores on seeds 9251-9260 were seen, so
those draws were scored twice; this bench scores it on unspent seeds 9261-9270 (``clean``
9261-9264, ``planted`` 9265-9267, ``lag`` 9268-9270; 12 campaigns, every 3rd test, 8 train).

Trees: ``main`` = f613a8fd (diag88c merged; this tree's src); ``pre`` = cfee3705 = f613a8fd^1, the
code before diag88c (``git worktree add /tmp/diag88d/before f613a8fd^1``, removed after).

The bar (the brief's; written here before any run of either tree on these seeds; all must hold):

1. No (draw, target) row has main's test RMSE (after, as deployed) more than 2 % above pre's.
2. The clean draws 9261-9264 accept nothing on any target (main).
3. The planted draws 9265-9267 keep their position: main finds the position effect (an
   ``interaction`` on S_pos_Y for E_Y) on every planted draw pre finds it on.

Failing any item: the rows are reported and the lead decides (no src change here either way).
"""

from __future__ import annotations

import sys
from pathlib import Path

HERE = Path(__file__).resolve().parent
sys.path[:0] = [str(HERE), str(HERE.parent / "tests" / "apps")]
import bench_diag86  # noqa: E402
import bench_diag88c  # noqa: E402
from _cli import run_commands  # noqa: E402

# (kind, seed, campaigns): every 3rd campaign test, so 12 -> 8 train
FRESH = ([("clean", s, 12) for s in range(9261, 9265)] + [("planted", s, 12) for s in range(9265, 9268)]
         + [("lag", s, 12) for s in range(9268, 9271)])


def fresh(root: str, label: str) -> None:
    """:data:`FRESH` through bench_diag88c's ``fresh`` -> ``ROOT/fresh-LABEL.jsonl``."""
    bench_diag88c.FRESH = FRESH
    bench_diag88c.fresh(root, label)


def main(argv: list[str]) -> int:
    commands = {"fresh": fresh, "compare": bench_diag86.compare}
    return run_commands(__doc__, commands, argv, cpu=sys.stderr)


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
