"""Per-target test blocks without the offsets stand-in, each target asked the checks its SHARED
design asks (stop 82, diag82e; issue 34: "diagnose accepts a planted position effect with 8 train
campaigns").

Usage (from the repository root, ``PYTHONPATH=<tree>/src``: the code measured is that tree's)::

    python benchmarks/bench_diag82e.py fresh ROOT LABEL     # the bar's draws -> ROOT/fresh-LABEL.jsonl
    python benchmarks/bench_diag82e.py compare ROOT A B     # two labels' rows: the bar's counts

``fresh`` / ``compare``: bench_diag82d's (test_diagnose_few's year-round VMC, 12 campaigns, 8
train; every target, ``max_effects=2``, MLR, test figures as deployed) on this stop's seeds:
planted (``axis_position`` on Y) 8281-8290, clean 8291-8300; ``compare`` adds the targets > 5 %
worse after than before.

The rule (written and committed before scoring)
-----------------------------------------------
1. diag82_rule.patch (bench_diag82, unchanged): each target tested on blocks as long as its own
   starting CV residual takes to decorrelate; the design's reach the target of fewest blocks
   (``cv.designs`` per target in ``diagnosis.json``); the control asked a candidate's
   within-campaign checks (``Search._within_checks``); the deployed penalty's one-SE rule on the
   shared (longest) block length (``Problem.penalty_index``).
2. No offsets stand-in (diag82b's cost climate_room's initial-state lags, bench_diag82d).
3. The checks a design with one block per campaign asks -- the saturation check
   (``Search.saturates``) and the "rise over the air" form offered where the product bank
   saturates (``Search._bank_untestable``) -- are asked of a target exactly where the SHARED
   design (every target on the slowest target's blocks: what shipped cuts, the penalty's blocks)
   has one block per unit (``Problem.shared_ranked`` False), whatever the target's own blocks.
   Why: asking saturation on every design refused test_diagnose_scenarios[lag_node]'s input lag
   bank (its shared design is ranked already, 31 blocks); keying it to the target's own blocks
   let a saturating bank through on test_diagnose_pde66 (E_Y's own 196 blocks) and dropped the
   "over" form (planted 8155 / 8157 +18.8 / +29.8 %, bench_diag82).  Only the blocks the test
   counts (sign flips, ranks, the margin) are per target.

Decided by the train rows only (never a candidate's test figure, never the test split).

The bar (all must hold, else REFUSED: src reverted, this bench and ``diag82e_rule.patch`` kept).
Shipped = main 14e20d26's src (= 7b8e171a's; ``PYTHONPATH=/work/main/src``), rule = this tree; the
two ``fresh`` runs alternated / side by side on the same draws:

1. Planted 8281-8290: found (an ``interaction`` on ``S_pos_Y`` accepted for E_Y) with the rule on
   at least shipped's count + 2.
2. Clean 8291-8300: nothing accepted on any target with the rule.
3. The control never clears the bar on any target of the 20 draws with the rule.
4. On the 20 draws the count of targets > 2 % worse as deployed (test RMSE after / before) with
   the rule not above shipped's, and no target > 5 % worse than before with the rule where
   shipped's is not.
5. ``bench_diagnose_faults58.py``'s 20 rows: every target's test RMSE after with the rule within
   2 % of shipped's after.
6. tests/apps/test_diagnose_*.py and tests/shell/test_diagnose_*.py pass with the rule.

Scored: not yet.
"""

from __future__ import annotations

import json
import sys
from pathlib import Path

HERE = Path(__file__).resolve().parent
sys.path[:0] = [str(HERE), str(HERE.parent / "tests" / "apps")]
import bench_diag82d  # noqa: E402
from _cli import run_commands  # noqa: E402

FRESH_PLANTED = list(range(8281, 8291))
FRESH_CLEAN = list(range(8291, 8301))


def fresh(root: str, label: str) -> None:
    """bench_diag82d's ``fresh`` on this stop's seeds."""
    bench_diag82d.FRESH_PLANTED, bench_diag82d.FRESH_CLEAN = FRESH_PLANTED, FRESH_CLEAN
    bench_diag82d.fresh(root, label)


def compare(root: str, a: str, b: str) -> None:
    """bench_diag82d's ``compare``, then per label the targets > 5 % worse after than before."""
    bench_diag82d.compare(root, a, b)
    for n in (a, b):
        with open(Path(root) / f"fresh-{n}.jsonl") as f:
            rows = [json.loads(line) for line in f]
        worse = [f"{r['case']} {t} {100 * (v['after'] / v['before'] - 1):+.1f} %" for r in rows
                 for t, v in r["targets"].items() if v["after"] > 1.05 * v["before"]]
        print(f"{n}: > 5 % worse {worse}")


def main(argv: list[str]) -> int:
    return run_commands(__doc__, {"fresh": fresh, "compare": compare}, argv, cpu=sys.stderr)


if __name__ == "__main__":
    raise SystemExit(main(sys.argv[1:]))
