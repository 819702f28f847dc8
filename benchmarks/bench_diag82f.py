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

Scored (2026-12-04, 2 shared cores; shipped = main's src, 65fa0069's, ``PYTHONPATH=/work/main/src``;
rule = this tree at 69e33fb5; the two ``fresh`` runs side by side on the same draws, then the two
``bench_diagnose_faults58.py`` runs side by side on one ``write`` root; ``compare ROOT shipped rule``;
diagnose CPU summed over the 20 draws 18.0 s shipped, 19.2 s rule)
------------------------------------------------------------------------------------------------
Test RMSE as deployed (µm); starting blocks of the target shipped / rule; every other target of
the 20 draws identical in both (clean: nothing accepted anywhere, either tree)::

  draw / target           before  shipped          rule
  planted:8352 E_Y (8/18)  5.889  5.889 nothing    1.370 S_pos_Y x (T_box1 over T_amb)
  planted:8360 E_Y (8/77)  4.574  4.574 nothing    1.753 the same

1. **Holds.**  Found 6 of 10 shipped (8351, 8353, 8354, 8357, 8358, 8359) -> 8 of 10 rule (+2:
   8352, 8360; 8355, 8356 missed by both); where both found, the same effect and after.
2. **Holds.**  Clean 8361-8370: nothing accepted on any target, either tree.
3. **Holds.**  The control is accepted nowhere; it clears the bar on 2 (draw, target) pairs
   shipped (planted:8358 E_Y, clean:8362 E_X: each on its 8 campaign blocks, nothing accepted
   on the clean one) -> 0 with the rule.
4. **Holds.**  > 2 % worse after than before: planted:8359 E_Y (+5.7 %, the planted product,
   also > 5 %) only, in both trees with the same after.
5. **Holds.**  bench_diagnose_faults58's 20 rows: 19 identical (43 of 45 targets), faults found
   10 of 16 in both; twin_lathe:drift E_Z1_error 0.386 -> 0.320 (-17.1 %, the inputs' 4 h lag,
   as diag82 / 82d / 82e) and E_Z2_error 1.123 -> 0.331 (-70.5 %, the inputs' 900 s and 1 h
   lags) after, shipped -> rule: gains, none worse.
6. **Holds.**  88 of 88 (tests/apps/test_diagnose_*.py, tests/shell/test_diagnose_*.py, with
   test_diagnose_blocks82.py's two re-cut tests; 60 s CPU) pass; so do 126 tests of 13 other
   files that run diagnose (shell/test_diagnose.py, test_diagnose57, test_iso67,
   test_deploy_diagnosed, test_export_diagnosed59, test_report_html, apps/test_clamp_gain61,
   test_stranger66, test_export_rest60, test_export_inputs_product62, test_joinfit62,
   test_deployed_guarded, apps/test_moved_decisions).

**KEPT.**  Checked on spent draws before the bar (not the bar): planted 8282 E_Y (diag82e's
failure) round 2 re-cut 38 x 13 -> 8 x 92 samples, the control 28.2 % at p 0.0156, not clearing,
the after unchanged (1.503); test_diagnose_blocks82's 8061 E_Y: 28 blocks of 18, then 9 of 45.
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
