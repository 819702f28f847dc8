"""``model=auto``'s hedge toward MLR on a record whose folds are ONE held-out campaign: auto106b's
measure (the MEAN of the blocks' error ratios) over auto106c's bounded blocks (at most 8, each at
least one decorrelation length) (issue 34; stop 106, auto106e).

Usage (from the repository root; ``PYTHONPATH=<tree>/src``: the vote and hedge code is that tree's)::

    python benchmarks/bench_auto106e.py seen STORE22 STOREONE [STORE ...]   # stored rows, replayed
    python benchmarks/bench_auto106e.py fl STORE                             # fl_thermal 90/10, replayed
    python benchmarks/bench_auto106e.py fresh OUT       # seeds 10110-10114, fitted and scored ONCE
    python benchmarks/bench_auto106e.py cost ROWS       # the hedge's CPU on a white one-fold residual

STORE22 / STOREONE / STORE: as bench_auto106d's (``/tmp/auto105b/main``, ``/tmp/auto105b/one``,
``/tmp/auto105b/fresh``, auto106b's fresh main-key fits of seeds 10069-10073) and auto106d's fresh
main-key fits of seeds 10095-10099 (seen now; a store with ``train_campaigns.json``, 3 each).  main
= the stored W with auto105b's hedge replayed.  ``seen`` and ``fl`` are bench_auto106b's, whose
``rule_weight`` calls this tree's :func:`~thermocomp.core.models.hedge.hedge_weight` over
:func:`~thermocomp.core.models.hedge.fold_blocks` (now capped): this rule.  Their printed "BAR (n)"
lines are bench_auto106b's numbering ((4a) is 25 % under MLR; here (4) asks main's figure);
``fresh`` prints bench_auto106c's "BAR (5)": here (6).

The rule (``hedge='campaigns_or_fold'``, the new default; ``AutoRegressor._hedged``): auto105b's
nested weight where the folds are >= 3 whole campaigns, unchanged.  Where the folds are ONE held-out
campaign (blocked forward on 2-3 train campaigns): the units are auto106c's, the fold cut into
contiguous blocks ``max(decorrelation length, ceil(rows / 8))`` long (``MAX_FOLD_BLOCKS`` 8: the
labs' folds had 3-8, so they keep theirs); A = the prediction of auto's whole choice made without
each block; the measure is auto106b's (and the votes'): lam least in the MEAN over the blocks of the
mix's squared error over MLR's, ``sum_b p_b / sum_b q_b`` clipped to [0, 1] (p_b = <e, d>_b /
|e|_b^2, q_b = |d|_b^2 / |e|_b^2, e = y - MLR, d = A - MLR).  Fewer than 2 blocks: lam 1.  No new
constant.  How it differs from refused rules: auto106b (REFUSED) had the same measure over
UNBOUNDED blocks (one-row on white residuals: 108 s CPU per target at 2,000 rows, lam ~0 against
a candidate at 0.81 of MLR's MSE; year4_10072 23 % worse than main); auto106c (REFUSED) the same
blocks with the POOLED error (lab10032 1.227 -> 1.250); auto106d (REFUSED) the same blocks with the
MEDIAN of the ratios (a sign vote on ties: fresh year4_10099 6.5 % worse than main).  A mean gives
a block a say in proportion to its margin (a tie moves lam little), and a bounded block is long
enough that its ratio is not one row's.

BAR (the lead's, written and committed with the rule before ``seen``, ``fl``, ``cost`` ran on it and
before seeds 10110-10114 were simulated; KEPT only if all hold):
(1) SEEN 22: losers (auto / MLR > 1) at most main's 6, geo auto / MLR at most 0.8192.
(2) SEEN, every record of the 22, the 10 one-campaign, auto105b's 5 fresh, auto106b's 5 fresh
    (10069-10073) and auto106d's 5 fresh (10095-10099; main-key fits): rule / main <= 1.01.
(3) The 10 one-campaign records unchanged: lam 1 on every target.
(4) fl_thermal 90/10 as main: mean RMSE equal to main's (2.481, 38.9 % under MLR's 4.060).
(5) Cost (``cost 2000``, fold_blocks + hedge_weight, CPU per target): at most 8 blocks and at most
    10 x one vote (``vote_weights`` on the same rows, timed there too).
(6) FRESH 10110-10114, one-fold records named before drawing (:data:`FRESH`, auto106b's kinds):
    lab10110, lab10111, lab10112 (bench_auto_losses56's ``lab_record``: 3 train runs, one fold) and
    year4_10113, year4_10114 (``yearround_spindle``, 4 campaigns, the last held out, 3 train
    forward).  Drawn only if (1)-(5) hold.  Each fitted twice, main's key (``hedge=campaigns``) and
    the rule's (the default), scored once on its own test: no new loser (main / MLR <= 1 < rule /
    MLR), geo rule / MLR <= geo main / MLR over the five, and no fresh record rule / main > 1.05.
"""

