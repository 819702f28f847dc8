"""``model=auto``'s hedge toward MLR on a record whose folds are ONE held-out campaign, moved only on
the fold's evidence that the choice is worse than MLR there: a paired t test over at most 8 blocks
(issue 34; stop 107, auto107).

Usage (from the repository root; ``PYTHONPATH=<tree>/src``: the vote and hedge code is that tree's)::

    python benchmarks/bench_auto107.py seen STORE22 STOREONE [STORE ...]   # stored rows, replayed
    python benchmarks/bench_auto107.py fl STORE                             # fl_thermal 90/10, replayed
    python benchmarks/bench_auto107.py cost ROWS       # the hedge's CPU on a white one-fold residual
    python benchmarks/bench_auto107.py fresh OUT       # seeds 10110-10114, fitted and scored ONCE
    python benchmarks/bench_auto107.py trace STORE RECORD   # per target: blocks, ratios, t, lam

STORE22 / STOREONE / STORE: bench_auto106e's stores: ``/tmp/auto105b/main`` (the 22),
``/tmp/auto105b/one`` (the 10 one-campaign records), ``/tmp/auto105b/fresh`` (auto105b's 5 fresh
incl. lab10032), auto106b's fresh main-key fits of 10069-10073 and auto106d's of 10095-10099 (each a
store with ``train_campaigns.json``, 3 train campaigns).  main = the stored W with auto105b's hedge
replayed (lam 1 on one fold).  ``seen``, ``fl``, ``cost`` are bench_auto106c's, whose
``rule_weight`` calls this tree's :func:`~thermocomp.core.models.hedge.one_fold_weight`: this rule.
Their printed "BAR (n)" lines carry this bar's numbers ((4a)'s 25 % is not this bar: (4) asks main's
figure, printed beside the rule's).

The rule (``hedge='campaigns_or_fold'``, the new default; ``AutoRegressor._hedged``,
:func:`~thermocomp.core.models.hedge.one_fold_weight`): auto105b's nested weight where the folds are
>= 3 whole campaigns, unchanged.  Where the folds are ONE held-out campaign (blocked forward on 2-3
train campaigns): auto106c's units, the fold cut into contiguous blocks ``max(decorrelation length,
ceil(rows / 8))`` long (at most 8, each about one independent look); A = the prediction of auto's
whole choice (votes, one-SE, zero rule) made without each block; r_b = A's squared error over
MLR's on block b (the votes' measure).  EVIDENCE: the blocks show A worse than MLR when a one-sided
paired t test at the 5 % level rejects "no worse": ``mean(r_b) - 1 > t_{0.95, k-1} * sd(r_b) /
sqrt(k)`` (``worse_than_mlr``; k blocks; t_{0.95}: 6.31, 2.92, 2.35, 2.13, 2.02, 1.94, 1.89 for
k = 2..8).  No evidence (or fewer than 2 blocks): lam = 1, main's W.  Evidence: lam = auto106e's
measure over the same blocks, least mean of the mix's ratios, ``sum_b p_b / sum_b q_b`` clipped to
[0, 1].  The level is the textbook one-sided 5 %, not a value fitted here; the project's one-SE
(t > 1) was not taken because the history already shows it fails: from auto106e's printed trace
of year4_10099 E_Z (seen), A / MLR 0.996, 1.001, 1.001, 1.046, 1.008, 1.010, 1.000 gives t = 1.37,
above 1 and below 1.94 (lam 0 there cost that record 6.5 %).  The same trace's year4_10072 E_Z
(2.537, 0.362, 0.377) gives t = 0.13 and lab10070 E_Y t = 0.33; those were computed by hand from the
notes before this bar, nothing else was replayed.
How it differs from the four refused: auto106b (mean of per-block ratios, unbounded blocks),
auto106c (pooled error), auto106d (median), auto106e (mean over <= 8 blocks) all MOVED lam wherever
their measure's optimum was below 1, so one block (year4_10072) or a sign near a tie (year4_10099)
ruled.  Here the measure acts only after a test on the same blocks says A loses to MLR by more than
the blocks' own spread; a block that disagrees widens the SE, and a margin of 1 % with a spread of
2 % is no evidence.  Not auto80's one-SE fallback either: that keeps MLR alone unless the blend is
better by one SE on >= 2 folds; this is a continuous mix, its burden of proof on the move.  Not
auto93d's per-member threshold (mean + SD of a member's resampled ratios): one test of auto's whole
nested choice.

BAR (written and committed with the rule before ``seen``, ``fl``, ``cost``, ``trace`` ran on it and
before seeds 10110-10114 were simulated; KEPT only if all hold):
(1) SEEN 22: losers (auto / MLR > 1) at most main's 6, geo auto / MLR at most 0.8192.
(2) SEEN, every record of the 22, the 10 one-campaign, auto105b's 5 fresh, auto106b's 5 fresh
    (10069-10073) and auto106d's 5 fresh (10095-10099; main-key fits): rule / main <= 1.01.
(3) The 10 one-campaign records unchanged: lam 1 on every target.
(4) fl_thermal 90/10 as main: mean RMSE equal to main's (2.481, 38.9 % under MLR's 4.060).
(5) FRESH 10110-10114, one-fold records named before drawing (:data:`FRESH`, auto106b's kinds, as
    auto106e named them): lab10110, lab10111, lab10112 (bench_auto_losses56's ``lab_record``: 3
    train runs, one fold) and year4_10113, year4_10114 (``yearround_spindle``, 4 campaigns, the last
    held out, 3 train forward).  Drawn only if (1)-(4) and (6) hold.  Each fitted twice, main's key
    (``hedge=campaigns``) and the rule's (the default), scored once on its own test: no new loser
    (main / MLR <= 1 < rule / MLR), geo rule / MLR <= geo main / MLR over the five, and no fresh
    record rule / main > 1.05.
(6) Cost (``cost 2000``, fold_blocks + one_fold_weight, CPU per target): at most 8 blocks and at most
    10 x one vote (``vote_weights`` on the same rows, timed there too).

Measured (2026-12-07, this tree's src, after the bar's commit 7f04ce0e; ``OMP_NUM_THREADS=1``, 2
shared cores; CPU user + sys by ``/usr/bin/time``: ``seen`` 4.1 s, ``fl`` 1.3, ``cost`` 1.3 / 1.7,
``fresh`` 25.5).  KEPT by the bar: all six hold -- but the rule moved NO lam anywhere.
REFUSED by the lead (stop 107): a rule that leaves every measured weight as main's adds a
config key, a code path and a test for no measured gain; src/conf/docs/test are in
``benchmarks/auto107_rule.patch`` (applies to 570d5a78).  Its finding stands: the fold's
blocks do not show the loss the new campaign shows, so no block-evidence hedge removes it.
(1) SEEN 22 (``seen /tmp/auto105b/main /tmp/auto105b/one /tmp/auto105b/fresh STORE106B STORE106D``;
    STORE106B: links to auto106b's ``fresh/main`` + ``train_campaigns.json``, STORE106D: auto106d's
    main-key fits, as auto106e used them): losers 6, geo 0.8192, as main: met.
(2) worst seen rule / main 1.0000 over 47 records: met.  No target's lam left 1: lab10032 stays 1.227.
(3) the 10 one-campaign records: no target hedged, geo 0.7654 both: met.
(4) fl_thermal 90/10 (one train record, 5 time-block folds: not hedged): 2.481 as main: met.
(5) FRESH 10110-10114 (drawn once, after (1)-(4), (6)), auto / MLR main -> rule: lab10110 1.107 ->
    1.107, lab10111 1.723 -> 1.723, lab10112 1.037 -> 1.037, year4_10113 0.933 -> 0.933, year4_10114
    1.200 -> 1.200; the built rule's weights equal main's on all 15 targets; no new loser, geo 1.1725
    both, none > 5 % worse: met.
(6) ``cost 2000``: 8 blocks, lam 1.000, hedge 0.37 s CPU = 5.4 x one vote (``cost 500``: 7 blocks,
    5.1 x): met.
Why nothing moved (``trace``, after the verdict): over the 33 blended one-fold targets seen and
the 15 fresh, the largest t is 1.72 (lab10032 E_Y, a test WIN 0.891 that auto106e's lam cut to
0.955), then 1.38 (year4_10099 E_Z), 1.29, 1.14, 1.00, 0.98; every crossing needs >= 1.89.  The
targets that lose to MLR on the test show no loss in the fold's blocks: lab10032 E_Z (test 1.793
x MLR) t 0.43, lab10069 E_Z (1.578) 0.68, lab10071 E_Y (1.833) -0.46, lab10095 E_Z (2.695) -0.02,
lab10070 E_Z (2.973) -4.57; fresh lab10111 E_X (1.663) -2.94, E_Z (2.856) -4.02, year4_10114 E_Z
(1.370) -1.99, lab10110 E_Y (1.259) 0.38, lab10112 E_Z (1.174) 0.30.  The refused measures moved
some of them only because their optimum leaves 1 on ANY disagreement among blocks (the same
moves cost year4_10072 / year4_10099).  And the fold's own votes make evidence rare: they choose by
the blocks' mean ratio, so one candidate chosen outright without each of 8 blocks has a ratio sum
below 7 over every 7 of them, hence below 8 over all 8, and cannot lose to MLR on average; A loses
consistently only where the choice changes from block to block (tests/core/test_auto_hedge107.py:
a candidate right on the first block only, 6 % worse on the rest).
The one fold does not see the new campaign's loss; no hedge read from its blocks can.
"""

