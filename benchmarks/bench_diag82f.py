"""Per-target test blocks re-cut each round on that round's residual (stop 82, diag82f; issue 34:
"diagnose accepts a planted position effect with 8 train campaigns, accepts nothing on clean
data", the control never).

Usage (from the repository root, ``PYTHONPATH=<tree>/src``: the code measured is that tree's)::

    python benchmarks/bench_diag82f.py fresh ROOT LABEL     # the bar's draws -> ROOT/fresh-LABEL.jsonl
    python benchmarks/bench_diag82f.py compare ROOT A B     # two labels' rows: the bar's counts

``fresh`` / ``compare``: bench_diag82e's (bench_diag82d's case: test_diagnose_few's year-round
VMC, 12 campaigns, 8 train; every target, ``max_effects=2``, MLR, test figures as deployed; the
targets > 5 % worse after than before) on this stop's seeds: planted (``axis_position`` on Y)
8351-8360, clean 8361-8370.

The rule (written and committed before scoring)
-----------------------------------------------
1. diag82e_rule.patch (bench_diag82e, unchanged, with its three test-stub fixes): each target
   tested on blocks as long as its own starting CV residual takes to decorrelate; the control
   asked a candidate's within-campaign checks; the deployed penalty's one-SE rule over the
   shared (longest) blocks; saturation and the "over the air" form asked where the shared
   design has one block per campaign.
2. New: at the start of every round a target's test blocks are re-cut on the round's CURRENT
   CV residual by the same rule (``Problem.recut_test_blocks``: ``decorrelation_length``, then
   ``cut_blocks``; the penalty's blocks unchanged), and the current result re-scored on them;
   so a later round never tests on blocks finer than its own residual's correlation.  Each
   round's blocks are reported (``rounds[i].test_blocks`` / ``block_samples``); ``cv.designs``
   and ``cv.min_p`` are the starting designs'.
   Checked before the bar (spent seed, not the bar): planted 8282 E_Y, bench_diag82e's failure:
   round 1 38 blocks of 13 samples (as before), round 2 re-cut to 8 blocks of 92: the random
   walk's 28.2 % CV gain now at p 0.0156 (> 0.01), not clearing; E_Y 5.592 -> 1.503 as diag82e.

Decided by the train rows only (never a candidate's test figure, never the test split).

The bar (all must hold, else REFUSED: src reverted, this bench and ``diag82f_rule.patch`` kept).
Shipped = main 65fa0069's src (= 7b8e171a's; ``PYTHONPATH=/work/main/src``), rule = this tree;
the two ``fresh`` runs alternated / side by side on the same draws:

1. Planted 8351-8360: found (an ``interaction`` on ``S_pos_Y`` accepted for E_Y) with the rule on
   at least shipped's count + 2.
2. Clean 8361-8370: nothing accepted on any target with the rule.
3. The control is never accepted, and clears the bar on no more (draw, target) pairs of the 20
   draws with the rule than with shipped.
4. On the 20 draws the count of targets > 2 % worse as deployed (test RMSE after / before) with
   the rule not above shipped's, and no target > 5 % worse than before with the rule where
   shipped's is not.
5. ``bench_diagnose_faults58.py``'s 20 rows: no target's test RMSE after with the rule more than
   2 % above shipped's after.
6. tests/apps/test_diagnose_*.py and tests/shell/test_diagnose_*.py pass with the rule.
"""

from __future__ import annotations

import sys
from pathlib import Path

HERE = Path(__file__).resolve().parent
sys.path[:0] = [str(HERE), str(HERE.parent / "tests" / "apps")]
import bench_diag82e  # noqa: E402
from _cli import run_commands  # noqa: E402

FRESH_PLANTED = list(range(8351, 8361))
FRESH_CLEAN = list(range(8361, 8371))


def fresh(root: str, label: str) -> None:
    """bench_diag82e's ``fresh`` on this stop's seeds."""
    bench_diag82e.FRESH_PLANTED, bench_diag82e.FRESH_CLEAN = FRESH_PLANTED, FRESH_CLEAN
    bench_diag82e.fresh(root, label)


def compare(root: str, a: str, b: str) -> None:
    """bench_diag82e's ``compare`` (the bar's counts, where the labels differ, > 5 % worse)."""
    bench_diag82e.compare(root, a, b)


def main(argv: list[str]) -> int:
    return run_commands(__doc__, {"fresh": fresh, "compare": compare}, argv, cpu=sys.stderr)


if __name__ == "__main__":
    raise SystemExit(main(sys.argv[1:]))