from __future__ import annotations

import sys
import time
from pathlib import Path

import numpy as np

HERE = Path(__file__).resolve().parent
sys.path[:0] = [str(HERE), str(HERE.parent / "tests" / "apps")]
import bench_auto105 as a105  # noqa: E402
import bench_auto106b as a106b  # noqa: E402
import bench_auto106c as a106c  # noqa: E402
from _cli import run_commands  # noqa: E402

YEAR4 = a106c.YEAR4
FRESH = {"lab10110": ["data.path={out}/lab10110"], "lab10111": ["data.path={out}/lab10111"],
         "lab10112": ["data.path={out}/lab10112"],
         "year4_10113": [*YEAR4, "seed=10113"], "year4_10114": [*YEAR4, "seed=10114"]}


def fresh(out: str) -> None:
    """Seeds 10110-10114 (:data:`FRESH`), each fitted with main's key and the rule's, scored ONCE
    (bench_auto106c's ``fresh`` with this record set and this rule's replayed lam)."""
    a106c.FRESH, a106c.rule_weight = FRESH, a106b.rule_weight
    a106c.fresh(out)


def cost(rows: str) -> None:
    """The one-fold hedge on ROWS rows of a white residual (bench_auto106c's data): blocks, lam, CPU
    of fold_blocks + hedge_weight and of one vote on the same rows."""
    from thermocomp.core.models.blend import vote_weights
    from thermocomp.core.models.hedge import fold_blocks, hedge_weight

    n, rng = int(rows), np.random.default_rng(1)
    y = rng.normal(0.0, 5.0, n)
    preds = np.column_stack([y + rng.normal(0.0, s, n) for s in (1.0, 0.9, 1.1)])
    t0 = time.process_time()
    vote_weights(preds, y, np.zeros(n, int), preds[:, 0], base_column=0, min_folds=a105.N_FOLDS)
    t1 = time.process_time()
    units = fold_blocks(y, preds[:, 0])
    lam = hedge_weight(preds, y, np.zeros(n, int), 0, a105.N_FOLDS, units)
    t2 = time.process_time()
    blocks = np.unique(units).size
    print(f"{n} rows: {blocks} blocks, lam {lam:.3f}, hedge {t2 - t1:.2f} s CPU, one vote {t1 - t0:.2f} s "
          f"({(t2 - t1) / max(t1 - t0, 1e-9):.1f} x): BAR (5) "
          f"{'met' if blocks <= 8 and t2 - t1 <= 10 * (t1 - t0) else 'NOT met'}")


def main(argv: list[str]) -> int:
    return run_commands(__doc__, {"seen": a106b.seen, "fl": lambda s: a106b.fl(s),
                                  "fresh": lambda out: fresh(out), "cost": lambda n: cost(n)},
                        argv, cpu=sys.stderr)


if __name__ == "__main__":
    raise SystemExit(main(sys.argv[1:]))
