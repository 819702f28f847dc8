"""``model=auto``'s hedge toward MLR on a record whose folds are ONE held-out campaign, by at most 8
of that fold's blocks, each block an equal say: lam least in the MEDIAN of the blocks' error ratios
(issue 34; stop 106, auto106d).

Usage (from the repository root; ``PYTHONPATH=<tree>/src``: the vote and hedge code is that tree's)::

    python benchmarks/bench_auto106d.py seen STORE22 STOREONE [STORE ...]   # stored rows, replayed
    python benchmarks/bench_auto106d.py fl STORE                             # fl_thermal 90/10, replayed
    python benchmarks/bench_auto106d.py fresh OUT       # seeds 10095-10099, fitted and scored ONCE
    python benchmarks/bench_auto106d.py cost ROWS       # the hedge's CPU on a white one-fold residual
    python benchmarks/bench_auto106d.py trace STORE RECORD   # per target: blocks, lam, per-block errors

The rule is REFUSED and its src is ``benchmarks/auto106d_rule.patch``: ``git apply`` it first (every
command calls its ``one_fold_weight`` / ``fold_blocks``).

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

Measured (2026-12-07, the rule's src (now ``benchmarks/auto106d_rule.patch``); ``OMP_NUM_THREADS=1``,
2 shared cores; CPU user + sys by ``/usr/bin/time``: ``seen`` 3.9 s, ``fl`` 1.2, ``fresh`` 23.7).
REFUSED: (6) fails.
(1) SEEN 22 (``seen /tmp/auto105b/main /tmp/auto105b/one /tmp/auto105b/fresh STORE106B``, STORE106B:
    links to auto106b's ``fresh/main`` + its ``train_campaigns.json``): lab5401 keeps lam 1; losers 6,
    geo 0.8192, as main: met.
(2) worst seen rule / main 1.0005 over 42 records (year4_10072, E_Y lam 0.985): met.  Moved: lab10032
    1.227 -> 1.016 x MLR (E_Y lam 0: 0.891 -> 1.000; E_Z lam 0: 1.793 -> 1.000), lab10069 1.204 ->
    0.993, lab10070 1.500 -> 1.494, lab10071 1.386 -> 1.205.
(3) the 10 one-campaign records: no target hedged, geo 0.7654 both: met.
(4) fl_thermal 90/10 (one train record, 5 time-block folds: not hedged): 2.481 as main: met.
(5) ``cost 2000``: 8 blocks, lam 0.534, hedge 0.37 s CPU = 6.7 x one vote (``cost 500``: 7 blocks,
    lam 0.543, 5.4 x): met.
(6) FRESH 10095-10099 (drawn once, after (1)-(5)), auto / MLR main -> rule: lab10095 1.595 -> 1.594,
    lab10096 1.008 -> 1.015, lab10097 0.938 -> 0.953, year4_10098 1.131 -> 0.942, year4_10099 0.926 ->
    0.986; no new loser, geo 1.0958 -> 1.0742, but year4_10099 1.065 x main (> 1.05): NOT met.
Why (``trace STORE year4_10099`` and ``lab10096``, after the verdict): the median is a sign vote
where A is near MLR.  year4_10099 E_Z: main W is MLR 0.96 + arx / lagbank 0.04; on the 7 blocks A /
MLR is 0.996, 1.001, 1.001, 1.046, 1.008, 1.010, 1.000: A loses the median block by 0.1-1 %, so lam
goes the whole way to 0 and the test's 0.917 x MLR goes to 1.000.  A block near ratio 1 does not sit
out, as the rule assumed: it votes by the sign of a tiny margin.  lab10096 E_Z (3 blocks of 400): A /
MLR 2.158, 0.723, 10.231 (the choice made on 2 of 3 blocks is not W: W / MLR 0.861 on block 2), lam 0,
test 0.834 -> 1.000.  A next rule must weigh a block's say by how far its margin is from a tie
(at least as the mean measures do), or leave lam near 1 where the margins are inside the noise.
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
