"""``model=auto``'s hedge toward MLR on a record whose folds are ONE held-out campaign, by at most 8
of that fold's blocks, each block an equal say: lam least in the MEDIAN of the blocks' error ratios
(issue 34; stop 106, auto106d).

Usage (from the repository root; ``PYTHONPATH=<tree>/src``: the vote and hedge code is that tree's)::

    python benchmarks/bench_auto106d.py seen STORE22 STOREONE [STORE ...]   # stored rows, replayed
    python benchmarks/bench_auto106d.py fl STORE                             # fl_thermal 90/10, replayed
    python benchmarks/bench_auto106d.py fresh OUT       # seeds 10095-10099, fitted and scored ONCE
    python benchmarks/bench_auto106d.py cost ROWS       # the hedge's CPU on a white one-fold residual
    python benchmarks/bench_auto106d.py trace STORE RECORD   # per target: blocks, lam, per-block errors

STORE22 / STOREONE / STORE: as bench_auto106c's (``/tmp/auto105b/main``, ``/tmp/auto105b/one``,
``/tmp/auto105b/fresh`` and auto106b's fresh main-key fits of seeds 10069-10073, seen now).  main =
the stored W with auto105b's hedge replayed.  The commands are bench_auto106c's, run with this tree's
:func:`thermocomp.core.models.hedge.one_fold_weight` (its ``rule_weight`` calls the src's); their
printed "BAR (n)" lines are bench_auto106c's numbering (its (4a) is 25 % under MLR, its (5) the fresh
and (6) the cost: here (4), (6) and (5)).

The rule (``hedge='campaigns_or_fold'``, the new default; ``AutoRegressor._hedged``): auto105b's
nested weight where the folds are >= 3 whole campaigns, unchanged.  Where the folds are ONE held-out
campaign (blocked forward on 2-3 train campaigns): auto106c's units, the fold cut into contiguous
blocks ``max(decorrelation length, ceil(rows / 8))`` long (at most 8, each about one independent
look), A = the prediction of auto's whole choice made without each block; a new measure: block b's
ratio of the mix's squared error to MLR's is ``r_b(lam) = 1 - 2 lam p_b + lam^2 q_b`` (p_b =
<e, d>_b / |e|_b^2, q_b = |d|_b^2 / |e|_b^2, e = y - MLR, d = A - MLR), and lam is the least of
``median_b r_b(lam)`` on [0, 1] (exact: the median is one r_b, or the mean of two, between the lams
where two cross; ties go to the larger lam).  Fewer than 2 blocks: lam 1.  No new constant.
How it differs from refused rules: auto106b (REFUSED) minimised the MEAN of the same ratios over
unbounded blocks: ruled by blocks where MLR is near right (lam ~0 against a candidate at 0.81 of
MLR's MSE), blocks x one vote of cost; auto106c (REFUSED) the fold's POOLED error over the same <= 8
blocks: ruled by blocks where MLR is far off (lab10032 E_Z: A loses 4 of 7 blocks, wins the 2 heavy
ones, lam 1).  The median gives each block one equal say and neither extreme rules; a block where
A ~ MLR sits at ratio 1 whatever lam (no vote for either side).  auto93d (REFUSED): a per-member
threshold on block resamples, not a continuous mix; auto105 (REFUSED): hedged one record's time
blocks, untouched here.

BAR (written and committed with the rule before ``seen``, ``fl``, ``cost``, ``trace`` ran on it and
before seeds 10095-10099 were simulated; KEPT only if all hold):
(1) SEEN 22: losers (auto / MLR > 1) at most main's 6, geo auto / MLR at most 0.8192.
(2) SEEN, every record of the 22, the 10 one-campaign, auto105b's 5 fresh and auto106b's 5 fresh
    (10069-10073, main-key fits): rule / main <= 1.01.
(3) The 10 one-campaign records unchanged: lam 1 on every target.
(4) fl_thermal 90/10 as main: mean RMSE equal to main's (2.481, 38.9 % under MLR's 4.060).
(5) Cost (``cost 2000``, fold_blocks + one_fold_weight, CPU per target): at most 8 blocks and at
    most 10 x one vote (``vote_weights`` on the same rows, timed there too).
(6) FRESH 10095-10099, one-fold records named before drawing (bench_auto106c's :data:`FRESH`,
    auto106b's kinds): lab10095, lab10096, lab10097 (bench_auto_losses56's ``lab_record``: 3 train
    runs, one fold) and year4_10098, year4_10099 (``yearround_spindle``, 4 campaigns, the last held
    out, 3 train forward).  Drawn only if (1)-(5) hold.  Each fitted twice, main's key
    (``hedge=campaigns``) and the rule's (the default), scored once on its own test: no new loser
    (main / MLR <= 1 < rule / MLR), geo rule / MLR <= geo main / MLR over the five, and no fresh
    record rule / main > 1.05.
"""

from __future__ import annotations

import sys
from pathlib import Path

HERE = Path(__file__).resolve().parent
sys.path[:0] = [str(HERE), str(HERE.parent / "tests" / "apps")]
import bench_auto106c as a106c  # noqa: E402
from _cli import run_commands  # noqa: E402


def main(argv: list[str]) -> int:
    return run_commands(__doc__, {"seen": a106c.seen, "fl": lambda s: a106c.fl(s),
                                  "fresh": lambda out: a106c.fresh(out), "cost": lambda n: a106c.cost(n),
                                  "trace": a106c.trace},
                        argv, cpu=sys.stderr)


if __name__ == "__main__":
    raise SystemExit(main(sys.argv[1:]))