from __future__ import annotations

import json
import sys
from pathlib import Path

import numpy as np

HERE = Path(__file__).resolve().parent
sys.path[:0] = [str(HERE), str(HERE.parent / "tests" / "apps")]
import bench_auto87b as b87  # noqa: E402
import bench_auto105 as a105  # noqa: E402
import bench_auto106c as a106c  # noqa: E402
from _cli import run_commands  # noqa: E402

YEAR4 = a106c.YEAR4
FRESH = {"lab10110": ["data.path={out}/lab10110"], "lab10111": ["data.path={out}/lab10111"],
         "lab10112": ["data.path={out}/lab10112"],
         "year4_10113": [*YEAR4, "seed=10113"], "year4_10114": [*YEAR4, "seed=10114"]}


def fresh(out: str) -> None:
    """Seeds 10110-10114 (:data:`FRESH`), each fitted with main's key and the rule's, scored ONCE
    (bench_auto106c's ``fresh``, whose replayed lam is this tree's ``one_fold_weight``)."""
    a106c.FRESH = FRESH
    a106c.fresh(out)


def trace(store: str, record: str) -> None:
    """Per one-fold target of RECORD in STORE: the blocks' A / MLR, the t statistic against the 5 %
    quantile, lam; the test at lam 1 and at the rule's lam."""
    from scipy.special import stdtrit

    from thermocomp.core.models.blend import fold_ratios
    from thermocomp.core.models.hedge import EVIDENCE_LEVEL, fold_blocks, nested_prediction, one_fold_weight

    rep = json.loads((Path(store) / f"{record}.json").read_text())
    for t, r in rep["targets"].items():
        with np.load(Path(store) / f"{record}.{t}.npz", allow_pickle=True) as z:
            a = {k: z[k] for k in z.files}
        w = {n: float(v) for n, v in r["auto"]["weights"].items()}
        if np.unique(a["oof_fold"]).size != 1 or b87._nonzero(w) == {"mlr": 1.0}:
            print(f"{t}: not hedged (not one fold, or MLR alone)")
            continue
        names = [n for n in b87.ORDER if f"oof_{n}" in a]
        preds, y = np.column_stack([a[f"oof_{n}"] for n in names]), a["oof_y"]
        base = names.index("mlr")
        units = fold_blocks(y, preds[:, base])
        e = y - preds[:, base]
        d = nested_prediction(preds, y, np.zeros(len(y), int), base, a105.N_FOLDS, units) - preds[:, base]
        ratios = fold_ratios((e - d) ** 2, e ** 2, units)
        k = ratios.size
        se = float(np.std(ratios, ddof=1) / np.sqrt(k)) if k > 1 else float("nan")
        lam = one_fold_weight(preds, y, base, a105.N_FOLDS)
        print(f"{t}: {len(y)} rows, {k} blocks, A / MLR {np.round(ratios, 3).tolist()}, t "
              f"{(ratios.mean() - 1) / se:.2f} vs {float(stdtrit(max(k - 1, 1), 1 - EVIDENCE_LEVEL)):.2f}, "
              f"lam {lam:.3f}, kept W { {n: round(v, 2) for n, v in w.items()} }")
        test = sum(v * a[f"test_{n}"] for n, v in w.items())
        for lam_ in (1.0, lam):
            mix = lam_ * test + (1 - lam_) * a["test_mlr"]
            print(f"   test RMSE / MLR at lam {lam_:.3f}: "
                  f"{b87._rmse(a['test_y'] - mix) / b87._rmse(a['test_y'] - a['test_mlr']):.3f}")


def main(argv: list[str]) -> int:
    return run_commands(__doc__, {"seen": a106c.seen, "fl": lambda s: a106c.fl(s),
                                  "cost": lambda n: a106c.cost(n), "fresh": lambda out: fresh(out),
                                  "trace": trace},
                        argv, cpu=sys.stderr)


if __name__ == "__main__":
    raise SystemExit(main(sys.argv[1:]))
