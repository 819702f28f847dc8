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

Scored (2026-12-04, after the bar above; 2 cores shared by seven helpers; CPU of each ``fresh``
process 15.3 s main / 15.1 s pre, diagnose 10.4 s in both: the rule costs nothing)
-------------------------------------------------------------------------------------------------
Test RMSE as deployed (µm), E_X, the only (draw, target) rows where main and pre differ::

  row           before (no effect)  pre (cfee3705)                      main (f613a8fd)
  lag:9268 E_X  1.3178              1.3178 nothing                      0.6631 T_box1 14400 s +init (2)
                                                                        (-49.7 %)
  lag:9269 E_X  1.6683              1.6683 nothing                      0.7263 T_box1 14400 s +init (2)
                                                                        (-56.5 %)
  lag:9270 E_X  2.2005              1.2836 T_box1 14400 s +init (3)     1.3731 T_box1 14400 s +init (2)
                                                                        (+7.0 %)

Identical in both trees: the other 27 rows.  Clean 9261-9264 accept nothing on any target (12
rows); planted 9266 / 9267 find the position on E_Y (2.888 -> 1.783, 2.367 -> 1.727), planted 9265
finds it in neither (E_Y 3.558, nothing accepted); every lag draw's E_Y / E_Z accepts nothing; no
control clears; no row above diagnose's own before in either tree.

1. **Fails** on one row: lag:9270 E_X, main 1.3731 against pre's 1.2836 (+7.0 %; still -37.6 %
   against diagnose's before, 2.2005).  2. **Holds** (clean: nothing).  3. **Holds** (9266 / 9267
   found in both, 9265 in neither).  The bar fails; no src change here: the lead decides.

Why lag:9270 (``bench_diag88c.py trace lag:9270 E_X``, both trees, round 1 identical): the lag of
every model input from the initial state, 3 directions, gains most (62.3 %) and does not clear;
T_box1's start lag clears with 3 directions (61.4 %) and with 2 (60.5 %).  pre: the uncleared
all-inputs lag is a rival and the choice is T_box1 (3 directions).  main: that rival is now the
same effect (rule 2), so the one-SE choice is among the cleared T_box1 reads and takes the leaner
2 directions; round 2's CV 0.7709 (pre) -> 0.7878 (main), test +7.0 %.  The same 3 -> 2 swap made
diag88c's fresh lag:9259 E_X better (0.781 -> 0.741): the direction count the one-SE choice lands
on is what moves these rows, not whether a start lag is taken.  Over the three lag draws' E_X
main's after sums to 2.763 against pre's 4.270.
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
